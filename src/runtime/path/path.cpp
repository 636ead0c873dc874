#include "fuzzygait/path/path.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "runtime/common/format.hpp"

namespace fuzzygait::path {

using common::number_text;

namespace {

// The point `u` metres along a piece of curvature `k` from (x, z) heading `h`: along the chord,
// 2 sin(ku/2)/k long at heading h + ku/2, which stays exact as k goes to 0.
GroundPoint advance(GroundPoint from, double heading, double curvature, double u) {
  const double half_turn = 0.5 * curvature * u;
  const double chord = std::abs(half_turn) < 1e-8 ? u : u * std::sin(half_turn) / half_turn;
  const double along = heading + half_turn;
  return {from.x + chord * std::sin(along), from.z + chord * std::cos(along)};
}

double wrap(double angle) {  // into (-pi, pi]
  angle = std::remainder(angle, 2.0 * std::numbers::pi);
  return angle;
}

}  // namespace

Path::Path() : Path({0.0, 0.0}, 0.0, {}) {}

Path::Path(GroundPoint start, double heading, std::vector<Piece> pieces)
    : pieces_(std::move(pieces)) {
  if (!std::isfinite(start.x) || !std::isfinite(start.z) || std::abs(start.x) > kLongest ||
      std::abs(start.z) > kLongest) {
    throw std::invalid_argument("path start is not a finite point within " + number_text(kLongest) +
                                " m of the origin");
  }
  if (!std::isfinite(heading)) throw std::invalid_argument("path heading is not finite");
  starts_.reserve(pieces_.size() + 1);
  Start s{start, heading, 0.0};
  for (std::size_t i = 0; i < pieces_.size(); ++i) {
    const Piece& p = pieces_[i];
    const std::string which = "path piece " + std::to_string(i + 1);
    if (!std::isfinite(p.length) || p.length <= 0.0) {
      throw std::invalid_argument(which + ": length must be positive, got " +
                                  number_text(p.length));
    }
    if (!std::isfinite(p.curvature) || std::abs(p.curvature) > 1.0 / kSmallestRadius) {
      throw std::invalid_argument(
          which + ": curvature must be at most " + number_text(1.0 / kSmallestRadius) + " 1/m (a " +
          number_text(kSmallestRadius) + " m radius), got " + number_text(p.curvature));
    }
    starts_.push_back(s);
    s.point = advance(s.point, s.heading, p.curvature, p.length);
    s.heading = wrap(s.heading + p.curvature * p.length);
    s.distance += p.length;
    if (s.distance > kLongest) {
      throw std::invalid_argument(which + ": the path is longer than " + number_text(kLongest) +
                                  " m");
    }
  }
  starts_.push_back(s);
  length_ = s.distance;
}

Path Path::polyline(std::span<const GroundPoint> points, double corner_radius) {
  if (points.size() < 2) {
    throw std::invalid_argument("a path needs at least two points, got " +
                                std::to_string(points.size()));
  }
  if (!std::isfinite(corner_radius) || corner_radius < kSmallestRadius) {
    throw std::invalid_argument("path corner radius must be at least " +
                                number_text(kSmallestRadius) + " m, got " +
                                number_text(corner_radius));
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const GroundPoint p = points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.z) || std::abs(p.x) > kLongest ||
        std::abs(p.z) > kLongest) {
      throw std::invalid_argument("path point " + std::to_string(i + 1) +
                                  " is not a finite point within " + number_text(kLongest) +
                                  " m of the origin");
    }
    if (i > 0 && std::hypot(p.x - points[i - 1].x, p.z - points[i - 1].z) < 1e-3) {
      throw std::invalid_argument("path point " + std::to_string(i + 1) +
                                  " is the same as the point before it");
    }
  }
  const std::size_t n = points.size();
  std::vector<double> leg(n - 1), heading(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double dx = points[i + 1].x - points[i].x;
    const double dz = points[i + 1].z - points[i].z;
    leg[i] = std::hypot(dx, dz);
    heading[i] = std::atan2(dx, dz);
  }
  // Each corner's turn and the length its arc takes from either leg (the tangent length).
  std::vector<double> turn(n, 0.0), tangent(n, 0.0), radius(n, 0.0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    turn[i] = wrap(heading[i] - heading[i - 1]);
    const double half = 0.5 * std::abs(turn[i]);
    if (half < 1e-9) continue;
    const std::string which = "path point " + std::to_string(i + 1);
    if (half > 0.5 * std::numbers::pi * (170.0 / 180.0)) {
      throw std::invalid_argument(which + ": the path turns back on itself there (" +
                                  number_text(std::abs(turn[i]) * 180.0 / std::numbers::pi) +
                                  " deg)");
    }
    const double fits =
        std::min(i == 1 ? leg[0] : 0.5 * leg[i - 1], i + 2 == n ? leg[i] : 0.5 * leg[i]);
    radius[i] = std::min(corner_radius, fits / std::tan(half));
    if (radius[i] < kSmallestRadius) {
      throw std::invalid_argument(which + ": the corner is too sharp for its legs (" +
                                  number_text(std::abs(turn[i]) * 180.0 / std::numbers::pi) +
                                  " deg needs a " + number_text(radius[i]) +
                                  " m radius, the smallest is " + number_text(kSmallestRadius) +
                                  " m): move the points apart");
    }
    tangent[i] = radius[i] * std::tan(half);
  }
  std::vector<Piece> pieces;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double straight = leg[i] - tangent[i] - tangent[i + 1];
    if (straight > 1e-9) pieces.push_back({straight, 0.0});
    const std::size_t c = i + 1;
    if (tangent[c] > 0.0) {
      pieces.push_back({radius[c] * std::abs(turn[c]), (turn[c] > 0.0 ? 1.0 : -1.0) / radius[c]});
    }
  }
  return Path(points[0], heading[0], std::move(pieces));
}

PathSample Path::at(double distance) const {
  if (std::isnan(distance)) distance = 0.0;
  distance = std::clamp(distance, -4.0 * kLongest, 4.0 * kLongest);  // infinities go straight on
  if (distance < 0.0 || pieces_.empty()) {
    const Start& s = starts_.front();
    const double u = pieces_.empty() ? distance : std::min(distance, 0.0);
    return {advance(s.point, s.heading, 0.0, u), s.heading, 0.0};
  }
  if (distance >= length_) {
    const Start& s = starts_.back();
    return {advance(s.point, s.heading, 0.0, distance - length_), s.heading, 0.0};
  }
  // The last piece starting at or before the distance.
  const auto it = std::upper_bound(starts_.begin(), starts_.end() - 1, distance,
                                   [](double d, const Start& s) { return d < s.distance; });
  const std::size_t i = static_cast<std::size_t>(it - starts_.begin()) - 1;
  const Start& s = starts_[i];
  const Piece& p = pieces_[i];
  const double u = distance - s.distance;
  return {advance(s.point, s.heading, p.curvature, u), wrap(s.heading + p.curvature * u),
          p.curvature};
}

}  // namespace fuzzygait::path

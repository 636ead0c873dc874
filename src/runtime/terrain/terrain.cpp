#include "fuzzygait/terrain/terrain.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace fuzzygait::terrain {

Terrain::Terrain(std::vector<Point> points) : points_(std::move(points)) {
  // Once per segment: the walker asks for slopes several times a time step.
  slopes_.reserve(points_.size() - 1);
  for (std::size_t i = 0; i + 1 < points_.size(); ++i) {
    slopes_.push_back(std::atan2(points_[i + 1].y - points_[i].y, points_[i + 1].x - points_[i].x));
  }
  level_ = std::all_of(points_.begin(), points_.end(), [&](const Point& p) {
    return std::bit_cast<std::uint64_t>(p.y) == std::bit_cast<std::uint64_t>(points_[0].y);
  });
}

Terrain Terrain::flat() {
  return Terrain({{-kMaxCoordinate, 0.0}, {kMaxCoordinate, 0.0}});
}

Terrain Terrain::polyline(std::vector<Point> points) {
  if (points.size() < 2) throw std::invalid_argument("terrain needs at least two points");
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y)) {
      throw std::invalid_argument("terrain point " + std::to_string(i) + " is not finite");
    }
    if (std::abs(points[i].x) > kMaxCoordinate || std::abs(points[i].y) > kMaxCoordinate) {
      throw std::invalid_argument("terrain point " + std::to_string(i) +
                                  " lies more than 1000 km from the origin");
    }
    if (i > 0 && !(points[i].x > points[i - 1].x)) {
      throw std::invalid_argument("terrain point " + std::to_string(i) +
                                  ": x must increase along the profile");
    }
  }
  return Terrain(std::move(points));
}

std::size_t Terrain::search_segment(double x) const {
  const auto it = std::upper_bound(points_.begin(), points_.end(), x,
                                   [](double v, const Point& p) { return v < p.x; });
  const std::size_t i = static_cast<std::size_t>(it - points_.begin());
  return std::clamp<std::size_t>(i == 0 ? 0 : i - 1, 0, points_.size() - 2);
}

std::vector<Point> Terrain::profile(double x0, double x1) const {
  std::vector<Point> out{{x0, height(x0)}};
  for (const Point& p : points_) {
    if (p.x > x0 && p.x < x1) out.push_back(p);
  }
  out.push_back({x1, height(x1)});
  return out;
}

}  // namespace fuzzygait::terrain

#include "fuzzygait/terrain/terrain.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "runtime/common/format.hpp"

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
  // Runs: the ground between risers.
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double begin = points_.front().x;
  for (std::size_t i = 0; i + 1 < points_.size(); ++i) {
    if (std::abs(slopes_[i]) <= kSteepestFoothold) continue;
    if (points_[i].x > begin) runs_.push_back({begin, points_[i].x, kNaN});
    begin = points_[i + 1].x;
  }
  runs_.push_back({begin, points_.back().x, kNaN});
  // A tread's pitch: the mean rise of the risers at its ends over its length.
  for (std::size_t r = 0; r < runs_.size(); ++r) {
    const double length = runs_[r].end - runs_[r].begin;
    if (!(length < kLongestTread)) continue;
    double rise = 0.0;
    int risers = 0;
    if (r > 0) {
      rise += height(runs_[r].begin) - height(runs_[r - 1].end);
      ++risers;
    }
    if (r + 1 < runs_.size()) {
      rise += height(runs_[r + 1].begin) - height(runs_[r].end);
      ++risers;
    }
    if (risers > 0) runs_[r].pitch = std::atan2(rise / risers, length);
  }
}

double Terrain::pitch(double x) const {
  if (level_) return 0.0;
  const double tread = runs_[run_at(x)].pitch;
  return std::isnan(tread) ? slope(x) : tread;
}

std::size_t Terrain::run_at(double x) const {
  const auto after = std::upper_bound(runs_.begin(), runs_.end(), x,
                                      [](double v, const Run& r) { return v < r.begin; });
  return after == runs_.begin() ? 0 : static_cast<std::size_t>(after - runs_.begin()) - 1;
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
  // Walls: consecutive segments too steep to stand on, and how high they climb or drop together.
  double wall = 0.0;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const double dx = points[i + 1].x - points[i].x;
    const double dy = points[i + 1].y - points[i].y;
    const bool steep = std::atan2(std::abs(dy), dx) > kSteepestFoothold;
    wall = steep && (wall == 0.0 || (wall > 0.0) == (dy > 0.0)) ? wall + dy : (steep ? dy : 0.0);
    if (std::abs(wall) > kTallestWall) {
      throw std::invalid_argument("terrain point " + std::to_string(i + 1) + ": a wall " +
                                  common::number_text(std::abs(wall), 3) +
                                  " m high at x = " + common::number_text(points[i + 1].x, 3) +
                                  " is taller than a leg climbs in a step (" +
                                  common::number_text(kTallestWall) + " m)");
    }
  }
  return Terrain(std::move(points));
}

namespace {

// "terrain piece N (KIND): " for the errors of a sequence.
std::string piece_name(std::size_t index, const Terrain::Piece& p) {
  const char* kinds[] = {"flat", "ramp", "stairs", "profile"};
  return "terrain piece " + std::to_string(index + 1) + " (" + kinds[static_cast<int>(p.kind)] +
         "): ";
}

void within(const std::string& where, const char* field, double value, double low, double high,
            const char* unit) {
  if (!(value >= low && value <= high)) {
    throw std::invalid_argument(where + field + " must be between " + common::number_text(low) +
                                " and " + common::number_text(high) + unit + ", got " +
                                common::number_text(value));
  }
}

}  // namespace

Terrain::Piece Terrain::flat_piece(double length) {
  Piece p;
  p.kind = Piece::Kind::Flat;
  p.length = length;
  return p;
}

Terrain::Piece Terrain::ramp_piece(double degrees, double length) {
  Piece p;
  p.kind = Piece::Kind::Ramp;
  p.degrees = degrees;
  p.length = length;
  return p;
}

Terrain::Piece Terrain::stairs_piece(double rise, double tread, int count) {
  Piece p;
  p.kind = Piece::Kind::Stairs;
  p.rise = rise;
  p.tread = tread;
  p.count = count;
  return p;
}

Terrain::Piece Terrain::profile_piece(std::vector<Point> points) {
  Piece p;
  p.kind = Piece::Kind::Profile;
  p.points = std::move(points);
  return p;
}

Terrain Terrain::sequence(std::span<const Piece> pieces, double start) {
  within("terrain: ", "the start", start, -1e3, 1e3, " m");
  std::vector<Point> points{{-kMaxCoordinate, 0.0}, {start, 0.0}};
  constexpr double kLandingLength = 1.0;  // m of level ground after stairs that something follows
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const Piece& piece = pieces[i];
    const std::string where = piece_name(i, piece);
    const bool last = i + 1 == pieces.size();
    const Point at = points.back();
    switch (piece.kind) {
      case Piece::Kind::Flat:
        within(where, "length", piece.length, 0.01, 1e4, " m");
        if (!last) points.push_back({at.x + piece.length, at.y});
        break;
      case Piece::Kind::Ramp: {
        within(where, "angle", piece.degrees, -25.0, 25.0, " deg");
        within(where, "length", piece.length, 0.01, 1e4, " m");
        const double grade = std::tan(piece.degrees * (3.14159265358979323846 / 180.0));
        // The last ramp goes on as far as the ground reaches.
        double length = piece.length;
        if (last) {
          length = kMaxCoordinate - at.x;
          if (grade != 0.0)
            length = std::min(length, (kMaxCoordinate - std::abs(at.y)) / std::abs(grade));
        }
        if (piece.degrees != 0.0 || !last) points.push_back({at.x + length, at.y + grade * length});
        break;
      }
      case Piece::Kind::Stairs: {
        if (!(std::abs(piece.rise) >= 0.05 && std::abs(piece.rise) <= 0.25)) {
          throw std::invalid_argument(where +
                                      "rise must be between 0.05 and 0.25 m (-0.25 to "
                                      "-0.05 going down), got " +
                                      common::number_text(piece.rise));
        }
        within(where, "tread", piece.tread, 0.20, 0.40, " m");
        within(where, "count", piece.count, 1, 200, " steps");
        Point p = at;  // the foot of the first riser: the last point already
        for (int step = 0; step < piece.count; ++step) {
          if (step > 0) {
            p.x += piece.tread - kRiserWidth;
            points.push_back(p);
          }
          p = {p.x + kRiserWidth, p.y + piece.rise};
          points.push_back(p);
        }
        if (!last) points.push_back({p.x + kLandingLength, p.y});
        break;
      }
      case Piece::Kind::Profile: {
        if (piece.points.size() < 2) {
          throw std::invalid_argument(where + "a profile needs at least two points");
        }
        const Point first = piece.points.front();
        for (std::size_t k = 1; k < piece.points.size(); ++k) {
          points.push_back(
              {at.x + (piece.points[k].x - first.x), at.y + (piece.points[k].y - first.y)});
        }
        break;
      }
    }
  }
  if (points.back().x < kMaxCoordinate) points.push_back({kMaxCoordinate, points.back().y});
  try {
    return polyline(std::move(points));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("terrain: " + std::string(e.what()));
  }
}

Terrain Terrain::ramp(double degrees, double start) {
  const Piece piece = ramp_piece(degrees);
  return sequence(std::span(&piece, 1), start);
}

Terrain Terrain::stairs(double rise, double tread, int count, double start) {
  const Piece piece = stairs_piece(rise, tread, count);
  return sequence(std::span(&piece, 1), start);
}

std::size_t Terrain::search_segment(double x) const {
  const auto it = std::upper_bound(points_.begin(), points_.end(), x,
                                   [](double v, const Point& p) { return v < p.x; });
  const std::size_t i = static_cast<std::size_t>(it - points_.begin());
  return std::clamp<std::size_t>(i == 0 ? 0 : i - 1, 0, points_.size() - 2);
}

double Terrain::ahead_along_ground(double from_x, double distance) const {
  const double to = from_x + distance;
  if (level_ || corners_between(from_x, to).empty()) {
    const double y0 = height(from_x);
    if (height(to) == y0) return to;  // level between: exactly the distance ahead
  }
  // The straight distance to the ground point at x grows with x on ground a foot stands on.
  const double y0 = height(from_x);
  double near = from_x;
  double far = to;
  for (int i = 0; i < 50; ++i) {
    const double mid = 0.5 * (near + far);
    (std::hypot(mid - from_x, height(mid) - y0) < distance ? near : far) = mid;
  }
  return near;
}

std::span<const Point> Terrain::corners_between(double x0, double x1) const {
  const auto first = std::upper_bound(points_.begin(), points_.end(), x0,
                                      [](double v, const Point& p) { return v < p.x; });
  const auto last =
      std::lower_bound(first, points_.end(), x1, [](const Point& p, double v) { return p.x < v; });
  return {first, last};
}

Terrain::Foothold Terrain::foothold(double from_x, double wanted_x, double foot_length,
                                    double margin, double shortest) const {
  const std::size_t from_run = run_at(from_x);
  // The heels a run holds whole feet at, [low, high] (low > high: the run is too short).
  auto heels = [&](std::size_t r) {
    return std::pair{runs_[r].begin + margin, runs_[r].end - margin - foot_length};
  };
  // This run, ahead of the foot: the wanted place, or short of the edge.
  const auto [low, high] = heels(from_run);
  const double ahead = std::max(low, from_x);
  if (ahead <= high && wanted_x <= high) return {std::max(wanted_x, ahead), from_run};
  if (ahead <= high && high - from_x >= shortest) return {high, from_run};
  // The next run.
  const std::size_t next = from_run + 1;
  if (next >= runs_.size()) return {std::max(wanted_x, ahead), from_run};
  const auto [next_low, next_high] = heels(next);
  if (next_low <= next_high) return {std::clamp(wanted_x, next_low, next_high), next};
  // A tread shorter than the foot: the toes clear of the riser ahead going up, the heel against
  // the riser behind going down.
  const bool up = height(0.5 * (runs_[next].begin + runs_[next].end)) > height(from_x);
  return {up ? runs_[next].end - margin - foot_length : runs_[next].begin + margin, next};
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

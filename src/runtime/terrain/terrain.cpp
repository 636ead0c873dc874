#include "fuzzygait/terrain/terrain.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <optional>
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

std::size_t Terrain::search_run(double x) const {
  const auto after = std::upper_bound(runs_.begin(), runs_.end(), x,
                                      [](double v, const Run& r) { return v < r.begin; });
  return after == runs_.begin() ? 0 : static_cast<std::size_t>(after - runs_.begin()) - 1;
}

Terrain Terrain::flat() {
  return Terrain({{-kMaxCoordinate, 0.0}, {kMaxCoordinate, 0.0}});
}

std::optional<Terrain::Fault> Terrain::find_fault(std::span<const Point> points) {
  if (points.size() < 2) return Fault{0, "terrain needs at least two points", false};
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y)) {
      return Fault{i, "is not finite", true};
    }
    if (std::abs(points[i].x) > kMaxCoordinate || std::abs(points[i].y) > kMaxCoordinate) {
      return Fault{i, "lies more than 1000 km from the origin", true};
    }
    if (i > 0 && !(points[i].x > points[i - 1].x)) {
      return Fault{i, "x must increase along the profile", false};
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
      return Fault{i + 1,
                   "a wall " + common::number_text(std::abs(wall), 3) +
                       " m high at x = " + common::number_text(points[i + 1].x, 3) +
                       " is taller than a leg climbs in a step (" +
                       common::number_text(kTallestWall) + " m)",
                   false};
    }
  }
  return std::nullopt;
}

namespace {

// "terrain point 3 is not finite", "terrain point 3: x must increase ..."; `subject` names the
// point.
std::string fault_text(const std::string& subject, const Terrain::Fault& fault) {
  return subject + (fault.about_point ? " " : ": ") + fault.reason;
}

}  // namespace

Terrain Terrain::polyline(std::vector<Point> points) {
  if (points.size() < 2) throw std::invalid_argument("terrain needs at least two points");
  if (const std::optional<Fault> fault = find_fault(points)) {
    throw std::invalid_argument(
        fault_text("terrain point " + std::to_string(fault->point), *fault));
  }
  return Terrain(std::move(points));
}

namespace {

// "terrain piece N (KIND): " for the errors of a sequence.
std::string piece_name(std::size_t index, const Terrain::Piece& p) {
  const char* kinds[] = {"flat", "ramp", "stairs", "profile"};
  const auto kind = static_cast<std::size_t>(p.kind);
  return "terrain piece " + std::to_string(index + 1) + " (" +
         (kind < std::size(kinds) ? kinds[kind] : "unknown kind") + "): ";
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

void Terrain::validate(const Piece& piece) {
  switch (piece.kind) {
    case Piece::Kind::Flat:
      within("", "length", piece.length, 0.01, 1e4, " m");
      return;
    case Piece::Kind::Ramp:
      within("", "angle", piece.degrees, -25.0, 25.0, " deg");
      within("", "length", piece.length, 0.01, 1e4, " m");
      return;
    case Piece::Kind::Stairs:
      if (!(std::abs(piece.rise) >= 0.05 && std::abs(piece.rise) <= 0.25)) {
        throw std::invalid_argument(
            "rise must be between 0.05 and 0.25 m (-0.25 to -0.05 going down), got " +
            common::number_text(piece.rise));
      }
      within("", "tread", piece.tread, 0.20, 0.40, " m");
      within("", "count", piece.count, 1, 200, " steps");
      return;
    case Piece::Kind::Profile:
      if (piece.points.size() < 2)
        throw std::invalid_argument("a profile needs at least two points");
      // Its own faults, named by its own points (once moved, a point's place is another).
      if (const std::optional<Fault> fault = find_fault(piece.points)) {
        throw std::invalid_argument(fault_text("point " + std::to_string(fault->point), *fault));
      }
      return;
  }
  throw std::invalid_argument("not a kind of piece");
}

Terrain Terrain::sequence(std::span<const Piece> pieces, double start) {
  within("terrain: ", "the start", start, -1e3, 1e3, " m");
  std::vector<Point> points{{-kMaxCoordinate, 0.0}, {start, 0.0}};
  // Which piece each point comes from (pieces.size() for the ground around them), and for a
  // profile's points their index in the piece: a fault is named by its piece.
  std::vector<std::size_t> owner{pieces.size(), pieces.size()};
  std::vector<std::size_t> owner_point{0, 0};
  constexpr double kLandingLength = 1.0;  // m of level ground after stairs that something follows
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const Piece& piece = pieces[i];
    try {
      validate(piece);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(piece_name(i, piece) + e.what());
    }
    const bool last = i + 1 == pieces.size();
    const Point at = points.back();
    switch (piece.kind) {
      case Piece::Kind::Flat:
        if (!last) points.push_back({at.x + piece.length, at.y});
        break;
      case Piece::Kind::Ramp: {
        const double grade = std::tan(piece.degrees * (3.14159265358979323846 / 180.0));
        if (!last) {
          points.push_back({at.x + piece.length, at.y + grade * piece.length});
        } else if (grade != 0.0) {
          // The last ramp goes on as far as the ground reaches: to x = kMaxCoordinate, or where
          // its height does; the end stays within the ground's extent despite rounding.
          const double end_x =
              std::min(kMaxCoordinate, at.x + (kMaxCoordinate - std::abs(at.y)) / std::abs(grade));
          const double end_y =
              std::clamp(at.y + grade * (end_x - at.x), -kMaxCoordinate, kMaxCoordinate);
          if (end_x > at.x) points.push_back({end_x, end_y});
        }
        break;
      }
      case Piece::Kind::Stairs: {
        // The first riser rises from where the piece begins (the last point already).
        Point p = at;
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
        const Point first = piece.points.front();
        for (std::size_t k = 1; k < piece.points.size(); ++k) {
          points.push_back(
              {at.x + (piece.points[k].x - first.x), at.y + (piece.points[k].y - first.y)});
          owner.push_back(i);
          owner_point.push_back(k);
        }
        break;
      }
    }
    owner.resize(points.size(), i);
    owner_point.resize(points.size(), 0);
  }
  if (points.back().x < kMaxCoordinate) {
    points.push_back({kMaxCoordinate, points.back().y});
    owner.push_back(pieces.size());
    owner_point.push_back(0);
  }
  if (const std::optional<Fault> fault = find_fault(points)) {
    const std::size_t piece = owner[fault->point];
    if (piece == pieces.size()) {
      throw std::invalid_argument(
          fault_text("terrain: point " + std::to_string(fault->point), *fault));
    }
    const std::string where = piece_name(piece, pieces[piece]);
    const bool profile = pieces[piece].kind == Piece::Kind::Profile;
    throw std::invalid_argument(
        profile ? fault_text(where + "point " + std::to_string(owner_point[fault->point]), *fault)
                : where + (fault->about_point ? "a point " : "") + fault->reason);
  }
  return Terrain(std::move(points));
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

std::span<const Point> Terrain::search_corners(double x0, double x1) const {
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

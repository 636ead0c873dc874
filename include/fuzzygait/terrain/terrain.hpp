// Ground profiles in the sagittal plane: a height for every x, as a polyline. Flat ground, ramps
// and stairs are all polylines; the walker asks for height, slope and where a foot may stand.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fuzzygait/rig/rig.hpp"

namespace fuzzygait::terrain {

using rig::Point;

class Terrain {
 public:
  // The farthest a ground point may lie from the origin in x or y, metres: the extent of flat()
  // ground. Beyond it a coordinate is a wrong unit or a broken file, and heights of 1e300 make
  // every contact figure nonsense.
  static constexpr double kMaxCoordinate = 1e6;
  // A riser of a stair is a segment this wide (m): x must increase along a profile.
  static constexpr double kRiserWidth = 0.001;
  // Segments steeper than this (radians, 60 deg) are risers or walls: a foot stands on none.
  static constexpr double kSteepestFoothold = 1.0471975511965976;
  // The tallest wall a profile may hold (m): a riser or a run of risers taller than this is more
  // than a leg climbs in a step.
  static constexpr double kTallestWall = 0.30;

  // Level ground at height 0.
  static Terrain flat();
  // Ground through the given points, sorted by x; constant beyond the ends. Throws
  // std::invalid_argument when points are fewer than two, not finite, beyond kMaxCoordinate, when
  // x does not increase (a vertical riser is two points kRiserWidth apart), or for a wall taller
  // than kTallestWall, naming the point.
  static Terrain polyline(std::vector<Point> points);

  // Why polyline() would refuse `points`, or nothing when it takes them: the first point at
  // fault and the reason, which reads after the point's name ("terrain point 3 is not finite",
  // "... point 3: x must increase along the profile"). Lets a reader name the file's line.
  struct Fault {
    std::size_t point = 0;
    std::string
        reason;  // "is not finite", "lies more than ...", "x must increase ...", "a wall ..."
    bool about_point = false;  // the reason continues the point's name ("is ..."), no colon
  };
  static std::optional<Fault> find_fault(std::span<const Point> points);

  // One piece of a sequence of ground, beginning where the piece before it ends.
  struct Piece {
    enum class Kind { Flat, Ramp, Stairs, Profile };
    Kind kind = Kind::Flat;
    double length = 2.0;        // Flat and Ramp: metres along x (the last piece goes on for ever)
    double degrees = 0.0;       // Ramp: -25 to 25, uphill +
    double rise = 0.17;         // Stairs: 0.05 to 0.25 m a step, or -0.25 to -0.05 going down
    double tread = 0.28;        // Stairs: 0.20 to 0.40 m
    int count = 10;             // Stairs: 1 to 200 steps; a level landing follows
    std::vector<Point> points;  // Profile: a polyline, moved so its first point is the start
  };
  static Piece flat_piece(double length = 2.0);
  static Piece ramp_piece(double degrees, double length = 4.0);
  static Piece stairs_piece(double rise, double tread, int count);
  static Piece profile_piece(std::vector<Point> points);
  // Throws std::invalid_argument naming the field of `piece` out of its range ("rise must be
  // between 0.05 and 0.25 m ..., got 0.3"), or a profile's point at fault ("point 2: x must
  // increase along the profile"), without naming the piece.
  static void validate(const Piece& piece);

  // Level ground at height 0 up to x = start, then the pieces one after another, then level
  // ground at the height the last piece ends (a slope that comes last goes on as far as the ground
  // reaches). Throws std::invalid_argument naming the piece and field out of its range.
  static Terrain sequence(std::span<const Piece> pieces, double start = 1.0);
  // Level ground, then from x = start a ramp of `degrees` (-25 to 25, uphill +) for ever.
  static Terrain ramp(double degrees, double start = 1.0);
  // Level ground, then from x = start `count` steps of `rise` and `tread` metres (a negative rise
  // goes down), then a level landing for ever.
  static Terrain stairs(double rise, double tread, int count, double start = 1.0);

  double height(double x) const {
    // Inline: the walker asks several times a time step, mostly of level ground, which answers
    // at once (the same bits as the search below).
    if (level_ && !std::isnan(x)) return points_.front().y;
    if (x <= points_.front().x) return points_.front().y;
    if (x >= points_.back().x) return points_.back().y;
    const std::size_t i = segment(x);
    const Point& a = points_[i];
    const Point& b = points_[i + 1];
    if (a.y == b.y && !std::isnan(x)) return a.y;  // level: the same value, no division
    return a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x);
  }
  // Slope angle (radians, uphill forward +) of the segment under x. Inline, as height().
  double slope(double x) const {
    if (level_) return 0.0;  // every segment's slope is +0 too
    if (x < points_.front().x || x > points_.back().x) return 0.0;
    return slopes_[segment(x)];
  }
  // The profile between x0 and x1 as points, for drawing and files.
  std::vector<Point> profile(double x0, double x1) const;
  const std::vector<Point>& points() const { return points_; }
  // Whether every point's height is the same, to the bit.
  bool level() const { return level_; }

  // Where a foot may stand: the stretches of ground between risers (segments steeper than
  // kSteepestFoothold), in order along x. A tread of a stair is one; a ramp and the level ground
  // around it are one.
  struct Run {
    double begin;  // x where it starts (a riser's top or foot ends there)
    double end;    // x where it ends
    double pitch;  // a tread's pitch (radians); NaN for a longer run
  };
  const std::vector<Run>& runs() const { return runs_; }
  // Index of the run holding x; x on a riser belongs to the run behind it. (Inline: most ground
  // is one run, which answers at once.)
  std::size_t run_at(double x) const { return runs_.size() == 1 ? 0 : search_run(x); }
  // The x nearest x on run r (x itself when the run holds it).
  double point_on_run(double x, std::size_t r) const {
    return std::clamp(x, runs_[r].begin, runs_[r].end);
  }
  // The pitch of the ground a foot stands on at x (radians, uphill forward +): on a tread (a run
  // shorter than kLongestTread between risers) the rise of its risers over its length, as a
  // stair's pitch line; elsewhere the slope.
  double pitch(double x) const;
  // Whether x lies on a tread (a run shorter than kLongestTread between risers).
  bool on_tread(double x) const { return !level_ && !std::isnan(runs_[run_at(x)].pitch); }
  static constexpr double kLongestTread = 0.6;  // m

  // The x whose ground point lies `distance` metres (straight line) ahead of the ground point at
  // from_x: from_x + distance on level ground, less on a ramp.
  double ahead_along_ground(double from_x, double distance) const;

  // Where a foot lands, stepping from a foot at from_x (its run is the one the foot stands on)
  // whose heel aims at wanted_x: the foot, heel to toe tip (foot_length metres along x), stands
  // wholly on one run, `margin` clear of its ends, and at most one riser above or below from_x's
  // run (one stair a step). Where the wanted place is not such, the step is shortened to stop
  // before the edge if it stays at least `shortest` metres ahead of from_x, else lengthened onto
  // the next run. On a tread shorter than the foot, the toes stand `margin` clear of the riser
  // ahead (going up) or the heel `margin` from the riser behind (going down).
  struct Foothold {
    double heel_x;
    std::size_t run;  // the run (tread) it aims at
  };
  Foothold foothold(double from_x, double wanted_x, double foot_length, double margin,
                    double shortest = 0.0) const;

  // The ground's corners (points) strictly between x0 and x1. (Inline: one straight segment
  // has none between its ends, which answers at once.)
  std::span<const Point> corners_between(double x0, double x1) const {
    if (points_.size() == 2 && x0 >= points_[0].x && !(x1 > points_[1].x)) return {};
    return search_corners(x0, x1);
  }

 private:
  explicit Terrain(std::vector<Point> points);
  // Index of the segment under x; inline for one-segment ground (a single slope).
  std::size_t segment(double x) const { return points_.size() == 2 ? 0 : search_segment(x); }
  std::size_t search_segment(double x) const;
  std::size_t search_run(double x) const;
  std::span<const Point> search_corners(double x0, double x1) const;
  std::vector<Point> points_;
  std::vector<double> slopes_;  // of each segment, radians
  std::vector<Run> runs_;
  bool level_ = false;  // every point's y the same, to the bit
};

}  // namespace fuzzygait::terrain

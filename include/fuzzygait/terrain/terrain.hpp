// Ground profiles in the sagittal plane: a height for every x, as a polyline.
// Flat ground, slopes and stairs are all polylines; the walker asks for height and slope.
#pragma once

#include <cmath>
#include <cstddef>
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
  // Level ground at height 0.
  static Terrain flat();
  // Ground through the given points, sorted by x; constant beyond the ends. Throws
  // std::invalid_argument when points are fewer than two, not finite, beyond kMaxCoordinate, or
  // x does not increase (vertical risers are two points with x a millimetre apart).
  static Terrain polyline(std::vector<Point> points);

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

 private:
  explicit Terrain(std::vector<Point> points);
  // Index of the segment under x; inline for one-segment ground (a single slope).
  std::size_t segment(double x) const { return points_.size() == 2 ? 0 : search_segment(x); }
  std::size_t search_segment(double x) const;
  std::vector<Point> points_;
  std::vector<double> slopes_;  // of each segment, radians
  bool level_ = false;          // every point's y the same, to the bit
};

}  // namespace fuzzygait::terrain

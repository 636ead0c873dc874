// A path on the ground for a walker to follow: a curve in the ground plane (world X and Z, Y up,
// as body/humanoid.hpp), parameterised by distance along it. The walker walks the distance; the
// terrain under the path is a terrain::Terrain over the same distance.
//
// A path is a chain of pieces of constant curvature (straight lines and circular arcs), so its
// heading turns smoothly and its length is exact. Headings are radians, 0 along +Z, turning left
// (towards +X) positive; curvature is the heading's change per metre (1 / radius, left +).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace fuzzygait::path {

struct GroundPoint {
  double x = 0.0;
  double z = 0.0;
};

// Where the path is at a distance along it.
struct PathSample {
  GroundPoint point;
  double heading = 0.0;    // radians
  double curvature = 0.0;  // 1/m, left +
};

// One piece: `length` metres at constant `curvature` (0: straight).
struct Piece {
  double length = 0.0;
  double curvature = 0.0;
};

class Path {
 public:
  // The tightest turn a path may hold (m): a walker's legs cross on tighter ones.
  static constexpr double kSmallestRadius = 0.5;
  // The longest path (m), and the farthest a point may lie from the origin.
  static constexpr double kLongest = 1e6;

  // Straight ahead along +Z from the origin (the walk without a path).
  Path();
  // From a start point and heading, the pieces in order. Throws std::invalid_argument naming the
  // piece when a length is not positive and finite, a curvature not finite or tighter than
  // kSmallestRadius, or the whole longer than kLongest.
  Path(GroundPoint start, double heading, std::vector<Piece> pieces);
  // Through the points in order, each corner rounded by a circular arc of `corner_radius`, or the
  // largest that fits (half of a leg between two corners, all of the first and the last leg).
  // Throws std::invalid_argument naming the point when there are fewer than two points, a
  // coordinate is not finite or beyond kLongest, two points coincide (within 1 mm), or a corner is
  // so sharp that its arc would be tighter than kSmallestRadius.
  static Path polyline(std::span<const GroundPoint> points, double corner_radius = 1.0);

  double length() const { return length_; }
  std::span<const Piece> pieces() const { return pieces_; }
  // The curve at `distance` from the start; before the start and past the end it goes straight
  // on along the end's heading (infinities as 4 x kLongest). NaN gives the start.
  PathSample at(double distance) const;

 private:
  struct Start {
    GroundPoint point;
    double heading = 0.0;
    double distance = 0.0;  // along the path to the piece's start
  };
  std::vector<Piece> pieces_;
  std::vector<Start> starts_;  // one per piece, and one for the end
  double length_ = 0.0;
};

}  // namespace fuzzygait::path

#include "fuzzygait/path/path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace fuzzygait::path {
namespace {

constexpr double kPi = std::numbers::pi;

std::string error_of(auto&& make) {
  try {
    make();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(Path, StraightByDefault) {
  const Path path;
  EXPECT_EQ(path.length(), 0.0);
  const PathSample s = path.at(3.5);
  EXPECT_DOUBLE_EQ(s.point.z, 3.5);
  EXPECT_DOUBLE_EQ(s.point.x, 0.0);
  EXPECT_DOUBLE_EQ(s.heading, 0.0);
  EXPECT_DOUBLE_EQ(path.at(-1.0).point.z, -1.0);
  EXPECT_DOUBLE_EQ(path.at(NAN).point.z, 0.0);
  const Path turn({0.0, 0.0}, 0.0, {{1.0, 0.5}});
  for (const double far : {INFINITY, -INFINITY}) {
    const PathSample beyond = turn.at(far);
    EXPECT_TRUE(std::isfinite(beyond.point.x) && std::isfinite(beyond.point.z)) << far;
  }
}

TEST(Path, ArcsAreExact) {
  // A quarter circle of 2 m to the left from the origin facing +Z ends at (2, 2) facing +X.
  const Path path({0.0, 0.0}, 0.0, {{kPi, 0.5}});
  EXPECT_NEAR(path.length(), kPi, 1e-15);
  const PathSample end = path.at(kPi);
  EXPECT_NEAR(end.point.x, 2.0, 1e-12);
  EXPECT_NEAR(end.point.z, 2.0, 1e-12);
  EXPECT_NEAR(end.heading, kPi / 2, 1e-12);
  // Every point lies on the circle about (2, 0), at the heading's tangent.
  for (double d = 0.0; d <= kPi; d += 0.01) {
    const PathSample s = path.at(d);
    EXPECT_NEAR(std::hypot(s.point.x - 2.0, s.point.z), 2.0, 1e-12);
    EXPECT_NEAR(s.heading, d / 2.0, 1e-12);
    EXPECT_DOUBLE_EQ(s.curvature, 0.5);
  }
  // Past the end straight on along +X.
  const PathSample past = path.at(kPi + 1.0);
  EXPECT_NEAR(past.point.x, 3.0, 1e-12);
  EXPECT_NEAR(past.point.z, 2.0, 1e-12);
  EXPECT_EQ(past.curvature, 0.0);
}

TEST(Path, HeadingAndPositionAreContinuousAcrossPieces) {
  const Path path({1.0, -2.0}, 0.3, {{1.5, 0.0}, {2.0, -0.8}, {0.7, 1.9}, {3.0, 0.0}});
  double last_heading = path.at(0.0).heading;
  PathSample last = path.at(0.0);
  for (double d = 0.001; d < path.length() + 1.0; d += 0.001) {
    const PathSample s = path.at(d);
    EXPECT_NEAR(std::hypot(s.point.x - last.point.x, s.point.z - last.point.z), 0.001, 1e-9) << d;
    EXPECT_LT(std::abs(std::remainder(s.heading - last_heading, 2 * kPi)), 0.0021) << d;
    last_heading = s.heading;
    last = s;
  }
}

TEST(Path, PolylineCornersAreRounded) {
  const std::vector<GroundPoint> square = {{0, 0}, {0, 4}, {4, 4}};  // a left turn at (0, 4)
  const Path path = Path::polyline(square, 1.0);
  ASSERT_EQ(path.pieces().size(), 3u);
  EXPECT_NEAR(path.pieces()[1].curvature, 1.0, 1e-12);
  EXPECT_NEAR(path.length(), 8.0 - 2.0 + kPi / 2, 1e-12);
  const PathSample end = path.at(path.length());
  EXPECT_NEAR(end.point.x, 4.0, 1e-12);
  EXPECT_NEAR(end.point.z, 4.0, 1e-12);
  EXPECT_NEAR(end.heading, kPi / 2, 1e-12);  // atan2(dx, dz): facing +X
  // Short legs take a smaller radius, which must still be walkable.
  const Path tight = Path::polyline(std::vector<GroundPoint>{{0, 0}, {0, 0.8}, {0.8, 0.8}}, 2.0);
  EXPECT_NEAR(std::abs(tight.pieces()[0].curvature), 1.0 / 0.8, 1e-9);
}

TEST(Path, RefusesWhatCannotBeWalked) {
  EXPECT_NE(error_of([] {
              Path::polyline(std::vector<GroundPoint>{{0, 0}});
            }).find("at least two points"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              Path::polyline(std::vector<GroundPoint>{{0, 0}, {0, 1}, {0, 1}});
            }).find("path point 3"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              Path::polyline(std::vector<GroundPoint>{{0, 0}, {NAN, 1}});
            }).find("path point 2"),
            std::string::npos);
  // A hairpin turns back on itself; a sharp corner between short legs is too tight.
  EXPECT_NE(error_of([] {
              Path::polyline(std::vector<GroundPoint>{{0, 0}, {0, 5}, {0.1, 0}});
            }).find("turns back"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              Path::polyline(std::vector<GroundPoint>{{0, 0}, {0, 0.3}, {0.3, 0.3}});
            }).find("too sharp"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              Path({0, 0}, 0.0, {{1.0, 0.0}, {-1.0, 0.0}});
            }).find("piece 2"),
            std::string::npos);
  EXPECT_NE(error_of([] { Path({0, 0}, 0.0, {{1.0, 3.0}}); }).find("curvature"), std::string::npos);
  EXPECT_NE(error_of([] { Path({0, 0}, NAN, {}); }).find("heading"), std::string::npos);
}

}  // namespace
}  // namespace fuzzygait::path

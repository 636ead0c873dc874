#include "fuzzygait/terrain/terrain.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace fuzzygait::terrain {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

std::uint64_t bits(double x) {
  return std::bit_cast<std::uint64_t>(x);
}

// The walker's kerb: level, a slope up, level, a step down, level.
Terrain kerb() {
  return Terrain::polyline({{-10.0, 0.0}, {2.0, 0.0}, {4.0, 0.5}, {5.0, 0.5}, {5.001, 0.3}});
}

TEST(Terrain, HeightsInterpolateBetweenPointsAndStayLevelBeyondTheEnds) {
  const Terrain t = kerb();
  EXPECT_DOUBLE_EQ(t.height(-20.0), 0.0);
  EXPECT_DOUBLE_EQ(t.height(0.0), 0.0);
  EXPECT_DOUBLE_EQ(t.height(3.0), 0.25);
  EXPECT_DOUBLE_EQ(t.height(3.5), 0.375);
  EXPECT_DOUBLE_EQ(t.height(4.5), 0.5);
  EXPECT_NEAR(t.height(5.0005), 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(t.height(9.0), 0.3);
  // At a point itself, its own height.
  EXPECT_DOUBLE_EQ(t.height(2.0), 0.0);
  EXPECT_DOUBLE_EQ(t.height(4.0), 0.5);
}

TEST(Terrain, SlopesAreEachSegmentsAngleAndLevelBeyondTheEnds) {
  const Terrain t = kerb();
  EXPECT_DOUBLE_EQ(t.slope(-20.0), 0.0);
  EXPECT_DOUBLE_EQ(t.slope(0.0), 0.0);
  EXPECT_DOUBLE_EQ(t.slope(3.0), std::atan2(0.5, 2.0));
  EXPECT_DOUBLE_EQ(t.slope(4.5), 0.0);
  EXPECT_NEAR(t.slope(5.0005), std::atan2(-0.2, 0.001), 1e-12);
  EXPECT_DOUBLE_EQ(t.slope(9.0), 0.0);
}

// Level ground answers without searching its segments (the walker asks several times a time
// step): the same bits as a search would give, a NaN x still NaN.
TEST(Terrain, LevelGroundGivesTheSearchsBits) {
  const double y = 0.1;
  const Terrain level = Terrain::polyline({{-5.0, y}, {-1.0, y}, {0.5, y}, {7.0, y}});
  // The same ground with one far point a hair higher answers by searching its segments.
  const Terrain searched = Terrain::polyline(
      {{-5.0, y}, {-1.0, y}, {0.5, y}, {7.0, y}, {1000.0, std::nextafter(y, 1.0)}});
  for (double x : {-100.0, -5.0, -4.999, -1.0, 0.0, 0.25, 0.5, 6.999, 7.0, 9.0}) {
    EXPECT_EQ(bits(level.height(x)), bits(y)) << x;
    EXPECT_EQ(bits(searched.height(x)), bits(y)) << x;
    EXPECT_EQ(bits(level.slope(x)), bits(0.0)) << x;  // +0, not -0
    // (Past x = 7 the searched ground rises by its hair.)
    if (x < 7.0) {
      EXPECT_EQ(bits(level.slope(x)), bits(searched.slope(x))) << x;
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(std::isnan(level.height(nan)));
  EXPECT_EQ(bits(level.slope(nan)), bits(0.0));
  EXPECT_EQ(bits(level.height(inf)), bits(y));
  EXPECT_EQ(bits(level.height(-inf)), bits(y));
  EXPECT_EQ(bits(level.slope(-inf)), bits(0.0));
  // Ends at the same height with a bump between them is not level.
  const Terrain bump = Terrain::polyline({{-1.0, 0.0}, {0.0, 0.2}, {1.0, 0.0}});
  EXPECT_DOUBLE_EQ(bump.height(0.0), 0.2);
  EXPECT_DOUBLE_EQ(bump.height(0.5), 0.1);
  EXPECT_DOUBLE_EQ(bump.slope(0.5), std::atan2(-0.2, 1.0));
  EXPECT_TRUE(std::isnan(Terrain::flat().height(nan)));
  EXPECT_EQ(bits(Terrain::flat().height(123.0)), bits(0.0));
  // Zeros of both signs are not the same bits: such ground is searched, each segment giving its
  // own zero.
  const Terrain signed_zeros = Terrain::polyline({{-1.0, -0.0}, {0.0, 0.0}, {1.0, -0.0}});
  EXPECT_EQ(bits(signed_zeros.height(-0.5)), bits(-0.0));
  EXPECT_EQ(bits(signed_zeros.height(0.5)), bits(0.0));
}

TEST(Terrain, ManySegmentsAreFound) {
  // Stairs of 200 steps, 0.3 m deep and 0.17 m high, risers 1 mm wide.
  std::vector<Point> points{{-1.0, 0.0}};
  for (int i = 0; i < 200; ++i) {
    points.push_back({0.3 * i, 0.17 * i});
    points.push_back({0.3 * i + 0.001, 0.17 * (i + 1)});
  }
  const Terrain stairs = Terrain::polyline(points);
  for (int i = 0; i < 199; ++i) {
    EXPECT_NEAR(stairs.height(0.3 * i + 0.15), 0.17 * (i + 1), 1e-12) << i;
    EXPECT_NEAR(stairs.slope(0.3 * i + 0.15), 0.0, 1e-12) << i;
    EXPECT_GT(stairs.slope(0.3 * i + 0.0005), 1.5) << i;  // a riser, nearly vertical
  }
}

TEST(Terrain, ProfileKeepsTheCornersBetweenItsEnds) {
  const std::vector<Point> p = kerb().profile(1.0, 4.5);
  ASSERT_EQ(p.size(), 4u);
  EXPECT_DOUBLE_EQ(p[0].x, 1.0);
  EXPECT_DOUBLE_EQ(p[1].x, 2.0);
  EXPECT_DOUBLE_EQ(p[2].y, 0.5);
  EXPECT_DOUBLE_EQ(p[3].x, 4.5);
}

TEST(Terrain, BadPolylinesGetClearErrors) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(
      [] {
        Terrain::polyline({{0.0, 0.0}});
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("at least two points")));
  EXPECT_THAT(
      [&] {
        Terrain::polyline({{0.0, 0.0}, {1.0, nan}});
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("terrain point 1 is not finite")));
  EXPECT_THAT(
      [] {
        Terrain::polyline({{0.0, 0.0}, {2e6, 0.0}});
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("1000 km")));
  EXPECT_THAT(
      [] {
        Terrain::polyline({{0.0, 0.0}, {1.0, 0.0}, {1.0, 0.2}});
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("terrain point 2: x must increase")));
}

}  // namespace
}  // namespace fuzzygait::terrain

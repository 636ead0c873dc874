// A walk that stops going forward: found where it stops, named by time, position and the run of
// the ground its front foot is on.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "fuzzygait/eval/stall.hpp"

namespace fuzzygait::eval {
namespace {

using ::testing::HasSubstr;

// A walk of `seconds` at 100 frames a second whose pelvis is at pelvis_x(t), both toe tips
// 0.1 m ahead of it.
Motion walk(double seconds, const std::function<double(double)>& pelvis_x) {
  Motion m;
  m.fps = 100.0;
  for (int i = 0; i <= static_cast<int>(std::lround(seconds * m.fps)); ++i) {
    Frame f;
    f.time = i / m.fps;
    f.pose.pelvis = {pelvis_x(f.time), 0.9};
    for (rig::LegPoints& p : f.points)
      p.tip = {f.pose.pelvis.x + 0.1, 0.0};
    m.frames.push_back(f);
  }
  return m;
}

TEST(Stall, AWalkThatKeepsGoingHasNone) {
  const terrain::Terrain stairs = terrain::Terrain::stairs(-0.17, 0.28, 6);
  EXPECT_FALSE(find_stall(walk(20.0, [](double t) { return 0.2 * t; }), stairs));
  // Standing still half a second after each landing, 0.2 m/s between: still walking.
  EXPECT_FALSE(find_stall(walk(20.0,
                               [](double t) {
                                 return 0.2 * std::floor(t) +
                                        0.4 * std::max(0.0, t - std::floor(t) - 0.5);
                               }),
                          stairs));
  // Shorter than the window: nothing to tell.
  EXPECT_FALSE(find_stall(walk(2.9, [](double) { return 0.0; }), stairs));
}

TEST(Stall, AFrozenWalkIsFoundWhereItStopsAndNamed) {
  const terrain::Terrain stairs = terrain::Terrain::stairs(-0.17, 0.28, 6);
  // 1 m/s to x = 0.8 m, then frozen: from 0.7 s on the pelvis goes under 0.1 m in 3 s.
  const std::optional<Stall> stall =
      find_stall(walk(10.0, [](double t) { return std::min(t, 0.8); }), stairs);
  ASSERT_TRUE(stall.has_value());
  EXPECT_NEAR(stall->time, 0.705, 0.006);
  EXPECT_NEAR(stall->pelvis_x, stall->time, 1e-9);
  EXPECT_LT(stall->progress, kStallDistance);
  EXPECT_NEAR(stall->front_x, stall->pelvis_x + 0.1, 1e-9);
  EXPECT_EQ(stall->run, 0u);
  EXPECT_EQ(stall->runs, 7u);
  const std::string text = describe(*stall, stairs);
  EXPECT_THAT(text, HasSubstr("the walk stalled at 0.71 s with the pelvis at x = 0.71 m"));
  EXPECT_THAT(text, HasSubstr("the front foot on run 0 of 0-6 (before the 0.170 m drop at x = "
                              "1.00 m)"));
  EXPECT_THAT(text, HasSubstr("in the next 3.0 s (a walk goes at least 0.10 m)"));

  // Stepping back and forth on tread 2 is no walk either.
  const std::optional<Stall> rocking = find_stall(
      walk(12.0, [](double t) { return std::min(t, 1.45) + 0.03 * std::sin(6.0 * t); }), stairs);
  ASSERT_TRUE(rocking.has_value());
  EXPECT_EQ(rocking->run, 2u);
  EXPECT_THAT(describe(*rocking, stairs), HasSubstr("on run 2 of 0-6"));
}

TEST(Stall, OnGroundOfOneRunTheFrontFootIsNamedByItsX) {
  const std::optional<Stall> stall =
      find_stall(walk(6.0, [](double) { return 0.3; }), terrain::Terrain::flat());
  ASSERT_TRUE(stall.has_value());
  EXPECT_DOUBLE_EQ(stall->time, 0.0);
  EXPECT_THAT(describe(*stall, terrain::Terrain::flat()),
              HasSubstr("the front foot at x = 0.40 m"));
}

}  // namespace
}  // namespace fuzzygait::eval

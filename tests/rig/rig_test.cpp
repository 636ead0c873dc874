// The sagittal rig: proportions, forward kinematics, clinical sign conventions, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "fuzzygait/rig/rig.hpp"

using namespace fuzzygait::rig;

namespace {

TEST(Rig, SegmentsFromStatureFollowWinter) {
  const Segments s = segments_from_stature(1.75);
  EXPECT_NEAR(s.thigh + s.shank + s.ankle_height, 0.530 * 1.75, 1e-12);  // hip height
  EXPECT_NEAR(s.shank + s.ankle_height, 0.285 * 1.75, 1e-12);            // knee height
  EXPECT_NEAR(s.ankle_height, 0.039 * 1.75, 1e-12);
  EXPECT_NEAR(s.foot_length(), 0.152 * 1.75, 1e-12);
  EXPECT_NEAR(s.leg_length(), 0.530 * 1.75, 1e-12);
}

TEST(Rig, BadSegmentsNameTheField) {
  Segments s = segments_from_stature(1.75);
  s.thigh = 0.0;
  try {
    validate(s);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'thigh'"), std::string::npos);
  }
  s = segments_from_stature(1.75);
  s.shank = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(validate(s), std::invalid_argument);
  EXPECT_THROW(segments_from_stature(0.0), std::invalid_argument);
  EXPECT_THROW(segments_from_stature(std::nan("")), std::invalid_argument);
}

TEST(Rig, StandingStraightPutsTheSoleOnTheGround) {
  const Segments s = segments_from_stature(1.80);
  const LegPoints p = forward_kinematics(s, {0.0, s.leg_length()}, 0.0, LegAngles{});
  EXPECT_NEAR(p.knee.x, 0.0, 1e-12);
  EXPECT_NEAR(p.knee.y, s.shank + s.ankle_height, 1e-12);
  EXPECT_NEAR(p.ankle.y, s.ankle_height, 1e-12);
  EXPECT_NEAR(p.heel.y, 0.0, 1e-12);
  EXPECT_NEAR(p.ball.y, 0.0, 1e-12);
  EXPECT_NEAR(p.tip.y, 0.0, 1e-12);
  EXPECT_NEAR(p.heel.x, -s.heel, 1e-12);
  EXPECT_NEAR(p.ball.x, s.ball, 1e-12);
  EXPECT_NEAR(p.tip.x, s.ball + s.toe, 1e-12);
}

TEST(Rig, ClinicalSignConventions) {
  const Segments s = segments_from_stature(1.75);
  const Point hip{0.0, 1.0};
  // Hip flexion moves the knee forward.
  EXPECT_GT(forward_kinematics(s, hip, 0.0, {radians(30), 0, 0, 0}).knee.x, 0.0);
  // Knee flexion moves the ankle backward.
  EXPECT_LT(forward_kinematics(s, hip, 0.0, {0, radians(30), 0, 0}).ankle.x, 0.0);
  // Dorsiflexion lifts the ball of the foot.
  EXPECT_GT(forward_kinematics(s, hip, 0.0, {0, 0, radians(15), 0}).ball.y,
            forward_kinematics(s, hip, 0.0, {}).ball.y);
  // MTP extension lifts the toe tip.
  EXPECT_GT(forward_kinematics(s, hip, 0.0, {0, 0, 0, radians(30)}).tip.y,
            forward_kinematics(s, hip, 0.0, {}).tip.y);
  // Anterior pelvic tilt with the same hip flexion brings the thigh back: thigh = hip - tilt.
  const LegOrientation o = orientation(radians(10), {radians(30), radians(20), radians(5), 0});
  EXPECT_NEAR(o.thigh, radians(20), 1e-12);
  EXPECT_NEAR(o.shank, radians(0), 1e-12);
  EXPECT_NEAR(o.foot, radians(5), 1e-12);
}

TEST(Rig, SegmentLengthsArePreservedInAnyPose) {
  const Segments s = segments_from_stature(1.62);
  for (int i = 0; i < 50; ++i) {
    const LegAngles a{radians(-30 + 3.0 * i), radians(2.5 * i), radians(-40 + 1.3 * i),
                      radians(-20 + 2.0 * i)};
    const LegPoints p = forward_kinematics(s, {0.3, 0.9}, radians(11), a);
    EXPECT_NEAR(std::hypot(p.knee.x - p.hip.x, p.knee.y - p.hip.y), s.thigh, 1e-12);
    EXPECT_NEAR(std::hypot(p.ankle.x - p.knee.x, p.ankle.y - p.knee.y), s.shank, 1e-12);
    EXPECT_NEAR(std::hypot(p.ball.x - p.heel.x, p.ball.y - p.heel.y), s.heel + s.ball, 1e-12);
    EXPECT_NEAR(std::hypot(p.tip.x - p.ball.x, p.tip.y - p.ball.y), s.toe, 1e-12);
  }
}

TEST(Rig, JointLimits) {
  const JointLimits limits;
  EXPECT_TRUE(limits.contains({0, 0, 0, 0}));
  EXPECT_FALSE(limits.contains({0, -0.1, 0, 0}));  // no knee hyperextension
  const LegAngles c = limits.clamp({10.0, -1.0, 0.0, 0.0});
  EXPECT_EQ(c.hip, limits.maximum.hip);
  EXPECT_EQ(c.knee, 0.0);
}

}  // namespace

#include "fuzzygait/body/humanoid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

namespace fuzzygait::body {
namespace {

constexpr double kPi = std::numbers::pi;

void expect_near(Vec3 a, Vec3 b, double tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(BodyMath, FromAxesRebuildsEveryRotation) {
  // Rotations about each axis by angles that take every branch of Shepperd's method.
  const Vec3 axes[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, normalized(Vec3{1, -2, 0.5})};
  for (const Vec3 axis : axes) {
    for (const double angle : {0.0, 0.3, 1.5, 2.9, kPi, -2.2}) {
      const Quat q = axis_angle(axis, angle);
      const Quat r = from_axes(rotate(q, {1, 0, 0}), rotate(q, {0, 1, 0}), rotate(q, {0, 0, 1}));
      const Vec3 v{0.3, -0.7, 1.1};
      expect_near(rotate(r, v), rotate(q, v), 1e-12);
    }
  }
}

TEST(BodyMath, QuaternionProductAppliesRightFirst) {
  const Quat yaw = axis_angle({0, 1, 0}, kPi / 2);    // +Z to +X
  const Quat pitch = axis_angle({1, 0, 0}, kPi / 2);  // +Y to +Z
  expect_near(rotate(yaw * pitch, {0, 1, 0}), {1, 0, 0}, 1e-12);
  expect_near(rotate(conjugate(yaw) * yaw, {0.2, 0.4, 0.9}), {0.2, 0.4, 0.9}, 1e-12);
}

TEST(Humanoid, NamesAreVrmsAndRoundTrip) {
  std::set<std::string> seen;
  for (int i = 0; i < static_cast<int>(kJointCount); ++i) {
    const auto joint = static_cast<Joint>(i);
    EXPECT_EQ(joint_named(name(joint)), joint);
    EXPECT_TRUE(seen.insert(std::string(name(joint))).second);
    if (const auto p = parent(joint)) {
      EXPECT_LT(index(*p), i);
    }
  }
  EXPECT_EQ(name(Joint::left_upper_leg), "leftUpperLeg");
  EXPECT_EQ(name(Joint::right_lower_arm), "rightLowerArm");
  EXPECT_FALSE(parent(Joint::hips).has_value());
  EXPECT_FALSE(joint_named("LeftUpLeg").has_value());
}

TEST(Humanoid, FromStatureMatchesTheRigAndWinter) {
  const double H = 1.75;
  const Humanoid h = humanoid_from_stature(H);
  EXPECT_NO_THROW(validate(h));
  const rig::Segments s = rig::segments_from_stature(H);
  const rig::Segments t = h.segments();
  EXPECT_DOUBLE_EQ(t.thigh, s.thigh);
  EXPECT_DOUBLE_EQ(t.shank, s.shank);
  EXPECT_DOUBLE_EQ(t.ankle_height, s.ankle_height);
  EXPECT_DOUBLE_EQ(t.heel, s.heel);
  EXPECT_DOUBLE_EQ(t.ball, s.ball);
  EXPECT_DOUBLE_EQ(t.toe, s.toe);
  EXPECT_NEAR(h.hip_width(), 0.19 * s.leg_length(), 1e-12);

  BodyPose pose;
  forward_kinematics(h, h[Joint::hips], pose);  // standing on y = 0 in the reference pose
  EXPECT_NEAR(pose[Joint::head_end].y, H, 1e-12);
  EXPECT_NEAR(pose[Joint::left_upper_arm].y, 0.818 * H, 1e-12);
  EXPECT_NEAR(pose[Joint::left_upper_arm].x - pose[Joint::right_upper_arm].x, 0.259 * H, 1e-12);
  EXPECT_NEAR(pose[Joint::left_toes].y, 0.0, 1e-12);
  EXPECT_NEAR(pose.heel[0].y, 0.0, 1e-12);
  EXPECT_NEAR(pose.heel[0].z, -s.heel, 1e-12);
  EXPECT_GT(pose[Joint::left_hand_end].y, 0.3 * H);  // fingertips hang above mid thigh
  EXPECT_LT(pose[Joint::left_hand_end].y, 0.45 * H);
  EXPECT_THROW(humanoid_from_stature(std::nan("")), std::invalid_argument);
}

TEST(Humanoid, WithLegsTakesTheWalkersLegsUnderTheStaturesTrunk) {
  // A stature's own legs give that stature's humanoid, bit for bit.
  const Humanoid same = humanoid_with_legs(rig::segments_from_stature(1.8), 1.8);
  const Humanoid expected = humanoid_from_stature(1.8);
  for (std::size_t j = 0; j < kJointCount; ++j) {
    EXPECT_EQ(same.offset[j].x, expected.offset[j].x) << j;
    EXPECT_EQ(same.offset[j].y, expected.offset[j].y) << j;
    EXPECT_EQ(same.offset[j].z, expected.offset[j].z) << j;
  }
  // Long thighs (a trained set's body): the legs are the walker's, the arms a 1.75 m body's.
  rig::Segments legs = rig::segments_from_stature(1.75);
  legs.thigh += 0.08;
  const Humanoid tall = humanoid_with_legs(legs, 1.75);
  EXPECT_EQ(tall.segments().thigh, legs.thigh);
  EXPECT_EQ(tall[Joint::hips].y, legs.leg_length());
  EXPECT_EQ(tall[Joint::left_upper_arm].y, humanoid_from_stature(1.75)[Joint::left_upper_arm].y);
  // Without a stature, the one the legs stand for: hips at 0.530 of it.
  const Humanoid own = humanoid_with_legs(legs);
  EXPECT_NEAR(own[Joint::head_end].y, 0.130 * legs.leg_length() / kHipHeightPerStature, 1e-12);
  legs.shank = -1.0;
  EXPECT_THROW(humanoid_with_legs(legs, 1.75), std::invalid_argument);
}

TEST(Humanoid, ForwardKinematicsAgreesWithTheSagittalRig) {
  const Humanoid h = humanoid_from_stature(1.8);
  const rig::LegAngles angles{0.4, 0.7, -0.1, 0.3};
  const double tilt = 0.15;
  BodyPose pose;
  // Clinical angles as rotations about +X (BVH's signs: io/bvh.hpp).
  const Vec3 x{1, 0, 0};
  pose.rotation[index(Joint::hips)] = axis_angle(x, tilt);
  const Quat thigh = pose.rotation[index(Joint::hips)] * axis_angle(x, -angles.hip);
  const Quat shank = thigh * axis_angle(x, angles.knee);
  const Quat foot_q = shank * axis_angle(x, -angles.ankle);
  const Quat toes_q = foot_q * axis_angle(x, -angles.toe);
  pose.rotation[index(Joint::left_upper_leg)] = thigh;
  pose.rotation[index(Joint::left_lower_leg)] = shank;
  pose.rotation[index(Joint::left_foot)] = foot_q;
  pose.rotation[index(Joint::left_toes)] = toes_q;
  forward_kinematics(h, {0, 1, 0}, pose);
  const rig::LegPoints p = rig::forward_kinematics(h.segments(), {0.0, 0.0}, tilt, angles);
  const Vec3 hip = pose[Joint::left_upper_leg];
  auto sagittal = [&](Vec3 v) { return rig::Point{v.z - hip.z, v.y - hip.y}; };
  auto expect_point = [](rig::Point a, rig::Point b) {
    EXPECT_NEAR(a.x, b.x, 1e-12);
    EXPECT_NEAR(a.y, b.y, 1e-12);
  };
  expect_point(sagittal(pose[Joint::left_lower_leg]), p.knee);
  expect_point(sagittal(pose[Joint::left_foot]), p.ankle);
  expect_point(sagittal(pose[Joint::left_toes]), p.ball);
  expect_point(sagittal(pose[Joint::left_toes_end]), p.tip);
  expect_point(sagittal(pose.heel[0]), p.heel);
  const auto local = local_rotations(pose);
  expect_near(rotate(local[index(Joint::left_lower_leg)], {0, 0, 1}),
              rotate(axis_angle(x, angles.knee), {0, 0, 1}), 1e-12);
}

TEST(Humanoid, ValidateNamesTheJoint) {
  Humanoid h = humanoid_from_stature(1.7);
  h[Joint::right_lower_leg].y *= 1.1;
  try {
    validate(h);
    FAIL() << "legs of different lengths passed";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("rightLowerLeg"), std::string::npos) << error.what();
  }
  h = humanoid_from_stature(1.7);
  h[Joint::left_hand].x = std::nan("");
  EXPECT_THROW(validate(h), std::invalid_argument);
}

}  // namespace
}  // namespace fuzzygait::body

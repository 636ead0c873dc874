// The C face of the whole body (fuzzygait/fuzzygait.h): a follower poses the body bit for bit as
// the C++ PathFollower, a skeleton given as arrays is mapped by its names and posed bit for bit as
// the C++ SkeletonPoser, and every refusal comes back as a message naming what was wrong.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "body/skeleton_fixtures.hpp"
#include "fuzzygait/body/follower.hpp"
#include "fuzzygait/fuzzygait.h"

namespace fuzzygait::body {
namespace {

using ::testing::HasSubstr;

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
bool same_bits(fg_vec3 a, Vec3 b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}
bool same_bits(fg_quat a, Quat b) {
  return same_bits(a.w, b.w) && same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

// The S of the README's picture: (0,0) (0,3) (3,3) (3,6), corners rounded at 1 m.
constexpr double kCorners[] = {0.0, 0.0, 0.0, 3.0, 3.0, 3.0, 3.0, 6.0};

// A skeleton's arrays, as a C program holds them.
struct SkeletonArrays {
  std::vector<std::string> names;
  std::vector<const char*> name_pointers;
  std::vector<int> parents;
  std::vector<fg_vec3> offsets;
  std::vector<fg_quat> rotations;

  explicit SkeletonArrays(const Skeleton& skeleton) {
    for (const SkeletonJoint& joint : skeleton.joints) {
      names.push_back(joint.name);
      parents.push_back(joint.parent);
      offsets.push_back({joint.offset.x, joint.offset.y, joint.offset.z});
      rotations.push_back({joint.rotation.w, joint.rotation.x, joint.rotation.y, joint.rotation.z});
    }
    for (const std::string& name : names)
      name_pointers.push_back(name.c_str());
  }
  fg_skeleton_def def(double metres_per_unit) const {
    fg_skeleton_def d = fg_skeleton_def_default();
    d.joint_count = names.size();
    d.names = name_pointers.data();
    d.parents = parents.data();
    d.offsets = offsets.data();
    d.rotations = rotations.data();
    d.metres_per_unit = metres_per_unit;
    return d;
  }
};

TEST(CApiBody, AFollowerOnACurvedPathPosesAsTheCppFollower) {
  fg_error error;
  fg_set* set = fg_set_builtin("default", &error);
  fg_walker_def def = fg_walker_def_default();
  fg_segments_from_stature(1.80, &def);
  def.speed = 1.2;
  fg_walker* walker = fg_walker_new(set, &def, nullptr, &error);
  fg_path* route = fg_path_polyline(kCorners, 4, 1.0, &error);
  ASSERT_NE(route, nullptr) << error.message;
  fg_follower_def options = fg_follower_def_default();
  options.stature = 1.80;  // (0: leg length / 0.530, 1.80 to rounding)
  fg_follower* follower = fg_follower_new(walker, route, nullptr, &options, &error);
  ASSERT_NE(follower, nullptr) << error.message;

  const std::vector<path::GroundPoint> corners = {{0, 0}, {0, 3}, {3, 3}, {3, 6}};
  const path::Path path = path::Path::polyline(corners, 1.0);
  EXPECT_EQ(fg_path_length(route), path.length());
  const Humanoid humanoid = humanoid_from_stature(1.80);
  gait::WalkerOptions o;
  o.segments = humanoid.segments();
  o.speed = 1.2;
  o.event_capacity = 0;
  const terrain::Terrain flat = terrain::Terrain::flat();
  const gait::ControllerSet cpp_set = gait::ControllerSet::builtin("default");
  gait::Walker alone(cpp_set, o, flat);
  PathFollower cpp(humanoid, path, alone);
  for (int frame = 0; frame < 600; ++frame) {
    fg_walker_advance(walker, 1.0 / 60.0);
    alone.advance(1.0 / 60.0);
    const fg_body_pose* pose = fg_follower_update(follower, walker);
    const BodyPose& expected = cpp.update(alone);
    ASSERT_NE(pose, nullptr);
    for (std::size_t j = 0; j < kJointCount; ++j) {
      ASSERT_TRUE(same_bits(pose->position[j], expected.position[j])) << frame << " " << j;
      ASSERT_TRUE(same_bits(pose->rotation[j], expected.rotation[j])) << frame << " " << j;
    }
    ASSERT_TRUE(same_bits(pose->heel[FG_RIGHT], expected.heel[1])) << frame;
    ASSERT_TRUE(same_bits(fg_follower_pelvis_drop(follower), cpp.pelvis_drop())) << frame;
  }
  // 10 s at 1.2 m/s: round both corners.
  fg_path_sample end;
  fg_path_at(route, fg_path_length(route), &end);
  EXPECT_EQ(end.x, 3.0);
  EXPECT_EQ(end.z, 6.0);
  EXPECT_GT(fg_follower_update(follower, walker)->position[FG_HIPS].x, 2.5);

  fg_follower_free(follower);
  fg_path_free(route);
  fg_walker_free(walker);
  fg_set_free(set);
}

TEST(CApiBody, WithoutASkeletonTheBodyStandsOnTheWalkersLegs) {
  fg_error error;
  fg_set* set = fg_set_builtin("default", &error);
  fg_walker_def def = fg_walker_def_default();
  fg_segments_from_stature(1.60, &def);
  fg_walker* walker = fg_walker_new(set, &def, nullptr, &error);
  fg_path* route = fg_path_straight(&error);
  const fg_follower_def options = fg_follower_def_default();  // stature 0: the legs'
  fg_follower* follower = fg_follower_new(walker, route, nullptr, &options, &error);
  ASSERT_NE(follower, nullptr) << error.message;
  for (int frame = 0; frame < 30; ++frame) {
    fg_walker_advance(walker, 1.0 / 60.0);
    const fg_body_pose* body = fg_follower_update(follower, walker);
    fg_pose pose;
    fg_walker_pose(walker, &pose);
    EXPECT_NEAR(body->position[FG_HIPS].y, pose.pelvis_y - fg_follower_pelvis_drop(follower), 1e-9);
    EXPECT_LT(fg_follower_pelvis_drop(follower), 0.003);          // the pelvis's turn: a few mm
    EXPECT_NEAR(body->position[FG_HIPS].z, pose.pelvis_x, 0.01);  // along +Z, but for the sway
  }
  // Winter's 1.60 m body: the top of the head at 1.60 m above the hips' 0.530 x 1.60 m.
  const Humanoid expected = humanoid_from_stature(1.60);
  const fg_body_pose* body = fg_follower_update(follower, walker);
  const double head = body->position[FG_HEAD_END].y - body->position[FG_HIPS].y;
  EXPECT_NEAR(head,
              expected[Joint::spine].y + expected[Joint::chest].y + expected[Joint::neck].y +
                  expected[Joint::head].y + expected[Joint::head_end].y,
              0.01);
  fg_follower_free(follower);
  fg_path_free(route);
  fg_walker_free(walker);
  fg_set_free(set);
}

TEST(CApiBody, JointNamesAndParentsAreTheBodys) {
  for (int j = 0; j < FG_JOINT_COUNT; ++j) {
    EXPECT_EQ(fg_joint_name(j), name(static_cast<Joint>(j)));
    const auto p = parent(static_cast<Joint>(j));
    EXPECT_EQ(fg_joint_parent(j), p ? index(*p) : -1);
  }
  // Each of the header's names stands for the joint it names.
  const std::pair<int, const char*> named[] = {
      {FG_HIPS, "hips"},
      {FG_SPINE, "spine"},
      {FG_CHEST, "chest"},
      {FG_NECK, "neck"},
      {FG_HEAD, "head"},
      {FG_HEAD_END, "headEnd"},
      {FG_LEFT_UPPER_LEG, "leftUpperLeg"},
      {FG_LEFT_LOWER_LEG, "leftLowerLeg"},
      {FG_LEFT_FOOT, "leftFoot"},
      {FG_LEFT_TOES, "leftToes"},
      {FG_LEFT_TOES_END, "leftToesEnd"},
      {FG_RIGHT_UPPER_LEG, "rightUpperLeg"},
      {FG_RIGHT_LOWER_LEG, "rightLowerLeg"},
      {FG_RIGHT_FOOT, "rightFoot"},
      {FG_RIGHT_TOES, "rightToes"},
      {FG_RIGHT_TOES_END, "rightToesEnd"},
      {FG_LEFT_SHOULDER, "leftShoulder"},
      {FG_LEFT_UPPER_ARM, "leftUpperArm"},
      {FG_LEFT_LOWER_ARM, "leftLowerArm"},
      {FG_LEFT_HAND, "leftHand"},
      {FG_LEFT_HAND_END, "leftHandEnd"},
      {FG_RIGHT_SHOULDER, "rightShoulder"},
      {FG_RIGHT_UPPER_ARM, "rightUpperArm"},
      {FG_RIGHT_LOWER_ARM, "rightLowerArm"},
      {FG_RIGHT_HAND, "rightHand"},
      {FG_RIGHT_HAND_END, "rightHandEnd"},
  };
  ASSERT_EQ(std::size(named), static_cast<std::size_t>(FG_JOINT_COUNT));
  for (const auto& [joint, joint_name] : named)
    EXPECT_STREQ(fg_joint_name(joint), joint_name);
  EXPECT_EQ(fg_joint_name(FG_JOINT_COUNT), nullptr);
  EXPECT_EQ(fg_joint_name(-1), nullptr);
  EXPECT_EQ(fg_joint_parent(FG_JOINT_COUNT), -1);
}

TEST(CApiBody, AMixamoSkeletonFromArraysIsMappedByNameAndPosedAsInCpp) {
  const Quat facing_back = axis_angle({0, 1, 0}, 3.141592653589793);
  const Skeleton skeleton = testing::build_skeleton(testing::mixamo_joints(), facing_back, 0.01, 7);
  const SkeletonArrays arrays(skeleton);
  const fg_skeleton_def def = arrays.def(0.01);
  fg_error error;
  fg_skeleton* hero = fg_skeleton_new(&def, &error);
  ASSERT_NE(hero, nullptr) << error.message;
  ASSERT_EQ(fg_skeleton_joint_count(hero), skeleton.size());
  EXPECT_EQ(fg_skeleton_mapped(hero, FG_LEFT_UPPER_LEG), skeleton.find("mixamorig:LeftUpLeg"));
  EXPECT_EQ(fg_skeleton_mapped(hero, FG_RIGHT_HAND), skeleton.find("mixamorig:RightHand"));
  EXPECT_EQ(fg_skeleton_mapped(hero, FG_JOINT_COUNT), -1);

  const SkeletonPoser poser(skeleton, map_humanoid(skeleton));
  fg_walker_def legs = fg_walker_def_default();
  ASSERT_EQ(fg_skeleton_segments(hero, &legs), 1);
  EXPECT_EQ(legs.thigh, poser.humanoid().segments().thigh);
  EXPECT_EQ(legs.heel, poser.humanoid().segments().heel);

  std::vector<fg_quat> local(skeleton.size());
  std::vector<Quat> expected(skeleton.size());
  for (const double phase : {0.0, 1.0, 2.5}) {
    const BodyPose pose = testing::walking_pose(poser.humanoid(), phase, 0.7, 3);
    fg_body_pose c_pose;
    for (std::size_t j = 0; j < kJointCount; ++j) {
      c_pose.position[j] = {pose.position[j].x, pose.position[j].y, pose.position[j].z};
      const Quat q = pose.rotation[j];
      c_pose.rotation[j] = {q.w, q.x, q.y, q.z};
    }
    for (std::size_t k = 0; k < 2; ++k)
      c_pose.heel[k] = {pose.heel[k].x, pose.heel[k].y, pose.heel[k].z};
    fg_vec3 root;
    Vec3 expected_root;
    ASSERT_EQ(fg_skeleton_pose(hero, &c_pose, local.data(), &root), 1);
    ASSERT_TRUE(poser.pose(pose, expected, expected_root));
    EXPECT_TRUE(same_bits(root, expected_root));
    for (std::size_t i = 0; i < skeleton.size(); ++i)
      EXPECT_TRUE(same_bits(local[i], expected[i])) << skeleton.joints[i].name;
  }
  // A pose that is not finite: the rest pose, and 0.
  fg_body_pose broken{};
  broken.position[FG_HIPS].x = std::nan("");
  fg_vec3 root;
  EXPECT_EQ(fg_skeleton_pose(hero, &broken, local.data(), &root), 0);
  EXPECT_TRUE(same_bits(local[3], skeleton.joints[3].rotation));
  EXPECT_EQ(fg_skeleton_pose(hero, nullptr, local.data(), &root), 0);
  fg_skeleton_free(hero);
}

TEST(CApiBody, AFollowerWalksASkeletonsBodyAndAHandMadeMapIsTaken) {
  // The Mixamo rig renamed: found only through the names given by hand.
  const Skeleton mixamo = testing::build_skeleton(testing::mixamo_joints(), Quat{}, 0.01, 0);
  SkeletonArrays arrays(mixamo);
  for (std::string& name : arrays.names)
    name.replace(0, name.find(':') + 1, "bone_");
  for (std::size_t i = 0; i < arrays.names.size(); ++i)
    arrays.name_pointers[i] = arrays.names[i].c_str();
  fg_skeleton_def def = arrays.def(0.01);
  fg_error error;
  EXPECT_EQ(fg_skeleton_new(&def, &error), nullptr);
  EXPECT_THAT(error.message, HasSubstr("hips"));
  EXPECT_THAT(error.message, HasSubstr("LeftUpLeg"));  // among the names tried

  std::vector<const char*> by_hand(FG_JOINT_COUNT, nullptr);
  by_hand[FG_HIPS] = "bone_Hips";
  by_hand[FG_LEFT_UPPER_LEG] = "bone_LeftUpLeg";
  by_hand[FG_LEFT_LOWER_LEG] = "bone_LeftLeg";
  by_hand[FG_LEFT_FOOT] = "bone_LeftFoot";
  by_hand[FG_RIGHT_UPPER_LEG] = "bone_RightUpLeg";
  by_hand[FG_RIGHT_LOWER_LEG] = "bone_RightLeg";
  by_hand[FG_RIGHT_FOOT] = "bone_RightFoot";
  by_hand[FG_LEFT_HAND] = "";  // left out
  def.humanoid_names = by_hand.data();
  fg_skeleton* hero = fg_skeleton_new(&def, &error);
  ASSERT_NE(hero, nullptr) << error.message;
  EXPECT_EQ(fg_skeleton_mapped(hero, FG_LEFT_FOOT), mixamo.find("mixamorig:LeftFoot"));
  EXPECT_EQ(fg_skeleton_mapped(hero, FG_SPINE), -1);

  fg_set* set = fg_set_builtin("default", &error);
  fg_walker_def walker_def = fg_walker_def_default();
  fg_path* route = fg_path_straight(&error);
  const fg_follower_def options = fg_follower_def_default();
  fg_walker* stature_legs = fg_walker_new(set, &walker_def, nullptr, &error);
  EXPECT_EQ(fg_follower_new(stature_legs, route, hero, &options, &error), nullptr);
  EXPECT_THAT(error.message, HasSubstr("segments"));
  fg_skeleton_segments(hero, &walker_def);
  fg_walker* walker = fg_walker_new(set, &walker_def, nullptr, &error);
  fg_follower* follower = fg_follower_new(walker, route, hero, &options, &error);
  ASSERT_NE(follower, nullptr) << error.message;
  std::vector<fg_quat> local(fg_skeleton_joint_count(hero));
  fg_vec3 root{};
  for (int frame = 0; frame < 120; ++frame) {
    fg_walker_advance(walker, 1.0 / 60.0);
    ASSERT_EQ(fg_skeleton_pose(hero, fg_follower_update(follower, walker), local.data(), &root), 1);
  }
  EXPECT_GT(root.z, 100.0);  // walked over a metre along +Z, in centimetres
  fg_follower_free(follower);
  fg_walker_free(walker);
  fg_walker_free(stature_legs);
  fg_path_free(route);
  fg_set_free(set);
  fg_skeleton_free(hero);
}

TEST(CApiBody, RefusalsComeBackAsMessagesNamingWhatWasWrong) {
  fg_error error;
  const double doubled[] = {0.0, 0.0, 0.0, 3.0, 0.0, 3.0, 2.0, 5.0};
  EXPECT_EQ(fg_path_polyline(doubled, 4, 1.0, &error), nullptr);
  EXPECT_EQ(error.failed, 1);
  EXPECT_THAT(error.message, HasSubstr("path point 3"));
  EXPECT_EQ(fg_path_polyline(kCorners, 1, 1.0, &error), nullptr);
  EXPECT_THAT(error.message, HasSubstr("at least two points"));
  EXPECT_EQ(fg_path_polyline(nullptr, 3, 1.0, &error), nullptr);
  const fg_path_piece pieces[] = {{2.0, 0.0}, {1.0, 4.0}};  // a 0.25 m radius
  EXPECT_EQ(fg_path_pieces(0.0, 0.0, 0.0, pieces, 2, &error), nullptr);
  EXPECT_THAT(error.message, HasSubstr("piece 2"));
  EXPECT_TRUE(std::isnan(fg_path_length(nullptr)));
  fg_path_at(nullptr, 1.0, nullptr);

  fg_set* set = fg_set_builtin("default", &error);
  fg_walker_def def = fg_walker_def_default();
  fg_walker* walker = fg_walker_new(set, &def, nullptr, &error);
  fg_path* route = fg_path_straight(&error);
  fg_follower_def options = fg_follower_def_default();
  options.look_ahead = -1.0;
  EXPECT_EQ(fg_follower_new(walker, route, nullptr, &options, &error), nullptr);
  EXPECT_THAT(error.message, HasSubstr("look_ahead"));
  options = fg_follower_def_default();
  options.stature = 7.0;
  EXPECT_EQ(fg_follower_new(walker, route, nullptr, &options, &error), nullptr);
  EXPECT_THAT(error.message, HasSubstr("stature"));
  EXPECT_EQ(fg_follower_new(nullptr, route, nullptr, &options, &error), nullptr);
  EXPECT_EQ(fg_follower_update(nullptr, walker), nullptr);

  const char* names[] = {"Hips", "Hips"};
  const int parents[] = {-1, 0};
  const fg_vec3 offsets[] = {{0, 1, 0}, {0.1, 0, 0}};
  fg_skeleton_def skeleton = fg_skeleton_def_default();
  skeleton.joint_count = 2;
  skeleton.names = names;
  skeleton.parents = parents;
  skeleton.offsets = offsets;
  EXPECT_EQ(fg_skeleton_new(&skeleton, &error), nullptr);
  EXPECT_THAT(error.message, HasSubstr("'Hips'"));
  skeleton.offsets = nullptr;
  EXPECT_EQ(fg_skeleton_new(&skeleton, &error), nullptr);
  EXPECT_THAT(error.message, HasSubstr("offsets"));
  EXPECT_EQ(fg_skeleton_new(nullptr, nullptr), nullptr);  // no error to fill: still no crash
  EXPECT_EQ(fg_skeleton_joint_count(nullptr), 0u);
  EXPECT_EQ(fg_skeleton_segments(nullptr, &def), 0);

  fg_path_free(route);
  fg_walker_free(walker);
  fg_set_free(set);
}

}  // namespace
}  // namespace fuzzygait::body

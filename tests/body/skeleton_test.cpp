#include "fuzzygait/body/skeleton.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "body/skeleton_fixtures.hpp"
#include "fuzzygait/body/humanoid_map.hpp"
#include "fuzzygait/body/skeleton_poser.hpp"
#include "support/allocation_counter.hpp"

namespace fuzzygait::body {
namespace {

using testing::build_skeleton;
using testing::expect_near;
using testing::expect_same_rotation;
using testing::mixamo_joints;
using testing::named_joints;
using testing::posed_positions;
using testing::vrm_joints;
using testing::walking_pose;

constexpr double kPi = std::numbers::pi;
constexpr Vec3 kX{1, 0, 0};
constexpr Vec3 kY{0, 1, 0};
constexpr Vec3 kZ{0, 0, 1};

std::string message_of(auto&& call) {
  try {
    call();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "(no error)";
}

// The VRM rig's joints under VRoid's names ("J_Bip_L_UpperLeg") or Unreal's ("thigh_l", below a
// root bone on the floor).
std::vector<testing::PlacedJoint> renamed(bool unreal) {
  const std::map<std::string, std::pair<std::string, std::string>> names = {
      {"hips", {"J_Bip_C_Hips", "pelvis"}},
      {"spine", {"J_Bip_C_Spine", "spine_01"}},
      {"chest", {"J_Bip_C_Chest", "spine_02"}},
      {"upperChest", {"J_Bip_C_UpperChest", "spine_03"}},
      {"neck", {"J_Bip_C_Neck", "neck_01"}},
      {"head", {"J_Bip_C_Head", "head"}},
      {"UpperLeg", {"UpperLeg", "thigh"}},
      {"LowerLeg", {"LowerLeg", "calf"}},
      {"Foot", {"Foot", "foot"}},
      {"Toes", {"ToeBase", "ball"}},
      {"Shoulder", {"Shoulder", "clavicle"}},
      {"UpperArm", {"UpperArm", "upperarm"}},
      {"LowerArm", {"LowerArm", "lowerarm"}},
      {"Hand", {"Hand", "hand"}},
      {"MiddleProximal", {"Middle1", "middle_01"}},
  };
  auto rename = [&](const std::string& name) -> std::string {
    if (name.empty()) return unreal ? "root" : "";
    if (const auto it = names.find(name); it != names.end()) {
      return unreal ? it->second.second : it->second.first;
    }
    const bool left = name.starts_with("left");
    const auto& [vroid, ue] = names.at(name.substr(left ? 4 : 5));
    return unreal ? ue + (left ? "_l" : "_r") : "J_Bip_" + std::string(left ? "L_" : "R_") + vroid;
  };
  std::vector<testing::PlacedJoint> joints;
  if (unreal) joints.push_back({"root", "", {0.0, 0.0, 0.0}});
  for (testing::PlacedJoint j : vrm_joints()) {
    j.name = rename(j.name);
    j.parent = rename(j.parent);
    joints.push_back(j);
  }
  return joints;
}

// The rigs of the tests: Mixamo's in centimetres facing -Z, facing +X, and lying Z-up facing -Y
// (Blender's); the VRM one in metres facing +X.
struct Rig {
  std::string label;
  Skeleton skeleton;
};
std::vector<Rig> rigs() {
  const Quat face_back = axis_angle(kY, kPi);
  const Quat face_x = axis_angle(kY, kPi / 2);
  const Quat z_up = axis_angle(kX, kPi / 2) * face_back;       // +Y to +Z; facing -Y
  std::vector<testing::PlacedJoint> rooted = mixamo_joints();  // a root bone on the floor
  rooted.insert(rooted.begin(), {"Root", "", {0.1, 0.0, 0.3}});
  rooted[1].parent = "Root";
  return {
      {"mixamo facing -Z", build_skeleton(mixamo_joints(), face_back, 0.01, 7)},
      {"mixamo under a root bone", build_skeleton(rooted, face_back, 0.01, 8)},
      {"mixamo facing +X", build_skeleton(mixamo_joints(), face_x, 0.01, 11)},
      {"mixamo Z-up", build_skeleton(mixamo_joints(), z_up, 0.01, 13)},
      {"vrm facing +X", build_skeleton(vrm_joints(), face_x, 1.0, 17)},
      {"vrm facing +Z, no roll", build_skeleton(vrm_joints(), Quat{}, 1.0, 0)},
      {"vrm with VRoid's names", build_skeleton(renamed(false), face_back, 1.0, 19)},
      {"vrm with Unreal's names, Z-up", build_skeleton(renamed(true), z_up, 0.01, 23)},
  };
}

TEST(BodySkeleton, ValidateNamesTheJoint) {
  Skeleton skeleton = build_skeleton(mixamo_joints(), Quat{}, 0.01, 3);
  EXPECT_NO_THROW(validate(skeleton));
  Skeleton broken = skeleton;
  broken.joints[4].name = broken.joints[2].name;
  EXPECT_NE(
      message_of([&] { validate(broken); }).find("'mixamorig:Spine1': the name is used twice"),
      std::string::npos);
  broken = skeleton;
  broken.joints[3].parent = 5;
  EXPECT_NE(message_of([&] { validate(broken); }).find("'mixamorig:Spine2': parent 5"),
            std::string::npos);
  broken = skeleton;
  broken.joints[6].offset.y = std::nan("");
  EXPECT_NE(message_of([&] { validate(broken); }).find("'mixamorig:HeadTop_End': offset"),
            std::string::npos);
  broken = skeleton;
  broken.joints[1].rotation = {2, 0, 0, 0};
  EXPECT_NE(message_of([&] { validate(broken); }).find("unit quaternion"), std::string::npos);
  broken = skeleton;
  broken.metres_per_unit = 0.0;
  EXPECT_THROW(validate(broken), std::invalid_argument);
}

TEST(BodySkeleton, RestPositionsFollowOffsetsAndRotations) {
  const Skeleton skeleton = build_skeleton(mixamo_joints(), Quat{}, 0.01, 5);
  const std::vector<Vec3> rest = rest_positions(skeleton);
  const std::vector<testing::PlacedJoint> placed = mixamo_joints();
  for (std::size_t i = 0; i < skeleton.size(); ++i) {
    expect_near(0.01 * rest[i], placed[i].position, 1e-12, skeleton.joints[i].name);
  }
}

TEST(BodyHumanoidMap, FindsMixamoAndVrmNames) {
  const Skeleton mixamo = build_skeleton(mixamo_joints(), Quat{}, 0.01, 0);
  const HumanoidMap m = map_humanoid(mixamo);
  auto name_of = [&](const Skeleton& s, const HumanoidMap& map, Joint j) {
    return map[j] < 0 ? std::string("-") : s.joints[static_cast<std::size_t>(map[j])].name;
  };
  EXPECT_EQ(name_of(mixamo, m, Joint::hips), "mixamorig:Hips");
  EXPECT_EQ(name_of(mixamo, m, Joint::chest), "mixamorig:Spine2");
  EXPECT_EQ(name_of(mixamo, m, Joint::right_lower_leg), "mixamorig:RightLeg");
  EXPECT_EQ(name_of(mixamo, m, Joint::left_toes_end), "mixamorig:LeftToe_End");
  EXPECT_EQ(name_of(mixamo, m, Joint::right_hand_end), "mixamorig:RightHandMiddle1");
  EXPECT_EQ(name_of(mixamo, m, Joint::head_end), "mixamorig:HeadTop_End");

  const Skeleton vrm = build_skeleton(vrm_joints(), Quat{}, 1.0, 0);
  const HumanoidMap v = map_humanoid(vrm);
  for (const Joint j :
       {Joint::hips, Joint::spine, Joint::chest, Joint::neck, Joint::head, Joint::left_upper_leg,
        Joint::right_toes, Joint::left_shoulder, Joint::right_hand}) {
    EXPECT_EQ(name_of(vrm, v, j), name(j));
  }
  EXPECT_EQ(name_of(vrm, v, Joint::left_hand_end), "leftMiddleProximal");
  EXPECT_EQ(v[Joint::head_end], kUnmapped);
  EXPECT_NE(describe(v, vrm).find("rightUpperArm <- rightUpperArm"), std::string::npos);
}

TEST(BodyHumanoidMap, MissingLegsAreNamedWithTheNamesTried) {
  std::vector<testing::PlacedJoint> joints;
  for (testing::PlacedJoint j : mixamo_joints()) {
    if (j.name == "mixamorig:LeftLeg") continue;
    if (j.parent == "mixamorig:LeftLeg") j.parent = "mixamorig:LeftUpLeg";
    joints.push_back(j);
  }
  const Skeleton skeleton = build_skeleton(joints, Quat{}, 0.01, 0);
  const std::string message = message_of([&] { map_humanoid(skeleton); });
  EXPECT_NE(message.find("leftLowerLeg (tried LeftLeg, LeftLowerLeg"), std::string::npos)
      << message;
  EXPECT_EQ(message.find("rightLowerLeg"), std::string::npos) << message;

  // By hand: a name the skeleton lacks, and a map without a required joint.
  const Skeleton vrm = build_skeleton(vrm_joints(), Quat{}, 1.0, 0);
  const std::vector<NamedJoint> wrong = {{Joint::hips, "pelvis"}};
  EXPECT_NE(message_of([&] { map_humanoid(vrm, wrong); }).find("'pelvis'"), std::string::npos);
  const std::vector<NamedJoint> legless = {{Joint::hips, "hips"}};
  EXPECT_NE(message_of([&] { map_humanoid(vrm, legless); }).find("leftUpperLeg"),
            std::string::npos);
  const std::vector<NamedJoint> crossed = {{Joint::hips, "hips"},
                                           {Joint::left_upper_leg, "leftUpperLeg"},
                                           {Joint::left_lower_leg, "leftLowerLeg"},
                                           {Joint::left_foot, "rightFoot"},
                                           {Joint::right_upper_leg, "rightUpperLeg"},
                                           {Joint::right_lower_leg, "rightLowerLeg"},
                                           {Joint::right_foot, "leftFoot"}};
  EXPECT_NE(message_of([&] { map_humanoid(vrm, crossed); }).find("does not lie below"),
            std::string::npos);
}

TEST(BodyHumanoidMap, AMapByHandPosesTheSameAsTheNamedOne) {
  const Skeleton vrm = build_skeleton(vrm_joints(), axis_angle(kY, 0.7), 1.0, 21);
  const HumanoidMap automatic = map_humanoid(vrm);
  const HumanoidMap by_hand = map_humanoid(vrm, named_joints(automatic, vrm));
  EXPECT_EQ(by_hand.joint, automatic.joint);
}

TEST(BodyPoser, HumanoidTakesTheSkeletonsProportions) {
  for (const Rig& rig : rigs()) {
    const Humanoid h = humanoid_from_skeleton(rig.skeleton, map_humanoid(rig.skeleton));
    const rig::Segments s = h.segments();
    if (rig.label.starts_with("mixamo")) {
      EXPECT_NEAR(s.thigh, 0.42, 1e-12) << rig.label;
      EXPECT_NEAR(s.shank, 0.42, 1e-12) << rig.label;
      EXPECT_NEAR(s.ankle_height, 0.08, 1e-12) << rig.label;
      EXPECT_NEAR(s.ball, 0.13, 1e-12) << rig.label;
      EXPECT_NEAR(s.toe, 0.07, 1e-12) << rig.label;
      EXPECT_NEAR(s.heel, 0.13 * 0.25 / 0.48, 1e-12) << rig.label;  // Winter's proportions
      EXPECT_NEAR(h.hip_width(), 0.18, 1e-12) << rig.label;
      EXPECT_NEAR(h[Joint::hips].y, 0.92, 1e-12) << rig.label;
      EXPECT_NEAR(length(h[Joint::left_lower_arm]), 0.28, 1e-12) << rig.label;
      expect_near(h[Joint::left_lower_arm], {0, -0.28, 0}, 1e-12, rig.label);  // hanging down
    } else {
      EXPECT_NEAR(s.thigh, std::hypot(0.48, 0.02), 1e-12) << rig.label;
      EXPECT_NEAR(s.ankle_height, 0.09, 1e-12) << rig.label;
      EXPECT_NEAR(s.ball, 0.15, 1e-12) << rig.label;
      EXPECT_NEAR(s.toe, 0.15 * 0.27 / 0.48, 1e-12) << rig.label;  // no toe end
      EXPECT_NEAR(length(h[Joint::left_lower_arm]), 0.22, 1e-12) << rig.label;
      EXPECT_NEAR(length(h[Joint::left_hand]), 0.19, 1e-12) << rig.label;
    }
    EXPECT_NO_THROW(validate(h));
  }
}

TEST(BodyPoser, PosedSkeletonPutsEveryMappedJointWhereTheBodyPoseHasIt) {
  double worst = 0.0;
  for (const Rig& rig : rigs()) {
    const HumanoidMap map = map_humanoid(rig.skeleton);
    const SkeletonPoser poser(rig.skeleton, map);
    // Every joint found by name but the VRM rig's missing ends (head, toes).
    EXPECT_GE(std::count_if(map.joint.begin(), map.joint.end(), [](int j) { return j >= 0; }),
              rig.label.starts_with("mixamo") ? 26 : 23)
        << rig.label << ":\n"
        << describe(map, rig.skeleton);
    const std::vector<Vec3> rest = rest_positions(rig.skeleton);
    for (int k = 0; k < 12; ++k) {
      const BodyPose pose = walking_pose(poser.humanoid(), 0.6 * k, 0.5 * k - 2.0,
                                         k % 3 == 0 ? 0u : static_cast<std::uint32_t>(k));
      std::vector<Quat> local;
      const std::vector<Vec3> at = posed_positions(rig.skeleton, poser, pose, &local);
      for (std::size_t i = 0; i < kJointCount; ++i) {
        const auto joint = static_cast<Joint>(i);
        const int s = map.joint[i];
        if (s < 0 || joint == Joint::hips) continue;
        const Vec3 d = at[static_cast<std::size_t>(s)] - pose[joint];
        worst = std::max(worst, length(d));
        expect_near(at[static_cast<std::size_t>(s)], pose[joint], 1e-6,
                    rig.label + " " + std::string(name(joint)));
      }
      // The hips: the midpoint of the hip joints.
      const Vec3 mid = 0.5 * (at[static_cast<std::size_t>(map[Joint::left_upper_leg])] +
                              at[static_cast<std::size_t>(map[Joint::right_upper_leg])]);
      expect_near(mid, pose[Joint::hips], 1e-6, rig.label + " hips");
      // Every bone keeps its length; unmapped joints keep their rest rotation.
      for (std::size_t j = 1; j < rig.skeleton.size(); ++j) {
        const auto p = static_cast<std::size_t>(rig.skeleton.joints[j].parent);
        EXPECT_NEAR(length(at[j] - at[p]), rig.skeleton.metres_per_unit * length(rest[j] - rest[p]),
                    1e-9);
      }
    }
  }
  std::cout << "Posed rigs: mapped joints at most " << worst << " m from the BodyPose\n";
  RecordProperty("worst_mapped_joint_error_m", (std::ostringstream() << worst).str());
}

TEST(BodyPoser, AHeelJointGivesTheHeel) {
  std::vector<testing::PlacedJoint> joints = mixamo_joints();
  joints.push_back({"mixamorig:LeftHeel", "mixamorig:LeftFoot", {0.09, 0.0, -0.06}});
  joints.push_back({"mixamorig:RightHeel", "mixamorig:RightFoot", {-0.09, 0.0, -0.06}});
  const Skeleton skeleton = build_skeleton(joints, axis_angle(kY, 2.0), 0.01, 6);
  const HumanoidMap map = map_humanoid(skeleton);
  EXPECT_EQ(map.heel[0], skeleton.find("mixamorig:LeftHeel"));
  EXPECT_EQ(map.heel[1], skeleton.find("mixamorig:RightHeel"));
  const Humanoid h = humanoid_from_skeleton(skeleton, map);
  EXPECT_NEAR(h.heel, 0.06, 1e-12);
  EXPECT_NEAR(h.segments().ankle_height, 0.08, 1e-12);  // the heel on the same floor
}

TEST(BodyPoser, ReferencePoseTurnsBonesToTheCanonicalDirections) {
  for (const Rig& rig : rigs()) {
    const HumanoidMap map = map_humanoid(rig.skeleton);
    const SkeletonPoser poser(rig.skeleton, map);
    BodyPose pose;  // every rotation the identity: the reference pose
    forward_kinematics(poser.humanoid(), {0, 1, 0}, pose);
    const std::vector<Vec3> at = posed_positions(rig.skeleton, poser, pose);
    auto bone = [&](Joint from, Joint to) {
      return normalized(at[static_cast<std::size_t>(map[to])] -
                        at[static_cast<std::size_t>(map[from])]);
    };
    expect_near(bone(Joint::left_upper_leg, Joint::left_lower_leg), -kY, 1e-9, rig.label);
    expect_near(bone(Joint::right_lower_leg, Joint::right_foot), -kY, 1e-9, rig.label);
    expect_near(bone(Joint::left_upper_arm, Joint::left_lower_arm), -kY, 1e-9, rig.label);
    expect_near(bone(Joint::right_lower_arm, Joint::right_hand), -kY, 1e-9, rig.label);
    expect_near(bone(Joint::left_upper_leg, Joint::right_upper_leg), -kX, 1e-9, rig.label);
    expect_near(bone(Joint::neck, Joint::head), kY, 1e-9, rig.label);
    const Vec3 foot = bone(Joint::left_foot, Joint::left_toes);
    EXPECT_NEAR(foot.x, 0.0, 1e-9) << rig.label;
    EXPECT_GT(foot.z, 0.5) << rig.label;  // the feet point forward, along +Z
    if (map[Joint::left_shoulder] >= 0) {
      expect_near(bone(Joint::left_shoulder, Joint::left_upper_arm), kX, 1e-9, rig.label);
    }
  }
}

TEST(BodyPoser, StandingPutsTheSkeletonsFeetOnTheFloor) {
  for (const Rig& rig : rigs()) {
    const HumanoidMap map = map_humanoid(rig.skeleton);
    const SkeletonPoser poser(rig.skeleton, map);
    BodyPose pose;  // standing in the reference pose on y = 0
    forward_kinematics(poser.humanoid(), poser.humanoid()[Joint::hips], pose);
    const std::vector<Vec3> at = posed_positions(rig.skeleton, poser, pose);
    for (const rig::Side side : rig::kSides) {
      const Vec3 ankle = at[static_cast<std::size_t>(map[foot(side)])];
      EXPECT_NEAR(ankle.y, poser.humanoid().segments().ankle_height, 1e-9) << rig.label;
      EXPECT_NEAR(at[static_cast<std::size_t>(map[toes(side)])].y, 0.0, 1e-9) << rig.label;
      if (map[toes_end(side)] >= 0) {
        EXPECT_NEAR(at[static_cast<std::size_t>(map[toes_end(side)])].y, 0.0, 1e-9) << rig.label;
      }
    }
  }
}

TEST(BodyPoser, RestOrientationsReproduceTheRestPose) {
  for (const Rig& rig : rigs()) {
    const HumanoidMap map = map_humanoid(rig.skeleton);
    const SkeletonPoser poser(rig.skeleton, map);
    BodyPose pose;
    pose.rotation = poser.rest_orientations();
    forward_kinematics(poser.humanoid(), {0, 1, 0}, pose);
    std::vector<Quat> local;
    const std::vector<Vec3> at = posed_positions(rig.skeleton, poser, pose, &local);
    // Below the hips (whose rotation carries the turn to face +Z), every joint's rest rotation.
    for (std::size_t j = static_cast<std::size_t>(map[Joint::hips]) + 1; j < rig.skeleton.size();
         ++j) {
      expect_same_rotation(local[j], rig.skeleton.joints[j].rotation, 1e-12,
                           rig.label + " " + rig.skeleton.joints[j].name);
    }
    // ... turned to stand up along +Y and face +Z.
    const Vec3 up = at[static_cast<std::size_t>(map[Joint::hips])] -
                    at[static_cast<std::size_t>(map[Joint::left_foot])];
    EXPECT_GT(up.y, 0.9 * length(up)) << rig.label;
    const Vec3 ahead = at[static_cast<std::size_t>(map[Joint::left_toes])] -
                       at[static_cast<std::size_t>(map[Joint::left_foot])];
    EXPECT_GT(ahead.z, 0.0) << rig.label;
  }
}

TEST(BodyPoser, RetargetsAnotherHumanoidsPoseByRotation) {
  const Skeleton vrm = build_skeleton(vrm_joints(), Quat{}, 1.0, 9);
  const HumanoidMap map = map_humanoid(vrm);
  const SkeletonPoser poser(vrm, map);
  const Humanoid other = humanoid_from_stature(1.6);
  const BodyPose pose = walking_pose(other, 1.0, 0.3, 0);
  const std::vector<Vec3> at = posed_positions(vrm, poser, pose);
  const Vec3 mid = 0.5 * (at[static_cast<std::size_t>(map[Joint::left_upper_leg])] +
                          at[static_cast<std::size_t>(map[Joint::right_upper_leg])]);
  expect_near(mid, pose[Joint::hips], 1e-9, "hips");
  // The thigh points where the other humanoid's does.
  const Vec3 thigh = normalized(at[static_cast<std::size_t>(map[Joint::left_lower_leg])] -
                                at[static_cast<std::size_t>(map[Joint::left_upper_leg])]);
  expect_near(thigh, normalized(pose[Joint::left_lower_leg] - pose[Joint::left_upper_leg]), 1e-9,
              "thigh");
}

TEST(BodyPoser, UnposeGivesBackTheBodyPose) {
  for (const Rig& rig : rigs()) {
    const HumanoidMap map = map_humanoid(rig.skeleton);
    const SkeletonPoser poser(rig.skeleton, map);
    std::vector<Quat> local(poser.joint_count());
    std::vector<Quat> world(poser.joint_count());
    for (int k = 0; k < 6; ++k) {
      const BodyPose pose = walking_pose(poser.humanoid(), 0.9 * k, 0.7 * k, k + 1u);
      Vec3 root;
      ASSERT_TRUE(poser.pose(pose, local, root));
      BodyPose back;
      ASSERT_TRUE(poser.unpose(local, root, world, back));
      for (std::size_t i = 0; i < kJointCount; ++i) {
        const std::string what = rig.label + " " + std::string(name(static_cast<Joint>(i)));
        expect_near(back.position[i], pose.position[i], 1e-9, what);
        if (!is_end(static_cast<Joint>(i))) {
          expect_same_rotation(back.rotation[i], pose.rotation[i], 1e-12, what);
        }
      }
    }
    BodyPose untouched;
    local[3].y = std::nan("");
    EXPECT_FALSE(poser.unpose(local, {}, world, untouched));
    EXPECT_FALSE(poser.unpose(std::span<const Quat>(local).first(2), {}, world, untouched));
  }
}

TEST(BodyPoser, NotFinitePoseGivesTheRestPoseAndFalse) {
  const Skeleton skeleton = build_skeleton(mixamo_joints(), Quat{}, 0.01, 4);
  const SkeletonPoser poser(skeleton, map_humanoid(skeleton));
  BodyPose pose = walking_pose(poser.humanoid(), 0.3, 0.0, 0);
  pose.rotation[index(Joint::left_foot)].x = std::numeric_limits<double>::quiet_NaN();
  std::vector<Quat> local(skeleton.size());
  Vec3 root{5, 5, 5};
  EXPECT_FALSE(poser.pose(pose, local, root));
  for (std::size_t j = 0; j < skeleton.size(); ++j) {
    expect_same_rotation(local[j], skeleton.joints[j].rotation, 1e-15, skeleton.joints[j].name);
  }
  expect_near(root, skeleton.joints[0].offset, 0.0, "root");
  pose = walking_pose(poser.humanoid(), 0.3, 0.0, 0);
  pose.position[0].y = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(poser.pose(pose, local, root));
}

TEST(BodyPoser, PosingAllocatesNothingAndIsQuick) {
  const Skeleton skeleton = build_skeleton(mixamo_joints(), Quat{}, 0.01, 4);
  const SkeletonPoser poser(skeleton, map_humanoid(skeleton));
  const BodyPose pose = walking_pose(poser.humanoid(), 0.3, 0.0, 5);
  std::vector<Quat> local(poser.joint_count());
  Vec3 root;
  const long before = fuzzygait::testing::allocation_count();
  constexpr int kCalls = 20000;
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < kCalls; ++k)
    poser.pose(pose, local, root);
  const std::chrono::duration<double, std::micro> took = std::chrono::steady_clock::now() - start;
  EXPECT_EQ(fuzzygait::testing::allocation_count() - before, 0);
  std::cout << "SkeletonPoser::pose, " << skeleton.size() << " joints: " << took.count() / kCalls
            << " us a call\n";
}

TEST(BodyPoser, ZeroLengthBonesAreRefusedByName) {
  std::vector<testing::PlacedJoint> joints = mixamo_joints();
  for (testing::PlacedJoint& j : joints) {
    if (j.name == "mixamorig:LeftLeg") j.position = {0.09, 0.92, 0.0};  // on the hip
  }
  const Skeleton skeleton = build_skeleton(joints, Quat{}, 0.01, 0);
  // By name, the knee on the hip is passed over and the leg is missing.
  EXPECT_NE(message_of([&] { map_humanoid(skeleton); }).find("leftLowerLeg"), std::string::npos);
  const Skeleton good = build_skeleton(mixamo_joints(), Quat{}, 0.01, 0);
  const HumanoidMap forced = map_humanoid(skeleton, named_joints(map_humanoid(good), good));
  const std::string message = message_of([&] { humanoid_from_skeleton(skeleton, forced); });
  EXPECT_NE(message.find("mixamorig:LeftUpLeg"), std::string::npos) << message;
}

}  // namespace
}  // namespace fuzzygait::body

#include "body/skeleton_fixtures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

namespace fuzzygait::body::testing {

namespace {

constexpr Vec3 kX{1, 0, 0};
constexpr Vec3 kY{0, 1, 0};
constexpr Vec3 kZ{0, 0, 1};

Quat random_rotation(std::mt19937& random, double max_angle) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Vec3 axis = normalized(Vec3{unit(random), unit(random), unit(random)});
  return axis_angle(length(axis) > 0.0 ? axis : kY, max_angle * unit(random));
}

// Mirrors the left joints' names and positions onto the right.
void add_mirrored(std::vector<PlacedJoint>& joints, const std::vector<PlacedJoint>& left,
                  const std::string& left_word, const std::string& right_word) {
  auto swap_side = [&](std::string name) {
    const std::size_t at = name.find(left_word);
    if (at != std::string::npos) name.replace(at, left_word.size(), right_word);
    return name;
  };
  for (const PlacedJoint& j : left)
    joints.push_back(j);
  for (const PlacedJoint& j : left) {
    joints.push_back({swap_side(j.name),
                      swap_side(j.parent),
                      {-j.position.x, j.position.y, j.position.z},
                      j.end_site});
  }
}

}  // namespace

Skeleton build_skeleton(const std::vector<PlacedJoint>& joints, Quat facing, double metres_per_unit,
                        std::uint32_t roll_seed) {
  std::mt19937 random(roll_seed);
  Skeleton skeleton;
  skeleton.metres_per_unit = metres_per_unit;
  std::map<std::string, int> index_of;
  std::vector<Vec3> world_position;
  std::vector<Quat> world_rotation;
  for (const PlacedJoint& placed : joints) {
    const Vec3 p = (1.0 / metres_per_unit) * rotate(facing, placed.position);
    if (placed.end_site) {
      const int owner = index_of.at(placed.parent);
      const auto o = static_cast<std::size_t>(owner);
      skeleton.joints[o].end = rotate(conjugate(world_rotation[o]), p - world_position[o]);
      continue;
    }
    const Quat rest = roll_seed == 0 ? Quat{} : random_rotation(random, 3.0);
    SkeletonJoint joint;
    joint.name = placed.name;
    if (placed.parent.empty()) {
      joint.offset = p;
      joint.rotation = rest;
    } else {
      joint.parent = index_of.at(placed.parent);
      const auto q = static_cast<std::size_t>(joint.parent);
      joint.offset = rotate(conjugate(world_rotation[q]), p - world_position[q]);
      joint.rotation = normalized(conjugate(world_rotation[q]) * rest);
    }
    index_of[placed.name] = static_cast<int>(skeleton.joints.size());
    world_position.push_back(p);
    world_rotation.push_back(rest);
    skeleton.joints.push_back(joint);
  }
  return skeleton;
}

std::vector<PlacedJoint> mixamo_joints() {
  const std::string m = "mixamorig:";
  std::vector<PlacedJoint> joints = {
      {m + "Hips", "", {0.0, 1.00, -0.02}},
      {m + "Spine", m + "Hips", {0.0, 1.10, -0.03}},
      {m + "Spine1", m + "Spine", {0.0, 1.22, -0.03}},
      {m + "Spine2", m + "Spine1", {0.0, 1.35, -0.02}},
      {m + "Neck", m + "Spine2", {0.0, 1.52, -0.02}},
      {m + "Head", m + "Neck", {0.0, 1.62, 0.0}},
      {m + "HeadTop_End", m + "Head", {0.0, 1.80, 0.0}},
  };
  add_mirrored(joints,
               {
                   {m + "LeftUpLeg", m + "Hips", {0.09, 0.92, 0.0}},
                   {m + "LeftLeg", m + "LeftUpLeg", {0.09, 0.50, 0.0}},
                   {m + "LeftFoot", m + "LeftLeg", {0.09, 0.08, 0.0}},
                   {m + "LeftToeBase", m + "LeftFoot", {0.09, 0.0, 0.13}},
                   {m + "LeftToe_End", m + "LeftToeBase", {0.09, 0.0, 0.20}},
                   {m + "LeftShoulder", m + "Spine2", {0.03, 1.46, -0.02}},
                   {m + "LeftArm", m + "LeftShoulder", {0.17, 1.45, -0.02}},
                   {m + "LeftForeArm", m + "LeftArm", {0.45, 1.45, -0.02}},
                   {m + "LeftHand", m + "LeftForeArm", {0.70, 1.45, -0.02}},
                   {m + "LeftHandMiddle1", m + "LeftHand", {0.79, 1.45, -0.02}},
               },
               "Left", "Right");
  return joints;
}

std::vector<PlacedJoint> vrm_joints() {
  std::vector<PlacedJoint> joints = {
      {"hips", "", {0.0, 1.12, 0.0}},           {"spine", "hips", {0.0, 1.22, -0.01}},
      {"chest", "spine", {0.0, 1.34, -0.01}},   {"upperChest", "chest", {0.0, 1.44, -0.01}},
      {"neck", "upperChest", {0.0, 1.56, 0.0}}, {"head", "neck", {0.0, 1.64, 0.01}},
  };
  const double s = std::sqrt(0.5);  // the A-pose's 45 degrees
  const Vec3 shoulder{0.14, 1.51, -0.01};
  const Vec3 elbow = shoulder + 0.22 * Vec3{s, -s, 0.0};
  const Vec3 wrist = elbow + 0.19 * Vec3{s, -s, 0.0};
  const Vec3 finger = wrist + 0.06 * Vec3{s, -s, 0.0};
  add_mirrored(joints,
               {
                   {"leftUpperLeg", "hips", {0.085, 1.07, 0.0}},
                   {"leftLowerLeg", "leftUpperLeg", {0.085, 0.59, 0.02}},
                   {"leftFoot", "leftLowerLeg", {0.085, 0.09, 0.0}},
                   {"leftToes", "leftFoot", {0.085, 0.0, 0.15}},
                   {"leftShoulder", "upperChest", {0.02, 1.50, -0.01}},
                   {"leftUpperArm", "leftShoulder", shoulder},
                   {"leftLowerArm", "leftUpperArm", elbow},
                   {"leftHand", "leftLowerArm", wrist},
                   {"leftMiddleProximal", "leftHand", finger},
               },
               "left", "right");
  return joints;
}

BodyPose walking_pose(const Humanoid& humanoid, double phase, double yaw, std::uint32_t jitter) {
  std::array<Quat, kJointCount> local{};
  const double swing = std::sin(phase);
  local[index(Joint::hips)] = axis_angle(kY, yaw) * axis_angle(kX, 0.1) * axis_angle(kZ, 0.05);
  local[index(Joint::spine)] = axis_angle(kY, -0.15 * swing);
  local[index(Joint::chest)] = axis_angle(kX, 0.08);
  local[index(Joint::neck)] = axis_angle(kY, 0.1 * swing);
  local[index(Joint::head)] = axis_angle(kX, -0.1);
  for (const rig::Side side : rig::kSides) {
    const double sign = side == rig::Side::Left ? 1.0 : -1.0;
    const double s = sign * swing;
    local[index(upper_leg(side))] = axis_angle(kX, -0.45 * s) * axis_angle(kZ, 0.04 * sign);
    local[index(lower_leg(side))] = axis_angle(kX, 0.35 + 0.35 * s);
    local[index(foot(side))] = axis_angle(kX, -0.2 * s);
    local[index(toes(side))] = axis_angle(kX, -0.3 * std::max(0.0, s));
    const int arm = index(side == rig::Side::Left ? Joint::left_shoulder : Joint::right_shoulder);
    local[static_cast<std::size_t>(arm)] = axis_angle(kZ, 0.05 * sign);
    local[static_cast<std::size_t>(arm + 1)] = axis_angle(kX, 0.4 * s) * axis_angle(kZ, sign * 0.1);
    local[static_cast<std::size_t>(arm + 2)] = axis_angle(kX, -0.3 - 0.2 * s);
    local[static_cast<std::size_t>(arm + 3)] = axis_angle(kY, 0.2);
  }
  if (jitter != 0) {
    std::mt19937 random(jitter);
    for (Quat& q : local)
      q = q * random_rotation(random, 0.5);
  }
  BodyPose pose;
  for (std::size_t i = 0; i < kJointCount; ++i) {
    const std::optional<Joint> p = parent(static_cast<Joint>(i));
    pose.rotation[i] =
        p ? normalized(pose.rotation[static_cast<std::size_t>(index(*p))] * local[i]) : local[i];
  }
  forward_kinematics(humanoid, {0.4, humanoid[Joint::hips].y, -1.3}, pose);
  return pose;
}

void expect_near(Vec3 a, Vec3 b, double tolerance, const std::string& what) {
  EXPECT_NEAR(a.x, b.x, tolerance) << what;
  EXPECT_NEAR(a.y, b.y, tolerance) << what;
  EXPECT_NEAR(a.z, b.z, tolerance) << what;
}

void expect_same_rotation(Quat a, Quat b, double tolerance, const std::string& what) {
  const double d = std::abs(a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z);
  EXPECT_NEAR(d, 1.0, tolerance) << what;
}

std::vector<NamedJoint> named_joints(const HumanoidMap& map, const Skeleton& skeleton) {
  std::vector<NamedJoint> names;
  for (std::size_t i = 0; i < kJointCount; ++i) {
    if (map.joint[i] >= 0) {
      names.push_back(
          {static_cast<Joint>(i), skeleton.joints[static_cast<std::size_t>(map.joint[i])].name});
    }
  }
  return names;
}

std::vector<Vec3> posed_positions(const Skeleton& skeleton, const SkeletonPoser& poser,
                                  const BodyPose& pose, std::vector<Quat>* local_out) {
  std::vector<Quat> local(skeleton.size());
  Vec3 root;
  EXPECT_TRUE(poser.pose(pose, local, root));
  std::vector<Vec3> positions(skeleton.size());
  std::vector<Quat> world(skeleton.size());
  forward_kinematics(skeleton, local, root, positions, world);
  for (Vec3& p : positions)
    p = skeleton.metres_per_unit * p;
  if (local_out) *local_out = local;
  return positions;
}

}  // namespace fuzzygait::body::testing

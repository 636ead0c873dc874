// The whole body as the runtime poses it: a canonical humanoid of 26 joints, its proportions, and
// a pose of it in the world. Any game skeleton is posed from this (body/skeleton.hpp).
//
// Axes: Y up, Z forward, X to the character's left, as the BVH and glTF files (io/bvh.hpp). A
// character facing heading h (radians, turning left +) looks along (sin h, 0, cos h).
//
// The reference pose, in which every joint's rotation is the identity: standing upright facing
// +Z, every clinical angle of the rig zero (legs straight down, feet flat and pointing forward),
// trunk, neck and head upright, the clavicles pointing out sideways, arms hanging straight down
// beside the thighs. A Humanoid holds each joint's offset from its parent in that pose.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

#include "fuzzygait/body/math.hpp"
#include "fuzzygait/rig/rig.hpp"

namespace fuzzygait::body {

// The joints, parents before children. The *_end joints are end points (the top of the head,
// the tips of the toes and of the middle finger): positions only, no rotation of their own.
enum class Joint : int {
  hips,  // root: the midpoint of the hip joint centres; its rotation is the pelvis's
  spine,
  chest,
  neck,
  head,
  head_end,
  left_upper_leg,  // hip joint
  left_lower_leg,  // knee
  left_foot,       // ankle
  left_toes,       // ball of the foot (MTP joint)
  left_toes_end,
  right_upper_leg,
  right_lower_leg,
  right_foot,
  right_toes,
  right_toes_end,
  left_shoulder,   // the clavicle's inner end, on the chest
  left_upper_arm,  // shoulder joint
  left_lower_arm,  // elbow
  left_hand,       // wrist
  left_hand_end,
  right_shoulder,
  right_upper_arm,
  right_lower_arm,
  right_hand,
  right_hand_end,
};
inline constexpr std::size_t kJointCount = 26;

inline constexpr int index(Joint joint) {
  return static_cast<int>(joint);
}
// The parent joint; std::nullopt for hips.
std::optional<Joint> parent(Joint joint);
// The joint's name in VRM 1.0's humanoid ("hips", "leftUpperLeg", ...); the end points, which VRM
// does not name, as "headEnd", "leftToesEnd", "leftHandEnd".
std::string_view name(Joint joint);
// The joint of that name, or std::nullopt.
std::optional<Joint> joint_named(std::string_view name);
bool is_end(Joint joint);
// The leg joints of a side: upper_leg, lower_leg, foot, toes, toes_end.
Joint upper_leg(rig::Side side);
Joint lower_leg(rig::Side side);
Joint foot(rig::Side side);
Joint toes(rig::Side side);
Joint toes_end(rig::Side side);

// A body's proportions: each joint's offset from its parent in the reference pose (hips: from the
// ground point below it, so hips.y is the hip height standing), and the heel, which is no joint.
// The legs agree with rig::Segments: upper_leg (+-hip width / 2, 0, 0), lower_leg (0, -thigh, 0),
// foot (0, -shank, 0), toes (0, -ankle height, ball), toes_end (0, 0, toe).
struct Humanoid {
  std::array<Vec3, kJointCount> offset{};
  double heel = 0.0;  // ankle to the back of the heel, along the sole

  const Vec3& operator[](Joint joint) const { return offset[index(joint)]; }
  Vec3& operator[](Joint joint) { return offset[index(joint)]; }
  // The walker's segments of the left leg (both legs must match: validate checks).
  rig::Segments segments() const;
  double hip_width() const;  // between the hip joint centres
};

// A humanoid of the given stature with Winter's (2009, Fig. 4.1, after Drillis & Contini)
// proportions: the legs as rig::segments_from_stature, hip joints 0.19 x leg length apart
// (io::BvhOptions), the lumbar joint 0.100 H above the hips, shoulders at 0.818 H and 0.259 H
// apart, chin 0.870 H, upper arm 0.186 H, forearm 0.146 H, hand 0.108 H. Throws
// std::invalid_argument for a stature that rig::segments_from_stature refuses.
Humanoid humanoid_from_stature(double stature);
// The hip joint's height over stature in Winter's proportions (rig::segments_from_stature).
inline constexpr double kHipHeightPerStature = 0.530;
// A humanoid walking on these legs (a walker's segments): humanoid_from_stature(stature) with its
// legs replaced by `legs` and its hips their leg length high; stature by default the one the legs
// stand for, leg_length() / kHipHeightPerStature. Throws std::invalid_argument as
// humanoid_from_stature and validate do.
Humanoid humanoid_with_legs(const rig::Segments& legs,
                            std::optional<double> stature = std::nullopt);
// Throws std::invalid_argument naming the joint when an offset is not finite, a bone has no
// length, the legs differ between the sides, or the leg offsets are not rig segments
// (rig::validate).
void validate(const Humanoid& humanoid);

// A pose of the whole body in the world: each joint's position and world rotation (from the
// reference pose: position[child] = position[joint] + rotate(rotation[joint], offset[child])).
// An end point's rotation is its parent's.
struct BodyPose {
  std::array<Vec3, kJointCount> position{};
  std::array<Quat, kJointCount> rotation{};
  std::array<Vec3, 2> heel{};  // the backs of the heels (rig::Side order), for contact

  const Vec3& operator[](Joint joint) const { return position[index(joint)]; }
};

// Places every joint from the hips' position and each joint's world rotation (forward
// kinematics of `humanoid`), end points and heels included.
void forward_kinematics(const Humanoid& humanoid, Vec3 hips, BodyPose& pose);
// Joint rotations relative to their parents' (hips: its world rotation), from a pose's world ones.
std::array<Quat, kJointCount> local_rotations(const BodyPose& pose);

}  // namespace fuzzygait::body

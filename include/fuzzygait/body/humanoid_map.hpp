// Which joint of a game's skeleton stands for each canonical joint (body/humanoid.hpp): built by
// name for the common conventions, or given by hand.
#pragma once

#include <array>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fuzzygait/body/humanoid.hpp"
#include "fuzzygait/body/skeleton.hpp"

namespace fuzzygait::body {

inline constexpr int kUnmapped = -1;

struct HumanoidMap {
  // The skeleton joint of each canonical joint, or kUnmapped. An end point (headEnd, leftToesEnd,
  // leftHandEnd) mapped to a joint only lends its rest position; that joint is not posed.
  std::array<int, kJointCount> joint;
  // A heel joint per side (rig::Side order) when the skeleton has one, else kUnmapped: the heel's
  // length then comes from the foot's proportions.
  std::array<int, 2> heel{kUnmapped, kUnmapped};

  HumanoidMap() { joint.fill(kUnmapped); }
  int operator[](Joint j) const { return joint[static_cast<std::size_t>(index(j))]; }
  int& operator[](Joint j) { return joint[static_cast<std::size_t>(index(j))]; }
};

// The canonical joints every map must give: hips, and per leg the upper leg, lower leg and foot.
// Spine, chest, neck, head, toes, arms and end points are optional: an unmapped canonical joint is
// not applied to the skeleton, and a skeleton joint no canonical joint maps keeps its rest
// rotation relative to its parent.
bool is_required(Joint joint);

// Maps by name. Each canonical joint takes the first of its candidate names the skeleton has,
// compared without case and after any namespace prefix ending in ':' ("mixamorig:LeftUpLeg"), that
// lies below the joint its canonical parent maps to and not on it (CMU's LowerBack and Neck sit
// on Hips and Spine1 and are passed over for Spine and Neck1). The candidates, left side (the
// right side swaps Left for Right, _L_ for _R_ and a last _l for _r):
//   hips          Hips, Pelvis, J_Bip_C_Hips
//   spine         Spine, J_Bip_C_Spine, spine_01
//   chest         Spine2 (Mixamo), Chest, UpperChest, Spine1 (CMU), J_Bip_C_Chest, spine_05
//                 (Unreal 5), spine_03 (Unreal 4)
//   neck          Neck, Neck1, J_Bip_C_Neck, neck_01
//   head          Head, J_Bip_C_Head
//   headEnd       HeadTop_End, HeadEnd, Head_End, Head_Top
//   leftUpperLeg  LeftUpLeg, LeftUpperLeg, LeftThigh, J_Bip_L_UpperLeg, thigh_l
//   leftLowerLeg  LeftLeg, LeftLowerLeg, LeftKnee, LeftShin, J_Bip_L_LowerLeg, calf_l
//   leftFoot      LeftFoot, LeftAnkle, J_Bip_L_Foot, foot_l
//   leftToes      LeftToeBase, LeftToes, LeftToe, J_Bip_L_ToeBase, ball_l
//   leftToesEnd   LeftToe_End, LeftToesEnd, LeftToeEnd, LeftToeBase_End
//   leftShoulder  LeftShoulder, LeftCollar, LeftClavicle, J_Bip_L_Shoulder, clavicle_l
//   leftUpperArm  LeftArm, LeftUpperArm, J_Bip_L_UpperArm, upperarm_l
//   leftLowerArm  LeftForeArm, LeftLowerArm, J_Bip_L_LowerArm, lowerarm_l
//   leftHand      LeftHand, J_Bip_L_Hand, hand_l
//   leftHandEnd   LeftHandMiddle1, LeftMiddleProximal, LeftHandEnd, LeftHand_End,
//                 J_Bip_L_Middle1, middle_01_l
//   heel          LeftHeel, LeftHeel_End
// CMU's and Mixamo's names, VRM's (body::name), fuzzygait's BVH writer's (io/bvh.hpp), VRoid's
// J_Bip ones and Unreal's mannequin's (whose root bone on the floor stays unmapped). An end point
// left unmapped is found by humanoid_from_skeleton (body/skeleton_poser.hpp).
// Throws std::invalid_argument naming each required canonical joint not found and the names tried.
HumanoidMap map_humanoid(const Skeleton& skeleton);

// A map given by hand: (canonical joint, skeleton joint name) pairs; the rest stay unmapped.
struct NamedJoint {
  Joint joint;
  std::string name;
};
// Throws std::invalid_argument for a name the skeleton does not have, a canonical joint given
// twice, or a map that validate refuses.
HumanoidMap map_humanoid(const Skeleton& skeleton, std::span<const NamedJoint> names);

// Throws std::invalid_argument naming the joints when a required canonical joint is unmapped, an
// index is out of range, one skeleton joint stands for two canonical ones, or a mapped joint does
// not lie below the joint its nearest mapped canonical ancestor maps to.
void validate(const HumanoidMap& map, const Skeleton& skeleton);

// "leftUpperLeg <- LeftUpLeg" lines of the mapped joints, for logs and error messages.
std::string describe(const HumanoidMap& map, const Skeleton& skeleton);

}  // namespace fuzzygait::body

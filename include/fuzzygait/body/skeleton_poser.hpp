// Posing a game's skeleton from the canonical body: the skeleton's proportions as a Humanoid (so
// the walker walks with the skeleton's own legs) and, every frame, a BodyPose turned into the
// skeleton's local rotations and root position.
//
// How a skeleton is read (its rest pose, any facing, units, bone roll, T- or A-pose arms):
//   * facing: its left is the left hip joint minus the right one, its up runs from the ankles'
//     midpoint to the hips' (made square to left), its forward is left x up. The legs of a
//     standing rest pose are the surest vertical: CMU's head stands several degrees behind its
//     hip joints, and a rest pose may lean;
//   * each mapped canonical joint J has a rest orientation C_J: the rotation taking J's segment in
//     the canonical reference pose (body/humanoid.hpp: legs, arms and hands straight down, trunk
//     and head up, clavicles sideways) onto the same segment in the skeleton's rest pose. It is
//     built from the segment's direction (J to the next mapped joint along the body) and the
//     body's left axis (trunk, legs) or forward axis (clavicles, arms, hands); the hips' is the
//     body's facing. Feet and toes are taken as flat on the skeleton's floor in its rest pose:
//     their C is the facing turned about up to point along the foot.
//   * posing: a mapped skeleton joint s of canonical joint J with rest world rotation B_s gets the
//     world rotation Q_J * C_J^-1 * B_s (Q_J the BodyPose's rotation of J), so its bone turns from
//     the rest pose exactly as J turns from the reference pose, whatever the bone's roll; a joint
//     no canonical joint maps keeps its rest rotation relative to its parent. Local rotations are
//     parent_world^-1 * world.
// Positions and rotations come out in the BodyPose's world (Y up; the root's rotation carries the
// change from the skeleton's axes and facing), lengths in the skeleton's units.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "fuzzygait/body/humanoid.hpp"
#include "fuzzygait/body/humanoid_map.hpp"
#include "fuzzygait/body/skeleton.hpp"

namespace fuzzygait::body {

// The skeleton's proportions as a canonical Humanoid, metres:
//   legs      the rig's segments, each the mean of the two sides: thigh and shank from the bones;
//             the floor is the lowest of the toe bases, toe ends and heels in the rest pose (the
//             ankles less Winter's 0.039 stature when the feet have neither); ankle height above
//             it (Winter's 0.039 stature when under 5 mm); ball and toe along the foot; heel from
//             a heel joint, else Winter's foot proportions (0.25 : 0.48 of the ball's length); a
//             foot without toes splits its end point's distance 0.48 : 0.27 into ball and toe;
//   hips      hip width between the hip joints; hips.y the leg length;
//   trunk, arms, head: the bones' rest vectors turned into the reference pose, so a BodyPose of
//             this humanoid places every joint the skeleton maps where the posed skeleton has it;
//             a canonical joint the skeleton lacks takes humanoid_from_stature's offset with
//             stature (thigh + shank) / 0.491, or, between two mapped joints, a share of the
//             distance between them in humanoid_from_stature's proportions.
// An end point the map leaves out is the End Site of the joint before it, else that joint's first
// child (past children that lie on it). Stature: thigh + shank over 0.491 (Winter).
// Throws std::invalid_argument naming the joints for a skeleton or map that validate refuses,
// hip joints that coincide, a mapped bone of zero length, or proportions Humanoid's validate
// refuses.
Humanoid humanoid_from_skeleton(const Skeleton& skeleton, const HumanoidMap& map);

// The humanoid itself as a skeleton: its 21 joints named as VRM's (body::name), rest rotations
// none, the end points as End Sites, the root standing its hips' height above the floor, metres.
// map_humanoid finds every joint of it by name. Throws std::invalid_argument as validate does.
Skeleton skeleton_of(const Humanoid& humanoid);

// Poses one skeleton, every frame, without allocating: build once, call pose() per frame; const,
// so one poser serves many characters and threads.
class SkeletonPoser {
 public:
  // Throws as humanoid_from_skeleton does.
  SkeletonPoser(const Skeleton& skeleton, const HumanoidMap& map);

  // The humanoid to walk with: humanoid_from_skeleton(skeleton, map). A BodyPose of it puts the
  // posed skeleton's mapped joints where the BodyPose has them: exactly when the skeleton's legs
  // mirror each other, its toe bases lie on its floor and no unmapped canonical joint between
  // mapped ones turns (CMU's clavicles, which lie on its chest, stay unmapped and rigid with it);
  // otherwise within those differences, each mapped bone still turning from its rest pose as its
  // segment turns from the reference pose. A BodyPose of another humanoid is applied as rotations
  // (retargeting): the skeleton's hips follow the BodyPose's hips, its limbs keep their own
  // lengths.
  const Humanoid& humanoid() const { return humanoid_; }
  std::size_t joint_count() const { return parents_.size(); }

  // Writes each skeleton joint's local rotation (joint_count() of them) and the root joint's
  // position (skeleton units; it replaces the root's rest offset) for `pose`. Returns false and
  // writes the rest pose (rest rotations, the root's rest offset) when a rotation or the hips'
  // position of the pose is not finite; never throws. `local_rotations` must hold joint_count()
  // elements (asserted in debug builds).
  bool pose(const BodyPose& pose, std::span<Quat> local_rotations, Vec3& root_position) const;

  // The canonical world rotations that pose the skeleton into its own rest pose, turned to face
  // +Z with Y up (C_J relative to the facing): pose() of a BodyPose with these rotations gives
  // the rest local rotations below the root.
  const std::array<Quat, kJointCount>& rest_orientations() const { return rest_orientations_; }

  // The inverse of pose(): the BodyPose of humanoid() that a pose of the skeleton (its local
  // rotations and root position, as pose() writes them or a BVH frame holds them) shows, so a
  // clip of the game's skeleton can be measured or learned from as canonical angles. A mapped
  // canonical joint takes the rotation that pose() would turn into the skeleton joint's world
  // rotation, Q_J = W_s * B_s^-1 * C_J; an unmapped one its parent's; the hips sit where the
  // skeleton's hip joints' midpoint is, and the rest follows by forward_kinematics. `world` is
  // scratch of joint_count() rotations. Returns false and leaves `pose` alone when a value is
  // not finite or a span has another size; never throws or allocates.
  bool unpose(std::span<const Quat> local_rotations, Vec3 root_position, std::span<Quat> world,
              BodyPose& pose) const;

 private:
  Humanoid humanoid_;
  std::array<Quat, kJointCount> rest_orientations_{};
  std::vector<int> parents_;
  std::vector<Quat> rest_local_;
  // Each joint's world rotation is Q[anchor] * from_anchor (anchor: the canonical joint that
  // moves it, itself or its nearest mapped ancestor's; none above the hips: its rest rotation).
  std::vector<int> anchor_;
  std::vector<Quat> from_anchor_;
  std::vector<bool> mapped_;
  double units_per_metre_ = 1.0;
  int hips_joint_ = 0;
  Vec3 hips_joint_offset_;  // metres, canonical frame: the hips joint from the hips' midpoint
  Vec3 root_to_hips_rest_;  // skeleton units, rest world: from the root to the hips joint
  Vec3 root_rest_offset_;
  std::vector<Vec3> offsets_;  // rest offsets, skeleton units
};

}  // namespace fuzzygait::body

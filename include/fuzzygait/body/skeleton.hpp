// A game's skeleton as plain runtime data: joint names, parents, rest offsets and rest rotations in
// one flat array, parents before children. The body part poses it from a BodyPose
// (body/skeleton_poser.hpp); the offline library reads it from BVH and glTF (io/skeleton_file.hpp).
//
// Conventions, as BVH and glTF have them: a joint's rest transform is relative to its parent's
// frame: the joint lies at `offset` in its parent's frame, and its frame is its parent's rotated by
// `rotation`. Offsets are in the skeleton's units (centimetres for Mixamo's FBX-born rigs, CMU's
// 1/0.45 inch, metres for glTF); `metres_per_unit` converts them.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fuzzygait/body/math.hpp"

namespace fuzzygait::body {

struct SkeletonJoint {
  std::string name;
  int parent = -1;  // an earlier joint's index; -1 for the root, which is joint 0 and only it
  Vec3 offset;      // from the parent, in the parent's rest frame, skeleton units
  Quat rotation;    // rest rotation relative to the parent's (unit)
  // A BVH End Site: the end of the bone this joint starts, in this joint's frame. glTF has none.
  std::optional<Vec3> end;
};

struct Skeleton {
  std::vector<SkeletonJoint> joints;
  double metres_per_unit = 1.0;

  std::size_t size() const { return joints.size(); }
  // The joint named exactly `name`, or -1.
  int find(std::string_view name) const;
};

// Throws std::invalid_argument naming the joint when the skeleton is empty, a name is empty or
// repeated, a parent is not an earlier joint (a cycle or a parent after its child), a joint other
// than the first has no parent, an offset or end is not finite, a rotation is not a unit
// quaternion (within 1e-6), or metres_per_unit is not finite and positive. Bones of zero length
// are allowed (CMU's LHipJoint, glTF's helper nodes); where they matter, the humanoid map and
// humanoid_from_skeleton refuse them.
void validate(const Skeleton& skeleton);

// Rest-pose world positions (skeleton units, the root at its offset) and rotations, one per joint.
std::vector<Vec3> rest_positions(const Skeleton& skeleton);
std::vector<Quat> rest_world_rotations(const Skeleton& skeleton);

// Forward kinematics of a pose given as local rotations (one per joint) and the root's position
// (skeleton units; it replaces the root's offset): world positions (skeleton units) and world
// rotations. Every span holds skeleton.size() elements (the caller sizes them). No allocation.
void forward_kinematics(const Skeleton& skeleton, std::span<const Quat> local_rotations,
                        Vec3 root_position, std::span<Vec3> world_positions,
                        std::span<Quat> world_rotations);

}  // namespace fuzzygait::body

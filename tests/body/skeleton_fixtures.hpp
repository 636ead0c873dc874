// Skeletons and poses the skeleton tests share: a Mixamo-named rig and a VRM-named one built from
// joint positions, with any facing, unit and bone roll, and walking-like BodyPoses.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fuzzygait/body/humanoid.hpp"
#include "fuzzygait/body/humanoid_map.hpp"
#include "fuzzygait/body/skeleton.hpp"
#include "fuzzygait/body/skeleton_poser.hpp"

namespace fuzzygait::body::testing {

// A joint placed in the body's axes (metres, Y up, +Z forward, +X the character's left).
struct PlacedJoint {
  std::string name;
  std::string parent;  // empty for the root
  Vec3 position;
  bool end_site = false;  // the end of its parent's bone, kept as the parent's End Site
};

// The skeleton of `joints` turned by `facing` (from the body's axes into the skeleton's), in units
// of `metres_per_unit`, each joint given a rest rotation drawn from `roll_seed` (0: identity).
Skeleton build_skeleton(const std::vector<PlacedJoint>& joints, Quat facing, double metres_per_unit,
                        std::uint32_t roll_seed);

// A Mixamo rig ("mixamorig:" names, T-pose arms, toe bases on the floor), 1.80 m tall.
std::vector<PlacedJoint> mixamo_joints();
// A VRM-named rig with long legs, short arms in an A-pose, an upperChest, knees a little forward,
// no head or toe ends.
std::vector<PlacedJoint> vrm_joints();

// A pose of `humanoid`: walking-like flexion of hips, knees, ankles and toes at `phase`
// (radians), arms swinging, trunk turning, the whole body turned by `yaw` and, with `jitter`
// seeded non-zero, every joint turned a little more at random.
BodyPose walking_pose(const Humanoid& humanoid, double phase, double yaw, std::uint32_t jitter);

// Each component within `tolerance`; `what` names the failure.
void expect_near(Vec3 a, Vec3 b, double tolerance, const std::string& what);
// The same rotation (q and -q are): |q . r| within `tolerance` of 1.
void expect_same_rotation(Quat a, Quat b, double tolerance, const std::string& what);

// The (canonical joint, skeleton joint name) pairs of a map, as a map by hand gives them.
std::vector<NamedJoint> named_joints(const HumanoidMap& map, const Skeleton& skeleton);

// The posed skeleton's joint positions, metres. Fails the test when pose() refuses.
std::vector<Vec3> posed_positions(const Skeleton& skeleton, const SkeletonPoser& poser,
                                  const BodyPose& pose, std::vector<Quat>* local = nullptr);

}  // namespace fuzzygait::body::testing

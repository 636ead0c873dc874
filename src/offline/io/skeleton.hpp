// The skeleton the BVH and glTF writers share (include/fuzzygait/io/bvh.hpp explains it): the
// rig's legs set apart by a hip width, a static trunk in Winter's proportions, and which angle of
// a frame turns each joint about the lateral axis.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fuzzygait/rig/rig.hpp"

namespace fuzzygait::io::detail {

// Stature proportions (Winter 2009, Fig. 4.1) for the static trunk.
inline constexpr double kHipHeight = 0.530;
inline constexpr double kSpineAboveHips = 0.100;
inline constexpr double kShoulderHeight = 0.818;
inline constexpr double kChinHeight = 0.870;

// The stature a leg length stands for (the hip joint at 0.530 of it).
inline double stature_of(const rig::Segments& segments) {
  return segments.leg_length() / kHipHeight;
}

// Metres, Y up, Z forward, X to the character's left.
struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

// Which angle of a frame a joint's rotation about X comes from.
enum class Drive { PelvisTilt, Hip, Knee, Ankle, Toe, UprightTrunk, Still };

struct Joint {
  std::string name;
  Vec3 offset;  // from the parent joint, in the rest pose
  Drive drive = Drive::Still;
  int leg = 0;  // rig::index of the side, for the legs' drives
  std::vector<Joint> children;
  std::optional<Vec3> end_site;  // a leaf's tip (toes, top of the head), from the joint
};

// Hips (root, at the origin) with LeftUpLeg > LeftLeg > LeftFoot > LeftToeBase, the same on the
// right, and Spine > Neck > Head; the legs `hip_width` apart.
Joint skeleton(const rig::Segments& segments, double hip_width);

// The joint's rotation about +X (right-handed: positive turns +Y towards +Z), radians: minus its
// counter-clockwise angle in the (forward, up) plane, the sense in which the rig's inclinations
// and pitches add up (rig::orientation).
double x_rotation(const Joint& joint, const rig::Pose& pose);

}  // namespace fuzzygait::io::detail

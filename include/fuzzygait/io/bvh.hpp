// BVH (Biovision Hierarchy) export of a walk, for Blender, three.js and other animation tools.
//
// The skeleton (names as in most mocap files, so retargeting tools map them by themselves):
//   Hips (root: Xposition Yposition Zposition, then rotations)
//     LeftUpLeg > LeftLeg > LeftFoot > LeftToeBase > End Site (tip of the toes)
//     RightUpLeg > RightLeg > RightFoot > RightToeBase > End Site
//     Spine > Neck > Head > End Site (top of the head)
// Conventions:
//   axes       Y up, Z forward (the walk's x), X to the character's left: the character faces
//              and walks towards +Z, as in CMU's and most other BVH files. Blender's importer
//              (forward -Z, up Y by default) turns it to face -Y, its front view.
//   units      centimetres (BvhOptions::units_per_metre); Frame Time is 1 / the motion's fps.
//   rest pose  standing upright: legs straight down, feet flat and pointing forward, every
//              clinical angle zero.
//   root       OFFSET 0 0 0, and the position channels hold the hip joint centre's midpoint:
//              importers disagree whether root positions replace the offset (Blender) or add to
//              it (three.js); with a zero offset both put the pelvis where the walk has it.
//   rotations  channels Zrotation Yrotation Xrotation on every joint; a walk only uses Xrotation
//              (degrees, right-handed about +X, so positive turns +Y towards +Z), Z and Y stay 0:
//                Hips      +pelvis tilt   (anterior tilt leans the pelvis forward)
//                UpLeg     -hip flexion   (relative to the pelvis)
//                Leg       +knee flexion
//                Foot      -ankle dorsiflexion
//                ToeBase   -MTP extension
//                Spine     -pelvis tilt   (the trunk stays upright, as the lumbar spine does)
//                Neck/Head  0
//   offsets    from the rig's segments, so forward kinematics of the file reproduces the walk's
//              hip, knee, ankle, ball and toe-tip points (laterally apart by the hip width):
//                UpLeg   (+-hip width / 2, 0, 0)     Leg      (0, -thigh, 0)
//                Foot    (0, -shank, 0)              ToeBase  (0, -ankle height, ball)
//                toe End Site (0, 0, toe)
//              trunk from stature = leg length / 0.530 with Winter's (2009, Fig. 4.1)
//              proportions: Spine 0.100 H above the hips (lumbar), Neck at shoulder height
//              0.818 H, Head at chin height 0.870 H, head top at 1.000 H.
// Output is deterministic (same motion and options, same bytes): fixed six decimals, '\n'.
#pragma once

#include <iosfwd>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/rig/rig.hpp"

namespace fuzzygait::io {

struct BvhOptions {
  double units_per_metre = 100.0;  // centimetres
  // Distance between the hip joint centres over leg length. The walk is sagittal (both hips at
  // one point); the file sets the legs apart so both show. 0.19 x 0.93 m = 0.176 m for the
  // default 1.75 m rig, as Bell, Pedersen & Brand (1990, J Biomech 23:617) place the hip joint
  // centres: 14 % of the inter-ASIS width medial to each ASIS (0.72 x an adult's ~0.245 m).
  double hip_width_per_leg_length = 0.19;
};

// Lateral distance between the two hip joints, metres.
double bvh_hip_width(const rig::Segments& segments, const BvhOptions& options = {});

// Throws std::invalid_argument for a motion without frames, a bad fps or rig, a non-finite
// value in a frame (naming it), or options out of range.
void write_bvh(std::ostream& out, const eval::Motion& motion, const BvhOptions& options = {});

}  // namespace fuzzygait::io

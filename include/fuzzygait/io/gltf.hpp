// glTF 2.0 export of a walk as one binary file (.glb), for game engines, three.js, Blender and
// other tools: the character's skeleton and animation, a skinned body that shows the walk without
// a rig of one's own, and the ground walked on.
//
// What the file holds (one scene, docs/gltf.md has the details):
//   skeleton   the BVH writer's joints and rest pose (bvh.hpp explains offsets, hip width and the
//              trunk's proportions): Hips > LeftUpLeg > LeftLeg > LeftFoot > LeftToeBase >
//              LeftToe_End, the same on the right, and Hips > Spine > Neck > Head > HeadTop_End
//              (the _End leaves are BVH's End Sites: the toe tips and the top of the head).
//   animation  "Walk": for each of the twelve joints a rotation channel, unit quaternions about
//              +X only (the angles bvh.hpp lists), and the Hips' translation (the midpoint of the
//              hip joint centres); keyed at the frames' times (seconds), LINEAR.
//   body       the mesh "Body", skinned to the skeleton rigidly (each vertex to one joint, weight
//              1): low-poly capsules for thighs, shanks, feet and toes, a pelvis, a trunk with
//              shoulders, a neck, a head with a nose (it shows which way the character faces), and
//              arms hanging along the trunk, carried by the Spine (the skeleton has no arm
//              joints). Four flat materials: Shirt, Trousers, Skin, Shoes. Sizes from the stature
//              the leg length stands for (leg length / 0.530, Winter 2009).
//   ground     the mesh "Ground": the terrain's profile under the walk, from ground_margin behind
//              the rearmost pelvis position to as far past the foremost, extruded ground_width
//              across and cut into square tiles of two materials (Ground light, Ground dark) so
//              that a planted foot visibly stays put; flat-shaded, with normals.
// Conventions: Y up, Z forward (the walk's x), X to the character's left; the character faces
// +Z, glTF's front. Metres and seconds. Without its animation the character stands in its rest
// pose at the origin, feet on y = 0, every clinical angle zero.
// Output is deterministic: the same motion, terrain and options give the same bytes.
#pragma once

#include <filesystem>
#include <iosfwd>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::io {

struct GltfOptions {
  // As BvhOptions::hip_width_per_leg_length: the hip joints' distance over the leg length.
  double hip_width_per_leg_length = 0.19;
  double ground_width = 1.5;   // metres across the walk, centred on it; 0.1 to 100
  double ground_margin = 2.0;  // metres of ground behind and ahead of the pelvis; 0.1 to 100
  double ground_tile = 0.5;    // edge of the ground's checker tiles, metres; 0.05 to 100
};

// Writes `motion` walking on `ground` as binary glTF. Throws std::invalid_argument, before
// writing anything, for a motion without frames, an fps that is not a positive number, a bad rig
// (rig::validate), a frame with a value that is not finite, a position beyond
// terrain::Terrain::kMaxCoordinate or times that are negative or do not increase (naming the
// frame and the field; times are compared as the file's 32-bit floats), options out of range, or
// a file that would pass glTF's 4 GiB limit. Throws std::runtime_error when the stream fails.
void write_gltf(std::ostream& out, const eval::Motion& motion, const terrain::Terrain& ground,
                const GltfOptions& options = {});

// The same with the default options into the file at `path`, through write_file (which names
// the file in its errors).
void write_gltf(const std::filesystem::path& path, const eval::Motion& motion,
                const terrain::Terrain& ground);

}  // namespace fuzzygait::io

// A game's skeleton in and out of files: read from a BVH hierarchy or a glTF skin, and a posed
// skeleton's animation written as BVH or binary glTF.
#pragma once

#include <array>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "fuzzygait/body/humanoid_map.hpp"
#include "fuzzygait/body/skeleton.hpp"
#include "fuzzygait/io/mocap.hpp"

namespace fuzzygait::io {

// The hierarchy of a BVH clip as a Skeleton: its joints in file order, each End Site the end of
// its joint's bone, rest rotations the identity (BVH's rest pose), offsets in the file's units
// (the root's OFFSET included). metres_per_unit: as given, else the one of m, cm, mm, inch and CMU
// units (1/0.45 inch) that makes the left leg's hip-to-ankle length (body::map_humanoid's joints)
// closest to 0.80 m, as analyse_clip guesses; 1 when the legs cannot be found. Throws
// std::invalid_argument for a given metres_per_unit that is not finite and positive.
body::Skeleton skeleton_from_bvh(const BvhClip& clip,
                                 std::optional<double> metres_per_unit = std::nullopt);
// read_bvh_file, then skeleton_from_bvh.
body::Skeleton read_bvh_skeleton(const std::filesystem::path& path,
                                 std::optional<double> metres_per_unit = std::nullopt);

// Frame `frame` of a clip as the local rotations of skeleton_from_bvh(clip)'s joints (R(ch1)
// R(ch2) R(ch3) in the order of each CHANNELS line; degrees in the file) and the root's position
// (its OFFSET plus its position channels, file units). `local_rotations` holds one per non-End
// Site joint. Throws std::out_of_range for a frame beyond the clip, std::invalid_argument for a
// span of another size.
void bvh_frame(const BvhClip& clip, std::size_t frame, std::span<body::Quat> local_rotations,
               body::Vec3& root_position);

// The skeleton of a glTF (.gltf or .glb) skin: its joints (parents before children, in skin
// order otherwise), each node's translation and rotation (or matrix) as the rest offset and
// rotation. The nodes above the skin's root (an armature) fold into the root's offset and
// rotation, and their uniform scale times the root's becomes metres_per_unit (glTF's unit is the
// metre: an armature scaled 0.01 holds centimetres); the other joints' scales are ignored. Node
// names are the joints' names (a nameless node becomes "joint<N>"). Throws std::invalid_argument
// naming the file for a file TinyGLTF cannot load, no skin or a skin index out of range, a skin
// whose joints do not form one tree, a node with a non-uniform or non-positive scale.
body::Skeleton read_gltf_skeleton(const std::filesystem::path& path, int skin = 0);

// The humanoid map a VRM file declares (a glTF or GLB, .vrm included, with the VRMC_vrm 1.0 or
// the VRM 0.x extension): each human bone's node, found in `skeleton` (read_gltf_skeleton of the
// same file) by its name. VRM's bone names are the canonical joints' (body::name); its
// MiddleProximal finger bones stand for the hands' ends; bones the canonical body lacks
// (upperChest, eyes, jaw, the other fingers) are left out. std::nullopt when the file has neither
// extension. Throws std::invalid_argument naming the file for a file TinyGLTF cannot load, a bone
// whose node is not a joint of `skeleton`, or a map that body::validate refuses.
std::optional<body::HumanoidMap> read_vrm_humanoid_map(const std::filesystem::path& path,
                                                       const body::Skeleton& skeleton);

struct SkeletonBvhOptions {
  // The rotation channels' order, the same on every joint: R = R(first) R(second) R(third).
  std::string rotation_order = "ZXY";
  int decimals = 6;                // of offsets, positions (skeleton units) and angles (degrees)
  double frame_time = 1.0 / 60.0;  // s
};

// Writes a posed skeleton's animation: HIERARCHY with the skeleton's joints depth first (children
// in joint order), their offsets and End Sites, the root's OFFSET 0 0 0 (importers disagree
// whether position channels replace the offset or add to it; with a zero offset both put the root
// at root_positions), root channels Xposition Yposition Zposition then the three rotations, every
// other joint's three rotations; MOTION with one line per frame: the root's position then each
// joint's Euler angles in degrees. Forward kinematics of the file is the skeleton's (a joint's
// rest rotation, which BVH cannot hold, is part of its channels' rotation).
// `local_rotations` holds skeleton.size() rotations per frame, frame after frame;
// `root_positions` one per frame (skeleton units). The bytes depend only on the arguments: fixed
// decimals, no "-0", '\n' line ends. Throws std::invalid_argument for an invalid skeleton, spans
// that disagree, no frame, a value that is not finite, a rotation order that is not a permutation
// of "XYZ", decimals outside 1 to 12, a frame time outside 1e-4 to 1 s.
void write_skeleton_bvh(std::ostream& out, const body::Skeleton& skeleton,
                        std::span<const body::Quat> local_rotations,
                        std::span<const body::Vec3> root_positions,
                        const SkeletonBvhOptions& options = {});

struct SkeletonGltfOptions {
  double frame_time = 1.0 / 60.0;  // s between keys; 1e-4 to 1
};

// Writes a posed skeleton's animation as binary glTF 2.0 (.glb), one scene (docs/gltf.md, "The
// whole body"): a node "Armature" holding the joints as nodes in the skeleton's hierarchy and
// order, named as the joints, each with its rest offset as translation and rest rotation as
// rotation; a skin over the joints in skeleton order with inverse bind matrices of the rest
// pose; a mesh "Body" skinned to them, a thin octahedron along each bone (parent to child, and to
// its End Site), every vertex weighted 1 to the bone's joint; an animation "Walk", LINEAR, keyed
// at frame f's time f * frame_time: each joint's rotation, the root's translation. glTF's unit is
// the metre: offsets and root positions are multiplied by skeleton.metres_per_unit (rotations are
// unchanged), so forward kinematics of the file is the skeleton's (body::forward_kinematics)
// times metres_per_unit, to 32-bit float precision. Same span contract as write_skeleton_bvh:
// `local_rotations` holds skeleton.size() rotations per frame, frame after frame (each a unit
// quaternion, within 1e-6); `root_positions` one per frame (skeleton units). The bytes depend only
// on the arguments. Throws std::invalid_argument before writing anything for an invalid skeleton
// or one of more than 65,536 joints, spans that disagree, no frame, a value that is not finite or
// not a 32-bit float in metres, a rotation that is not a unit quaternion, a frame time outside
// 1e-4 to 1 s or frame times that do not increase as 32-bit floats, or a file over glTF's 4 GiB;
// std::runtime_error when the stream fails.
void write_skeleton_gltf(std::ostream& out, const body::Skeleton& skeleton,
                         std::span<const body::Quat> local_rotations,
                         std::span<const body::Vec3> root_positions,
                         const SkeletonGltfOptions& options = {});
// The same into the file at `path`, through write_file (which names the file in its errors); a
// refused animation leaves no file.
void write_skeleton_gltf(const std::filesystem::path& path, const body::Skeleton& skeleton,
                         std::span<const body::Quat> local_rotations,
                         std::span<const body::Vec3> root_positions,
                         const SkeletonGltfOptions& options = {});

// The Euler angles (radians) of a rotation for an order such as "ZXY": q = R_Z(a) R_X(b) R_Y(c)
// with b in [-pi/2, pi/2]; at b = +-pi/2 (gimbal lock) c is 0. Throws std::invalid_argument for
// an order that is not a permutation of "XYZ".
std::array<double, 3> euler_angles(body::Quat q, std::string_view order);

}  // namespace fuzzygait::io

// io::write_skeleton_gltf read back with TinyGLTF: the joints' nodes, names, hierarchy and rest
// transforms are the skeleton's (in metres), the skin's inverse bind matrices undo the rest pose,
// every mesh vertex is weighted 1 to a joint, and the animation "Walk" played by forward
// kinematics of the file's nodes (at keys and halfway between them) lands every joint where
// body::forward_kinematics puts it, for a Mixamo-named rig in centimetres, a VRM-named one in
// metres and CMU's skeleton read from BVH; the bytes are deterministic; refusals come before
// anything is written.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <numbers>
#include <span>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "body/skeleton_fixtures.hpp"
#include "fuzzygait/body/humanoid_map.hpp"
#include "fuzzygait/body/skeleton_poser.hpp"
#include "fuzzygait/io/skeleton_file.hpp"

namespace fuzzygait::io {
namespace {

using body::Quat;
using body::Vec3;
using body::testing::expect_near;

constexpr double kPi = std::numbers::pi;
// Forward kinematics of the file's 32-bit floats against the skeleton's doubles, metres.
constexpr double kPositionTolerance = 1e-5;
constexpr double kFrameTime = 1.0 / 30.0;

body::SkeletonJoint make_joint(std::string name, int parent, Vec3 offset) {
  body::SkeletonJoint made;
  made.name = std::move(name);
  made.parent = parent;
  made.offset = offset;
  return made;
}

struct Posed {
  std::vector<Quat> rotations;  // skeleton.size() a frame
  std::vector<Vec3> roots;
};

Posed walk(const body::Skeleton& skeleton, int frames) {
  const body::SkeletonPoser poser(skeleton, body::map_humanoid(skeleton));
  Posed posed;
  posed.rotations.resize(skeleton.size() * static_cast<std::size_t>(frames));
  for (int f = 0; f < frames; ++f) {
    const body::BodyPose pose = body::testing::walking_pose(poser.humanoid(), 0.4 * f, 0.15 * f,
                                                            static_cast<std::uint32_t>(f + 1));
    Vec3 root;
    poser.pose(pose,
               std::span<Quat>(posed.rotations)
                   .subspan(static_cast<std::size_t>(f) * skeleton.size(), skeleton.size()),
               root);
    posed.roots.push_back(root);
  }
  return posed;
}

std::string written(const body::Skeleton& skeleton, const Posed& posed) {
  std::ostringstream out;
  write_skeleton_gltf(out, skeleton, posed.rotations, posed.roots, {.frame_time = kFrameTime});
  return out.str();
}

tinygltf::Model read_back(const std::string& bytes) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  const bool loaded = loader.LoadBinaryFromMemory(
      &model, &error, &warning, reinterpret_cast<const unsigned char*>(bytes.data()),
      static_cast<unsigned int>(bytes.size()));
  EXPECT_TRUE(loaded) << error;
  EXPECT_EQ(warning, "");
  return model;
}

// An accessor's values as doubles (floats, bytes or shorts), components in order.
std::vector<double> values(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& accessor = model.accessors.at(static_cast<std::size_t>(index));
  const tinygltf::BufferView& view =
      model.bufferViews.at(static_cast<std::size_t>(accessor.bufferView));
  const unsigned char* data = model.buffers.at(static_cast<std::size_t>(view.buffer)).data.data() +
                              view.byteOffset + accessor.byteOffset;
  const std::size_t count =
      accessor.count * static_cast<std::size_t>(tinygltf::GetNumComponentsInType(
                           static_cast<std::uint32_t>(accessor.type)));
  EXPECT_EQ(view.byteStride, 0u);
  std::vector<double> out(count);
  for (std::size_t i = 0; i < count; ++i) {
    switch (accessor.componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float v;
        std::memcpy(&v, data + 4 * i, 4);
        out[i] = v;
        break;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v;
        std::memcpy(&v, data + 2 * i, 2);
        out[i] = v;
        break;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        out[i] = data[i];
        break;
      default:
        ADD_FAILURE() << "component type " << accessor.componentType;
    }
  }
  return out;
}

Quat slerp(Quat a, Quat b, double t) {
  double d = a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
  if (d < 0.0) {
    b = {-b.w, -b.x, -b.y, -b.z};
    d = -d;
  }
  const double angle = std::acos(std::min(1.0, d));
  const double s = std::sin(angle);
  const double wa = s < 1e-9 ? 1.0 - t : std::sin((1.0 - t) * angle) / s;
  const double wb = s < 1e-9 ? t : std::sin(t * angle) / s;
  return body::normalized(
      {wa * a.w + wb * b.w, wa * a.x + wb * b.x, wa * a.y + wb * b.y, wa * a.z + wb * b.z});
}

// The file's animation "Walk" at `time` (LINEAR: translations lerped, rotations slerped), then
// forward kinematics from the scene's roots: every node's world position, metres.
std::vector<Vec3> play(const tinygltf::Model& model, double time) {
  std::vector<Vec3> translation(model.nodes.size());
  std::vector<Quat> rotation(model.nodes.size());
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    const tinygltf::Node& node = model.nodes[n];
    EXPECT_TRUE(node.scale.empty() && node.matrix.empty()) << node.name;
    if (node.translation.size() == 3)
      translation[n] = {node.translation[0], node.translation[1], node.translation[2]};
    if (node.rotation.size() == 4)
      rotation[n] = {node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]};
  }
  const tinygltf::Animation& walk = model.animations.at(0);
  for (const tinygltf::AnimationChannel& channel : walk.channels) {
    const tinygltf::AnimationSampler& sampler =
        walk.samplers.at(static_cast<std::size_t>(channel.sampler));
    EXPECT_EQ(sampler.interpolation, "LINEAR");
    const std::vector<double> times = values(model, sampler.input);
    const std::vector<double> keys = values(model, sampler.output);
    std::size_t k = 0;
    while (k + 1 < times.size() && times[k + 1] <= time)
      ++k;
    const std::size_t next = std::min(k + 1, times.size() - 1);
    const double t =
        next == k ? 0.0 : std::clamp((time - times[k]) / (times[next] - times[k]), 0.0, 1.0);
    const auto n = static_cast<std::size_t>(channel.target_node);
    if (channel.target_path == "translation") {
      const Vec3 a{keys[3 * k], keys[3 * k + 1], keys[3 * k + 2]};
      const Vec3 b{keys[3 * next], keys[3 * next + 1], keys[3 * next + 2]};
      translation[n] = a + t * (b - a);
    } else {
      EXPECT_EQ(channel.target_path, "rotation");
      const Quat a{keys[4 * k + 3], keys[4 * k], keys[4 * k + 1], keys[4 * k + 2]};
      const Quat b{keys[4 * next + 3], keys[4 * next], keys[4 * next + 1], keys[4 * next + 2]};
      rotation[n] = slerp(a, b, t);
    }
  }
  std::vector<Vec3> position(model.nodes.size());
  std::vector<Quat> world(model.nodes.size());
  const auto visit = [&](auto& self, int node, Vec3 at, Quat turned) -> void {
    const auto n = static_cast<std::size_t>(node);
    position[n] = at + body::rotate(turned, translation[n]);
    world[n] = turned * rotation[n];
    for (const int child : model.nodes[n].children)
      self(self, child, position[n], world[n]);
  };
  for (const int root : model.scenes.at(0).nodes)
    visit(visit, root, Vec3{}, Quat{});
  return position;
}

// What every test checks of a rig's file.
void expect_plays_as_the_skeleton(const body::Skeleton& skeleton, const std::string& rig) {
  const std::size_t n = skeleton.size();
  const Posed posed = walk(skeleton, 12);
  const std::size_t frames = posed.roots.size();
  const std::string bytes = written(skeleton, posed);
  EXPECT_EQ(bytes, written(skeleton, posed)) << "the same arguments gave other bytes";
  const tinygltf::Model model = read_back(bytes);
  const double metres = skeleton.metres_per_unit;

  // Nodes: Armature, the joints in skeleton order, Body; one scene of Armature and Body.
  EXPECT_EQ(model.nodes.size(), n + 2);
  EXPECT_EQ(model.nodes.at(0).name, "Armature");
  EXPECT_EQ(model.nodes.at(0).children, std::vector<int>{1});
  EXPECT_EQ(model.scenes.size(), 1u);
  EXPECT_EQ(model.scenes.at(0).nodes, (std::vector<int>{0, static_cast<int>(n + 1)}));
  for (std::size_t i = 0; i < n; ++i) {
    const body::SkeletonJoint& joint = skeleton.joints[i];
    const tinygltf::Node& node = model.nodes.at(i + 1);
    EXPECT_EQ(node.name, joint.name);
    std::vector<int> children;
    for (std::size_t c = 0; c < n; ++c) {
      if (skeleton.joints[c].parent == static_cast<int>(i))
        children.push_back(static_cast<int>(c + 1));
    }
    EXPECT_EQ(node.children, children) << joint.name;
    ASSERT_EQ(node.translation.size(), 3u);
    expect_near({node.translation[0], node.translation[1], node.translation[2]},
                metres * joint.offset, 1e-12, rig + " offset of " + joint.name);
    ASSERT_EQ(node.rotation.size(), 4u);
    body::testing::expect_same_rotation(
        {node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]}, joint.rotation,
        1e-12, rig + " rest rotation of " + joint.name);
  }

  // The skin: the joints in skeleton order; each inverse bind matrix takes the joint's rest
  // position to the origin and its rest axes to the world's.
  EXPECT_EQ(model.skins.size(), 1u);
  const tinygltf::Skin& skin = model.skins.at(0);
  EXPECT_EQ(skin.skeleton, 1);
  std::vector<Vec3> rest = body::rest_positions(skeleton);
  const std::vector<Quat> rest_rotations = body::rest_world_rotations(skeleton);
  const std::vector<double> inverse = values(model, skin.inverseBindMatrices);
  ASSERT_EQ(inverse.size(), 16 * n);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(skin.joints.at(i), static_cast<int>(i + 1));
    const double* m = &inverse[16 * i];  // column-major
    const auto apply = [m](Vec3 p, double w) {
      return Vec3{m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12] * w,
                  m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13] * w,
                  m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14] * w};
    };
    expect_near(apply(metres * rest[i], 1.0), {}, 1e-5,
                rig + " bind of " + skeleton.joints[i].name);
    for (const Vec3 axis : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}) {
      expect_near(apply(body::rotate(rest_rotations[i], axis), 0.0), axis, 1e-6,
                  rig + " bind axes of " + skeleton.joints[i].name);
    }
    EXPECT_EQ(m[3], 0.0);
    EXPECT_EQ(m[7], 0.0);
    EXPECT_EQ(m[11], 0.0);
    EXPECT_EQ(m[15], 1.0);
  }

  // The body: one skinned primitive, each vertex weighted 1 to one joint.
  const tinygltf::Node& body_node = model.nodes.at(n + 1);
  EXPECT_EQ(body_node.name, "Body");
  EXPECT_EQ(body_node.skin, 0);
  const tinygltf::Primitive& primitive = model.meshes.at(0).primitives.at(0);
  const std::vector<double> joints = values(model, primitive.attributes.at("JOINTS_0"));
  const std::vector<double> weights = values(model, primitive.attributes.at("WEIGHTS_0"));
  const std::vector<double> positions = values(model, primitive.attributes.at("POSITION"));
  ASSERT_EQ(joints.size(), weights.size());
  ASSERT_EQ(positions.size() / 3, joints.size() / 4);
  EXPECT_GT(positions.size(), 0u);
  for (std::size_t v = 0; v < joints.size() / 4; ++v) {
    EXPECT_LT(joints[4 * v], static_cast<double>(n));
    EXPECT_EQ(weights[4 * v], 1.0);
    EXPECT_EQ(weights[4 * v + 1] + weights[4 * v + 2] + weights[4 * v + 3], 0.0);
  }

  // The animation: "Walk", the root's translation and every joint's rotation, keyed at f x the
  // frame time.
  ASSERT_EQ(model.animations.size(), 1u);
  const tinygltf::Animation& animation = model.animations.at(0);
  EXPECT_EQ(animation.name, "Walk");
  EXPECT_EQ(animation.channels.size(), n + 1);
  const std::vector<double> times = values(model, animation.samplers.at(0).input);
  ASSERT_EQ(times.size(), frames);
  for (std::size_t f = 0; f < frames; ++f) {
    EXPECT_EQ(times[f], static_cast<float>(static_cast<double>(f) * kFrameTime));
  }

  // Played, at every key and halfway between keys, it is the skeleton's forward kinematics.
  double worst = 0.0;
  std::vector<Vec3> expected(n);
  std::vector<Quat> world(n);
  std::vector<Quat> between(n);
  for (std::size_t f = 0; f < frames; ++f) {
    const std::span<const Quat> frame = std::span<const Quat>(posed.rotations).subspan(f * n, n);
    for (const bool halfway : {false, true}) {
      if (halfway && f + 1 == frames) continue;
      Vec3 root = posed.roots[f];
      if (halfway) {
        root = root + 0.5 * (posed.roots[f + 1] - root);
        for (std::size_t i = 0; i < n; ++i)
          between[i] = slerp(frame[i], posed.rotations[(f + 1) * n + i], 0.5);
      }
      body::forward_kinematics(skeleton, halfway ? std::span<const Quat>(between) : frame, root,
                               expected, world);
      const std::vector<Vec3> seen =
          play(model, halfway ? 0.5 * (times[f] + times[f + 1]) : times[f]);
      for (std::size_t i = 0; i < n; ++i) {
        const Vec3 d = seen[i + 1] - metres * expected[i];
        worst = std::max({worst, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
      }
    }
  }
  std::cout << rig << ": " << n << " joints, " << frames << " frames, " << bytes.size()
            << " bytes; forward kinematics of the file within " << worst * 1e3
            << " mm of the skeleton's\n";
  EXPECT_LE(worst, kPositionTolerance) << rig;

  // TinyGLTF's skin reader gives the skeleton back, in metres.
  const std::filesystem::path file =
      std::filesystem::path(::testing::TempDir()) / ("skeleton_gltf_" + rig + ".glb");
  write_skeleton_gltf(file, skeleton, posed.rotations, posed.roots, {.frame_time = kFrameTime});
  std::ifstream in(file, std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), bytes) << "the path overload";
  const body::Skeleton back = read_gltf_skeleton(file);
  EXPECT_DOUBLE_EQ(back.metres_per_unit, 1.0);
  EXPECT_EQ(back.size(), n);
  for (std::size_t i = 0; i < std::min(n, back.size()); ++i) {
    EXPECT_EQ(back.joints[i].name, skeleton.joints[i].name);
    EXPECT_EQ(back.joints[i].parent, skeleton.joints[i].parent);
    expect_near(back.joints[i].offset, metres * skeleton.joints[i].offset, 1e-12, rig);
  }
}

TEST(GltfSkeletonAnimation, MixamoRigInCentimetresPlaysAsItsForwardKinematics) {
  const body::Skeleton mixamo = body::testing::build_skeleton(
      body::testing::mixamo_joints(), body::axis_angle({0, 1, 0}, kPi), 0.01, 31);
  expect_plays_as_the_skeleton(mixamo, "mixamo_cm");
}

TEST(GltfSkeletonAnimation, VrmRigPlaysAsItsForwardKinematics) {
  const body::Skeleton vrm = body::testing::build_skeleton(
      body::testing::vrm_joints(), body::axis_angle({0, 1, 0}, 0.7), 1.0, 5);
  expect_plays_as_the_skeleton(vrm, "vrm_m");
}

TEST(GltfSkeletonAnimation, CmuSkeletonWithEndSitesPlaysAsItsForwardKinematics) {
  const body::Skeleton cmu =
      read_bvh_skeleton(std::filesystem::path(FUZZYGAIT_SOURCE_DIR) / "data/mocap/cmu/07_01.bvh");
  expect_plays_as_the_skeleton(cmu, "cmu");
}

TEST(GltfSkeletonAnimation, SkeletonWithoutBonesStillHasABody) {
  body::Skeleton point;
  point.joints.push_back(make_joint("root", -1, {1, 2, 3}));
  const std::vector<Quat> rotations(2);
  const std::vector<Vec3> roots = {{0, 1, 0}, {0, 1, 1}};
  std::ostringstream out;
  write_skeleton_gltf(out, point, rotations, roots);
  const tinygltf::Model model = read_back(out.str());
  const tinygltf::Primitive& primitive = model.meshes.at(0).primitives.at(0);
  EXPECT_EQ(values(model, primitive.attributes.at("POSITION")).size(), 6u * 3u);
  EXPECT_EQ(values(model, primitive.indices).size(), 8u * 3u);
}

TEST(GltfSkeletonAnimation, WriterRefusesBeforeWritingAnything) {
  const body::Skeleton vrm =
      body::testing::build_skeleton(body::testing::vrm_joints(), Quat{}, 1.0, 0);
  const Posed posed = walk(vrm, 2);
  const auto refused = [&](const body::Skeleton& skeleton, std::vector<Quat> rotations,
                           std::vector<Vec3> roots, SkeletonGltfOptions options,
                           const std::string& expected) {
    std::ostringstream out;
    try {
      write_skeleton_gltf(out, skeleton, rotations, roots, options);
      ADD_FAILURE() << "written, though: " << expected;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
    }
    EXPECT_EQ(out.str(), "") << expected;
  };
  const SkeletonGltfOptions fine;
  body::Skeleton twice = vrm;
  twice.joints[2].name = twice.joints[1].name;
  refused(twice, posed.rotations, posed.roots, fine, twice.joints[1].name);
  body::Skeleton no_unit = vrm;
  no_unit.metres_per_unit = 0.0;
  refused(no_unit, posed.rotations, posed.roots, fine, "metres");
  refused(vrm, {}, {}, fine, "no frame");
  refused(vrm, posed.rotations, {posed.roots[0]}, fine, "rotations for 1 frames");
  std::vector<Quat> rotations = posed.rotations;
  rotations[vrm.size() + 3].x = std::nan("");
  refused(vrm, rotations, posed.roots, fine, "frame 1: the rotation of 'upperChest' is not finite");
  rotations[vrm.size() + 3] = {0.5, 0.5, 0.5, 0.6};
  refused(vrm, rotations, posed.roots, fine, "'upperChest' is not a unit quaternion");
  std::vector<Vec3> roots = posed.roots;
  roots[1].y = std::numeric_limits<double>::infinity();
  refused(vrm, posed.rotations, roots, fine, "frame 1: the root position is not finite");
  roots[1].y = 1e39;
  refused(vrm, posed.rotations, roots, fine, "does not fit a 32-bit float");
  for (const double frame_time : {0.0, 5e-5, 2.0, std::nan("")}) {
    refused(vrm, posed.rotations, posed.roots, {.frame_time = frame_time}, "frame time");
  }
  body::Skeleton crowded;
  for (int i = 0; i <= 65536; ++i) {
    crowded.joints.push_back(make_joint("j" + std::to_string(i), i - 1, {0, 1, 0}));
  }
  refused(crowded, std::vector<Quat>(crowded.size()), {Vec3{}}, fine, "65537 joints");

  // Through a path: the refusal leaves no file; an unwritable path is named.
  const std::filesystem::path file = std::filesystem::path(::testing::TempDir()) / "refused.glb";
  std::filesystem::remove(file);
  EXPECT_THROW(write_skeleton_gltf(file, vrm, posed.rotations, {}), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(file));
  const std::filesystem::path nowhere = file.parent_path() / "no such folder" / "body.glb";
  try {
    write_skeleton_gltf(nowhere, vrm, posed.rotations, posed.roots);
    ADD_FAILURE() << "wrote into a missing folder";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(nowhere.string()), std::string::npos);
  }
}

}  // namespace
}  // namespace fuzzygait::io

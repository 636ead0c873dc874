// glTF export read back with TinyGLTF itself: the nodes are the BVH skeleton in metres, forward
// kinematics of the file's nodes and animation lands on the walk's joint points, the animation
// keys every frame, the skin binds the rest pose, the body is rigidly skinned and closed with
// outward normals, accessors' bounds are their data's, the ground is the terrain extruded across
// in two alternating tiles, the bytes are deterministic, and bad input is refused by name.
#include "fuzzygait/io/gltf.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/io/bvh.hpp"
#include "support/text.hpp"
#include "support/walks.hpp"

namespace {

namespace fs = std::filesystem;
using fuzzygait::eval::Motion;
using fuzzygait::io::GltfOptions;
using fuzzygait::io::write_gltf;
using fuzzygait::rig::Point;
using fuzzygait::terrain::Terrain;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr double kFloatPosition = 2e-5;  // metres: 32-bit floats over a walk of some metres
constexpr double kFloatAngle = 2e-6;     // radians

const Terrain& flat() {
  static const Terrain ground = Terrain::flat();
  return ground;
}

// A ramp up, a landing and two steps: the ground mesh's profile has slopes and risers.
const Terrain& hilly() {
  static const Terrain ground = Terrain::polyline({{0.5, 0.0},
                                                   {2.0, 0.15},
                                                   {2.6, 0.15},
                                                   {2.601, 0.32},
                                                   {2.9, 0.32},
                                                   {2.901, 0.49},
                                                   {4.0, 0.49}});
  return ground;
}

const Motion& walk() {
  static const Motion motion = [] {
    fuzzygait::gait::Walker walker = fuzzygait::test::make_walker(flat());
    return fuzzygait::eval::record(walker, 3.0, 60.0);
  }();
  return motion;
}

std::string glb(const Motion& motion, const Terrain& ground = flat(),
                const GltfOptions& options = {}) {
  std::ostringstream out;
  write_gltf(out, motion, ground, options);
  return out.str();
}

tinygltf::Model load(const std::string& bytes) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error;
  std::string warning;
  const bool loaded = loader.LoadBinaryFromMemory(
      &model, &error, &warning, reinterpret_cast<const unsigned char*>(bytes.data()),
      static_cast<unsigned int>(bytes.size()));
  EXPECT_TRUE(loaded) << error;
  EXPECT_EQ(error, "");
  EXPECT_EQ(warning, "");
  return model;
}

const tinygltf::Model& walk_model() {
  static const tinygltf::Model model = load(glb(walk()));
  return model;
}

// An accessor's values, each component as a double (no strides: the writer packs its views).
std::vector<double> values(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& a = model.accessors.at(static_cast<std::size_t>(index));
  const tinygltf::BufferView& view = model.bufferViews.at(static_cast<std::size_t>(a.bufferView));
  EXPECT_EQ(view.byteStride, 0u);
  const std::vector<unsigned char>& data = model.buffers.at(0).data;
  const std::size_t n = a.count * static_cast<std::size_t>(tinygltf::GetNumComponentsInType(
                                      static_cast<std::uint32_t>(a.type)));
  const std::size_t size = static_cast<std::size_t>(
      tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType)));
  EXPECT_LE(n * size, view.byteLength);
  const unsigned char* at = data.data() + view.byteOffset + a.byteOffset;
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char* p = at + i * size;
    switch (a.componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float f;
        std::memcpy(&f, p, sizeof f);
        out[i] = f;
        break;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        out[i] = *p;
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t u;
        std::memcpy(&u, p, sizeof u);
        out[i] = u;
        break;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        std::uint32_t u;
        std::memcpy(&u, p, sizeof u);
        out[i] = u;
        break;
      }
      default:
        ADD_FAILURE() << "unexpected component type " << a.componentType;
    }
  }
  return out;
}

int node_named(const tinygltf::Model& model, const std::string& name) {
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    if (model.nodes[i].name == name) return static_cast<int>(i);
  }
  ADD_FAILURE() << "no node " << name;
  return 0;
}

std::map<int, int> parents(const tinygltf::Model& model) {
  std::map<int, int> parent;
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    for (int child : model.nodes[i].children)
      parent[child] = static_cast<int>(i);
  }
  return parent;
}

// ---- Vectors and rotations about X, for forward kinematics of the file --------------------

struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;
};
Vec3 operator+(Vec3 a, Vec3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
Vec3 operator-(Vec3 a, Vec3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
double dot(Vec3 a, Vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// Turns v by `angle` about +X (right-handed).
Vec3 turn(double angle, Vec3 v) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  return {v.x, c * v.y - s * v.z, s * v.y + c * v.z};
}
// A node's translation; none is zero.
Vec3 translation_of(const tinygltf::Node& node) {
  if (node.translation.size() != 3) return {};
  return {node.translation[0], node.translation[1], node.translation[2]};
}

// The file's animation sampled at key `frame`: each node's translation and rotation about X
// (radians, from the quaternion); checks that every rotation is about X alone and unit.
struct Pose {
  std::map<int, Vec3> translation;
  std::map<int, double> angle;
};
Pose key(const tinygltf::Model& model, std::size_t frame) {
  Pose pose;
  const tinygltf::Animation& animation = model.animations.at(0);
  for (const tinygltf::AnimationChannel& channel : animation.channels) {
    const tinygltf::AnimationSampler& sampler =
        animation.samplers.at(static_cast<std::size_t>(channel.sampler));
    const std::vector<double> v = values(model, sampler.output);
    if (channel.target_path == "translation") {
      pose.translation[channel.target_node] = {v.at(3 * frame), v.at(3 * frame + 1),
                                               v.at(3 * frame + 2)};
    } else {
      const double x = v.at(4 * frame), y = v[4 * frame + 1], z = v[4 * frame + 2],
                   w = v[4 * frame + 3];
      EXPECT_EQ(y, 0.0);
      EXPECT_EQ(z, 0.0);
      EXPECT_NEAR(x * x + w * w, 1.0, 1e-6);
      pose.angle[channel.target_node] = 2.0 * std::atan2(x, w);
    }
  }
  return pose;
}

// World positions of every node in `pose` (rest translations where the pose has none).
std::vector<Vec3> world_positions(const tinygltf::Model& model, const Pose& pose) {
  const std::map<int, int> parent = parents(model);
  std::vector<Vec3> position(model.nodes.size());
  std::vector<double> angle(model.nodes.size(), 0.0);     // all rotations are about X: they add
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {  // parents come first
    const int n = static_cast<int>(i);
    const auto t = pose.translation.find(n);
    const Vec3 local = t != pose.translation.end() ? t->second : translation_of(model.nodes[i]);
    const auto a = pose.angle.find(n);
    const double own = a != pose.angle.end() ? a->second : 0.0;
    const auto p = parent.find(n);
    if (p == parent.end()) {
      position[i] = local;
      angle[i] = own;
    } else {
      EXPECT_LT(p->second, n) << "parents come before children";
      const std::size_t up = static_cast<std::size_t>(p->second);
      position[i] = position[up] + turn(angle[up], local);
      angle[i] = angle[up] + own;
    }
  }
  return position;
}

void expect_near(Vec3 seen, Vec3 expected, double tolerance, const std::string& what) {
  EXPECT_NEAR(seen.x, expected.x, tolerance) << what;
  EXPECT_NEAR(seen.y, expected.y, tolerance) << what;
  EXPECT_NEAR(seen.z, expected.z, tolerance) << what;
}

// ---- Tests ---------------------------------------------------------------------------------

TEST(Gltf, NodesAreTheBvhSkeletonInMetresWithTheBodyAndTheGround) {
  const tinygltf::Model& model = walk_model();
  std::vector<std::string> names;
  for (const tinygltf::Node& node : model.nodes)
    names.push_back(node.name);
  EXPECT_THAT(
      names, ElementsAre("Armature", "Hips", "LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase",
                         "LeftToe_End", "RightUpLeg", "RightLeg", "RightFoot", "RightToeBase",
                         "RightToe_End", "Spine", "Neck", "Head", "HeadTop_End", "Body", "Ground"));
  const std::map<int, int> parent = parents(model);
  const auto parent_of = [&](const std::string& name) {
    return model.nodes[static_cast<std::size_t>(parent.at(node_named(model, name)))].name;
  };
  EXPECT_EQ(parent_of("Hips"), "Armature");
  EXPECT_EQ(parent_of("LeftUpLeg"), "Hips");
  EXPECT_EQ(parent_of("RightToe_End"), "RightToeBase");
  EXPECT_EQ(parent_of("Spine"), "Hips");
  EXPECT_EQ(parent_of("HeadTop_End"), "Head");
  ASSERT_EQ(model.scenes.size(), 1u);
  EXPECT_EQ(model.defaultScene, 0);
  EXPECT_THAT(model.scenes[0].nodes,
              ElementsAre(0, node_named(model, "Body"), node_named(model, "Ground")));

  const fuzzygait::rig::Segments& s = walk().segments;
  const double half_width = 0.5 * fuzzygait::io::bvh_hip_width(s);
  const double stature = s.leg_length() / 0.530;
  const std::map<std::string, Vec3> rest = {
      {"Hips", {0.0, s.leg_length(), 0.0}},
      {"LeftUpLeg", {half_width, 0.0, 0.0}},
      {"RightUpLeg", {-half_width, 0.0, 0.0}},
      {"LeftLeg", {0.0, -s.thigh, 0.0}},
      {"LeftFoot", {0.0, -s.shank, 0.0}},
      {"LeftToeBase", {0.0, -s.ankle_height, s.ball}},
      {"LeftToe_End", {0.0, 0.0, s.toe}},
      {"Spine", {0.0, 0.100 * stature, 0.0}},
      {"Neck", {0.0, (0.818 - 0.530 - 0.100) * stature, 0.0}},
      {"Head", {0.0, (0.870 - 0.818) * stature, 0.0}},
      {"HeadTop_End", {0.0, (1.0 - 0.870) * stature, 0.0}},
  };
  for (const auto& [name, offset] : rest) {
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(node_named(model, name))];
    ASSERT_EQ(node.translation.size(), 3u) << name;
    expect_near(translation_of(node), offset, 1e-12, name);
    EXPECT_TRUE(node.rotation.empty() && node.scale.empty() && node.matrix.empty()) << name;
  }
  const tinygltf::Node& body = model.nodes[static_cast<std::size_t>(node_named(model, "Body"))];
  EXPECT_EQ(body.skin, 0);
  EXPECT_TRUE(body.translation.empty() && body.rotation.empty()) << "a skinned mesh stays put";
}

TEST(Gltf, ForwardKinematicsOfTheFileReproducesTheWalk) {
  const tinygltf::Model& model = walk_model();
  const Motion& motion = walk();
  const double half_width = 0.5 * fuzzygait::io::bvh_hip_width(motion.segments);
  const char* sides[] = {"Left", "Right"};
  for (std::size_t f = 0; f < motion.frames.size(); f += 7) {
    const fuzzygait::eval::Frame& frame = motion.frames[f];
    const std::vector<Vec3> world = world_positions(model, key(model, f));
    expect_near(world[static_cast<std::size_t>(node_named(model, "Hips"))],
                {0.0, frame.pose.pelvis.y, frame.pose.pelvis.x}, kFloatPosition,
                "Hips at frame " + std::to_string(f));
    for (std::size_t leg = 0; leg < 2; ++leg) {
      const std::string side = sides[leg];
      const double x = leg == 0 ? half_width : -half_width;
      const fuzzygait::rig::LegPoints& p = frame.points[leg];
      const std::pair<std::string, Point> joints[] = {{"UpLeg", p.hip},
                                                      {"Leg", p.knee},
                                                      {"Foot", p.ankle},
                                                      {"ToeBase", p.ball},
                                                      {"Toe_End", p.tip}};
      for (const auto& [joint, point] : joints) {
        expect_near(world[static_cast<std::size_t>(node_named(model, side + joint))],
                    {x, point.y, point.x}, kFloatPosition,
                    side + joint + " at frame " + std::to_string(f));
      }
    }
  }
}

TEST(Gltf, TheAnimationKeysEveryFrameWithTheWalksAngles) {
  const tinygltf::Model& model = walk_model();
  const Motion& motion = walk();
  ASSERT_EQ(model.animations.size(), 1u);
  const tinygltf::Animation& animation = model.animations[0];
  EXPECT_EQ(animation.name, "Walk");
  // The root's translation and a rotation for each of the twelve joints (not the end leaves).
  ASSERT_EQ(animation.channels.size(), 13u);
  std::set<std::string> rotated;
  for (const tinygltf::AnimationChannel& channel : animation.channels) {
    const std::string& node = model.nodes[static_cast<std::size_t>(channel.target_node)].name;
    if (channel.target_path == "translation") {
      EXPECT_EQ(node, "Hips");
    } else {
      EXPECT_EQ(channel.target_path, "rotation");
      rotated.insert(node);
    }
    const tinygltf::AnimationSampler& sampler =
        animation.samplers.at(static_cast<std::size_t>(channel.sampler));
    EXPECT_EQ(sampler.interpolation, "LINEAR");
    EXPECT_EQ(model.accessors[static_cast<std::size_t>(sampler.output)].count,
              motion.frames.size());
    const tinygltf::Accessor& input = model.accessors[static_cast<std::size_t>(sampler.input)];
    ASSERT_EQ(input.count, motion.frames.size());
    EXPECT_THAT(input.minValues, ElementsAre(static_cast<float>(motion.frames.front().time)));
    EXPECT_THAT(input.maxValues, ElementsAre(static_cast<float>(motion.frames.back().time)));
  }
  EXPECT_EQ(rotated.size(), 12u);
  EXPECT_EQ(rotated.count("Head"), 1u);
  EXPECT_EQ(rotated.count("HeadTop_End"), 0u);

  const std::vector<double> times =
      values(model, animation.samplers[0].input);  // every sampler shares it
  for (std::size_t f = 0; f < motion.frames.size(); ++f) {
    EXPECT_EQ(times[f], static_cast<float>(motion.frames[f].time));
  }
  // The root at a few frames, and every joint's angle at every frame.
  for (std::size_t f :
       {std::size_t{0}, std::size_t{1}, motion.frames.size() / 2, motion.frames.size() - 1}) {
    const Pose pose = key(model, f);
    const fuzzygait::rig::Pose& p = motion.frames[f].pose;
    expect_near(pose.translation.at(node_named(model, "Hips")), {0.0, p.pelvis.y, p.pelvis.x}, 1e-6,
                "root at frame " + std::to_string(f));
  }
  for (std::size_t f = 0; f < motion.frames.size(); ++f) {
    const Pose pose = key(model, f);
    const fuzzygait::rig::Pose& p = motion.frames[f].pose;
    const auto angle = [&](const std::string& node) {
      return pose.angle.at(node_named(model, node));
    };
    EXPECT_NEAR(angle("Hips"), p.pelvis_tilt, kFloatAngle);
    EXPECT_NEAR(angle("Spine"), -p.pelvis_tilt, kFloatAngle);
    EXPECT_EQ(angle("Neck"), 0.0);
    EXPECT_EQ(angle("Head"), 0.0);
    for (std::size_t leg = 0; leg < 2; ++leg) {
      const std::string side = leg == 0 ? "Left" : "Right";
      const fuzzygait::rig::LegAngles& a = p.legs[leg];
      EXPECT_NEAR(angle(side + "UpLeg"), -a.hip, kFloatAngle) << f;
      EXPECT_NEAR(angle(side + "Leg"), a.knee, kFloatAngle) << f;
      EXPECT_NEAR(angle(side + "Foot"), -a.ankle, kFloatAngle) << f;
      EXPECT_NEAR(angle(side + "ToeBase"), -a.toe, kFloatAngle) << f;
    }
  }
}

TEST(Gltf, TheSkinBindsEveryJointAtItsRestPosition) {
  const tinygltf::Model& model = walk_model();
  ASSERT_EQ(model.skins.size(), 1u);
  const tinygltf::Skin& skin = model.skins[0];
  EXPECT_EQ(skin.skeleton, node_named(model, "Hips"));
  ASSERT_EQ(skin.joints.size(), 15u);
  const std::vector<Vec3> rest = world_positions(model, {});
  EXPECT_NEAR(rest[static_cast<std::size_t>(node_named(model, "Hips"))].y,
              walk().segments.leg_length(), 1e-12);
  const std::vector<double> matrices = values(model, skin.inverseBindMatrices);
  ASSERT_EQ(matrices.size(), 16u * skin.joints.size());
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    const double* m = &matrices[16 * j];  // column-major
    const Vec3 joint = rest[static_cast<std::size_t>(skin.joints[j])];
    for (int i = 0; i < 12; ++i)
      EXPECT_EQ(m[i], i % 5 == 0 ? 1.0 : 0.0) << "joint " << j << " element " << i;
    expect_near({m[12], m[13], m[14]}, {-joint.x, -joint.y, -joint.z}, 1e-6,
                "joint " + std::to_string(j));
    EXPECT_EQ(m[15], 1.0);
  }
}

TEST(Gltf, TheBodyIsRigidlySkinnedClosedAndStandsOnTheGroundAtRest) {
  const tinygltf::Model& model = walk_model();
  const tinygltf::Mesh& body = model.meshes.at(0);
  EXPECT_EQ(body.name, "Body");
  ASSERT_EQ(body.primitives.size(), 4u);
  std::set<std::string> materials;
  double lowest = std::numeric_limits<double>::infinity();
  double highest = -lowest;
  double leftmost = -lowest;
  double rightmost = lowest;
  std::set<int> skinned_joints;
  for (const tinygltf::Primitive& primitive : body.primitives) {
    EXPECT_EQ(primitive.mode, TINYGLTF_MODE_TRIANGLES);
    materials.insert(model.materials.at(static_cast<std::size_t>(primitive.material)).name);
    const std::vector<double> position = values(model, primitive.attributes.at("POSITION"));
    const std::vector<double> normal = values(model, primitive.attributes.at("NORMAL"));
    const std::vector<double> joints = values(model, primitive.attributes.at("JOINTS_0"));
    const std::vector<double> weights = values(model, primitive.attributes.at("WEIGHTS_0"));
    const std::vector<double> index = values(model, primitive.indices);
    const std::size_t n = position.size() / 3;
    ASSERT_EQ(normal.size(), 3 * n);
    ASSERT_EQ(joints.size(), 4 * n);
    ASSERT_EQ(weights.size(), 4 * n);
    ASSERT_EQ(index.size() % 3, 0u);
    for (std::size_t v = 0; v < n; ++v) {
      EXPECT_EQ(weights[4 * v], 1.0);
      EXPECT_EQ(weights[4 * v + 1] + weights[4 * v + 2] + weights[4 * v + 3], 0.0);
      EXPECT_EQ(joints[4 * v + 1] + joints[4 * v + 2] + joints[4 * v + 3], 0.0);
      EXPECT_LT(joints[4 * v], 15.0);
      skinned_joints.insert(static_cast<int>(joints[4 * v]));
      const Vec3 nv{normal[3 * v], normal[3 * v + 1], normal[3 * v + 2]};
      EXPECT_NEAR(dot(nv, nv), 1.0, 1e-6);
      lowest = std::min(lowest, position[3 * v + 1]);
      highest = std::max(highest, position[3 * v + 1]);
      leftmost = std::max(leftmost, position[3 * v]);
      rightmost = std::min(rightmost, position[3 * v]);
    }
    // Counter-clockwise seen from outside: each face's own normal leans the way its corners'
    // normals point. Every edge is shared by exactly two triangles, in opposite directions.
    std::map<std::pair<double, double>, int> edges;
    for (std::size_t t = 0; t < index.size(); t += 3) {
      const auto corner = [&](std::size_t k) {
        const std::size_t v = static_cast<std::size_t>(index[t + k]);
        EXPECT_LT(v, n);
        return Vec3{position[3 * v], position[3 * v + 1], position[3 * v + 2]};
      };
      const Vec3 face = cross(corner(1) - corner(0), corner(2) - corner(0));
      for (std::size_t k = 0; k < 3; ++k) {
        const std::size_t v = static_cast<std::size_t>(index[t + k]);
        EXPECT_GT(dot(face, {normal[3 * v], normal[3 * v + 1], normal[3 * v + 2]}), 0.0)
            << "triangle " << t / 3 << " of "
            << model.materials[static_cast<std::size_t>(primitive.material)].name;
        ++edges[{index[t + k], index[t + (k + 1) % 3]}];
      }
    }
    for (const auto& [edge, count] : edges) {
      EXPECT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second;
      EXPECT_EQ(edges.count({edge.second, edge.first}), 1u)
          << "edge " << edge.first << "-" << edge.second << " has no twin: a hole";
    }
  }
  EXPECT_THAT(materials, ::testing::UnorderedElementsAre("Shirt", "Trousers", "Skin", "Shoes"));
  // Every joint carries some of the body but the end leaves.
  EXPECT_EQ(skinned_joints, (std::set<int>{0, 1, 2, 3, 4, 6, 7, 8, 9, 11, 12, 13}));
  const double stature = walk().segments.leg_length() / 0.530;
  EXPECT_NEAR(lowest, 0.0, 1e-6) << "the soles rest on y = 0";
  EXPECT_NEAR(highest, stature, 1e-6) << "the head's top at the stature";
  EXPECT_NEAR(leftmost, -rightmost, 1e-6) << "left and right mirror each other";
  EXPECT_GT(leftmost, 0.13 * stature) << "arms beside the trunk";
  EXPECT_LT(leftmost, 0.2 * stature);
}

TEST(Gltf, AccessorBoundsAreTheirDataAndEveryPositionHasThem) {
  const tinygltf::Model& model = walk_model();
  std::set<int> positions;
  for (const tinygltf::Mesh& mesh : model.meshes) {
    for (const tinygltf::Primitive& primitive : mesh.primitives)
      positions.insert(primitive.attributes.at("POSITION"));
  }
  for (std::size_t i = 0; i < model.accessors.size(); ++i) {
    const tinygltf::Accessor& a = model.accessors[i];
    if (positions.count(static_cast<int>(i)) > 0) {
      EXPECT_FALSE(a.minValues.empty()) << "POSITION accessor " << i << " without bounds";
    }
    if (a.minValues.empty()) continue;
    const std::vector<double> v = values(model, static_cast<int>(i));
    const std::size_t width = a.minValues.size();
    for (std::size_t c = 0; c < width; ++c) {
      double low = v[c];
      double high = v[c];
      for (std::size_t k = c; k < v.size(); k += width) {
        low = std::min(low, v[k]);
        high = std::max(high, v[k]);
      }
      EXPECT_EQ(a.minValues[c], low) << "accessor " << i << " component " << c;
      EXPECT_EQ(a.maxValues[c], high) << "accessor " << i << " component " << c;
    }
  }
}

TEST(Gltf, TheGroundIsTheTerrainExtrudedAcrossInAlternatingTiles) {
  fuzzygait::gait::Walker walker = fuzzygait::test::make_walker(hilly());
  const Motion motion = fuzzygait::eval::record(walker, 2.0, 60.0);
  const tinygltf::Model model = load(glb(motion, hilly()));
  const tinygltf::Mesh& ground = model.meshes.at(1);
  EXPECT_EQ(ground.name, "Ground");
  ASSERT_EQ(ground.primitives.size(), 2u);
  double rearmost = motion.frames.front().pose.pelvis.x;
  double foremost = rearmost;
  for (const fuzzygait::eval::Frame& frame : motion.frames) {
    rearmost = std::min(rearmost, frame.pose.pelvis.x);
    foremost = std::max(foremost, frame.pose.pelvis.x);
  }
  // Tile centres (across, along) by material: neighbours differ.
  std::map<std::pair<long, long>, std::string> tiles;
  double nearest = std::numeric_limits<double>::infinity();
  double farthest = -nearest;
  for (const tinygltf::Primitive& primitive : ground.primitives) {
    EXPECT_EQ(primitive.attributes.count("JOINTS_0"), 0u);
    const std::string material =
        model.materials.at(static_cast<std::size_t>(primitive.material)).name;
    const std::vector<double> position = values(model, primitive.attributes.at("POSITION"));
    const std::vector<double> normal = values(model, primitive.attributes.at("NORMAL"));
    const std::vector<double> index = values(model, primitive.indices);
    for (std::size_t v = 0; v < position.size() / 3; ++v) {
      const double x = position[3 * v], y = position[3 * v + 1], z = position[3 * v + 2];
      EXPECT_LE(std::abs(x), 0.75 + 1e-6);
      EXPECT_NEAR(y, hilly().height(z), 1e-3) << "at z = " << z;
      EXPECT_NEAR(normal[3 * v], 0.0, 1e-9);
      EXPECT_GE(normal[3 * v + 1], 0.0) << "faces up or back, towards the walker";
      nearest = std::min(nearest, z);
      farthest = std::max(farthest, z);
    }
    for (std::size_t t = 0; t < index.size(); t += 3) {
      const auto corner = [&](std::size_t k) {
        const std::size_t v = static_cast<std::size_t>(index[t + k]);
        return Vec3{position[3 * v], position[3 * v + 1], position[3 * v + 2]};
      };
      const Vec3 face = cross(corner(1) - corner(0), corner(2) - corner(0));
      const std::size_t v = static_cast<std::size_t>(index[t]);
      const Vec3 n{normal[3 * v], normal[3 * v + 1], normal[3 * v + 2]};
      EXPECT_GT(dot(face, n), 0.0) << "counter-clockwise seen from above";
      // Flat: the normal is the face's own.
      EXPECT_NEAR(dot(face, n) * dot(face, n), dot(face, face), 1e-6 * dot(face, face) + 1e-18);
      const Vec3 centre = corner(0) + Vec3{0.5 * (corner(1).x - corner(0).x), 0.0,
                                           0.5 * (corner(2).z - corner(0).z)};
      tiles[{std::lround(std::floor(centre.x / 0.5)), std::lround(std::floor(centre.z / 0.5))}] =
          material;
    }
  }
  EXPECT_NEAR(nearest, rearmost - 2.0, 1e-5);
  EXPECT_NEAR(farthest, foremost + 2.0, 1e-5);
  EXPECT_GT(tiles.size(), 3u * 8u);
  for (const auto& [tile, material] : tiles) {
    const auto ahead = tiles.find({tile.first, tile.second + 1});
    if (ahead != tiles.end()) {
      EXPECT_NE(ahead->second, material);
    }
    const auto beside = tiles.find({tile.first + 1, tile.second});
    if (beside != tiles.end()) {
      EXPECT_NE(beside->second, material);
    }
  }
}

TEST(Gltf, TheSameInputGivesTheSameBytesAndOptionsChangeThem) {
  const std::string first = glb(walk());
  EXPECT_EQ(first, glb(walk()));
  EXPECT_EQ(first.substr(0, 4), "glTF");
  Motion shorter = walk();
  shorter.frames.pop_back();
  EXPECT_NE(first, glb(shorter));
  EXPECT_NE(first, glb(walk(), flat(), {.ground_width = 2.0}));
  EXPECT_NE(first, glb(walk(), hilly()));

  const fs::path dir = fs::path(::testing::TempDir()) / "fuzzygait_gltf_test";
  fs::create_directories(dir);
  write_gltf(dir / "walk.glb", walk(), flat());
  EXPECT_EQ(fuzzygait::test::read_text(dir / "walk.glb"), first);
  try {
    write_gltf(dir / "missing" / "walk.glb", walk(), flat());
    ADD_FAILURE() << "wrote into a folder that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing/walk.glb"));
  }
}

// The message of the std::invalid_argument write_gltf throws; nothing may have been written.
std::string refusal(const Motion& motion, const GltfOptions& options = {},
                    const Terrain& ground = flat()) {
  std::ostringstream out;
  try {
    write_gltf(out, motion, ground, options);
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(out.str(), "") << "wrote before refusing";
    return e.what();
  }
  return "(accepted)";
}

TEST(Gltf, RefusesBadMotionsNamingTheFrameAndTheField) {
  const Motion& good = walk();
  Motion m = good;
  m.frames.clear();
  EXPECT_THAT(refusal(m), HasSubstr("no frames"));
  for (double fps : {0.0, -60.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    m = good;
    m.fps = fps;
    EXPECT_THAT(refusal(m), HasSubstr("fps")) << fps;
  }
  m = good;
  m.frames[3].pose.legs[0].knee = std::nan("");
  EXPECT_THAT(refusal(m), HasSubstr("frame 3: the left knee angle is not a finite number (nan)"));
  m = good;
  m.frames[5].pose.legs[1].toe = -std::numeric_limits<double>::infinity();
  EXPECT_THAT(refusal(m), HasSubstr("frame 5: the right toe angle is not a finite number (-inf)"));
  m = good;
  m.frames[7].pose.pelvis_tilt = std::nan("");
  EXPECT_THAT(refusal(m), HasSubstr("frame 7: the pelvis tilt"));
  m = good;
  m.frames[2].pose.pelvis.x = std::numeric_limits<double>::infinity();
  EXPECT_THAT(refusal(m), HasSubstr("frame 2: the pelvis x is not a finite number (inf)"));
  m = good;
  m.frames[4].pose.pelvis.y = 2e6;
  EXPECT_THAT(refusal(m), HasSubstr("frame 4: the pelvis y lies beyond 1e+06 m"));
  m = good;
  m.frames[6].time = std::nan("");
  EXPECT_THAT(refusal(m), HasSubstr("frame 6: the time is not a finite number"));
  m = good;
  m.frames[0].time = -0.5;
  EXPECT_THAT(refusal(m), HasSubstr("frame 0: the time is negative"));
  m = good;
  m.frames[9].time = m.frames[8].time;
  EXPECT_THAT(refusal(m), HasSubstr("frame 9: the time (0.133333"));
  EXPECT_THAT(refusal(m), HasSubstr("does not come after frame 8's"));
  m = good;
  m.frames[9].time = m.frames[8].time + 1e-12;  // the same 32-bit float
  EXPECT_THAT(refusal(m), HasSubstr("as a 32-bit float"));
  m = good;
  m.segments.thigh = 0.0;
  EXPECT_THAT(refusal(m), HasSubstr("thigh"));
  m = good;
  m.frames[10].pose.legs[0].hip = 1e300;  // finite: a turn like any other
  EXPECT_EQ(refusal(m), "(accepted)");
}

TEST(Gltf, RefusesOptionsOutOfRange) {
  const std::pair<GltfOptions, std::string> cases[] = {
      {{.hip_width_per_leg_length = -0.1}, "hip_width_per_leg_length"},
      {{.hip_width_per_leg_length = std::nan("")}, "hip_width_per_leg_length"},
      {{.ground_width = 0.0}, "ground_width must be between 0.1 and 100, got 0"},
      {{.ground_margin = 0.0}, "ground_margin must be between 0.1 and 100, got 0"},
      {{.ground_margin = std::numeric_limits<double>::infinity()}, "ground_margin"},
      {{.ground_tile = 0.01}, "ground_tile"},
  };
  for (const auto& [options, message] : cases) {
    EXPECT_THAT(refusal(walk(), options), HasSubstr(message));
  }
  // A walk of a thousand kilometres on tiles of 5 cm.
  Motion far = walk();
  far.frames.back().pose.pelvis.x = 1e6;
  EXPECT_THAT(refusal(far, {.ground_tile = 0.05}), HasSubstr("the ground would have"));
}

TEST(Gltf, OneTileOfGroundHasOneMaterialAndStillLoads) {
  Motion still = walk();
  still.frames.resize(1);
  still.frames[0].pose.pelvis.x = 50.0;  // in the middle of the tile from 0 to 100 m
  const tinygltf::Model model =
      load(glb(still, flat(), {.ground_width = 0.2, .ground_margin = 0.1, .ground_tile = 100.0}));
  ASSERT_EQ(model.meshes.at(1).primitives.size(), 1u);
  EXPECT_EQ(model.animations.at(0).channels.size(), 13u);
  EXPECT_EQ(
      model.accessors.at(static_cast<std::size_t>(model.animations[0].samplers[0].input)).count,
      1u);
}

}  // namespace

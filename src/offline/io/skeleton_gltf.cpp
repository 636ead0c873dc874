// A posed skeleton's animation as binary glTF (io::write_skeleton_gltf; docs/gltf.md, "The whole
// body").
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzzygait/io/files.hpp"
#include "fuzzygait/io/skeleton_file.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::io {
namespace {

using body::Quat;
using body::Vec3;

[[noreturn]] void refuse(const std::string& what) {
  throw std::invalid_argument("glTF: " + what);
}

// A GLB's length is a 32-bit number; the JSON chunk takes some kilobytes of it.
constexpr double kMaxBinaryBytes = 4.0e9;
// JOINTS_0 holds 16-bit joint indices at most.
constexpr std::size_t kMaxJoints = 65536;
// As body::validate's rest rotations.
constexpr double kUnitTolerance = 1e-6;
// Bones shorter than this (metres) get no mesh: helper joints on top of their parents.
constexpr double kShortestBone = 1e-4;
// The mesh of a skeleton without a bone of length: one this long, up from the root.
constexpr double kStandInBone = 0.05;
// The octahedron's waist: its distance from the head and its half-width, over the bone's length.
constexpr double kWaistAlong = 0.1;
constexpr double kWaistWidth = 0.08;

bool fits_float(double value) {
  return std::isfinite(value) && std::abs(value) <= std::numeric_limits<float>::max();
}

void check_metres(Vec3 v, double metres_per_unit, const std::string& what) {
  for (const double c : {v.x, v.y, v.z}) {
    if (!std::isfinite(c)) refuse(what + " is not finite");
    if (!fits_float(c * metres_per_unit)) refuse(what + " does not fit a 32-bit float in metres");
  }
}

void check_rotation(Quat q, const std::string& what) {
  if (!std::isfinite(q.w) || !std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) {
    refuse(what + " is not finite");
  }
  const double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  if (std::abs(norm - 1.0) > kUnitTolerance) {
    refuse(what + " is not a unit quaternion (norm " + common::number_text(norm) + ")");
  }
}

// The binary chunk: each accessor a 4-byte aligned view of its own.
class BinaryChunk {
 public:
  explicit BinaryChunk(tinygltf::Model& model) : model_(model) { model_.buffers.resize(1); }

  template <class T>
  int add(const std::vector<T>& values, int component_type, int type, std::size_t count,
          int target) {
    std::vector<unsigned char>& data = model_.buffers[0].data;
    data.resize((data.size() + 3) / 4 * 4, 0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = values.size() * sizeof(T);
    view.target = target;
    data.resize(data.size() + view.byteLength);
    std::memcpy(data.data() + view.byteOffset, values.data(), view.byteLength);
    model_.bufferViews.push_back(view);
    tinygltf::Accessor accessor;
    accessor.bufferView = static_cast<int>(model_.bufferViews.size() - 1);
    accessor.componentType = component_type;
    accessor.type = type;
    accessor.count = count;
    model_.accessors.push_back(accessor);
    return static_cast<int>(model_.accessors.size() - 1);
  }

  // Floats, `width` a value (1, 3, 4 or 16); with their bounds when `bounded` (glTF requires them
  // for positions and animation times).
  int add_floats(const std::vector<float>& values, std::size_t width, int target, bool bounded) {
    const int type = width == 1   ? TINYGLTF_TYPE_SCALAR
                     : width == 3 ? TINYGLTF_TYPE_VEC3
                     : width == 4 ? TINYGLTF_TYPE_VEC4
                                  : TINYGLTF_TYPE_MAT4;
    const int index =
        add(values, TINYGLTF_COMPONENT_TYPE_FLOAT, type, values.size() / width, target);
    if (bounded) {
      tinygltf::Accessor& accessor = model_.accessors.back();
      accessor.minValues.assign(width, 0.0);
      accessor.maxValues.assign(width, 0.0);
      for (std::size_t c = 0; c < width; ++c) {
        float low = values[c];
        float high = values[c];
        for (std::size_t i = c; i < values.size(); i += width) {
          low = std::min(low, values[i]);
          high = std::max(high, values[i]);
        }
        accessor.minValues[c] = low;
        accessor.maxValues[c] = high;
      }
    }
    return index;
  }

 private:
  tinygltf::Model& model_;
};

// The body: an octahedron along each bone, every vertex weighted 1 to the bone's joint.
struct BoneMesh {
  std::vector<float> positions;       // x, y, z a vertex, metres, rest pose
  std::vector<std::uint16_t> joints;  // the skin joint of each vertex
  std::vector<std::uint32_t> indices;

  void add_bone(Vec3 head, Vec3 tail, std::uint16_t joint) {
    const Vec3 along = tail - head;
    const double length = body::length(along);
    const Vec3 d = (1.0 / length) * along;
    const Vec3 across = std::abs(d.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 u = body::normalized(body::cross(across, d));
    const Vec3 v = body::cross(d, u);  // u x v = d
    const Vec3 waist = head + (kWaistAlong * length) * d;
    const double w = kWaistWidth * length;
    const auto first = static_cast<std::uint32_t>(joints.size());
    for (const Vec3 p : {head, waist + w * u, waist + w * v, waist - w * u, waist - w * v, tail}) {
      positions.insert(positions.end(),
                       {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
      joints.push_back(joint);
    }
    // Counter-clockwise seen from outside: the head's cap turns against the ring, the tail's with.
    for (std::uint32_t k = 0; k < 4; ++k) {
      const std::uint32_t a = first + 1 + k;
      const std::uint32_t b = first + 1 + (k + 1) % 4;
      indices.insert(indices.end(), {first, b, a, first + 5, a, b});
    }
  }
};

// Column-major inverse of the rest transform T(position) R(rotation).
std::array<float, 16> inverse_bind(Vec3 position, Quat q) {
  const double w = q.w, x = q.x, y = q.y, z = q.z;
  const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  const double p[3] = {position.x, position.y, position.z};
  std::array<float, 16> m{};
  for (int row = 0; row < 3; ++row) {
    double t = 0.0;
    for (int col = 0; col < 3; ++col) {
      m[static_cast<std::size_t>(col * 4 + row)] = static_cast<float>(r[col][row]);  // R^T
      t -= r[col][row] * p[col];
    }
    m[static_cast<std::size_t>(12 + row)] = static_cast<float>(t);
  }
  m[15] = 1.0f;
  return m;
}

}  // namespace

void write_skeleton_gltf(std::ostream& out, const body::Skeleton& skeleton,
                         std::span<const Quat> local_rotations,
                         std::span<const Vec3> root_positions, const SkeletonGltfOptions& options) {
  body::validate(skeleton);
  const std::size_t n = skeleton.size();
  if (n > kMaxJoints) {
    refuse("a skeleton of " + std::to_string(n) + " joints: at most " + std::to_string(kMaxJoints) +
           " fit a skin's 16-bit joint indices");
  }
  if (!std::isfinite(options.frame_time) || options.frame_time < 1e-4 || options.frame_time > 1.0) {
    refuse("frame time must be 1e-4 to 1 s, got " + common::number_text(options.frame_time));
  }
  const std::size_t frames = root_positions.size();
  if (frames == 0) refuse("no frame to write");
  if (local_rotations.size() != frames * n) {
    refuse(std::to_string(local_rotations.size()) + " rotations for " + std::to_string(frames) +
           " frames of " + std::to_string(n) + " joints");
  }
  // Times, the root's translations and a rotation a joint, every frame; the rest is small.
  const double animation_bytes =
      static_cast<double>(frames) * (4.0 + 12.0 + 16.0 * static_cast<double>(n));
  if (animation_bytes > kMaxBinaryBytes) {
    refuse("the animation's " + std::to_string(frames) + " frames of " + std::to_string(n) +
           " joints would not fit glTF's 4 GiB: write fewer frames");
  }
  const double metres = skeleton.metres_per_unit;
  for (const body::SkeletonJoint& joint : skeleton.joints) {
    check_metres(joint.offset, metres, "the offset of '" + joint.name + "'");
    if (joint.end) check_metres(*joint.end, metres, "the end of '" + joint.name + "'");
  }

  // The animation's values, checked before anything is written.
  std::vector<float> times(frames);
  std::vector<float> translations;
  translations.reserve(3 * frames);
  for (std::size_t f = 0; f < frames; ++f) {
    times[f] = static_cast<float>(static_cast<double>(f) * options.frame_time);
    if (f > 0 && !(times[f] > times[f - 1])) {
      refuse("frame " + std::to_string(f) + "'s time " + common::number_text(times[f]) +
             " s does not follow the previous one's as a 32-bit float: write fewer frames");
    }
    const Vec3 root = root_positions[f];
    check_metres(root, metres, "frame " + std::to_string(f) + ": the root position");
    translations.insert(translations.end(),
                        {static_cast<float>(root.x * metres), static_cast<float>(root.y * metres),
                         static_cast<float>(root.z * metres)});
  }
  // Per joint, frame after frame: x, y, z, w, each key in the previous one's hemisphere so that
  // interpolating between keys takes the short way.
  std::vector<std::vector<float>> rotations(n, std::vector<float>(4 * frames));
  for (std::size_t i = 0; i < n; ++i) {
    Quat previous = skeleton.joints[i].rotation;
    for (std::size_t f = 0; f < frames; ++f) {
      Quat q = local_rotations[f * n + i];
      check_rotation(
          q, "frame " + std::to_string(f) + ": the rotation of '" + skeleton.joints[i].name + "'");
      if (q.w * previous.w + q.x * previous.x + q.y * previous.y + q.z * previous.z < 0.0) {
        q = {-q.w, -q.x, -q.y, -q.z};
      }
      previous = q;
      const Quat unit = body::normalized(q);
      float* key = &rotations[i][4 * f];
      key[0] = static_cast<float>(unit.x);
      key[1] = static_cast<float>(unit.y);
      key[2] = static_cast<float>(unit.z);
      key[3] = static_cast<float>(unit.w);
    }
  }

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "fuzzygait";
  BinaryChunk chunk(model);

  // Node 0, "Armature", holds the joints (Blender's importer makes the joints' common ancestor
  // its armature object); joint i is node 1 + i, and skin joint i.
  const auto node_of = [](std::size_t joint) { return static_cast<int>(joint + 1); };
  tinygltf::Node armature;
  armature.name = "Armature";
  armature.children = {node_of(0)};
  model.nodes.push_back(armature);
  std::vector<std::vector<int>> children(n);
  for (std::size_t i = 1; i < n; ++i)
    children[static_cast<std::size_t>(skeleton.joints[i].parent)].push_back(node_of(i));
  for (std::size_t i = 0; i < n; ++i) {
    const body::SkeletonJoint& joint = skeleton.joints[i];
    tinygltf::Node node;
    node.name = joint.name;
    node.translation = {joint.offset.x * metres, joint.offset.y * metres, joint.offset.z * metres};
    const Quat r = body::normalized(joint.rotation);
    node.rotation = {r.x, r.y, r.z, r.w};
    node.children = children[i];
    model.nodes.push_back(node);
  }

  // The skin, in the rest pose (the root at its offset), metres.
  std::vector<Vec3> rest = body::rest_positions(skeleton);
  for (Vec3& p : rest)
    p = metres * p;
  const std::vector<Quat> rest_rotations = body::rest_world_rotations(skeleton);
  tinygltf::Skin skin;
  skin.name = "Armature";
  skin.skeleton = node_of(0);
  std::vector<float> inverse_binds;
  inverse_binds.reserve(16 * n);
  for (std::size_t i = 0; i < n; ++i) {
    skin.joints.push_back(node_of(i));
    const std::array<float, 16> m = inverse_bind(rest[i], body::normalized(rest_rotations[i]));
    inverse_binds.insert(inverse_binds.end(), m.begin(), m.end());
  }
  skin.inverseBindMatrices = chunk.add_floats(inverse_binds, 16, 0, false);
  model.skins.push_back(skin);

  BoneMesh mesh;
  for (std::size_t i = 0; i < n; ++i) {
    const body::SkeletonJoint& joint = skeleton.joints[i];
    if (joint.parent >= 0) {
      const auto parent = static_cast<std::size_t>(joint.parent);
      if (body::length(rest[i] - rest[parent]) >= kShortestBone) {
        mesh.add_bone(rest[parent], rest[i], static_cast<std::uint16_t>(parent));
      }
    }
    if (joint.end) {
      const Vec3 tail = rest[i] + body::rotate(rest_rotations[i], metres * *joint.end);
      if (body::length(tail - rest[i]) >= kShortestBone) {
        mesh.add_bone(rest[i], tail, static_cast<std::uint16_t>(i));
      }
    }
  }
  if (mesh.indices.empty()) mesh.add_bone(rest[0], rest[0] + Vec3{0, kStandInBone, 0}, 0);
  const std::size_t vertices = mesh.joints.size();
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.material = 0;
  primitive.attributes["POSITION"] =
      chunk.add_floats(mesh.positions, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
  if (n <= 256) {
    std::vector<std::uint8_t> joints(4 * vertices, 0);
    for (std::size_t v = 0; v < vertices; ++v)
      joints[4 * v] = static_cast<std::uint8_t>(mesh.joints[v]);
    primitive.attributes["JOINTS_0"] =
        chunk.add(joints, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, vertices,
                  TINYGLTF_TARGET_ARRAY_BUFFER);
  } else {
    std::vector<std::uint16_t> joints(4 * vertices, 0);
    for (std::size_t v = 0; v < vertices; ++v)
      joints[4 * v] = mesh.joints[v];
    primitive.attributes["JOINTS_0"] =
        chunk.add(joints, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, vertices,
                  TINYGLTF_TARGET_ARRAY_BUFFER);
  }
  std::vector<float> weights(4 * vertices, 0.0f);
  for (std::size_t v = 0; v < vertices; ++v)
    weights[4 * v] = 1.0f;
  primitive.attributes["WEIGHTS_0"] =
      chunk.add_floats(weights, 4, TINYGLTF_TARGET_ARRAY_BUFFER, false);
  if (vertices <= 65535) {
    const std::vector<std::uint16_t> narrow(mesh.indices.begin(), mesh.indices.end());
    primitive.indices =
        chunk.add(narrow, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR,
                  narrow.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  } else {
    primitive.indices =
        chunk.add(mesh.indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                  mesh.indices.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  }
  tinygltf::Mesh body_mesh;
  body_mesh.name = "Body";
  body_mesh.primitives.push_back(primitive);
  model.meshes.push_back(body_mesh);
  tinygltf::Material material;
  material.name = "Body";
  material.pbrMetallicRoughness.baseColorFactor = {0.8, 0.8, 0.8, 1.0};
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 0.8;
  model.materials.push_back(material);
  // A skinned mesh's node is a root of the scene, without a transform (glTF's rule).
  tinygltf::Node body_node;
  body_node.name = "Body";
  body_node.mesh = 0;
  body_node.skin = 0;
  model.nodes.push_back(body_node);

  tinygltf::Animation animation;
  animation.name = "Walk";
  const int input = chunk.add_floats(times, 1, 0, true);
  const auto channel = [&](int node, const char* path, int output) {
    tinygltf::AnimationSampler sampler;
    sampler.input = input;
    sampler.output = output;
    sampler.interpolation = "LINEAR";
    animation.samplers.push_back(sampler);
    tinygltf::AnimationChannel c;
    c.sampler = static_cast<int>(animation.samplers.size() - 1);
    c.target_node = node;
    c.target_path = path;
    animation.channels.push_back(c);
  };
  channel(node_of(0), "translation", chunk.add_floats(translations, 3, 0, false));
  for (std::size_t i = 0; i < n; ++i)
    channel(node_of(i), "rotation", chunk.add_floats(rotations[i], 4, 0, false));
  model.animations.push_back(animation);

  tinygltf::Scene scene;
  scene.name = "Walk";
  scene.nodes = {0, node_of(n)};  // Armature, Body
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  if (static_cast<double>(model.buffers[0].data.size()) > kMaxBinaryBytes) {
    refuse("the file would not fit glTF's 4 GiB: write fewer frames");
  }
  tinygltf::TinyGLTF writer;
  writer.WriteGltfSceneToStream(&model, out, false, true);
  if (!out) throw std::runtime_error("glTF: the stream failed while writing");
}

void write_skeleton_gltf(const std::filesystem::path& path, const body::Skeleton& skeleton,
                         std::span<const Quat> local_rotations,
                         std::span<const Vec3> root_positions, const SkeletonGltfOptions& options) {
  // Refusals come before the file is opened: into memory first.
  std::ostringstream bytes;
  write_skeleton_gltf(bytes, skeleton, local_rotations, root_positions, options);
  write_file(path, bytes.view());
}

}  // namespace fuzzygait::io

#include "fuzzygait/io/skeleton_file.hpp"

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzzygait/body/humanoid_map.hpp"
#include "offline/io/bvh_text.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::io {

using body::Quat;
using body::Vec3;
using common::number_text;

namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;
// The unit candidates of the guess (m, cm, mm, inch, CMU), as analyse_clip's, and its aim.
constexpr std::array<double, 5> kUnitCandidates = {1.0, 0.01, 0.001, 0.0254, 0.0254 / 0.45};
constexpr double kTypicalHipToAnkle = 0.80;  // m

double guess_metres_per_unit(const body::Skeleton& skeleton) {
  body::Skeleton trial = skeleton;
  trial.metres_per_unit = 1.0;
  double leg = 0.0;
  try {
    const body::HumanoidMap map = body::map_humanoid(trial);
    const std::vector<Vec3> rest = body::rest_positions(trial);
    auto at = [&](body::Joint j) { return rest[static_cast<std::size_t>(map[j])]; };
    leg = body::length(at(body::Joint::left_lower_leg) - at(body::Joint::left_upper_leg)) +
          body::length(at(body::Joint::left_foot) - at(body::Joint::left_lower_leg));
  } catch (const std::invalid_argument&) {
    return 1.0;  // no legs by name: the skeleton's own problem, told when it is mapped
  }
  if (!(leg > 0.0)) return 1.0;
  double best = kUnitCandidates[0];
  auto miss = [&](double unit) { return std::abs(std::log(leg * unit / kTypicalHipToAnkle)); };
  for (const double unit : kUnitCandidates) {
    if (miss(unit) < miss(best)) best = unit;
  }
  return best;
}

Vec3 vec(const std::array<double, 3>& a) {
  return {a[0], a[1], a[2]};
}
Vec3 unit_axis(int axis) {
  return {axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0};
}

std::array<int, 3> parse_order(std::string_view order) {
  std::array<int, 3> axes{};
  bool seen[3] = {false, false, false};
  if (order.size() != 3) {
    throw std::invalid_argument("rotation order '" + std::string(order) +
                                "' is not a permutation of XYZ");
  }
  for (std::size_t k = 0; k < 3; ++k) {
    const char c = order[k];
    const int axis = c == 'X' ? 0 : c == 'Y' ? 1 : c == 'Z' ? 2 : -1;
    if (axis < 0 || seen[axis]) {
      throw std::invalid_argument("rotation order '" + std::string(order) +
                                  "' is not a permutation of XYZ");
    }
    seen[axis] = true;
    axes[k] = axis;
  }
  return axes;
}

using detail::append_fixed;

bool finite(Vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// A node's rest transform: translation, rotation and a uniform scale.
struct NodeTransform {
  Vec3 translation;
  Quat rotation;
  double scale = 1.0;
};
NodeTransform node_transform(const tinygltf::Node& node, const std::string& file) {
  NodeTransform t;
  auto refuse_scale = [&] {
    throw std::invalid_argument(file + ": node '" + node.name +
                                "' has a non-uniform or non-positive scale");
  };
  if (node.matrix.size() == 16) {  // column-major: rotation times scale, then translation
    const std::vector<double>& m = node.matrix;
    const Vec3 cx{m[0], m[1], m[2]}, cy{m[4], m[5], m[6]}, cz{m[8], m[9], m[10]};
    const double sx = body::length(cx), sy = body::length(cy), sz = body::length(cz);
    if (!(sx > 0.0) || std::abs(sx - sy) > 1e-6 * sx || std::abs(sx - sz) > 1e-6 * sx) {
      refuse_scale();
    }
    t.rotation = body::from_axes((1.0 / sx) * cx, (1.0 / sy) * cy, (1.0 / sz) * cz);
    t.translation = {m[12], m[13], m[14]};
    t.scale = sx;
    return t;
  }
  if (node.translation.size() == 3) {
    t.translation = {node.translation[0], node.translation[1], node.translation[2]};
  }
  if (node.rotation.size() == 4) {  // glTF: x, y, z, w
    t.rotation = body::normalized(
        Quat{node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]});
  }
  if (node.scale.size() == 3) {
    const double sx = node.scale[0];
    if (!(sx > 0.0) || std::abs(sx - node.scale[1]) > 1e-6 * sx ||
        std::abs(sx - node.scale[2]) > 1e-6 * sx) {
      refuse_scale();
    }
    t.scale = sx;
  }
  return t;
}

tinygltf::Model load_gltf(const std::filesystem::path& path) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error;
  std::string warning;
  const std::string file = path.string();
  std::string extension = path.extension().string();
  for (char& c : extension)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool binary = extension == ".glb" || extension == ".vrm";
  const bool loaded = binary ? loader.LoadBinaryFromFile(&model, &error, &warning, file)
                             : loader.LoadASCIIFromFile(&model, &error, &warning, file);
  if (!loaded) throw std::invalid_argument(file + ": cannot load glTF: " + error);
  return model;
}

// A node's name as a skeleton joint's: "joint<N>" for a nameless node.
std::string joint_name(const tinygltf::Model& model, int node) {
  const std::string& name = model.nodes[static_cast<std::size_t>(node)].name;
  return name.empty() ? "joint" + std::to_string(node) : name;
}

}  // namespace

body::Skeleton skeleton_from_bvh(const BvhClip& clip, std::optional<double> metres_per_unit) {
  if (metres_per_unit && (!std::isfinite(*metres_per_unit) || *metres_per_unit <= 0.0)) {
    throw std::invalid_argument("BVH skeleton: metres per unit must be finite and positive, got " +
                                number_text(*metres_per_unit));
  }
  body::Skeleton skeleton;
  std::vector<int> joint_of(clip.joints.size(), -1);  // BVH index -> skeleton index
  for (std::size_t i = 0; i < clip.joints.size(); ++i) {
    const BvhJoint& bvh = clip.joints[i];
    if (bvh.end_site) {
      const int owner = joint_of[static_cast<std::size_t>(bvh.parent)];
      skeleton.joints[static_cast<std::size_t>(owner)].end = vec(bvh.offset);
      continue;
    }
    body::SkeletonJoint joint;
    joint.name = bvh.name;
    joint.parent = bvh.parent < 0 ? -1 : joint_of[static_cast<std::size_t>(bvh.parent)];
    joint.offset = vec(bvh.offset);
    joint_of[i] = static_cast<int>(skeleton.joints.size());
    skeleton.joints.push_back(std::move(joint));
  }
  skeleton.metres_per_unit = metres_per_unit ? *metres_per_unit : guess_metres_per_unit(skeleton);
  body::validate(skeleton);
  return skeleton;
}

body::Skeleton read_bvh_skeleton(const std::filesystem::path& path,
                                 std::optional<double> metres_per_unit) {
  return skeleton_from_bvh(read_bvh_file(path), metres_per_unit);
}

void bvh_frame(const BvhClip& clip, std::size_t frame, std::span<Quat> local_rotations,
               Vec3& root_position) {
  if (frame >= clip.frame_count()) {
    throw std::out_of_range("BVH frame " + std::to_string(frame) + " beyond the clip's " +
                            std::to_string(clip.frame_count()));
  }
  const std::size_t joints = static_cast<std::size_t>(std::count_if(
      clip.joints.begin(), clip.joints.end(), [](const BvhJoint& j) { return !j.end_site; }));
  if (local_rotations.size() != joints) {
    throw std::invalid_argument("BVH frame: " + std::to_string(local_rotations.size()) +
                                " rotations for " + std::to_string(joints) + " joints");
  }
  const std::span<const double> values = clip.frame(frame);
  std::size_t out = 0;
  for (const BvhJoint& joint : clip.joints) {
    if (joint.end_site) continue;
    Quat q;
    Vec3 moved;
    for (std::size_t c = 0; c < joint.channels.size(); ++c) {
      const double value = values[joint.first_column + c];
      const int axis = axis_of(joint.channels[c]);
      if (is_rotation(joint.channels[c])) {
        q = q * body::axis_angle(unit_axis(axis), value / kDegrees);
      } else {
        moved = moved + value * unit_axis(axis);
      }
    }
    if (joint.parent < 0) root_position = vec(joint.offset) + moved;
    local_rotations[out++] = body::normalized(q);
  }
}

std::array<double, 3> euler_angles(Quat q, std::string_view order) {
  const std::array<int, 3> axes = parse_order(order);
  q = body::normalized(q);
  // The rotation matrix m[row][column].
  const double w = q.w, x = q.x, y = q.y, z = q.z;
  const double m[3][3] = {
      {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
      {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
      {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)},
  };
  const auto i = static_cast<std::size_t>(axes[0]);
  const auto j = static_cast<std::size_t>(axes[1]);
  const auto k = static_cast<std::size_t>(axes[2]);
  // +1 for the cyclic orders XYZ, YZX, ZXY.
  const double sign = (axes[1] - axes[0] + 3) % 3 == 1 ? 1.0 : -1.0;
  const double sin_b = std::clamp(sign * m[i][k], -1.0, 1.0);
  const double b = std::asin(sin_b);
  if (std::abs(sin_b) > 1.0 - 1e-12) {  // gimbal lock: the first angle takes the whole turn
    const Quat first = q * body::axis_angle(unit_axis(axes[1]), -b);
    const double along = axes[0] == 0 ? first.x : axes[0] == 1 ? first.y : first.z;
    return {2.0 * std::atan2(along, first.w), b, 0.0};
  }
  const double a = std::atan2(-sign * m[j][k], m[k][k]);
  const double c = std::atan2(-sign * m[i][j], m[i][i]);
  return {a, b, c};
}

void write_skeleton_bvh(std::ostream& out, const body::Skeleton& skeleton,
                        std::span<const Quat> local_rotations, std::span<const Vec3> root_positions,
                        const SkeletonBvhOptions& options) {
  body::validate(skeleton);
  const std::array<int, 3> axes = parse_order(options.rotation_order);
  if (options.decimals < 1 || options.decimals > 12) {
    throw std::invalid_argument("BVH: decimals must be 1 to 12, got " +
                                std::to_string(options.decimals));
  }
  if (!std::isfinite(options.frame_time) || options.frame_time < 1e-4 || options.frame_time > 1.0) {
    throw std::invalid_argument("BVH: frame time must be 1e-4 to 1 s, got " +
                                number_text(options.frame_time));
  }
  const std::size_t n = skeleton.size();
  const std::size_t frames = root_positions.size();
  if (frames == 0) throw std::invalid_argument("BVH: no frame to write");
  if (local_rotations.size() != frames * n) {
    throw std::invalid_argument("BVH: " + std::to_string(local_rotations.size()) +
                                " rotations for " + std::to_string(frames) + " frames of " +
                                std::to_string(n) + " joints");
  }
  const int d = options.decimals;
  auto vector_text = [d](Vec3 v) {
    std::string text;
    append_fixed(text, v.x, d);
    append_fixed(text, v.y, d);
    append_fixed(text, v.z, d);
    return text;
  };
  std::string rotation_channels;
  for (const int axis : axes) {
    rotation_channels += std::string(" ") + "XYZ"[axis] + "rotation";
  }
  std::vector<std::vector<std::size_t>> children(n);
  for (std::size_t i = 1; i < n; ++i) {
    children[static_cast<std::size_t>(skeleton.joints[i].parent)].push_back(i);
  }

  out << "HIERARCHY\n";
  // Depth first in joint order, which keeps the skeleton's order when parents come first and
  // each joint's subtree follows it (BVH's and glTF's usual order).
  std::vector<std::size_t> written;
  auto write = [&](auto& self, std::size_t i, std::size_t depth) -> void {
    const body::SkeletonJoint& joint = skeleton.joints[i];
    const std::string indent(depth * 2, ' ');
    out << indent << (depth == 0 ? "ROOT " : "JOINT ") << joint.name << "\n" << indent << "{\n";
    out << indent << "  OFFSET " << vector_text(depth == 0 ? Vec3{} : joint.offset) << "\n";
    out << indent << "  CHANNELS " << (depth == 0 ? "6 Xposition Yposition Zposition" : "3")
        << rotation_channels << "\n";
    written.push_back(i);
    for (const std::size_t child : children[i])
      self(self, child, depth + 1);
    if (joint.end) {
      out << indent << "  End Site\n" << indent << "  {\n";
      out << indent << "    OFFSET " << vector_text(*joint.end) << "\n" << indent << "  }\n";
    }
    out << indent << "}\n";
  };
  write(write, 0, 0);

  std::string line;
  append_fixed(line, options.frame_time, 8);
  out << "MOTION\nFrames: " << frames << "\nFrame Time: " << line << "\n";
  for (std::size_t f = 0; f < frames; ++f) {
    const Vec3 root = root_positions[f];
    if (!finite(root)) {
      throw std::invalid_argument("BVH: frame " + std::to_string(f) +
                                  ": the root position is not finite");
    }
    line = vector_text(root);
    for (const std::size_t i : written) {
      const Quat q = local_rotations[f * n + i];
      if (!std::isfinite(q.w) || !std::isfinite(q.x) || !std::isfinite(q.y) ||
          !std::isfinite(q.z)) {
        throw std::invalid_argument("BVH: frame " + std::to_string(f) + ": the rotation of '" +
                                    skeleton.joints[i].name + "' is not finite");
      }
      for (const double angle : euler_angles(q, options.rotation_order)) {
        append_fixed(line, angle * kDegrees, d);
      }
    }
    out << line << "\n";
  }
}

body::Skeleton read_gltf_skeleton(const std::filesystem::path& path, int skin_index) {
  const tinygltf::Model model = load_gltf(path);
  const std::string file = path.string();
  if (skin_index < 0 || skin_index >= static_cast<int>(model.skins.size())) {
    throw std::invalid_argument(file + ": no skin " + std::to_string(skin_index) +
                                " (the file has " + std::to_string(model.skins.size()) + ")");
  }
  const std::vector<int>& joints = model.skins[static_cast<std::size_t>(skin_index)].joints;
  if (joints.empty()) throw std::invalid_argument(file + ": the skin has no joints");
  // Each skin joint's parent node among the skin's joints.
  std::vector<int> node_parent(model.nodes.size(), -1);
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    for (const int child : model.nodes[n].children) {
      if (child >= 0 && child < static_cast<int>(model.nodes.size())) {
        node_parent[static_cast<std::size_t>(child)] = static_cast<int>(n);
      }
    }
  }
  auto skin_slot = [&](int node) {
    const auto it = std::find(joints.begin(), joints.end(), node);
    return it == joints.end() ? -1 : static_cast<int>(it - joints.begin());
  };
  // Order: parents before children, otherwise as the skin lists them.
  std::vector<int> order;
  std::vector<bool> placed(joints.size(), false);
  while (order.size() < joints.size()) {
    bool progress = false;
    for (std::size_t s = 0; s < joints.size(); ++s) {
      if (placed[s]) continue;
      const int p = skin_slot(node_parent[static_cast<std::size_t>(joints[s])]);
      if (p >= 0 && !placed[static_cast<std::size_t>(p)]) continue;
      if (p < 0 && !order.empty()) {
        throw std::invalid_argument(file + ": the skin's joints form more than one tree (node " +
                                    std::to_string(joints[s]) + " has no parent among them)");
      }
      placed[s] = true;
      order.push_back(static_cast<int>(s));
      progress = true;
    }
    if (!progress) throw std::invalid_argument(file + ": the skin's joints form no tree");
  }
  body::Skeleton skeleton;
  skeleton.metres_per_unit = 1.0;
  std::vector<int> index_of(joints.size(), -1);
  for (const int s : order) {
    const int node_index = joints[static_cast<std::size_t>(s)];
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(node_index)];
    body::SkeletonJoint joint;
    joint.name = joint_name(model, node_index);
    const int p = skin_slot(node_parent[static_cast<std::size_t>(node_index)]);
    joint.parent = p < 0 ? -1 : index_of[static_cast<std::size_t>(p)];
    const NodeTransform local = node_transform(node, file);
    joint.offset = local.translation;
    joint.rotation = local.rotation;
    if (p < 0) {
      // The nodes above the skin's root (an armature's turn and scale) fold into the root; their
      // scale becomes the skeleton's unit.
      NodeTransform above;
      for (int a = node_parent[static_cast<std::size_t>(node_index)]; a >= 0;
           a = node_parent[static_cast<std::size_t>(a)]) {
        const NodeTransform t = node_transform(model.nodes[static_cast<std::size_t>(a)], file);
        above.translation = t.translation + t.scale * rotate(t.rotation, above.translation);
        above.rotation = t.rotation * above.rotation;
        above.scale *= t.scale;
      }
      skeleton.metres_per_unit = above.scale * local.scale;
      joint.offset = (1.0 / skeleton.metres_per_unit) *
                     (above.translation + above.scale * rotate(above.rotation, joint.offset));
      joint.rotation = body::normalized(above.rotation * joint.rotation);
    }
    index_of[static_cast<std::size_t>(s)] = static_cast<int>(skeleton.joints.size());
    skeleton.joints.push_back(std::move(joint));
  }
  body::validate(skeleton);
  return skeleton;
}

}  // namespace fuzzygait::io

namespace fuzzygait::io {

std::optional<body::HumanoidMap> read_vrm_humanoid_map(const std::filesystem::path& path,
                                                       const body::Skeleton& skeleton) {
  const tinygltf::Model model = load_gltf(path);
  const std::string file = path.string();
  // (bone name, node) pairs: VRM 1.0 keys an object by bone; VRM 0.x lists {bone, node} objects.
  std::vector<std::pair<std::string, int>> bones;
  auto node_of = [](const tinygltf::Value& bone) {
    return bone.IsObject() && bone.Has("node") && bone.Get("node").IsNumber()
               ? bone.Get("node").GetNumberAsInt()
               : -1;
  };
  auto humanoid_of = [&](const char* extension) -> const tinygltf::Value* {
    const auto it = model.extensions.find(extension);
    if (it == model.extensions.end() || !it->second.IsObject()) return nullptr;
    const tinygltf::Value& humanoid = it->second.Get("humanoid");
    return humanoid.IsObject() && humanoid.Has("humanBones") ? &humanoid.Get("humanBones")
                                                             : nullptr;
  };
  if (const tinygltf::Value* human_bones = humanoid_of("VRMC_vrm")) {
    if (human_bones->IsObject()) {
      for (const std::string& key : human_bones->Keys()) {
        bones.emplace_back(key, node_of(human_bones->Get(key)));
      }
    }
  } else if (const tinygltf::Value* listed = humanoid_of("VRM")) {
    for (std::size_t i = 0; i < listed->ArrayLen(); ++i) {
      const tinygltf::Value& bone = listed->Get(static_cast<int>(i));
      if (bone.IsObject() && bone.Has("bone") && bone.Get("bone").IsString()) {
        bones.emplace_back(bone.Get("bone").Get<std::string>(), node_of(bone));
      }
    }
  } else {
    return std::nullopt;
  }
  body::HumanoidMap map;
  for (const auto& [bone, node] : bones) {
    const std::string canonical = bone == "leftMiddleProximal"    ? "leftHandEnd"
                                  : bone == "rightMiddleProximal" ? "rightHandEnd"
                                                                  : bone;
    const std::optional<body::Joint> joint = body::joint_named(canonical);
    if (!joint) continue;
    const int found = node >= 0 && node < static_cast<int>(model.nodes.size())
                          ? skeleton.find(joint_name(model, node))
                          : -1;
    if (found < 0) {
      throw std::invalid_argument(file + ": VRM bone '" + bone + "' is node " +
                                  std::to_string(node) + ", not a joint of the skeleton");
    }
    map[*joint] = found;
  }
  try {
    body::validate(map, skeleton);
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(file + ": VRM humanoid: " + error.what());
  }
  return map;
}

}  // namespace fuzzygait::io

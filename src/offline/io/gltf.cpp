#include "fuzzygait/io/gltf.hpp"

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzzygait/io/bvh.hpp"
#include "fuzzygait/io/files.hpp"
#include "offline/io/skeleton.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::io {
namespace {

using common::number_text;
using detail::Vec3;

[[noreturn]] void refuse(const std::string& what) {
  throw std::invalid_argument("glTF: " + what);
}

Vec3 operator+(Vec3 a, Vec3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
Vec3 operator-(Vec3 a, Vec3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Vec3 operator*(double s, Vec3 v) {
  return {s * v.x, s * v.y, s * v.z};
}
double dot(Vec3 a, Vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Vec3 normalized(Vec3 v) {
  return (1.0 / std::sqrt(dot(v, v))) * v;
}

// ---- What is refused ---------------------------------------------------------------------

// A GLB's length is a 32-bit number; the JSON chunk takes some kilobytes of it.
constexpr double kMaxBinaryBytes = 4.0e9;
// Ground tiles beyond this are a unit mistake (a margin of kilometres, tiles of centimetres).
constexpr double kMaxGroundQuads = 4.0e6;

void check_range(double value, double low, double high, const char* name) {
  if (!(value >= low && value <= high)) {
    refuse(std::string(name) + " must be between " + number_text(low) + " and " +
           number_text(high) + ", got " + number_text(value));
  }
}

void check_options(const GltfOptions& o) {
  check_range(o.hip_width_per_leg_length, 0.0, 1.0, "hip_width_per_leg_length");
  check_range(o.ground_width, 0.1, 100.0, "ground_width");
  check_range(o.ground_margin, 0.1, 100.0, "ground_margin");
  check_range(o.ground_tile, 0.05, 100.0, "ground_tile");
}

void check_value(double value, std::size_t frame, const std::string& field) {
  if (!std::isfinite(value)) {
    refuse("frame " + std::to_string(frame) + ": the " + field + " is not a finite number (" +
           number_text(value) + ")");
  }
}

void check_position(double value, std::size_t frame, const std::string& field) {
  check_value(value, frame, field);
  if (std::abs(value) > terrain::Terrain::kMaxCoordinate) {
    refuse("frame " + std::to_string(frame) + ": the " + field + " lies beyond " +
           number_text(terrain::Terrain::kMaxCoordinate) + " m (" + number_text(value) + ")");
  }
}

void check_motion(const eval::Motion& motion) {
  if (!std::isfinite(motion.fps) || motion.fps <= 0.0) {
    refuse("the motion's fps must be a positive number, got " + number_text(motion.fps));
  }
  if (motion.frames.empty()) refuse("the motion has no frames");
  rig::validate(motion.segments);
  float previous_time = 0.0f;
  for (std::size_t i = 0; i < motion.frames.size(); ++i) {
    const eval::Frame& frame = motion.frames[i];
    check_value(frame.time, i, "time");
    if (frame.time < 0.0) {
      refuse("frame " + std::to_string(i) + ": the time is negative (" + number_text(frame.time) +
             " s)");
    }
    const float time = static_cast<float>(frame.time);
    if (i > 0 && !(time > previous_time)) {
      refuse("frame " + std::to_string(i) + ": the time (" + number_text(frame.time) +
             " s) does not come after frame " + std::to_string(i - 1) + "'s (" +
             number_text(motion.frames[i - 1].time) + " s) as a 32-bit float");
    }
    previous_time = time;
    const rig::Pose& p = frame.pose;
    check_position(p.pelvis.x, i, "pelvis x");
    check_position(p.pelvis.y, i, "pelvis y");
    check_value(p.pelvis_tilt, i, "pelvis tilt");
    for (const rig::Side side : rig::kSides) {
      const rig::LegAngles& a = p.legs[static_cast<std::size_t>(rig::index(side))];
      const std::string leg = side == rig::Side::Left ? "left " : "right ";
      check_value(a.hip, i, leg + "hip angle");
      check_value(a.knee, i, leg + "knee angle");
      check_value(a.ankle, i, leg + "ankle angle");
      check_value(a.toe, i, leg + "toe angle");
    }
  }
}

// ---- The skeleton as glTF nodes -----------------------------------------------------------

struct Bone {
  std::string name;
  Vec3 offset;                           // from the parent, at rest
  Vec3 rest;                             // in the scene, at rest
  const detail::Joint* joint = nullptr;  // nullptr for the end leaves (not animated)
  std::vector<int> children;
};

std::string end_name(const std::string& joint) {
  if (joint == "Head") return "HeadTop_End";
  const std::string toe_base = "ToeBase";
  if (joint.ends_with(toe_base)) return joint.substr(0, joint.size() - toe_base.size()) + "Toe_End";
  return joint + "_End";
}

// Depth first, parents before children: Hips, the left leg, the right leg, the trunk.
void flatten(const detail::Joint& joint, int parent, Vec3 offset, std::vector<Bone>& bones) {
  const int index = static_cast<int>(bones.size());
  const Vec3 rest = parent < 0 ? offset : bones[static_cast<std::size_t>(parent)].rest + offset;
  bones.push_back({joint.name, offset, rest, &joint, {}});
  if (parent >= 0) bones[static_cast<std::size_t>(parent)].children.push_back(index);
  for (const detail::Joint& child : joint.children) {
    flatten(child, index, child.offset, bones);
  }
  if (joint.end_site) {
    const int end = static_cast<int>(bones.size());
    bones.push_back({end_name(joint.name), *joint.end_site, rest + *joint.end_site, nullptr, {}});
    bones[static_cast<std::size_t>(index)].children.push_back(end);
  }
}

int bone_index(const std::vector<Bone>& bones, const std::string& name) {
  for (std::size_t i = 0; i < bones.size(); ++i) {
    if (bones[i].name == name) return static_cast<int>(i);
  }
  throw std::logic_error("glTF: the skeleton has no joint " + name);
}

// ---- Meshes -------------------------------------------------------------------------------

enum Material : int { Shirt, Trousers, Skin, Shoes, GroundLight, GroundDark, kMaterials };

struct MaterialLook {
  const char* name;
  std::array<double, 3> colour;  // linear RGB, as glTF's baseColorFactor
  double roughness;
};
constexpr std::array<MaterialLook, kMaterials> kLooks = {{
    {"Shirt", {0.10, 0.22, 0.45}, 0.85},
    {"Trousers", {0.09, 0.09, 0.11}, 0.9},
    {"Skin", {0.70, 0.45, 0.32}, 0.7},
    {"Shoes", {0.28, 0.08, 0.04}, 0.6},
    {"Ground light", {0.60, 0.60, 0.57}, 1.0},
    {"Ground dark", {0.40, 0.40, 0.38}, 1.0},
}};

struct Primitive {
  std::vector<float> positions;  // x, y, z per vertex
  std::vector<float> normals;
  std::vector<std::uint8_t> joints;  // 4 per vertex (skinned meshes only)
  std::vector<float> weights;        // 4 per vertex (skinned meshes only)
  std::vector<std::uint32_t> indices;

  std::uint32_t vertex_count() const { return static_cast<std::uint32_t>(positions.size() / 3); }
  // `joint` < 0: not skinned.
  void add_vertex(Vec3 p, Vec3 n, int joint) {
    positions.insert(positions.end(),
                     {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
    normals.insert(normals.end(),
                   {static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z)});
    if (joint >= 0) {
      joints.insert(joints.end(), {static_cast<std::uint8_t>(joint), 0, 0, 0});
      weights.insert(weights.end(), {1.0f, 0.0f, 0.0f, 0.0f});
    }
  }
  void add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    indices.insert(indices.end(), {a, b, c});
  }
};

// A capsule with an elliptic section: it spans from `from` to `to` exactly, its section has the
// radius `radius_across` along `across` (made perpendicular to the axis) and `radius_other`
// perpendicular to both, and its ends are half ellipsoids reaching `cap` along the axis.
struct Capsule {
  Vec3 from;
  Vec3 to;
  Vec3 across;
  double radius_across = 0.0;
  double radius_other = 0.0;
  double cap = 0.0;
  int around = 12;  // vertices around a ring
  int rings = 3;    // rings per end, the equator included
};

// Triangles wind counter-clockwise seen from outside (glTF's front faces); normals are smooth.
void add_capsule(Primitive& mesh, const Capsule& c, int joint) {
  const Vec3 axis = c.to - c.from;
  const double length = std::sqrt(dot(axis, axis));
  const Vec3 w = (1.0 / length) * axis;
  const Vec3 u = normalized(c.across - dot(c.across, w) * w);
  const Vec3 v = cross(w, u);  // (u, v, w) right-handed
  const double cap = std::min(c.cap, 0.5 * length);
  const Vec3 bottom = c.from + cap * w;
  const Vec3 top = c.to - cap * w;
  const double ru = c.radius_across;
  const double rv = c.radius_other;

  const std::uint32_t first = mesh.vertex_count();
  mesh.add_vertex(c.from, -1.0 * w, joint);
  // An ellipsoid (the ends meet) has one equator; a capsule has one at each end.
  const bool ellipsoid = cap >= 0.5 * length;
  const int ring_count = 2 * c.rings - (ellipsoid ? 1 : 0);
  const double step = 0.5 * std::numbers::pi / c.rings;
  for (int r = 0; r < ring_count; ++r) {
    // From the bottom pole (polar angle pi) up to the top one (0): the bottom end's rings up to
    // its equator, then the top end's from its equator (the same one in an ellipsoid).
    const bool lower = r < c.rings;
    const int above = r - c.rings + (ellipsoid ? 1 : 0);  // rings above the top end's equator
    const double polar =
        lower ? std::numbers::pi - (r + 1) * step : 0.5 * std::numbers::pi - above * step;
    const Vec3 centre = lower ? bottom : top;
    for (int k = 0; k < c.around; ++k) {
      const double azimuth = 2.0 * std::numbers::pi * k / c.around;
      const double du = std::sin(polar) * std::cos(azimuth);
      const double dv = std::sin(polar) * std::sin(azimuth);
      const double dw = std::cos(polar);
      const Vec3 position = centre + (ru * du) * u + (rv * dv) * v + (cap * dw) * w;
      const Vec3 normal = normalized((du / ru) * u + (dv / rv) * v + (dw / cap) * w);
      mesh.add_vertex(position, normal, joint);
    }
  }
  mesh.add_vertex(c.to, w, joint);

  const auto at = [&](int ring, int k) {
    return first + 1 + static_cast<std::uint32_t>(ring * c.around + k % c.around);
  };
  const std::uint32_t last = first + 1 + static_cast<std::uint32_t>(ring_count * c.around);
  for (int k = 0; k < c.around; ++k) {
    mesh.add_triangle(first, at(0, k + 1), at(0, k));
    for (int r = 0; r + 1 < ring_count; ++r) {
      mesh.add_triangle(at(r, k), at(r, k + 1), at(r + 1, k + 1));
      mesh.add_triangle(at(r, k), at(r + 1, k + 1), at(r + 1, k));
    }
    mesh.add_triangle(at(ring_count - 1, k), at(ring_count - 1, k + 1), last);
  }
}

// A limb between two joints: round, reaching `radius` beyond each joint so that it stays closed
// when the joint bends.
Capsule limb(Vec3 upper, Vec3 lower, double radius) {
  const Vec3 w = normalized(lower - upper);
  return {upper - radius * w, lower + radius * w, {1.0, 0.0, 0.0}, radius, radius, radius};
}

// Body sizes as shares of the stature (about 1.75 m: 0.04 is 7 cm), after the segment
// lengths and widths Winter (2009, Fig. 4.1) and adult anthropometric tables give, rounded.
struct BodyShape {
  double thigh_radius = 0.04;
  double shank_radius = 0.028;
  double foot_half_width = 0.026;
  double foot_height_per_ankle = 1.15;  // top of the foot over the ankle's height
  double toes_height_per_ankle = 0.6;
  double pelvis_bottom = 0.485;  // heights above the soles
  double pelvis_top = 0.64;
  double pelvis_half_depth = 0.06;
  double trunk_bottom = 0.60;
  double trunk_top = 0.835;
  double trunk_half_width = 0.095;
  double trunk_half_depth = 0.062;
  double shoulder_height = 0.80;
  double shoulder_x = 0.125;  // the arms' hanging line, off the middle
  double shoulder_half_height = 0.025;
  double shoulder_half_depth = 0.04;
  double upper_arm_radius = 0.025;
  double elbow_height = 0.615;
  double forearm_radius = 0.02;
  double wrist_height = 0.47;
  double wrist_forward = 0.02;
  double fingertip_height = 0.37;
  double hand_half_width = 0.011;
  double hand_half_depth = 0.024;
  double neck_radius = 0.03;
  double head_bottom = 0.868;
  double head_half_width = 0.044;
  double head_half_depth = 0.056;
  double nose_height = 0.925;
  double nose_radius = 0.009;
};

// The body in the rest pose, one primitive per material, skinned to `bones`.
std::array<Primitive, 4> body(const rig::Segments& s, const std::vector<Bone>& bones) {
  const BodyShape shape;
  const double h = detail::stature_of(s);
  std::array<Primitive, 4> mesh;
  const auto add = [&](Material material, const Capsule& c, const std::string& joint, int around,
                       int rings) {
    Capsule detailed = c;
    detailed.around = around;
    detailed.rings = rings;
    add_capsule(mesh[static_cast<std::size_t>(material)], detailed, bone_index(bones, joint));
  };
  const auto at = [&](const std::string& joint) {
    return bones[static_cast<std::size_t>(bone_index(bones, joint))].rest;
  };
  const Vec3 x_axis{1.0, 0.0, 0.0};
  const Vec3 up{0.0, 1.0, 0.0};
  const Vec3 forward{0.0, 0.0, 1.0};

  for (const char* side : {"Left", "Right"}) {
    const std::string name = side;
    const double x = at(name + "UpLeg").x;
    add(Trousers, limb(at(name + "UpLeg"), at(name + "Leg"), shape.thigh_radius * h),
        name + "UpLeg", 12, 3);
    add(Trousers, limb(at(name + "Leg"), at(name + "Foot"), shape.shank_radius * h), name + "Leg",
        12, 3);
    // The foot from the back of the heel to past the ball (under the toes' root), sole on y = 0.
    const double foot_radius = 0.5 * shape.foot_height_per_ankle * s.ankle_height;
    add(Shoes,
        {{x, foot_radius, -s.heel},
         {x, foot_radius, s.ball + 0.3 * s.toe},
         x_axis,
         shape.foot_half_width * h,
         foot_radius,
         0.5 * s.heel},
        name + "Foot", 12, 3);
    const double toes_radius = 0.5 * shape.toes_height_per_ankle * s.ankle_height;
    add(Shoes,
        {{x, toes_radius, s.ball},
         {x, toes_radius, s.ball + s.toe},
         x_axis,
         0.9 * shape.foot_half_width * h,
         toes_radius,
         0.4 * s.toe},
        name + "ToeBase", 12, 3);

    const double arm_x = (x > 0.0 ? 1.0 : -1.0) * shape.shoulder_x * h;
    const Vec3 shoulder{arm_x, shape.shoulder_height * h, 0.0};
    const Vec3 elbow{1.03 * arm_x, shape.elbow_height * h, -0.005 * h};
    const Vec3 wrist{1.06 * arm_x, shape.wrist_height * h, shape.wrist_forward * h};
    const Vec3 fingertips{1.07 * arm_x, shape.fingertip_height * h, 1.4 * shape.wrist_forward * h};
    add(Shirt, limb(shoulder, elbow, shape.upper_arm_radius * h), "Spine", 12, 3);
    add(Shirt, limb(elbow, wrist, shape.forearm_radius * h), "Spine", 12, 3);
    add(Skin,
        {wrist, fingertips, x_axis, shape.hand_half_width * h, shape.hand_half_depth * h,
         shape.hand_half_depth * h},
        "Spine", 12, 3);
  }

  const Vec3 middle{0.0, 0.0, 0.0};
  const double hips_half_width = at("LeftUpLeg").x + 0.9 * shape.thigh_radius * h;
  add(Trousers,
      {middle + (shape.pelvis_bottom * h) * up, middle + (shape.pelvis_top * h) * up, x_axis,
       hips_half_width, shape.pelvis_half_depth * h, 0.045 * h},
      "Hips", 16, 4);
  add(Shirt,
      {middle + (shape.trunk_bottom * h) * up, middle + (shape.trunk_top * h) * up, x_axis,
       shape.trunk_half_width * h, shape.trunk_half_depth * h, 0.06 * h},
      "Spine", 16, 4);
  // Shoulders: across, from one arm's hanging line to the other, the upper arms' tops rounding
  // them off.
  add(Shirt,
      {Vec3{-shape.shoulder_x * h, shape.shoulder_height * h, 0.0},
       Vec3{shape.shoulder_x * h, shape.shoulder_height * h, 0.0}, up,
       shape.shoulder_half_height * h, shape.shoulder_half_depth * h,
       shape.shoulder_half_height * h},
      "Spine", 12, 3);
  add(Skin,
      {at("Neck") - (0.02 * h) * up, at("Head") + (0.015 * h) * up, x_axis, shape.neck_radius * h,
       shape.neck_radius * h, shape.neck_radius * h},
      "Neck", 12, 2);
  // The head: an ellipsoid from below the chin to the top of the head.
  const Vec3 head_top = at("HeadTop_End");
  const double head_forward = 0.008 * h;
  add(Skin,
      {Vec3{0.0, shape.head_bottom * h, head_forward}, head_top + head_forward * forward, x_axis,
       shape.head_half_width * h, shape.head_half_depth * h,
       0.5 * (head_top.y - shape.head_bottom * h)},
      "Head", 16, 5);
  add(Skin,
      {Vec3{0.0, shape.nose_height * h, head_forward + 0.8 * shape.head_half_depth * h},
       Vec3{0.0, (shape.nose_height - 0.008) * h,
            head_forward + (shape.head_half_depth + 0.014) * h},
       x_axis, shape.nose_radius * h, shape.nose_radius * h, shape.nose_radius * h},
      "Head", 8, 2);
  return mesh;
}

// The ground under the walk: the profile cut at the tiles' edges, extruded across.
std::array<Primitive, 2> ground_mesh(const terrain::Terrain& ground, double x0, double x1,
                                     const GltfOptions& o) {
  const double tile = o.ground_tile;
  std::vector<rig::Point> points = ground.profile(x0, x1);
  const int strips = std::max(1, static_cast<int>(std::ceil(o.ground_width / tile - 1e-9)));
  const double estimate =
      (static_cast<double>(points.size()) + (x1 - x0) / tile + 1.0) * static_cast<double>(strips);
  if (estimate > kMaxGroundQuads) {
    refuse("the ground would have " + number_text(std::round(estimate)) +
           " tiles: shorten the walk or widen ground_tile");
  }
  for (double k = std::ceil(x0 / tile); k * tile < x1; k += 1.0) {
    if (k * tile > x0) points.push_back({k * tile, ground.height(k * tile)});
  }
  // The profile's own points first where a tile's edge falls on one.
  std::stable_sort(points.begin(), points.end(),
                   [](const rig::Point& a, const rig::Point& b) { return a.x < b.x; });
  points.erase(std::unique(points.begin(), points.end(),
                           [](const rig::Point& a, const rig::Point& b) { return a.x == b.x; }),
               points.end());

  std::array<Primitive, 2> mesh;
  const double half = 0.5 * o.ground_width;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const rig::Point& p = points[i];
    const rig::Point& q = points[i + 1];
    const double along = q.x - p.x;
    const double rise = q.y - p.y;
    const double length = std::hypot(along, rise);
    const Vec3 normal{0.0, along / length, -rise / length};
    const auto row = static_cast<long long>(std::floor(0.5 * (p.x + q.x) / tile));
    for (int strip = 0; strip < strips; ++strip) {
      const double left = half - strip * tile;  // +X is the character's left
      const double right = std::max(-half, left - tile);
      Primitive& m = mesh[static_cast<std::size_t>(((row + strip) % 2 + 2) % 2)];
      const std::uint32_t a = m.vertex_count();
      m.add_vertex({left, p.y, p.x}, normal, -1);
      m.add_vertex({right, p.y, p.x}, normal, -1);
      m.add_vertex({right, q.y, q.x}, normal, -1);
      m.add_vertex({left, q.y, q.x}, normal, -1);
      m.add_triangle(a, a + 1, a + 2);
      m.add_triangle(a, a + 2, a + 3);
    }
  }
  return mesh;
}

// ---- The binary buffer and its accessors --------------------------------------------------

class Buffers {
 public:
  explicit Buffers(tinygltf::Model& model) : model_(model) { model_.buffers.resize(1); }

  // A view of its own for each accessor, 4-byte aligned. `target`: 0 for none.
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
    if (view.byteLength > 0)
      std::memcpy(data.data() + view.byteOffset, values.data(), view.byteLength);
    model_.bufferViews.push_back(view);

    tinygltf::Accessor accessor;
    accessor.bufferView = static_cast<int>(model_.bufferViews.size() - 1);
    accessor.byteOffset = 0;
    accessor.componentType = component_type;
    accessor.type = type;
    accessor.count = count;
    model_.accessors.push_back(accessor);
    return static_cast<int>(model_.accessors.size() - 1);
  }

  // Floats with `width` components a value; with their bounds when `bounded` (glTF requires them
  // for positions and animation times).
  int add_floats(const std::vector<float>& values, int width, int target, bool bounded) {
    static constexpr std::array<int, 17> kTypes = {0,
                                                   TINYGLTF_TYPE_SCALAR,
                                                   0,
                                                   TINYGLTF_TYPE_VEC3,
                                                   TINYGLTF_TYPE_VEC4,
                                                   0,
                                                   0,
                                                   0,
                                                   0,
                                                   0,
                                                   0,
                                                   0,
                                                   0,
                                                   0,
                                                   0,
                                                   0,
                                                   TINYGLTF_TYPE_MAT4};
    const std::size_t n = static_cast<std::size_t>(width);
    const int index =
        add(values, TINYGLTF_COMPONENT_TYPE_FLOAT, kTypes[n], values.size() / n, target);
    if (bounded) {
      tinygltf::Accessor& accessor = model_.accessors.back();
      accessor.minValues.assign(n, 0.0);
      accessor.maxValues.assign(n, 0.0);
      for (std::size_t c = 0; c < n; ++c) {
        float low = values[c];
        float high = values[c];
        for (std::size_t i = c; i < values.size(); i += n) {
          low = std::min(low, values[i]);
          high = std::max(high, values[i]);
        }
        accessor.minValues[c] = low;
        accessor.maxValues[c] = high;
      }
    }
    return index;
  }

  // Triangle indices, 16-bit when the vertices allow it.
  int add_indices(const std::vector<std::uint32_t>& indices, std::uint32_t vertex_count) {
    if (vertex_count <= 65535) {
      const std::vector<std::uint16_t> narrow(indices.begin(), indices.end());
      return add(narrow, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR,
                 narrow.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    }
    return add(indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, indices.size(),
               TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  }

  tinygltf::Primitive primitive(const Primitive& mesh, int material) {
    tinygltf::Primitive p;
    p.mode = TINYGLTF_MODE_TRIANGLES;
    p.material = material;
    p.attributes["POSITION"] = add_floats(mesh.positions, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
    p.attributes["NORMAL"] = add_floats(mesh.normals, 3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
    if (!mesh.joints.empty()) {
      p.attributes["JOINTS_0"] =
          add(mesh.joints, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4,
              mesh.vertex_count(), TINYGLTF_TARGET_ARRAY_BUFFER);
      p.attributes["WEIGHTS_0"] = add_floats(mesh.weights, 4, TINYGLTF_TARGET_ARRAY_BUFFER, false);
    }
    p.indices = add_indices(mesh.indices, mesh.vertex_count());
    return p;
  }

 private:
  tinygltf::Model& model_;
};

tinygltf::Material material(Material which) {
  const MaterialLook& look = kLooks[static_cast<std::size_t>(which)];
  tinygltf::Material m;
  m.name = look.name;
  m.pbrMetallicRoughness.baseColorFactor = {look.colour[0], look.colour[1], look.colour[2], 1.0};
  m.pbrMetallicRoughness.metallicFactor = 0.0;
  m.pbrMetallicRoughness.roughnessFactor = look.roughness;
  return m;
}

}  // namespace

void write_gltf(std::ostream& out, const eval::Motion& motion, const terrain::Terrain& ground,
                const GltfOptions& options) {
  check_options(options);
  check_motion(motion);
  const std::size_t frame_count = motion.frames.size();

  const rig::Segments& s = motion.segments;
  const BvhOptions bvh{.hip_width_per_leg_length = options.hip_width_per_leg_length};
  const detail::Joint root = detail::skeleton(s, bvh_hip_width(s, bvh));
  std::vector<Bone> bones;
  flatten(root, -1, {0.0, s.leg_length(), 0.0}, bones);  // standing on y = 0 at rest
  std::size_t animated = 0;
  for (const Bone& bone : bones)
    animated += bone.joint != nullptr ? 1 : 0;
  // Times, the root's translations and a rotation a joint, every frame.
  const double animation_bytes =
      static_cast<double>(frame_count) * (4.0 + 12.0 + 16.0 * static_cast<double>(animated));
  if (animation_bytes > kMaxBinaryBytes) {
    refuse("the animation's " + std::to_string(frame_count) +
           " frames would not fit glTF's 4 GiB: record fewer frames");
  }

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "fuzzygait";
  Buffers buffers(model);
  for (int m = 0; m < kMaterials; ++m)
    model.materials.push_back(material(static_cast<Material>(m)));

  // Node 0, "Armature", holds the skeleton (so that importers such as Blender's make it the
  // armature object, apart from the ground); the joints follow as nodes 1 .. bones.size(), in
  // the skin in the same order.
  tinygltf::Node armature;
  armature.name = "Armature";
  armature.children = {1};
  model.nodes.push_back(armature);
  const auto node_of = [](std::size_t bone) { return static_cast<int>(bone + 1); };
  tinygltf::Skin skin;
  skin.name = "Armature";
  skin.skeleton = node_of(0);
  std::vector<float> inverse_binds;
  for (std::size_t i = 0; i < bones.size(); ++i) {
    const Bone& bone = bones[i];
    tinygltf::Node node;
    node.name = bone.name;
    node.translation = {bone.offset.x, bone.offset.y, bone.offset.z};
    for (const int child : bone.children)
      node.children.push_back(node_of(static_cast<std::size_t>(child)));
    model.nodes.push_back(node);
    skin.joints.push_back(node_of(i));
    // The rest pose turns nothing: each inverse bind matrix moves the joint back to the origin
    // (column-major).
    inverse_binds.insert(inverse_binds.end(), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0});
    inverse_binds.insert(inverse_binds.end(),
                         {static_cast<float>(-bone.rest.x), static_cast<float>(-bone.rest.y),
                          static_cast<float>(-bone.rest.z), 1.0f});
  }
  skin.inverseBindMatrices = buffers.add_floats(inverse_binds, 16, 0, false);
  model.skins.push_back(skin);

  tinygltf::Mesh body_mesh;
  body_mesh.name = "Body";
  const std::array<Primitive, 4> body_parts = body(s, bones);
  for (std::size_t m = 0; m < body_parts.size(); ++m) {
    body_mesh.primitives.push_back(buffers.primitive(body_parts[m], static_cast<int>(m)));
  }
  model.meshes.push_back(body_mesh);
  tinygltf::Node body_node;
  body_node.name = "Body";
  body_node.mesh = 0;
  body_node.skin = 0;
  model.nodes.push_back(body_node);

  double rearmost = motion.frames.front().pose.pelvis.x;
  double foremost = rearmost;
  for (const eval::Frame& frame : motion.frames) {
    rearmost = std::min(rearmost, frame.pose.pelvis.x);
    foremost = std::max(foremost, frame.pose.pelvis.x);
  }
  tinygltf::Mesh ground_node_mesh;
  ground_node_mesh.name = "Ground";
  const std::array<Primitive, 2> tiles = ground_mesh(ground, rearmost - options.ground_margin,
                                                     foremost + options.ground_margin, options);
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    if (tiles[t].indices.empty()) continue;  // one tile alone: no dark ones
    ground_node_mesh.primitives.push_back(
        buffers.primitive(tiles[t], GroundLight + static_cast<int>(t)));
  }
  model.meshes.push_back(ground_node_mesh);
  tinygltf::Node ground_node;
  ground_node.name = "Ground";
  ground_node.mesh = 1;
  model.nodes.push_back(ground_node);

  // The animation: one sampler a channel, all keyed at the frames' times.
  std::vector<float> times;
  std::vector<float> translations;
  times.reserve(frame_count);
  translations.reserve(3 * frame_count);
  for (const eval::Frame& frame : motion.frames) {
    times.push_back(static_cast<float>(frame.time));
    translations.insert(translations.end(), {0.0f, static_cast<float>(frame.pose.pelvis.y),
                                             static_cast<float>(frame.pose.pelvis.x)});
  }
  tinygltf::Animation animation;
  animation.name = "Walk";
  const int input = buffers.add_floats(times, 1, 0, true);
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
  channel(node_of(0), "translation", buffers.add_floats(translations, 3, 0, false));
  std::vector<float> rotations(4 * frame_count);
  for (std::size_t i = 0; i < bones.size(); ++i) {
    if (bones[i].joint == nullptr) continue;
    for (std::size_t f = 0; f < frame_count; ++f) {
      const double half = 0.5 * detail::x_rotation(*bones[i].joint, motion.frames[f].pose);
      rotations[4 * f] = static_cast<float>(std::sin(half));  // x, y, z, w
      rotations[4 * f + 1] = 0.0f;
      rotations[4 * f + 2] = 0.0f;
      rotations[4 * f + 3] = static_cast<float>(std::cos(half));
    }
    channel(node_of(i), "rotation", buffers.add_floats(rotations, 4, 0, false));
  }
  model.animations.push_back(animation);

  tinygltf::Scene scene;
  scene.name = "Walk";
  scene.nodes = {0, node_of(bones.size()), node_of(bones.size() + 1)};  // Body, Ground
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  if (static_cast<double>(model.buffers[0].data.size()) > kMaxBinaryBytes) {
    refuse("the file would not fit glTF's 4 GiB: record fewer frames or a shorter ground");
  }
  tinygltf::TinyGLTF writer;
  writer.WriteGltfSceneToStream(&model, out, false, true);
  if (!out) throw std::runtime_error("glTF: the stream failed while writing");
}

void write_gltf(const std::filesystem::path& path, const eval::Motion& motion,
                const terrain::Terrain& ground) {
  write_file(path, [&](std::ostream& out) { write_gltf(out, motion, ground); });
}

}  // namespace fuzzygait::io

#include "fuzzygait/body/humanoid.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "runtime/common/format.hpp"

namespace fuzzygait::body {

using common::number_text;

namespace {

struct JointInfo {
  std::string_view name;
  int parent;  // -1 for the root
};

constexpr std::array<JointInfo, kJointCount> kJoints = {{
    {"hips", -1},          {"spine", 0},         {"chest", 1},          {"neck", 2},
    {"head", 3},           {"headEnd", 4},       {"leftUpperLeg", 0},   {"leftLowerLeg", 6},
    {"leftFoot", 7},       {"leftToes", 8},      {"leftToesEnd", 9},    {"rightUpperLeg", 0},
    {"rightLowerLeg", 11}, {"rightFoot", 12},    {"rightToes", 13},     {"rightToesEnd", 14},
    {"leftShoulder", 2},   {"leftUpperArm", 16}, {"leftLowerArm", 17},  {"leftHand", 18},
    {"leftHandEnd", 19},   {"rightShoulder", 2}, {"rightUpperArm", 21}, {"rightLowerArm", 22},
    {"rightHand", 23},     {"rightHandEnd", 24},
}};

constexpr Joint joint_at(int i) {
  return static_cast<Joint>(i);
}

Joint leg_joint(rig::Side side, int along) {
  return joint_at(
      (side == rig::Side::Left ? index(Joint::left_upper_leg) : index(Joint::right_upper_leg)) +
      along);
}

}  // namespace

std::optional<Joint> parent(Joint joint) {
  const int p = kJoints[static_cast<std::size_t>(index(joint))].parent;
  if (p < 0) return std::nullopt;
  return joint_at(p);
}

std::string_view name(Joint joint) {
  return kJoints[static_cast<std::size_t>(index(joint))].name;
}

std::optional<Joint> joint_named(std::string_view joint_name) {
  for (std::size_t i = 0; i < kJointCount; ++i) {
    if (kJoints[i].name == joint_name) return joint_at(static_cast<int>(i));
  }
  return std::nullopt;
}

bool is_end(Joint joint) {
  switch (joint) {
    case Joint::head_end:
    case Joint::left_toes_end:
    case Joint::right_toes_end:
    case Joint::left_hand_end:
    case Joint::right_hand_end:
      return true;
    default:
      return false;
  }
}

Joint upper_leg(rig::Side side) {
  return leg_joint(side, 0);
}
Joint lower_leg(rig::Side side) {
  return leg_joint(side, 1);
}
Joint foot(rig::Side side) {
  return leg_joint(side, 2);
}
Joint toes(rig::Side side) {
  return leg_joint(side, 3);
}
Joint toes_end(rig::Side side) {
  return leg_joint(side, 4);
}

rig::Segments Humanoid::segments() const {
  const Humanoid& h = *this;
  rig::Segments s;
  s.thigh = -h[Joint::left_lower_leg].y;
  s.shank = -h[Joint::left_foot].y;
  s.ankle_height = -h[Joint::left_toes].y;
  s.ball = h[Joint::left_toes].z;
  s.toe = h[Joint::left_toes_end].z;
  s.heel = heel;
  return s;
}

double Humanoid::hip_width() const {
  return (*this)[Joint::left_upper_leg].x - (*this)[Joint::right_upper_leg].x;
}

Humanoid humanoid_from_stature(double stature) {
  const rig::Segments s = rig::segments_from_stature(stature);  // checks the stature
  const double H = stature;
  const double half_hips = 0.5 * 0.19 * s.leg_length();
  const double half_shoulders = 0.5 * 0.259 * H;
  const double hip_height = s.leg_length();
  const double lumbar = 0.100 * H;
  const double shoulder_height = 0.818 * H;
  const double chest_height = 0.5 * (hip_height + lumbar + shoulder_height);  // mid thorax
  const double neck_height = shoulder_height + 0.012 * H;  // the base of the neck, C7
  const double clavicle_height = shoulder_height - 0.010 * H;
  Humanoid h;
  h[Joint::hips] = {0.0, hip_height, 0.0};
  h[Joint::spine] = {0.0, lumbar, 0.0};
  h[Joint::chest] = {0.0, chest_height - hip_height - lumbar, 0.0};
  h[Joint::neck] = {0.0, neck_height - chest_height, 0.0};
  h[Joint::head] = {0.0, 0.870 * H - neck_height, 0.0};
  h[Joint::head_end] = {0.0, 0.130 * H, 0.0};
  for (const rig::Side side : rig::kSides) {
    const double out = side == rig::Side::Left ? 1.0 : -1.0;  // +X is the left
    h[upper_leg(side)] = {out * half_hips, 0.0, 0.0};
    h[lower_leg(side)] = {0.0, -s.thigh, 0.0};
    h[foot(side)] = {0.0, -s.shank, 0.0};
    h[toes(side)] = {0.0, -s.ankle_height, s.ball};
    h[toes_end(side)] = {0.0, 0.0, s.toe};
    const Joint shoulder = side == rig::Side::Left ? Joint::left_shoulder : Joint::right_shoulder;
    const int arm = index(shoulder);
    h.offset[static_cast<std::size_t>(arm)] = {out * 0.015 * H, clavicle_height - chest_height,
                                               0.0};
    h.offset[static_cast<std::size_t>(arm + 1)] = {out * (half_shoulders - 0.015 * H),
                                                   shoulder_height - clavicle_height, 0.0};
    h.offset[static_cast<std::size_t>(arm + 2)] = {0.0, -0.186 * H, 0.0};
    h.offset[static_cast<std::size_t>(arm + 3)] = {0.0, -0.146 * H, 0.0};
    h.offset[static_cast<std::size_t>(arm + 4)] = {0.0, -0.108 * H, 0.0};
  }
  h.heel = s.heel;
  return h;
}

Humanoid humanoid_with_legs(const rig::Segments& legs, std::optional<double> stature) {
  Humanoid h = humanoid_from_stature(stature.value_or(legs.leg_length() / kHipHeightPerStature));
  for (const rig::Side side : rig::kSides) {
    h[lower_leg(side)] = {0.0, -legs.thigh, 0.0};
    h[foot(side)] = {0.0, -legs.shank, 0.0};
    h[toes(side)] = {0.0, -legs.ankle_height, legs.ball};
    h[toes_end(side)] = {0.0, 0.0, legs.toe};
  }
  h[Joint::hips].y = legs.leg_length();
  h.heel = legs.heel;
  validate(h);
  return h;
}

void validate(const Humanoid& h) {
  for (std::size_t i = 0; i < kJointCount; ++i) {
    const Vec3& v = h.offset[i];
    const std::string joint(name(joint_at(static_cast<int>(i))));
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
      throw std::invalid_argument("humanoid joint '" + joint + "': offset is not finite");
    }
    if (i > 0 && length(v) < 1e-4) {
      throw std::invalid_argument("humanoid joint '" + joint + "': offset has no length (" +
                                  number_text(length(v)) + " m)");
    }
  }
  if (!std::isfinite(h.heel)) throw std::invalid_argument("humanoid heel is not finite");
  for (int along = 0; along < 5; ++along) {
    const Vec3 l = h.offset[static_cast<std::size_t>(index(leg_joint(rig::Side::Left, along)))];
    const Vec3 r = h.offset[static_cast<std::size_t>(index(leg_joint(rig::Side::Right, along)))];
    if (std::abs(l.x + r.x) > 1e-9 || l.y != r.y || l.z != r.z) {
      throw std::invalid_argument("humanoid joint '" +
                                  std::string(name(leg_joint(rig::Side::Right, along))) +
                                  "': the legs must mirror each other");
    }
  }
  if (h.hip_width() <= 0.0) {
    throw std::invalid_argument("humanoid joint 'leftUpperLeg': the left hip must lie at +X");
  }
  rig::validate(h.segments());
}

void forward_kinematics(const Humanoid& humanoid, Vec3 hips, BodyPose& pose) {
  pose.position[0] = hips;
  for (std::size_t i = 1; i < kJointCount; ++i) {
    const auto p = static_cast<std::size_t>(kJoints[i].parent);
    if (is_end(joint_at(static_cast<int>(i)))) pose.rotation[i] = pose.rotation[p];
    pose.position[i] = pose.position[p] + rotate(pose.rotation[p], humanoid.offset[i]);
  }
  for (const rig::Side side : rig::kSides) {
    const auto f = static_cast<std::size_t>(index(foot(side)));
    const Vec3 toes_offset = humanoid.offset[static_cast<std::size_t>(index(toes(side)))];
    pose.heel[static_cast<std::size_t>(rig::index(side))] =
        pose.position[f] + rotate(pose.rotation[f], Vec3{0.0, toes_offset.y, -humanoid.heel});
  }
}

std::array<Quat, kJointCount> local_rotations(const BodyPose& pose) {
  std::array<Quat, kJointCount> local{};
  local[0] = pose.rotation[0];
  for (std::size_t i = 1; i < kJointCount; ++i) {
    const auto p = static_cast<std::size_t>(kJoints[i].parent);
    local[i] = normalized(conjugate(pose.rotation[p]) * pose.rotation[i]);
  }
  return local;
}

}  // namespace fuzzygait::body

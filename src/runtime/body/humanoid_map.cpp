#include "fuzzygait/body/humanoid_map.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <string>
#include <vector>

namespace fuzzygait::body {

namespace {

// Candidate names of the canonical joints, left side and trunk; the right side's are derived.
struct Candidates {
  Joint joint;
  std::vector<std::string_view> names;
};

const std::vector<Candidates>& candidate_table() {
  static const std::vector<Candidates> table = {
      {Joint::hips, {"Hips", "Pelvis", "J_Bip_C_Hips"}},
      {Joint::spine, {"Spine", "J_Bip_C_Spine", "spine_01"}},
      {Joint::chest,
       {"Spine2", "Chest", "UpperChest", "Spine1", "J_Bip_C_Chest", "spine_05", "spine_03"}},
      {Joint::neck, {"Neck", "Neck1", "J_Bip_C_Neck", "neck_01"}},
      {Joint::head, {"Head", "J_Bip_C_Head"}},
      {Joint::head_end, {"HeadTop_End", "HeadEnd", "Head_End", "Head_Top"}},
      {Joint::left_upper_leg,
       {"LeftUpLeg", "LeftUpperLeg", "LeftThigh", "J_Bip_L_UpperLeg", "thigh_l"}},
      {Joint::left_lower_leg,
       {"LeftLeg", "LeftLowerLeg", "LeftKnee", "LeftShin", "J_Bip_L_LowerLeg", "calf_l"}},
      {Joint::left_foot, {"LeftFoot", "LeftAnkle", "J_Bip_L_Foot", "foot_l"}},
      {Joint::left_toes, {"LeftToeBase", "LeftToes", "LeftToe", "J_Bip_L_ToeBase", "ball_l"}},
      {Joint::left_toes_end, {"LeftToe_End", "LeftToesEnd", "LeftToeEnd", "LeftToeBase_End"}},
      {Joint::left_shoulder,
       {"LeftShoulder", "LeftCollar", "LeftClavicle", "J_Bip_L_Shoulder", "clavicle_l"}},
      {Joint::left_upper_arm, {"LeftArm", "LeftUpperArm", "J_Bip_L_UpperArm", "upperarm_l"}},
      {Joint::left_lower_arm, {"LeftForeArm", "LeftLowerArm", "J_Bip_L_LowerArm", "lowerarm_l"}},
      {Joint::left_hand, {"LeftHand", "J_Bip_L_Hand", "hand_l"}},
      {Joint::left_hand_end,
       {"LeftHandMiddle1", "LeftMiddleProximal", "LeftHandEnd", "LeftHand_End", "J_Bip_L_Middle1",
        "middle_01_l"}},
  };
  return table;
}
constexpr std::string_view kLeftHeelNames[] = {"LeftHeel", "LeftHeel_End"};

// The right side's counterpart of a left joint (the leg and arm blocks follow each other).
Joint right_of(Joint left) {
  const int offset = index(left) < index(Joint::right_upper_leg)
                         ? index(Joint::right_upper_leg) - index(Joint::left_upper_leg)
                         : index(Joint::right_shoulder) - index(Joint::left_shoulder);
  return static_cast<Joint>(index(left) + offset);
}
bool is_left(Joint joint) {
  return (index(joint) >= index(Joint::left_upper_leg) &&
          index(joint) < index(Joint::right_upper_leg)) ||
         (index(joint) >= index(Joint::left_shoulder) &&
          index(joint) < index(Joint::right_shoulder));
}
// The right side's name of a left candidate: "Left..." (Mixamo, CMU), "J_Bip_L_..." (VRoid),
// "..._l" (Unreal).
std::string to_right(std::string_view left_name) {
  std::string name(left_name);
  if (name.starts_with("Left")) return "Right" + name.substr(4);
  if (const std::size_t at = name.find("_L_"); at != std::string::npos) {
    return name.replace(at, 3, "_R_");
  }
  if (name.ends_with("_l")) name.back() = 'r';
  return name;
}

std::string lower(std::string_view text) {
  std::string out(text);
  for (char& c : out)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}
// A skeleton name without its namespace ("mixamorig:LeftUpLeg" -> "leftupleg"), lower case.
std::string key(std::string_view name) {
  const std::size_t colon = name.rfind(':');
  if (colon != std::string_view::npos) name.remove_prefix(colon + 1);
  return lower(name);
}

bool is_below(const Skeleton& skeleton, int joint, int ancestor) {
  for (int j = skeleton.joints[static_cast<std::size_t>(joint)].parent; j >= 0;
       j = skeleton.joints[static_cast<std::size_t>(j)].parent) {
    if (j == ancestor) return true;
  }
  return false;
}

// The nearest canonical ancestor of `joint` that `map` maps, or std::nullopt.
std::optional<Joint> mapped_ancestor(const HumanoidMap& map, Joint joint) {
  for (std::optional<Joint> p = parent(joint); p; p = parent(*p)) {
    if (map[*p] != kUnmapped) return p;
  }
  return std::nullopt;
}

std::string joint_list(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& n : names)
    text += (text.empty() ? "" : ", ") + n;
  return text;
}

}  // namespace

bool is_required(Joint joint) {
  switch (joint) {
    case Joint::hips:
    case Joint::left_upper_leg:
    case Joint::left_lower_leg:
    case Joint::left_foot:
    case Joint::right_upper_leg:
    case Joint::right_lower_leg:
    case Joint::right_foot:
      return true;
    default:
      return false;
  }
}

HumanoidMap map_humanoid(const Skeleton& skeleton) {
  validate(skeleton);
  const std::vector<Vec3> rest = rest_positions(skeleton);
  // Joints closer than this (1 mm) to the joint their canonical parent maps to are passed over:
  // they carry no bone of the canonical body.
  const double on_joint = 1e-3 / skeleton.metres_per_unit;
  std::vector<std::string> keys;
  for (const SkeletonJoint& j : skeleton.joints)
    keys.push_back(key(j.name));
  auto find_key = [&](std::string_view name) {
    const std::string wanted = lower(name);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (keys[i] == wanted) return static_cast<int>(i);
    }
    return -1;
  };

  HumanoidMap map;
  std::array<std::vector<std::string>, kJointCount> tried;
  auto try_names = [&](Joint joint, const std::vector<std::string>& names) {
    const std::optional<Joint> above = mapped_ancestor(map, joint);
    for (const std::string& name : names) {
      tried[static_cast<std::size_t>(index(joint))].push_back(name);
      const int found = find_key(name);
      if (found < 0) continue;
      if (above) {
        const int a = map[*above];
        if (!is_below(skeleton, found, a)) continue;
        if (length(rest[static_cast<std::size_t>(found)] - rest[static_cast<std::size_t>(a)]) <
            on_joint) {
          continue;
        }
      }
      map[joint] = found;
      return;
    }
  };
  // The table lists parents before children, as the canonical joints do.
  std::array<std::vector<std::string>, kJointCount> names_of;
  for (const Candidates& c : candidate_table()) {
    std::vector<std::string> names;
    for (std::string_view n : c.names)
      names.emplace_back(n);
    names.emplace_back(name(c.joint));  // VRM's
    names_of[static_cast<std::size_t>(index(c.joint))] = names;
    if (is_left(c.joint)) {
      std::vector<std::string> right;
      for (std::string_view n : c.names)
        right.push_back(to_right(n));
      right.emplace_back(name(right_of(c.joint)));
      names_of[static_cast<std::size_t>(index(right_of(c.joint)))] = right;
    }
  }
  for (std::size_t i = 0; i < kJointCount; ++i) {
    // Names already taken (VRM's name repeating a candidate) are tried once.
    std::vector<std::string> unique;
    for (const std::string& n : names_of[i]) {
      if (std::find_if(unique.begin(), unique.end(), [&](const std::string& u) {
            return lower(u) == lower(n);
          }) == unique.end()) {
        unique.push_back(n);
      }
    }
    try_names(static_cast<Joint>(i), unique);
  }
  for (const rig::Side side : rig::kSides) {
    for (std::string_view n : kLeftHeelNames) {
      const int found = find_key(side == rig::Side::Left ? std::string(n) : to_right(n));
      const int f = map[foot(side)];
      if (found >= 0 && f >= 0 && is_below(skeleton, found, f)) {
        map.heel[static_cast<std::size_t>(rig::index(side))] = found;
        break;
      }
    }
  }

  std::vector<std::string> missing;
  for (std::size_t i = 0; i < kJointCount; ++i) {
    const auto joint = static_cast<Joint>(i);
    if (is_required(joint) && map[joint] == kUnmapped) {
      missing.push_back(std::string(name(joint)) + " (tried " + joint_list(tried[i]) + ")");
    }
  }
  if (!missing.empty()) {
    throw std::invalid_argument(
        "skeleton: no joint found for the required humanoid joints " + joint_list(missing) +
        "; names are compared without case and namespace prefix; give a map by hand otherwise");
  }
  validate(map, skeleton);
  return map;
}

HumanoidMap map_humanoid(const Skeleton& skeleton, std::span<const NamedJoint> names) {
  validate(skeleton);
  HumanoidMap map;
  for (const NamedJoint& named : names) {
    const int found = skeleton.find(named.name);
    if (found < 0) {
      throw std::invalid_argument("humanoid map: " + std::string(name(named.joint)) +
                                  " is mapped to '" + named.name +
                                  "', which the skeleton does not have");
    }
    if (map[named.joint] != kUnmapped) {
      throw std::invalid_argument("humanoid map: " + std::string(name(named.joint)) +
                                  " is given twice");
    }
    map[named.joint] = found;
  }
  validate(map, skeleton);
  return map;
}

void validate(const HumanoidMap& map, const Skeleton& skeleton) {
  const int count = static_cast<int>(skeleton.size());
  std::vector<std::string> missing;
  std::vector<int> used_by(skeleton.size(), -1);
  auto joint_name = [&](int j) {
    return "'" + skeleton.joints[static_cast<std::size_t>(j)].name + "'";
  };
  for (std::size_t i = 0; i < kJointCount; ++i) {
    const auto joint = static_cast<Joint>(i);
    const int j = map.joint[i];
    if (j == kUnmapped) {
      if (is_required(joint)) missing.emplace_back(name(joint));
      continue;
    }
    if (j < 0 || j >= count) {
      throw std::invalid_argument("humanoid map: " + std::string(name(joint)) + " maps to joint " +
                                  std::to_string(j) + ", beyond the skeleton's " +
                                  std::to_string(count));
    }
    int& user = used_by[static_cast<std::size_t>(j)];
    if (user >= 0) {
      throw std::invalid_argument("humanoid map: " + joint_name(j) + " stands for both " +
                                  std::string(name(static_cast<Joint>(user))) + " and " +
                                  std::string(name(joint)));
    }
    user = static_cast<int>(i);
    if (const std::optional<Joint> above = mapped_ancestor(map, joint)) {
      if (!is_below(skeleton, j, map[*above])) {
        throw std::invalid_argument("humanoid map: " + std::string(name(joint)) + " <- " +
                                    joint_name(j) + " does not lie below " +
                                    std::string(name(*above)) + " <- " + joint_name(map[*above]));
      }
    }
  }
  for (std::size_t side = 0; side < 2; ++side) {
    const int h = map.heel[side];
    if (h != kUnmapped && (h < 0 || h >= count)) {
      throw std::invalid_argument("humanoid map: heel joint " + std::to_string(h) +
                                  " beyond the skeleton's " + std::to_string(count));
    }
  }
  if (!missing.empty()) {
    throw std::invalid_argument("humanoid map: the required humanoid joints " +
                                joint_list(missing) + " are not mapped");
  }
}

std::string describe(const HumanoidMap& map, const Skeleton& skeleton) {
  std::string text;
  for (std::size_t i = 0; i < kJointCount; ++i) {
    const int j = map.joint[i];
    if (j < 0 || j >= static_cast<int>(skeleton.size())) continue;
    text += std::string(name(static_cast<Joint>(i))) + " <- " +
            skeleton.joints[static_cast<std::size_t>(j)].name + "\n";
  }
  return text;
}

}  // namespace fuzzygait::body

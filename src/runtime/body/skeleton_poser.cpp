#include "fuzzygait/body/skeleton_poser.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace fuzzygait::body {

namespace {

constexpr Vec3 kLeft{1.0, 0.0, 0.0};
constexpr Vec3 kUp{0.0, 1.0, 0.0};
constexpr Vec3 kDown{0.0, -1.0, 0.0};
constexpr Vec3 kForward{0.0, 0.0, 1.0};

// Winter's (2009, Fig. 4.1) shares, as rig::segments_from_stature has them.
constexpr double kThighAndShankPerStature = 0.530 - 0.039;
constexpr double kAnkleHeightPerStature = 0.039;
constexpr double kFootPerStature = 0.152;
constexpr double kHeelShare = 0.25;        // of the foot's length, behind the ankle
constexpr double kBallShare = 0.48;        // ankle to the ball
constexpr double kToeShare = 0.27;         // ball to the tip
constexpr double kMinAnkleHeight = 0.005;  // m: below it the skeleton's feet say nothing
constexpr double kMinBone = 1e-4;          // m: Humanoid's validate refuses shorter offsets

// Where a segment points in the reference pose, and which body axis fixes its roll.
enum class Roll { left, forward };
struct Segment {
  Joint joint;
  std::vector<Joint> toward;  // the joints that give its direction, nearest first
  Vec3 reference;
  Roll roll;
};

std::vector<Segment> segments_table() {
  std::vector<Segment> table = {
      {Joint::spine, {Joint::chest, Joint::neck, Joint::head, Joint::head_end}, kUp, Roll::left},
      {Joint::chest, {Joint::neck, Joint::head, Joint::head_end}, kUp, Roll::left},
      {Joint::neck, {Joint::head, Joint::head_end}, kUp, Roll::left},
      {Joint::head, {Joint::head_end}, kUp, Roll::left},
  };
  for (const rig::Side side : rig::kSides) {
    const bool left = side == rig::Side::Left;
    const int arm = index(left ? Joint::left_shoulder : Joint::right_shoulder);
    auto a = [arm](int along) { return static_cast<Joint>(arm + along); };
    table.push_back({upper_leg(side), {lower_leg(side), foot(side)}, kDown, Roll::left});
    table.push_back({lower_leg(side), {foot(side)}, kDown, Roll::left});
    table.push_back({a(0), {a(1), a(2), a(3)}, left ? kLeft : -kLeft, Roll::forward});
    table.push_back({a(1), {a(2), a(3), a(4)}, kDown, Roll::forward});
    table.push_back({a(2), {a(3), a(4)}, kDown, Roll::forward});
    table.push_back({a(3), {a(4)}, kDown, Roll::forward});
  }
  return table;
}

// The rotation whose x axis is `direction` and whose y axis is `roll_axis` made perpendicular to
// it; std::nullopt when they are (nearly) parallel.
std::optional<Quat> segment_frame(Vec3 direction, Vec3 roll_axis) {
  const Vec3 d = normalized(direction);
  const Vec3 across = roll_axis - dot(roll_axis, d) * d;
  if (length(across) < 1e-6) return std::nullopt;
  const Vec3 y = normalized(across);
  return from_axes(d, y, cross(d, y));
}

struct Fit {
  Humanoid humanoid;
  std::array<Quat, kJointCount> orientation{};  // C_J of each mapped joint (hips: the facing)
  std::array<bool, kJointCount> oriented{};
  Quat facing;
  Vec3 hips_joint_offset;  // metres, canonical frame
};

class Fitter {
 public:
  Fitter(const Skeleton& skeleton, const HumanoidMap& map)
      : skeleton_(skeleton),
        map_(map),
        rest_(rest_positions(skeleton)),
        rest_rotation_(rest_world_rotations(skeleton)),
        scale_(skeleton.metres_per_unit),
        on_joint_(1e-3 / skeleton.metres_per_unit) {}

  Fit run() {
    find_facing();
    orient_segments();
    measure_legs();
    place_the_rest();
    validate(fit_.humanoid);
    return fit_;
  }

 private:
  std::string joint_text(int j) const {
    return "'" + skeleton_.joints[static_cast<std::size_t>(j)].name + "'";
  }
  Vec3 rest(int j) const { return rest_[static_cast<std::size_t>(j)]; }
  int mapped(Joint joint) const {
    return is_end(joint) ? kUnmapped : map_[joint];  // end points are never posed
  }

  // The end of the bone joint `s` starts: its End Site, else its first child past children that
  // lie on it.
  std::optional<Vec3> end_point(int s) const {
    const SkeletonJoint& joint = skeleton_.joints[static_cast<std::size_t>(s)];
    if (joint.end) return rest(s) + rotate(rest_rotation_[static_cast<std::size_t>(s)], *joint.end);
    int at = s;
    for (;;) {
      int child = -1;
      for (std::size_t i = static_cast<std::size_t>(at) + 1; i < skeleton_.size(); ++i) {
        if (skeleton_.joints[i].parent == at) {
          child = static_cast<int>(i);
          break;
        }
      }
      if (child < 0) return std::nullopt;
      if (length(rest(child) - rest(s)) >= on_joint_) return rest(child);
      at = child;
    }
  }

  // A canonical joint's rest position in the skeleton: the hips' is the hip joints' midpoint.
  std::optional<Vec3> point(Joint joint) const {
    if (joint == Joint::hips) return mid_;
    if (map_[joint] != kUnmapped) return rest(map_[joint]);
    if (is_end(joint)) {
      const Joint before = *parent(joint);
      if (map_[before] != kUnmapped) return end_point(map_[before]);
    }
    return std::nullopt;
  }

  double height(Vec3 p) const { return scale_ * dot(p - mid_, up_); }

  void find_facing() {
    const int l = map_[Joint::left_upper_leg];
    const int r = map_[Joint::right_upper_leg];
    if (length(rest(l) - rest(r)) < on_joint_) {
      throw std::invalid_argument("skeleton: the hip joints " + joint_text(l) + " and " +
                                  joint_text(r) + " coincide; the body's left cannot be told");
    }
    mid_ = 0.5 * (rest(l) + rest(r));
    left_ = normalized(rest(l) - rest(r));
    // Up from the ankles to the hips: a standing rest pose's legs are the surest vertical (CMU's
    // head stands several degrees behind its hip joints).
    const Vec3 ankles = 0.5 * (rest(map_[Joint::left_foot]) + rest(map_[Joint::right_foot]));
    const Vec3 rise = mid_ - ankles;
    up_ = normalized(rise - dot(rise, left_) * left_);
    if (length(up_) < 0.5) {
      throw std::invalid_argument(
          "skeleton: the hips lie level with the ankles; up cannot be told");
    }
    forward_ = cross(left_, up_);
    fit_.facing = from_axes(left_, up_, forward_);
    set_orientation(Joint::hips, fit_.facing);
    fit_.hips_joint_offset =
        scale_ * rotate(conjugate(fit_.facing), rest(map_[Joint::hips]) - mid_);
  }

  void set_orientation(Joint joint, Quat c) {
    fit_.orientation[static_cast<std::size_t>(index(joint))] = c;
    fit_.oriented[static_cast<std::size_t>(index(joint))] = true;
  }
  Quat orientation(Joint joint) const {
    return fit_.orientation[static_cast<std::size_t>(index(joint))];
  }
  bool oriented(Joint joint) const { return fit_.oriented[static_cast<std::size_t>(index(joint))]; }
  // The nearest canonical ancestor with an orientation (hips at least).
  Joint oriented_ancestor(Joint joint) const {
    Joint p = *parent(joint);
    while (!oriented(p))
      p = *parent(p);
    return p;
  }

  // The facing turned about up so that forward points along `along`'s horizontal part.
  Quat flat_frame(Vec3 along) const {
    const Vec3 horizontal = along - dot(along, up_) * up_;
    if (length(horizontal) < on_joint_) return fit_.facing;
    const Vec3 z = normalized(horizontal);
    return from_axes(cross(up_, z), up_, z);
  }

  void orient_segments() {
    for (const Segment& segment : segments_table()) {
      const int s = mapped(segment.joint);
      if (s == kUnmapped) continue;
      std::optional<Vec3> toward;
      for (const Joint next : segment.toward) {
        if ((toward = point(next))) break;
      }
      if (!toward) {  // a bone without an end: aligned as the one before it
        set_orientation(segment.joint, orientation(oriented_ancestor(segment.joint)));
        continue;
      }
      const Vec3 direction = *toward - rest(s);
      if (length(direction) < on_joint_) {
        throw std::invalid_argument("skeleton joint " + joint_text(s) + " (" +
                                    std::string(name(segment.joint)) + "): its bone has no length");
      }
      const Vec3 roll = segment.roll == Roll::left ? left_ : forward_;
      const Vec3 roll_reference = segment.roll == Roll::left ? kLeft : kForward;
      std::optional<Quat> rest_frame = segment_frame(direction, roll);
      std::optional<Quat> reference_frame = segment_frame(segment.reference, roll_reference);
      if (!rest_frame) {  // the bone lies along the roll axis: its roll from up instead
        rest_frame = segment_frame(direction, up_);
        reference_frame = segment_frame(segment.reference, kUp);
        if (!rest_frame || !reference_frame) {  // along up as well: impossible for a unit vector
          rest_frame = segment_frame(direction, forward_);
          reference_frame = segment_frame(segment.reference, kForward);
        }
      }
      set_orientation(segment.joint, normalized(*rest_frame * conjugate(*reference_frame)));
    }
    for (const rig::Side side : rig::kSides) {
      const int f = mapped(foot(side));
      const int t = mapped(toes(side));
      const std::optional<Vec3> tip = t != kUnmapped ? point(toes_end(side)) : end_point(f);
      const std::optional<Vec3> ahead = t != kUnmapped ? std::optional<Vec3>(rest(t)) : tip;
      const Quat foot_frame = ahead ? flat_frame(*ahead - rest(f)) : fit_.facing;
      set_orientation(foot(side), foot_frame);
      if (t != kUnmapped) {
        set_orientation(toes(side), tip ? flat_frame(*tip - rest(t)) : foot_frame);
      }
    }
  }

  void measure_legs() {
    struct Leg {
      double thigh = 0.0, shank = 0.0, ankle = 0.0;
      std::optional<double> ball, toe, heel, tip_from_ankle;
    };
    std::array<Leg, 2> legs;
    std::vector<double> floor_heights;
    for (const rig::Side side : rig::kSides) {
      Leg& leg = legs[static_cast<std::size_t>(rig::index(side))];
      const int h = map_[upper_leg(side)];
      const int k = map_[lower_leg(side)];
      const int a = map_[foot(side)];
      leg.thigh = scale_ * length(rest(k) - rest(h));
      leg.shank = scale_ * length(rest(a) - rest(k));
      for (const auto& [bone, size] : {std::pair{k, leg.thigh}, std::pair{a, leg.shank}}) {
        if (size < kMinBone) {
          throw std::invalid_argument("skeleton joint " + joint_text(bone) +
                                      ": the leg bone ending there has no length");
        }
      }
      leg.ankle = height(rest(a));
      const Vec3 along = rotate(orientation(foot(side)), kForward);
      auto ahead_of = [&](Vec3 p, Vec3 from) { return scale_ * dot(p - from, along); };
      const int t = mapped(toes(side));
      const std::optional<Vec3> tip = t != kUnmapped ? point(toes_end(side)) : end_point(a);
      if (t != kUnmapped) {
        leg.ball = ahead_of(rest(t), rest(a));
        floor_heights.push_back(height(rest(t)));
        if (tip) leg.toe = ahead_of(*tip, rest(t));
      } else if (tip) {
        leg.tip_from_ankle = ahead_of(*tip, rest(a));
      }
      if (tip) floor_heights.push_back(height(*tip));
      if (const int heel = map_.heel[static_cast<std::size_t>(rig::index(side))]; heel >= 0) {
        leg.heel = -ahead_of(rest(heel), rest(a));
        floor_heights.push_back(height(rest(heel)));
      }
    }
    auto mean = [&](auto field) { return 0.5 * (field(legs[0]) + field(legs[1])); };
    rig::Segments s;
    s.thigh = mean([](const Leg& l) { return l.thigh; });
    s.shank = mean([](const Leg& l) { return l.shank; });
    stature_ = (s.thigh + s.shank) / kThighAndShankPerStature;
    const double ankle = mean([](const Leg& l) { return l.ankle; });
    const double floor = floor_heights.empty()
                             ? ankle - kAnkleHeightPerStature * stature_
                             : *std::min_element(floor_heights.begin(), floor_heights.end());
    s.ankle_height = ankle - floor;
    if (s.ankle_height < kMinAnkleHeight) s.ankle_height = kAnkleHeightPerStature * stature_;
    auto mean_of = [&](std::optional<double> Leg::*field) -> std::optional<double> {
      if (!(legs[0].*field) || !(legs[1].*field)) return std::nullopt;
      return 0.5 * (*(legs[0].*field) + *(legs[1].*field));
    };
    const std::optional<double> ball = mean_of(&Leg::ball);
    const std::optional<double> toe = mean_of(&Leg::toe);
    const std::optional<double> tip = mean_of(&Leg::tip_from_ankle);
    const std::optional<double> heel = mean_of(&Leg::heel);
    const double foot_ahead = kBallShare + kToeShare;
    s.ball = ball  ? *ball
             : tip ? *tip * kBallShare / foot_ahead
                   : kBallShare * kFootPerStature * stature_;
    s.toe = toe ? *toe : tip ? *tip * kToeShare / foot_ahead : s.ball * kToeShare / kBallShare;
    s.heel = heel ? *heel : s.ball * kHeelShare / kBallShare;

    Humanoid& out = fit_.humanoid;
    out = humanoid_from_stature(std::clamp(stature_, 0.5, 3.0));
    const double half_width =
        0.5 * scale_ *
        length(rest(map_[Joint::left_upper_leg]) - rest(map_[Joint::right_upper_leg]));
    out[Joint::hips] = {0.0, s.leg_length(), 0.0};
    for (const rig::Side side : rig::kSides) {
      const double outward = side == rig::Side::Left ? 1.0 : -1.0;
      out[upper_leg(side)] = {outward * half_width, 0.0, 0.0};
      out[lower_leg(side)] = {0.0, -s.thigh, 0.0};
      out[foot(side)] = {0.0, -s.shank, 0.0};
      out[toes(side)] = {0.0, -s.ankle_height, s.ball};
      out[toes_end(side)] = {0.0, 0.0, s.toe};
    }
    out.heel = s.heel;
  }

  bool is_leg(Joint joint) const {
    return index(joint) >= index(Joint::left_upper_leg) &&
           index(joint) <= index(Joint::right_toes_end);
  }

  // Trunk, head and arms: each joint the skeleton has from the nearest one above it that has an
  // orientation, through the canonical joints it lacks in between.
  void place_the_rest() {
    Humanoid& out = fit_.humanoid;
    const Humanoid reference = out;  // humanoid_from_stature's offsets for what is missing
    for (std::size_t i = 1; i < kJointCount; ++i) {
      const auto joint = static_cast<Joint>(i);
      if (is_leg(joint)) continue;
      const std::optional<Vec3> at = point(joint);
      if (!at) continue;
      const Joint above = oriented_ancestor(joint);
      const Vec3 from = *point(above);
      const Vec3 v = scale_ * rotate(conjugate(orientation(above)), *at - from);
      if (length(v) < kMinBone) {
        const int s = map_[joint] != kUnmapped ? map_[joint] : map_[*parent(joint)];
        throw std::invalid_argument("skeleton joint " + joint_text(s) + " (" +
                                    std::string(name(joint)) + ") lies on " +
                                    std::string(name(above)) + "'s joint; map another joint");
      }
      std::vector<Joint> chain{joint};
      for (Joint p = *parent(joint); p != above; p = *parent(p))
        chain.push_back(p);
      double total = 0.0;
      for (const Joint c : chain)
        total += length(reference[c]);
      for (const Joint c : chain)
        out[c] = (length(reference[c]) / total) * v;
    }
  }

  const Skeleton& skeleton_;
  const HumanoidMap& map_;
  std::vector<Vec3> rest_;
  std::vector<Quat> rest_rotation_;
  double scale_;
  double on_joint_;
  Vec3 mid_, left_, up_, forward_;
  double stature_ = 0.0;
  Fit fit_;
};

Fit fit_skeleton(const Skeleton& skeleton, const HumanoidMap& map) {
  validate(skeleton);
  validate(map, skeleton);
  return Fitter(skeleton, map).run();
}

bool finite(Vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(Quat q) {
  return std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
}

}  // namespace

Humanoid humanoid_from_skeleton(const Skeleton& skeleton, const HumanoidMap& map) {
  return fit_skeleton(skeleton, map).humanoid;
}

SkeletonPoser::SkeletonPoser(const Skeleton& skeleton, const HumanoidMap& map) {
  const Fit fit = fit_skeleton(skeleton, map);
  humanoid_ = fit.humanoid;
  const Quat unface = conjugate(fit.facing);
  for (std::size_t i = 0; i < kJointCount; ++i) {
    Joint joint = static_cast<Joint>(i);
    while (!fit.oriented[static_cast<std::size_t>(index(joint))])
      joint = *parent(joint);
    rest_orientations_[i] =
        normalized(unface * fit.orientation[static_cast<std::size_t>(index(joint))]);
  }
  const std::size_t n = skeleton.size();
  const std::vector<Quat> rest_rotation = rest_world_rotations(skeleton);
  const std::vector<Vec3> rest = rest_positions(skeleton);
  std::vector<int> canonical_of(n, -1);
  for (std::size_t i = 0; i < kJointCount; ++i) {
    if (!is_end(static_cast<Joint>(i)) && map.joint[i] != kUnmapped) {
      canonical_of[static_cast<std::size_t>(map.joint[i])] = static_cast<int>(i);
    }
  }
  parents_.resize(n);
  rest_local_.resize(n);
  anchor_.assign(n, -1);
  from_anchor_.resize(n);
  mapped_.assign(n, false);
  for (std::size_t s = 0; s < n; ++s) {
    const SkeletonJoint& joint = skeleton.joints[s];
    parents_[s] = joint.parent;
    rest_local_[s] = joint.rotation;
    mapped_[s] = canonical_of[s] >= 0;
    anchor_[s] = mapped_[s]          ? canonical_of[s]
                 : joint.parent >= 0 ? anchor_[static_cast<std::size_t>(joint.parent)]
                                     : -1;
    from_anchor_[s] =
        anchor_[s] < 0
            ? rest_rotation[s]
            : normalized(conjugate(fit.orientation[static_cast<std::size_t>(anchor_[s])]) *
                         rest_rotation[s]);
  }
  units_per_metre_ = 1.0 / skeleton.metres_per_unit;
  hips_joint_ = map[Joint::hips];
  hips_joint_offset_ = fit.hips_joint_offset;
  root_to_hips_rest_ = rest[static_cast<std::size_t>(hips_joint_)] - rest[0];
  root_rest_offset_ = skeleton.joints[0].offset;
  offsets_.resize(n);
  for (std::size_t s = 0; s < n; ++s)
    offsets_[s] = skeleton.joints[s].offset;
}

bool SkeletonPoser::pose(const BodyPose& body, std::span<Quat> local, Vec3& root_position) const {
  assert(local.size() == parents_.size());
  const std::size_t n = std::min(local.size(), parents_.size());
  bool usable = finite(body[Joint::hips]);
  for (const Quat& q : body.rotation)
    usable = usable && finite(q);
  if (!usable) {
    std::copy_n(rest_local_.begin(), n, local.begin());
    root_position = root_rest_offset_;
    return false;
  }
  auto world = [&](std::size_t s) {
    const int a = anchor_[s];
    return a < 0 ? from_anchor_[s] : body.rotation[static_cast<std::size_t>(a)] * from_anchor_[s];
  };
  for (std::size_t s = 0; s < n; ++s) {
    if (!mapped_[s]) {
      local[s] = rest_local_[s];
      continue;
    }
    const int p = parents_[s];
    local[s] = p < 0 ? normalized(world(s))
                     : normalized(conjugate(world(static_cast<std::size_t>(p))) * world(s));
  }
  const Vec3 hips_joint =
      body[Joint::hips] +
      rotate(body.rotation[static_cast<std::size_t>(index(Joint::hips))], hips_joint_offset_);
  root_position = units_per_metre_ * hips_joint - root_to_hips_rest_;
  return true;
}

}  // namespace fuzzygait::body

namespace fuzzygait::body {

bool SkeletonPoser::unpose(std::span<const Quat> local, Vec3 root_position, std::span<Quat> world,
                           BodyPose& body) const {
  const std::size_t n = parents_.size();
  if (local.size() != n || world.size() != n || !finite(root_position)) return false;
  for (std::size_t s = 0; s < n; ++s) {
    if (!finite(local[s])) return false;
    const int p = parents_[s];
    world[s] = p < 0 ? local[s] : world[static_cast<std::size_t>(p)] * local[s];
  }
  std::array<Quat, kJointCount> rotation{};
  std::array<bool, kJointCount> shown{};
  for (std::size_t s = 0; s < n; ++s) {
    if (!mapped_[s]) continue;
    const auto j = static_cast<std::size_t>(anchor_[s]);
    rotation[j] = normalized(world[s] * conjugate(from_anchor_[s]));
    shown[j] = true;
  }
  for (std::size_t i = 1; i < kJointCount; ++i) {  // the rest follow their parents
    if (!shown[i])
      rotation[i] = rotation[static_cast<std::size_t>(index(*parent(static_cast<Joint>(i))))];
  }
  // The hips joint's position, walking up from it to the root.
  Vec3 hips_joint = root_position;
  for (int s = hips_joint_; parents_[static_cast<std::size_t>(s)] >= 0;
       s = parents_[static_cast<std::size_t>(s)]) {
    const auto p = static_cast<std::size_t>(parents_[static_cast<std::size_t>(s)]);
    hips_joint = hips_joint + rotate(world[p], offsets_[static_cast<std::size_t>(s)]);
  }
  body.rotation = rotation;
  const Vec3 hips =
      (1.0 / units_per_metre_) * hips_joint -
      rotate(rotation[static_cast<std::size_t>(index(Joint::hips))], hips_joint_offset_);
  forward_kinematics(humanoid_, hips, body);
  return true;
}

Skeleton skeleton_of(const Humanoid& humanoid) {
  validate(humanoid);
  Skeleton skeleton;
  std::array<int, kJointCount> at{};  // each non-end joint's index in the skeleton
  for (std::size_t j = 0; j < kJointCount; ++j) {
    const auto joint = static_cast<Joint>(j);
    const std::optional<Joint> up = parent(joint);
    if (is_end(joint)) {
      skeleton.joints[static_cast<std::size_t>(at[static_cast<std::size_t>(index(*up))])].end =
          humanoid.offset[j];
      continue;
    }
    at[j] = static_cast<int>(skeleton.joints.size());
    SkeletonJoint s;
    s.name = std::string(name(joint));
    s.parent = up ? at[static_cast<std::size_t>(index(*up))] : -1;
    s.offset = humanoid.offset[j];
    skeleton.joints.push_back(std::move(s));
  }
  validate(skeleton);
  return skeleton;
}

}  // namespace fuzzygait::body

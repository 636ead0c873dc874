#include "fuzzygait/body/follower.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "runtime/common/format.hpp"

namespace fuzzygait::body {

using common::number_text;

namespace {

constexpr Vec3 kUp{0.0, 1.0, 0.0};
constexpr Vec3 kLeft{1.0, 0.0, 0.0};
constexpr Vec3 kForward{0.0, 0.0, 1.0};

Vec3 forward_of(double heading) {
  return {std::sin(heading), 0.0, std::cos(heading)};
}

Vec3 left_of(double heading) {
  return {std::cos(heading), 0.0, -std::sin(heading)};
}

Quat yaw(double heading) {
  return axis_angle(kUp, heading);
}

// A sagittal-plane rotation (about the character's left) by `pitch`, the toes-up angle of a
// foot: rotating about +X turns +Z down, so toes up is a negative turn.
Quat pitch_up(double pitch) {
  return axis_angle(kLeft, -pitch);
}

// A bone's world rotation from its direction from parent joint to child (`along`, where the
// reference pose points down) and the direction its knee side faces (`front`).
Quat limb_rotation(Vec3 along, Vec3 front) {
  const Vec3 up = -along;
  Vec3 f = normalized(front - dot(front, along) * along);
  if (length(f) == 0.0) f = normalized(cross(kLeft, up));  // front along the bone: any
  return from_axes(cross(up, f), up, f);
}

// Share of the way from lift-off to the swing's target over which a lifted foot keeps its stance
// frame: its toes leave the ground before it turns.
constexpr double kHeld = 0.15;

double smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

PathFollower::PathFollower(const Humanoid& humanoid, const path::Path& path,
                           const gait::Walker& walker, const FollowerOptions& options)
    : humanoid_(humanoid),
      path_(&path),
      options_(options),
      set_(&walker.controllers()),
      last_time_(walker.time()),
      upper_body_share_(walker.standing() ? 0.0 : 1.0) {
  validate(humanoid_);
  auto check = [](const char* field, double value, double low, double high) {
    if (!std::isfinite(value) || value < low || value > high) {
      throw std::invalid_argument(std::string("follower option '") + field + "' must be between " +
                                  number_text(low) + " and " + number_text(high) + ", got " +
                                  number_text(value));
    }
  };
  check("step_width_per_leg_length", options.step_width_per_leg_length, 0.0, 0.5);
  check("swing_release", options.swing_release, 0.3, 1.0);
  check("look_ahead", options.look_ahead, 0.0, 5.0);
  const rig::Segments a = humanoid_.segments();
  const rig::Segments& b = walker.segments();
  const double difference =
      std::max({std::abs(a.thigh - b.thigh), std::abs(a.shank - b.shank),
                std::abs(a.ankle_height - b.ankle_height), std::abs(a.heel - b.heel),
                std::abs(a.ball - b.ball), std::abs(a.toe - b.toe)});
  if (difference > 1e-9) {
    throw std::invalid_argument(
        "the walker's leg segments are not the humanoid's (they differ by " +
        number_text(difference) + " m): make the walker with humanoid.segments()");
  }
  step_width_ = options.step_width_per_leg_length * a.leg_length();
  for (const auto& controller : walker.controllers().upper_body) {
    workspaces_.push_back(controller ? controller->make_workspace() : fuzzy::Workspace{});
  }
}

gait::MetricValues PathFollower::leg_metrics(const gait::Walker& walker, int leg) noexcept {
  const gait::WalkerState& state = walker.state();
  const gait::LegState& l = state.legs[static_cast<std::size_t>(leg)];
  gait::MetricValues metrics{};
  auto set = [&](gait::Metric m, double value) { metrics[static_cast<std::size_t>(m)] = value; };
  set(gait::Metric::Delta, l.delta);
  set(gait::Metric::OtherDelta, state.legs[static_cast<std::size_t>(1 - leg)].delta);
  set(gait::Metric::Hip, rig::degrees(l.angles.hip));
  set(gait::Metric::Knee, rig::degrees(l.angles.knee));
  set(gait::Metric::Ankle, rig::degrees(l.angles.ankle));
  set(gait::Metric::Toe, rig::degrees(l.angles.toe));
  set(gait::Metric::Pace, gait::Walker::pace(state.speed, walker.segments()));
  const std::array<double, 2> ground = walker.ground_metrics(static_cast<rig::Side>(leg));
  set(gait::Metric::Incline, ground[0]);
  set(gait::Metric::Stairs, ground[1]);
  return metrics;
}

double PathFollower::upper_body_answer(const gait::ControllerSet& set, gait::UpperBody part,
                                       const gait::MetricValues& metrics) noexcept {
  const auto p = static_cast<std::size_t>(part);
  const auto& controller = set.upper_body[p];
  if (!options_.upper_body || !controller || &set != set_) return 0.0;
  const double answer = controller->evaluate(metrics, workspaces_[p]);
  return std::isfinite(answer) ? answer * upper_body_share_ : 0.0;
}

double PathFollower::upper_body_angle(const gait::ControllerSet& set, gait::UpperBody part,
                                      const gait::MetricValues& metrics) noexcept {
  return upper_body_answer(set, part, metrics) * (std::numbers::pi / 180.0);
}

PathFollower::FootFrame PathFollower::path_frame(double x, double lateral) const noexcept {
  const path::PathSample s = path_->at(x);
  // The character's left at heading h is (cos h, 0, -sin h).
  return {{s.point.x + lateral * std::cos(s.heading), s.point.z - lateral * std::sin(s.heading)},
          s.heading,
          x};
}

const BodyPose& PathFollower::update(const gait::Walker& walker) noexcept {
  const rig::Pose sagittal = walker.pose();
  const path::PathSample at_hips = path_->at(sagittal.pelvis.x);
  const Quat facing = yaw(at_hips.heading);
  // Each side turns forward by the answer to the other side's leg; the body turns right (heading
  // turns left +) as its left side comes forward.
  // The upper body plays while the walker walks and fades to rest while it stands.
  const double moving = walker.standing() ? 0.0 : 1.0;
  // (The first update counts as a start.)
  const bool restarted = walker.time() < last_time_ || !updated_;
  updated_ = true;
  const double elapsed = walker.time() - last_time_;
  if (walker.time() < last_time_) {
    feet_ = {};  // started again: nothing stands where it stood
    upper_body_share_ = moving;
  } else if (!(upper_body_share_ == moving)) {
    const double most = elapsed / kUpperBodyEasing;
    upper_body_share_ += std::clamp(moving - upper_body_share_, -most, most);
  }
  last_time_ = walker.time();
  const gait::ControllerSet& set = walker.controllers();
  const std::array<gait::MetricValues, 2> metrics = {leg_metrics(walker, 0),
                                                     leg_metrics(walker, 1)};
  auto turn = [&](gait::UpperBody part) {
    return upper_body_angle(set, part, metrics[0]) - upper_body_angle(set, part, metrics[1]);
  };
  // The frontal plane: the left side's answer less the right's, each from its own leg.
  const double obliquity = turn(gait::UpperBody::PelvisObliquity);  // left side up +
  const rig::Segments segments = humanoid_.segments();
  const double sway = (upper_body_answer(set, gait::UpperBody::PelvisSway, metrics[0]) -
                       upper_body_answer(set, gait::UpperBody::PelvisSway, metrics[1])) *
                      0.01 * segments.leg_length();  // to the left +, m
  const Quat pelvis = facing * yaw(turn(gait::UpperBody::PelvisRotation)) *
                      axis_angle(kForward, obliquity) * axis_angle(kLeft, sagittal.pelvis_tilt);
  // The trunk leans forward (+) by the mean of the two sides' answers (on slopes and stairs),
  // eased.
  const double lean = 0.5 * (upper_body_angle(set, gait::UpperBody::TrunkLean, metrics[0]) +
                             upper_body_angle(set, gait::UpperBody::TrunkLean, metrics[1]));
  if (restarted || std::abs(lean - lean_) < 1e-9) {
    lean_ = lean;  // (within a nanoradian it is there, so level ground is upright to the bit)
  } else {
    lean_ += (lean - lean_) * -std::expm1(-elapsed / kLeanEasing);
  }
  // The arms hang from the chest as it turns, not as it leans: their swing is from the vertical.
  const Quat square_chest = facing * yaw(turn(gait::UpperBody::ThoraxRotation));
  const Quat thorax = lean_ != 0.0 ? square_chest * axis_angle(kLeft, lean_) : square_chest;
  const Vec3 hips_before_drop =
      Vec3{at_hips.point.x, sagittal.pelvis.y, at_hips.point.z} + sway * left_of(at_hips.heading);
  const double reach = segments.thigh + segments.shank;

  struct LegTarget {
    Vec3 ankle;
    Vec3 pole;
    Vec3 forward;  // the foot's
    Quat foot;
    Quat toes;
    Vec3 hip_offset;
  };
  std::array<LegTarget, 2> legs{};
  for (const rig::Side side : rig::kSides) {
    const int i = rig::index(side);
    FootState& foot_state = feet_[static_cast<std::size_t>(i)];
    const rig::LegPoints points = walker.points(side);
    const double lateral = (side == rig::Side::Left ? 0.5 : -0.5) * step_width_;
    // A foot that stays planted stands in its locked frame: the path's frame under it is not
    // needed, nor its heading's sines (kept from the landing).
    const bool planted = walker.in_contact(side);
    const bool stays = planted && foot_state.locked;
    const FootFrame on_path = stays ? foot_state.frame : path_frame(points.heel.x, lateral);
    FootFrame frame = on_path;
    if (planted && !stays) {
      // Landed: it stays where it is drawn now; still easing from its last stance frame, that
      // is the frame it was drawn in, carried to this heel.
      foot_state.locked = true;
      foot_state.frame = on_path;
      if (foot_state.releasing) {
        const FootFrame& d = foot_state.drawn;
        const Vec3 ahead = (points.heel.x - d.anchor) * forward_of(d.heading);
        foot_state.frame = {{d.origin.x + ahead.x, d.origin.z + ahead.z}, d.heading, points.heel.x};
      }
      foot_state.releasing = false;
      foot_state.locked_forward = forward_of(foot_state.frame.heading);
      foot_state.locked_yaw = yaw(foot_state.frame.heading);
      frame = foot_state.frame;
    } else if (!planted) {
      if (foot_state.locked) {
        // Lifted: keep how far the stance frame is off the path's here, in the path's frame.
        const FootFrame& from = foot_state.frame;
        const Vec3 ahead = (points.heel.x - from.anchor) * forward_of(from.heading);
        const Vec3 off{from.origin.x + ahead.x - on_path.origin.x, 0.0,
                       from.origin.z + ahead.z - on_path.origin.z};
        foot_state.offset_along = dot(off, forward_of(on_path.heading));
        foot_state.offset_left = dot(off, left_of(on_path.heading));
        foot_state.offset_turn =
            std::remainder(from.heading - on_path.heading, 2.0 * std::numbers::pi);
        foot_state.locked = false;
        foot_state.releasing = true;
        foot_state.release_x = points.heel.x;
        foot_state.release_way = std::max(
            walker.state().legs[static_cast<std::size_t>(i)].target_x - points.heel.x, 0.05);
        foot_state.share = 0.0;
      }
      if (foot_state.releasing) {
        // The offset fades over the swing's first part (never back, though the target moves);
        // the foot follows the path meanwhile.
        const double way = foot_state.release_way;
        foot_state.share = std::max(
            foot_state.share, smoothstep((points.heel.x - foot_state.release_x - kHeld * way) /
                                         (way * (options_.swing_release - kHeld))));
        if (foot_state.share >= 1.0) foot_state.releasing = false;
        const double keep = 1.0 - foot_state.share;
        const Vec3 off = keep * foot_state.offset_along * forward_of(on_path.heading) +
                         keep * foot_state.offset_left * left_of(on_path.heading);
        frame.origin = {on_path.origin.x + off.x, on_path.origin.z + off.z};
        frame.heading = on_path.heading + keep * foot_state.offset_turn;
      }
    }
    foot_state.drawn = frame;
    const bool locked = foot_state.locked;
    const Vec3 forward = locked ? foot_state.locked_forward : forward_of(frame.heading);
    auto world = [&](rig::Point p) {
      return Vec3{frame.origin.x, 0.0, frame.origin.z} + (p.x - frame.anchor) * forward + p.y * kUp;
    };
    // The knee's side: the walker's knee direction, square to its hip-ankle line.
    const double hx = points.ankle.x - points.hip.x;
    const double hy = points.ankle.y - points.hip.y;
    const double hl = std::hypot(hx, hy);
    const rig::Point square = hl > 0.0 ? rig::Point{-hy / hl, hx / hl} : rig::Point{1.0, 0.0};
    const rig::LegOrientation o = rig::orientation(sagittal.pelvis_tilt, sagittal.legs[i]);
    const Quat heading = locked ? foot_state.locked_yaw : yaw(frame.heading);
    legs[static_cast<std::size_t>(i)] = {world(points.ankle),
                                         square.x * forward + square.y * kUp,
                                         forward,
                                         heading * pitch_up(o.foot),
                                         heading * pitch_up(o.toes),
                                         rotate(pelvis, humanoid_[upper_leg(side)])};
  }

  // Lower the hips as far as the foot farther out of reach needs, at most 0.1 of a leg.
  double drop = 0.0;
  for (const LegTarget& leg : legs) {
    const Vec3 hip = hips_before_drop + leg.hip_offset;
    const double across = std::hypot(hip.x - leg.ankle.x, hip.z - leg.ankle.z);
    const double down = hip.y - leg.ankle.y;
    if (across * across + down * down <= reach * reach) continue;
    const double needed =
        across < reach ? down - std::sqrt(reach * reach - across * across) : 0.1 * reach;
    drop = std::max(drop, std::min(needed, 0.1 * reach));
  }
  drop_ = drop;
  const Vec3 hips = hips_before_drop - drop * kUp;

  pose_.rotation[index(Joint::hips)] = pelvis;
  for (const Joint trunk :
       {Joint::spine, Joint::chest, Joint::neck, Joint::left_shoulder, Joint::right_shoulder}) {
    pose_.rotation[index(trunk)] = thorax;
  }
  for (const rig::Side side : rig::kSides) {
    // The arm swings against its own leg.
    const gait::MetricValues& own = metrics[static_cast<std::size_t>(rig::index(side))];
    const double shoulder = upper_body_angle(set, gait::UpperBody::Shoulder, own);
    const double elbow = upper_body_angle(set, gait::UpperBody::Elbow, own);
    const int arm = index(side == rig::Side::Left ? Joint::left_upper_arm : Joint::right_upper_arm);
    const Quat upper = square_chest * axis_angle(kLeft, -shoulder);
    const Quat lower = upper * axis_angle(kLeft, -elbow);
    pose_.rotation[static_cast<std::size_t>(arm)] = upper;
    pose_.rotation[static_cast<std::size_t>(arm + 1)] = lower;  // the lower arm
    pose_.rotation[static_cast<std::size_t>(arm + 2)] = lower;  // the hand
  }
  pose_.rotation[index(Joint::head)] =
      yaw(path_->at(sagittal.pelvis.x + options_.look_ahead).heading);

  for (const rig::Side side : rig::kSides) {
    const LegTarget& leg = legs[static_cast<std::size_t>(rig::index(side))];
    const Vec3 hip = hips + leg.hip_offset;
    // Two-bone IK: the knee on the circle where thigh and shank meet, towards the pole.
    Vec3 to_ankle = leg.ankle - hip;
    const double distance = std::min(length(to_ankle), reach);
    const Vec3 along = normalized(to_ankle);
    const double from_hip = distance > 0.0
                                ? (distance * distance + segments.thigh * segments.thigh -
                                   segments.shank * segments.shank) /
                                      (2.0 * distance)
                                : 0.0;
    const double out =
        std::sqrt(std::max(segments.thigh * segments.thigh - from_hip * from_hip, 0.0));
    Vec3 pole = normalized(leg.pole - dot(leg.pole, along) * along);
    if (length(pole) == 0.0) pole = normalized(leg.forward - dot(leg.forward, along) * along);
    const Vec3 knee = hip + from_hip * along + out * pole;
    const Vec3 ankle = hip + distance * along;
    pose_.rotation[index(upper_leg(side))] = limb_rotation(normalized(knee - hip), leg.pole);
    pose_.rotation[index(lower_leg(side))] = limb_rotation(normalized(ankle - knee), leg.pole);
    pose_.rotation[index(foot(side))] = leg.foot;
    pose_.rotation[index(toes(side))] = leg.toes;
  }
  forward_kinematics(humanoid_, hips, pose_);
  return pose_;
}

}  // namespace fuzzygait::body

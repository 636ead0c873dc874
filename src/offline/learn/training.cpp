#include "fuzzygait/learn/training.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "fuzzygait/gait/walker.hpp"
#include "runtime/common/format.hpp"
#include "runtime/gait/leg_metrics.hpp"

namespace fuzzygait::learn {
namespace {

using gait::detail::foot_of;
using gait::detail::thigh_of;

// Catmull-Rom through p1 and p2 (with neighbours p0 and p3) at u in [0, 1].
double cubic(double p0, double p1, double p2, double p3, double u) {
  const double a = -0.5 * p0 + 1.5 * p1 - 1.5 * p2 + 0.5 * p3;
  const double b = p0 - 2.5 * p1 + 2.0 * p2 - 0.5 * p3;
  const double c = -0.5 * p0 + 0.5 * p2;
  return ((a * u + b) * u + c) * u + p1;
}

// The motion's pose at time t (s from its first frame), legs in the walker's convention for a set
// of pelvis tilt `tilt`, and whether each foot is in contact (the frame at or before t).
struct Sample {
  rig::Point pelvis;
  std::array<rig::LegAngles, 2> legs;
  std::array<bool, 2> contact{};
};

Sample sample_at(const eval::Motion& m, double t, double tilt) {
  const double position = t * m.fps;
  const std::size_t last = m.frames.size() - 1;
  const auto i = std::min(static_cast<std::size_t>(std::floor(position + 1e-9)), last);
  // (A motion sampled at the time step itself is read as it is, not interpolated.)
  double u = std::clamp(position - static_cast<double>(i), 0.0, 1.0);
  if (u < 1e-9) u = 0.0;
  auto frame = [&](std::ptrdiff_t k) -> const eval::Frame& {
    return m.frames[static_cast<std::size_t>(
        std::clamp<std::ptrdiff_t>(k, 0, static_cast<std::ptrdiff_t>(last)))];
  };
  const auto k = static_cast<std::ptrdiff_t>(i);
  const eval::Frame& f0 = frame(k - 1);
  const eval::Frame& f1 = frame(k);
  const eval::Frame& f2 = frame(k + 1);
  const eval::Frame& f3 = frame(k + 2);
  auto at = [&](auto value) {
    if (u == 0.0) return value(f1);
    return cubic(value(f0), value(f1), value(f2), value(f3), u);
  };
  Sample s;
  s.pelvis = {at([](const eval::Frame& f) { return f.pose.pelvis.x; }),
              at([](const eval::Frame& f) { return f.pose.pelvis.y; })};
  for (std::size_t leg = 0; leg < 2; ++leg) {
    // The thigh's inclination, then the set's tilt added back: hip = thigh + tilt.
    const double thigh =
        at([leg](const eval::Frame& f) { return thigh_of(f.pose.pelvis_tilt, f.pose.legs[leg]); });
    s.legs[leg] = {thigh + tilt, at([leg](const eval::Frame& f) { return f.pose.legs[leg].knee; }),
                   at([leg](const eval::Frame& f) { return f.pose.legs[leg].ankle; }),
                   at([leg](const eval::Frame& f) { return f.pose.legs[leg].toe; })};
    s.contact[leg] = f1.contact[leg];
  }
  return s;
}

}  // namespace

bool driven(const LegStep& step, gait::Joint joint) {
  if (!step.known) return false;
  if (step.phase == gait::LegPhase::Swing) return true;
  switch (joint) {
    case gait::Joint::Hip:
    case gait::Joint::Knee:
      return step.carrying;
    case gait::Joint::Ankle:
      return step.foot == FootContact::Heel || step.foot == FootContact::Ball;
    case gait::Joint::Toe:
      return step.foot == FootContact::Heel || step.foot == FootContact::Flat;
  }
  return false;
}

TrainingClip training_data(const eval::Motion& motion, const terrain::Terrain& ground,
                           double step_length, const gait::ControllerSet& set,
                           const TrainingOptions& options) {
  if (motion.frames.size() < 2 || !(motion.fps > 0.0)) {
    throw std::invalid_argument(
        "training data: the motion needs two frames or more and a frame "
        "rate above 0");
  }
  if (!(options.time_step > 0.0) || !(step_length > 0.0)) {
    throw std::invalid_argument(
        "training data: the time step (" + common::number_text(options.time_step) +
        " s) and the step length (" + common::number_text(step_length) + " m) must be above 0");
  }
  TrainingClip clip;
  clip.time_step = options.time_step;
  clip.pelvis_tilt = set.pelvis_tilt;
  clip.swing_knee_reference_sweep = set.swing_knee_reference_sweep;
  clip.segments = motion.segments;
  clip.step_length = step_length;
  // The pace a walker walking this step by step length reads (the step at the set's cadence).
  const double pace = gait::Walker::pace(step_length * set.cadence / 60.0, clip.segments);
  const double tilt = set.pelvis_tilt;
  const double h = options.time_step;
  const double duration = motion.frames.back().time - motion.frames.front().time;
  const auto count = static_cast<std::size_t>(std::floor(duration / h + 1e-9)) + 1;
  std::vector<Sample> samples;
  samples.reserve(count);
  for (std::size_t n = 0; n < count; ++n)
    samples.push_back(sample_at(motion, static_cast<double>(n) * h, tilt));

  const double heel_offset = gait::detail::heel_offset(clip.segments);
  const double stance_target = gait::detail::stance_target(clip.segments, step_length);
  clip.steps.resize(count);
  // Per leg: where its last phase began (strike x, thigh), and where a swing aims.
  struct LegTrack {
    bool seen_change = false;
    double sweep_start = 0.0;
    double strike_x = 0.0;
    std::size_t strike_step = 0;
    double target_x = 0.0;
    bool target_known = false;
  };
  // Where the heel of `leg` lands after step n (the next strike in the clip), if it does.
  auto landing_x = [&](std::size_t n, std::size_t leg) -> std::optional<double> {
    for (std::size_t k = n + 1; k < count; ++k) {
      if (samples[k].contact[leg] && !samples[k - 1].contact[leg]) {
        return rig::forward_kinematics(clip.segments, samples[k].pelvis, tilt, samples[k].legs[leg])
            .heel.x;
      }
    }
    return std::nullopt;
  };
  std::array<LegTrack, 2> track;
  for (std::size_t n = 0; n < count; ++n) {
    const Sample& s = samples[n];
    std::array<rig::LegPoints, 2> points;
    for (std::size_t leg = 0; leg < 2; ++leg)
      points[leg] = rig::forward_kinematics(clip.segments, s.pelvis, tilt, s.legs[leg]);
    for (std::size_t leg = 0; leg < 2; ++leg) {
      LegTrack& t = track[leg];
      const bool contact = s.contact[leg];
      const bool changed = n > 0 && samples[n - 1].contact[leg] != contact;
      if (changed) {
        t.seen_change = true;
        t.sweep_start = thigh_of(tilt, s.legs[leg]);
        if (contact) {
          t.strike_x = points[leg].heel.x;
          t.strike_step = n;
        } else {
          // Toe off: one step length ahead of where the other foot struck, as the walker aims;
          // where the clip began with the other foot down (its strike unseen), where this heel
          // lands.
          const LegTrack& other = track[1 - leg];
          t.target_known = true;
          if (s.contact[1 - leg] && other.seen_change) {
            t.target_x = ground.ahead_along_ground(other.strike_x, step_length);
          } else if (const std::optional<double> x = landing_x(n, leg)) {
            t.target_x = *x;
          } else if (!s.contact[1 - leg]) {
            t.target_x = ground.ahead_along_ground(points[leg].heel.x, step_length);
          } else {
            t.target_known = false;
          }
        }
      }
      LegStep& out = clip.steps[n][leg];
      out.known = t.seen_change && (contact || t.target_known);
      out.phase = contact ? gait::LegPhase::Stance : gait::LegPhase::Swing;
      out.angles = s.legs[leg];
      out.velocity = n == 0
                         ? rig::LegAngles{}
                         : rig::LegAngles{(s.legs[leg].hip - samples[n - 1].legs[leg].hip) / h,
                                          (s.legs[leg].knee - samples[n - 1].legs[leg].knee) / h,
                                          (s.legs[leg].ankle - samples[n - 1].legs[leg].ankle) / h,
                                          (s.legs[leg].toe - samples[n - 1].legs[leg].toe) / h};
      out.slope = ground.slope(points[leg].ankle.x);
      out.sweep_start = t.sweep_start;
      if (contact) {
        out.sweep_end = stance_target;
      } else {
        const rig::Point target{t.target_x, ground.height(t.target_x)};
        out.sweep_end = gait::detail::inclination(points[leg].hip, target) + heel_offset;
      }
      const rig::LegAngles& a = out.angles;
      gait::detail::leg_metrics(tilt, a.hip, a.knee, a.ankle, a.toe, out.sweep_start, out.sweep_end,
                                out.slope, out.metrics);
      out.metrics[static_cast<std::size_t>(gait::Metric::Pace)] = pace;
    }
    // The other leg's progress; who carries in double support (the leg planted first).
    for (std::size_t leg = 0; leg < 2; ++leg) {
      LegStep& out = clip.steps[n][leg];
      const LegStep& other = clip.steps[n][1 - leg];
      out.metrics[static_cast<std::size_t>(gait::Metric::OtherDelta)] =
          other.metrics[static_cast<std::size_t>(gait::Metric::Delta)];
      // (An other foot whose strike the clip does not show struck first.)
      out.carrying =
          s.contact[leg] &&
          (!s.contact[1 - leg] ||
           (track[1 - leg].seen_change && track[leg].strike_step <= track[1 - leg].strike_step));
    }
  }
  // The planted feet's contact, from the sole's angle over each stance: on the heel until the sole
  // first lies flat, on the ball after it last does.
  const double flat = rig::radians(options.flat_sole);
  for (std::size_t leg = 0; leg < 2; ++leg) {
    std::size_t n = 0;
    while (n < count) {
      if (clip.steps[n][leg].phase == gait::LegPhase::Swing) {
        clip.steps[n][leg].foot = FootContact::Swing;
        ++n;
        continue;
      }
      std::size_t end = n;
      while (end < count && clip.steps[end][leg].phase == gait::LegPhase::Stance)
        ++end;
      auto sole = [&](std::size_t k) {
        const LegStep& l = clip.steps[k][leg];
        return foot_of(tilt, l.angles) - l.slope;
      };
      std::optional<std::size_t> first_flat;
      std::size_t last_flat = n;
      for (std::size_t k = n; k < end; ++k) {
        if (std::abs(sole(k)) > flat) continue;
        if (!first_flat) first_flat = k;
        last_flat = k;
      }
      for (std::size_t k = n; k < end; ++k) {
        FootContact& foot = clip.steps[k][leg].foot;
        if (!first_flat) {
          foot = sole(k) > 0.0 ? FootContact::Heel : FootContact::Ball;
        } else {
          foot = k < *first_flat ? FootContact::Heel
                 : k > last_flat ? FootContact::Ball
                                 : FootContact::Flat;
        }
      }
      n = end;
    }
  }
  return clip;
}

}  // namespace fuzzygait::learn

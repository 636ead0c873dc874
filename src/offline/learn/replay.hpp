// The controllers replayed along training data: each joint a controller drives is integrated as
// the walker integrates it (its velocity following the command with the set's inertia, the angle
// within its limits, the remembered speed capped), from the clip's state where the stretch begins,
// while the joints not simulated take the clip's values. Templated on the scalar so that the fits
// differentiate it. Internal to the offline library.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "fuzzygait/learn/network.hpp"
#include "fuzzygait/learn/training.hpp"
#include "runtime/gait/leg_metrics.hpp"

namespace fuzzygait::learn::detail {

// A stretch of one leg's steps in one phase: steps first to last (inclusive), all known.
struct Run {
  std::size_t leg = 0;
  std::size_t first = 0;
  std::size_t last = 0;
};

// Every leg's phases, in order of leg then step.
inline std::vector<Run> phase_runs(const TrainingClip& clip) {
  std::vector<Run> runs;
  for (std::size_t leg = 0; leg < 2; ++leg) {
    std::size_t n = 0;
    while (n < clip.steps.size()) {
      const LegStep& s = clip.steps[n][leg];
      if (!s.known) {
        ++n;
        continue;
      }
      std::size_t end = n;
      while (end + 1 < clip.steps.size() && clip.steps[end + 1][leg].known &&
             clip.steps[end + 1][leg].phase == s.phase) {
        ++end;
      }
      if (end > n) runs.push_back({leg, n, end});
      n = end + 1;
    }
  }
  return runs;
}

inline double joint_angle(const rig::LegAngles& a, std::size_t joint) {
  const double v[4] = {a.hip, a.knee, a.ankle, a.toe};
  return v[joint];
}

// The command (rad/s) the walker makes of a controller's output for `joint` of a leg at `step`: the
// hip's in shares of the sweep per second, the swing knee's scaled by the sweep, the others' in
// degrees per second.
template <class T>
T joint_command(const TrainingClip& clip, const LegStep& step, std::size_t joint, const T& output) {
  constexpr double per_degree = rig::radians(1.0);
  if (joint == 0) return output * gait::detail::sweep_scale(step.sweep_start, step.sweep_end);
  if (joint == 1) {
    const double scale = step.phase == gait::LegPhase::Swing
                             ? gait::detail::swing_knee_scale(step.sweep_start, step.sweep_end,
                                                              clip.swing_knee_reference_sweep)
                             : 1.0;
    return T(output * per_degree) * scale;
  }
  return output * per_degree;
}

// Replays `run` with weights w, simulating the joints of `simulated` where their controllers drive
// them. After every time step, `error(step, joint, degrees)` receives each simulated joint's
// angle minus the clip's at that step, where its controller drove it.
template <class T, class Error>
void replay_run(const SetNetwork& network, const T* w, const TrainingClip& clip, const Run& run,
                const std::array<bool, 4>& simulated, const T& follow, Error error) {
  const rig::JointLimits limits;
  const double h = clip.time_step;
  const std::size_t leg = run.leg;
  const LegStep& start = clip.steps[run.first][leg];
  std::array<T, 4> angle;
  std::array<T, 4> velocity;
  for (std::size_t j = 0; j < 4; ++j) {
    angle[j] = T(joint_angle(start.angles, j));
    velocity[j] = T(joint_angle(start.velocity, j));
  }
  Metrics<T> metrics;
  for (std::size_t n = run.first; n < run.last; ++n) {
    const LegStep& now = clip.steps[n][leg];
    const LegStep& next = clip.steps[n + 1][leg];
    for (std::size_t m = 0; m < metrics.size(); ++m)
      metrics[m] = T(now.metrics[m]);
    gait::detail::leg_metrics(clip.pelvis_tilt, angle[0], angle[1], angle[2], angle[3],
                              now.sweep_start, now.sweep_end, now.slope, metrics);
    std::array<bool, 4> moves{};
    std::array<T, 4> command;
    for (std::size_t j = 0; j < 4; ++j) {
      moves[j] = simulated[j] && driven(now, static_cast<gait::Joint>(j));
      if (!moves[j]) continue;
      const int slot = gait::slot(now.phase, static_cast<gait::Joint>(j));
      command[j] = joint_command(clip, now, j, network.evaluate(slot, w, metrics));
    }
    for (std::size_t j = 0; j < 4; ++j) {
      if (!moves[j]) {
        angle[j] = T(joint_angle(next.angles, j));
        velocity[j] = T(joint_angle(next.velocity, j));
        continue;
      }
      const T before = angle[j];
      gait::detail::follow_command(command[j], velocity[j], angle[j], follow, h,
                                   T(joint_angle(limits.minimum, j)),
                                   T(joint_angle(limits.maximum, j)));
      velocity[j] = gait::detail::remembered_speed(angle[j], before, h,
                                                   T(joint_angle(gait::detail::kMaxJointSpeed, j)));
      error(n + 1, j, gait::detail::in_degrees(T(angle[j] - joint_angle(next.angles, j))));
    }
  }
}

// The per-frame view of a run: at every step where a controller drives a joint and does again at
// the next step, the command that would take the clip's velocity at this step to the next one's,
// given the inertia's `follow` share; `error(step, joint, degrees per second)` receives the
// controller's command minus it.
template <class T, class Error>
void command_errors(const SetNetwork& network, const T* w, const TrainingClip& clip, const Run& run,
                    const T& follow, Error error) {
  Metrics<T> metrics;
  for (std::size_t n = run.first; n < run.last; ++n) {
    const LegStep& now = clip.steps[n][run.leg];
    const LegStep& next = clip.steps[n + 1][run.leg];
    for (std::size_t m = 0; m < metrics.size(); ++m)
      metrics[m] = T(now.metrics[m]);
    for (std::size_t j = 0; j < 4; ++j) {
      const auto joint = static_cast<gait::Joint>(j);
      if (!driven(now, joint) || !driven(next, joint)) continue;
      const int slot = gait::slot(now.phase, joint);
      const T command = joint_command(clip, now, j, network.evaluate(slot, w, metrics));
      const double v0 = joint_angle(now.velocity, j);
      const double v1 = joint_angle(next.velocity, j);
      const T wanted = T(v0) + T(v1 - v0) / follow;
      error(n, j, gait::detail::in_degrees(T(command - wanted)));
    }
  }
}

}  // namespace fuzzygait::learn::detail

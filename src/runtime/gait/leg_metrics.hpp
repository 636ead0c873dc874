// What a walker measures of a leg and how it turns a controller's command into motion, as
// functions of the leg's angles: the walker's own code, shared with the learning tools (which
// replay the controllers along a clip, in doubles and in dual numbers), so that what is trained
// is what walks. Internal to fuzzygait (not installed).
//
// Templated on the scalar where the learning tools differentiate through them (T = double is the
// walker's arithmetic, operation for operation); the walker's lanes (simd::Double2) have their own
// overloads of the two helpers that branch.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "fuzzygait/compiler.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "runtime/rig/trigonometry.hpp"
#include "runtime/simd/lanes.hpp"

namespace fuzzygait::gait::detail {

// Inclinations from the downward vertical (forward +) of a leg's thigh and shank, and the foot's
// pitch (toes up +), from its joint angles and the pelvis tilt.
template <class T>
FUZZYGAIT_ALWAYS_INLINE T thigh_inclination(double tilt, const T& hip) {
  return hip - tilt;
}
template <class T>
FUZZYGAIT_ALWAYS_INLINE T shank_inclination(double tilt, const T& hip, const T& knee) {
  return thigh_inclination(tilt, hip) - knee;
}
template <class T>
FUZZYGAIT_ALWAYS_INLINE T foot_pitch(double tilt, const T& hip, const T& knee, const T& ankle) {
  return shank_inclination(tilt, hip, knee) + ankle;
}

inline double thigh_of(double tilt, const rig::LegAngles& a) {
  return thigh_inclination(tilt, a.hip);
}
inline double shank_of(double tilt, const rig::LegAngles& a) {
  return shank_inclination(tilt, a.hip, a.knee);
}
inline double foot_of(double tilt, const rig::LegAngles& a) {
  return foot_pitch(tilt, a.hip, a.knee, a.ankle);
}

// Inclination of the line from `from` to `to`, from the downward vertical, forward positive.
inline double inclination(rig::Point from, rig::Point to) {
  return rig::detail::arctan2(to.x - from.x, from.y - to.y);
}

// Two-link IK: the angle at the root between the root-to-target line and the upper link, when
// links `upper` and `lower` span `distance` (the law of cosines; a distance out of reach gives the
// straight or folded chain).
inline double chain_opening(double upper, double lower, double distance) {
  const double cosine =
      (upper * upper + distance * distance - lower * lower) / (2.0 * upper * distance);
  return rig::detail::arccos(std::clamp(cosine, -1.0, 1.0));
}

// The paper's delta: -1 at the start angle, 0 when the thigh is vertical, +1 at the end angle
// (linear between start and end when both lie on the same side of the vertical), within [-2, 2].
template <class T>
FUZZYGAIT_ALWAYS_INLINE T progress(const T& theta, double start, double end) {
  T d;
  if ((start < 0.0 && end > 0.0) || (start > 0.0 && end < 0.0)) {
    d = (theta * start >= 0.0) ? T(-theta / start) : T(theta / end);
  } else {
    d = end == start ? T(1.0) : T(-1.0 + 2.0 * (theta - start) / (end - start));
  }
  // std::clamp(d, -2.0, 2.0), for any T.
  return d < -2.0 ? T(-2.0) : (2.0 < d ? T(2.0) : d);
}

// d(theta)/d(delta) averaged over the sweep: hip controllers command a share of the sweep per
// second, so the thigh's velocity stays smooth where the mapping bends at the vertical.
inline double sweep_scale(double start, double end) {
  return 0.5 * (end - start);
}

// How much faster than its controller says a swinging knee turns: the thigh's sweep over the
// set's reference sweep (ControllerSet::swing_knee_reference_sweep; 1 without one).
inline double swing_knee_scale(double start, double end, double reference) {
  return reference > 0.0 ? std::abs(end - start) / reference : 1.0;
}

// Where a planted leg's delta reaches +1: the thigh of a leg whose hip has moved half a step past
// its foot (radians).
inline double stance_target(const rig::Segments& s, double step_length) {
  const double reach = s.thigh + s.shank;
  const double half = 0.5 * step_length / reach;
  // std::clamp(half, 0.0, 0.95)
  return -rig::detail::arcsin(half < 0.0 ? 0.0 : (0.95 < half ? 0.95 : half));
}

// The thigh's angle to the hip-heel line of a straight leg with a neutral ankle: a swinging leg
// has arrived (delta +1) when its thigh lies this far behind the line from its hip to the target.
inline double heel_offset(const rig::Segments& s) {
  const rig::LegPoints straight = rig::forward_kinematics(s, {0.0, 0.0}, 0.0, rig::LegAngles{});
  return -inclination(straight.hip, straight.heel);
}

// Fastest each joint turns (rad/s; hip, knee, ankle, toe), about 1150 deg/s, a sprinter's knee:
// the shipped sets' walks peak at 9, 20, 8 and 27 over the step/stature grid (the toes are turned
// by the ground). What a joint remembers as its speed is capped at this.
inline constexpr rig::LegAngles kMaxJointSpeed{20.0, 20.0, 20.0, 40.0};

// The share of the way a joint's velocity goes to its command in a time step h, with the set's
// inertia time constant.
template <class T>
T follow_share(double h, const T& inertia) {
  using std::exp;
  return T(1.0) - exp(T(-h) / inertia);
}

// rig::degrees for any scalar.
template <class T>
FUZZYGAIT_ALWAYS_INLINE T in_degrees(const T& radians) {
  return radians * (180.0 / std::numbers::pi);
}

// The metrics a leg's controllers read of the leg itself (delta, the joint angles, the sole's
// angle to ground of pitch `slope`), from its angles (radians), the pelvis tilt and the thigh's
// sweep (radians, where delta is -1 and +1). The other leg's delta and the ground's words are
// not touched.
template <class T>
FUZZYGAIT_ALWAYS_INLINE void leg_metrics(double tilt, const T& hip, const T& knee, const T& ankle,
                                         const T& toe, double sweep_start, double sweep_end,
                                         double slope, std::array<T, kMetricCount>& m) {
  m[static_cast<std::size_t>(Metric::Delta)] =
      progress(thigh_inclination(tilt, hip), sweep_start, sweep_end);
  m[static_cast<std::size_t>(Metric::Hip)] = in_degrees(hip);
  m[static_cast<std::size_t>(Metric::Knee)] = in_degrees(knee);
  m[static_cast<std::size_t>(Metric::Ankle)] = in_degrees(ankle);
  m[static_cast<std::size_t>(Metric::Toe)] = in_degrees(toe);
  m[static_cast<std::size_t>(Metric::Sole)] =
      in_degrees(T(foot_pitch(tilt, hip, knee, ankle) - slope));
}

// The walker's lanes: hip and knee, or ankle and toe, side by side.
using JointPair = simd::Double2;
FUZZYGAIT_ALWAYS_INLINE JointPair finite_or_zero(JointPair command) {
  return select((command - command) == 0.0, command, JointPair{});
}
FUZZYGAIT_ALWAYS_INLINE JointPair clamp_angle(JointPair v, JointPair low, JointPair high) {
  const JointPair raised = select(v < low, low, v);
  return select(high < raised, high, raised);
}

// x - x is 0 exactly when x is finite: a NaN or infinite command is no command.
template <class T>
FUZZYGAIT_ALWAYS_INLINE T finite_or_zero(const T& command) {
  return (command - command) == T(0.0) ? command : T(0.0);
}
// std::clamp (a NaN stays NaN).
template <class T>
FUZZYGAIT_ALWAYS_INLINE T clamp_angle(const T& v, const T& low, const T& high) {
  const T raised = v < low ? low : v;
  return high < raised ? high : raised;
}

// One time step of a joint: its velocity follows the command (angular velocity) by `follow`, and
// the angle moves by it within its limits.
template <class T, class Share>
FUZZYGAIT_ALWAYS_INLINE void follow_command(const T& command, T& velocity, T& angle,
                                            const Share& follow, double h, const T& low,
                                            const T& high) {
  const T wanted = finite_or_zero(command);
  velocity += (wanted - velocity) * follow;
  angle = clamp_angle(T(angle + velocity * h), low, high);
}

// What a joint remembers as its speed after a time step that took it from `before` to `now`:
// the change over h, capped at `most`.
template <class T>
FUZZYGAIT_ALWAYS_INLINE T remembered_speed(const T& now, const T& before, double h, const T& most) {
  return clamp_angle(T((now - before) / h), T(-most), most);
}

}  // namespace fuzzygait::gait::detail

// The sagittal-plane leg rig of the paper: pelvis (position and tilt) and, per leg, hip, knee,
// ankle and ball of the foot. x forward, y up, metres; angles in radians in code.
//
// Clinical sign conventions, so curves compare directly with gait-lab data:
//   hip flexion   thigh forward of the pelvis           (+)
//   knee flexion  shank behind the thigh, >= 0          (+)
//   ankle         dorsiflexion, toes towards the shin   (+)
//   toe           MTP extension, toes up                (+)
//   pelvis tilt   anterior tilt                         (+)
// so the thigh's inclination to the vertical (forward +) is hip flexion minus pelvis tilt.
#pragma once

#include <algorithm>
#include <array>
#include <numbers>
#include <string>

namespace fuzzygait::rig {

struct Point {
  double x = 0.0;
  double y = 0.0;
};

// Segment lengths of one leg, metres.
struct Segments {
  double thigh = 0.0;         // hip centre to knee centre
  double shank = 0.0;         // knee centre to ankle centre
  double ankle_height = 0.0;  // ankle centre above the sole
  double heel = 0.0;          // ankle to the back of the heel, along the sole
  double ball = 0.0;          // ankle to the ball of the foot (MTP joint), along the sole
  double toe = 0.0;           // ball to the tip of the toes

  double leg_length() const { return thigh + shank + ankle_height; }  // hip height standing
  double foot_length() const { return heel + ball + toe; }
};

// Segment lengths from stature with the anthropometric proportions of Drillis & Contini (1966)
// as tabulated by Winter, "Biomechanics and Motor Control of Human Movement" (4th ed., 2009,
// Fig. 4.1): hip 0.530 H, knee 0.285 H, ankle 0.039 H above the floor; foot length 0.152 H,
// split at the ankle (25 % of foot length from the heel) and at the MTP joint (73 %).
Segments segments_from_stature(double stature);

// Throws std::invalid_argument naming the field when a length is not a finite, positive and
// plausible number (a leg of length zero, NaN, ...).
void validate(const Segments& segments);

enum class Side : int { Left = 0, Right = 1 };
inline constexpr std::array<Side, 2> kSides = {Side::Left, Side::Right};
inline int index(Side side) {
  return static_cast<int>(side);
}
inline Side other(Side side) {
  return side == Side::Left ? Side::Right : Side::Left;
}

// The four degrees of freedom of one leg, radians, clinical conventions.
struct LegAngles {
  double hip = 0.0;
  double knee = 0.0;
  double ankle = 0.0;
  double toe = 0.0;
};

struct Pose {
  Point pelvis;              // hip joint centre (both hips project onto it)
  double pelvis_tilt = 0.0;  // radians, anterior +
  std::array<LegAngles, 2> legs;
};

// Absolute orientations derived from the joint angles: inclinations from the downward
// vertical (forward +) for thigh and shank, pitch from the horizontal (toes up +) for foot and
// toes.
struct LegOrientation {
  double thigh = 0.0;
  double shank = 0.0;
  double foot = 0.0;
  double toes = 0.0;
};
inline LegOrientation orientation(double pelvis_tilt, const LegAngles& angles) {
  LegOrientation o;
  o.thigh = angles.hip - pelvis_tilt;
  o.shank = o.thigh - angles.knee;
  o.foot = o.shank + angles.ankle;
  o.toes = o.foot + angles.toe;
  return o;
}

// Sines and cosines of a LegOrientation: all the trigonometry forward kinematics needs, so that
// a caller placing a leg several times with the same angles computes it once. The defaults are
// those of a zero orientation.
struct LegTrig {
  double thigh_sin = 0.0, thigh_cos = 1.0;
  double shank_sin = 0.0, shank_cos = 1.0;
  double foot_sin = 0.0, foot_cos = 1.0;
  double toes_sin = 0.0, toes_cos = 1.0;
};
LegTrig trig(const LegOrientation& orientation);

struct LegPoints {
  Point hip;
  Point knee;
  Point ankle;
  Point heel;
  Point ball;
  Point tip;
};
LegPoints forward_kinematics(const Segments& segments, Point hip, double pelvis_tilt,
                             const LegAngles& angles);
// The same from the orientation's trigonometry (the same values, rounding included).
inline LegPoints forward_kinematics(const Segments& s, Point hip, const LegTrig& t) {
  LegPoints p;
  p.hip = hip;
  p.knee = {hip.x + s.thigh * t.thigh_sin, hip.y - s.thigh * t.thigh_cos};
  p.ankle = {p.knee.x + s.shank * t.shank_sin, p.knee.y - s.shank * t.shank_cos};
  const double fx = t.foot_cos;  // along the sole, forward
  const double fy = t.foot_sin;
  const double ux = -fy;  // out of the sole, up
  const double uy = fx;
  const Point sole{p.ankle.x - s.ankle_height * ux, p.ankle.y - s.ankle_height * uy};
  p.heel = {sole.x - s.heel * fx, sole.y - s.heel * fy};
  p.ball = {sole.x + s.ball * fx, sole.y + s.ball * fy};
  p.tip = {p.ball.x + s.toe * t.toes_cos, p.ball.y + s.toe * t.toes_sin};
  return p;
}

// Joint ranges, radians (defaults: typical adult passive ranges of motion).
struct JointLimits {
  LegAngles minimum{-0.52, 0.0, -0.79, -0.52};  // hip -30, knee 0, ankle -45, toe -30 deg
  LegAngles maximum{2.09, 2.44, 0.52, 1.40};    // hip 120, knee 140, ankle 30, toe 80 deg
  bool contains(const LegAngles& a) const;
  // Inline: the walker clamps every time step.
  LegAngles clamp(const LegAngles& a) const {
    return {std::clamp(a.hip, minimum.hip, maximum.hip),
            std::clamp(a.knee, minimum.knee, maximum.knee),
            std::clamp(a.ankle, minimum.ankle, maximum.ankle),
            std::clamp(a.toe, minimum.toe, maximum.toe)};
  }
};

// Throws std::invalid_argument naming the joint when a limit is not finite, beyond a full turn,
// or a minimum lies above its maximum (clamping to such a range is undefined).
void validate(const JointLimits& limits);

// Inline: the walker converts its metrics every time step. One multiplication by the ratio (a
// division per conversion was sixteen divisions a walker step); within an ulp of converting with
// a multiply and a divide.
constexpr double degrees(double radians) {
  return radians * (180.0 / std::numbers::pi);
}
constexpr double radians(double degrees) {
  return degrees * (std::numbers::pi / 180.0);
}

}  // namespace fuzzygait::rig

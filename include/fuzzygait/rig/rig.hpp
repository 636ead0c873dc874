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

#include <array>
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
inline int index(Side side) { return static_cast<int>(side); }
inline Side other(Side side) { return side == Side::Left ? Side::Right : Side::Left; }

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
LegOrientation orientation(double pelvis_tilt, const LegAngles& angles);

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

// Joint ranges, radians (defaults: typical adult passive ranges of motion).
struct JointLimits {
  LegAngles minimum{-0.52, 0.0, -0.79, -0.52};  // hip -30, knee 0, ankle -45, toe -30 deg
  LegAngles maximum{2.09, 2.44, 0.52, 1.40};    // hip 120, knee 140, ankle 30, toe 80 deg
  bool contains(const LegAngles& a) const;
  LegAngles clamp(const LegAngles& a) const;
};

double degrees(double radians);
double radians(double degrees);

}  // namespace fuzzygait::rig

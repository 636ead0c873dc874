#include "fuzzygait/rig/rig.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace fuzzygait::rig {

double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }
double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

Segments segments_from_stature(double stature) {
  if (!std::isfinite(stature) || stature < 0.5 || stature > 3.0) {
    throw std::invalid_argument("stature must be between 0.5 and 3.0 m, got " +
                                std::to_string(stature));
  }
  const double foot = 0.152 * stature;
  Segments s;
  s.thigh = (0.530 - 0.285) * stature;
  s.shank = (0.285 - 0.039) * stature;
  s.ankle_height = 0.039 * stature;
  s.heel = 0.25 * foot;
  s.ball = (0.73 - 0.25) * foot;
  s.toe = (1.0 - 0.73) * foot;
  return s;
}

void validate(const Segments& s) {
  auto check = [](const char* field, double value, double low, double high) {
    if (!std::isfinite(value) || value < low || value > high) {
      throw std::invalid_argument(std::string("segment '") + field + "' must be between " +
                                  std::to_string(low) + " and " + std::to_string(high) +
                                  " m, got " + std::to_string(value));
    }
  };
  check("thigh", s.thigh, 0.05, 1.5);
  check("shank", s.shank, 0.05, 1.5);
  check("ankle_height", s.ankle_height, 0.005, 0.3);
  check("heel", s.heel, 0.0, 0.3);
  check("ball", s.ball, 0.01, 0.5);
  check("toe", s.toe, 0.0, 0.3);
}

LegOrientation orientation(double pelvis_tilt, const LegAngles& a) {
  LegOrientation o;
  o.thigh = a.hip - pelvis_tilt;
  o.shank = o.thigh - a.knee;
  o.foot = o.shank + a.ankle;
  o.toes = o.foot + a.toe;
  return o;
}

LegPoints forward_kinematics(const Segments& s, Point hip, double pelvis_tilt,
                             const LegAngles& angles) {
  const LegOrientation o = orientation(pelvis_tilt, angles);
  LegPoints p;
  p.hip = hip;
  p.knee = {hip.x + s.thigh * std::sin(o.thigh), hip.y - s.thigh * std::cos(o.thigh)};
  p.ankle = {p.knee.x + s.shank * std::sin(o.shank), p.knee.y - s.shank * std::cos(o.shank)};
  const double fx = std::cos(o.foot);  // along the sole, forward
  const double fy = std::sin(o.foot);
  const double ux = -fy;  // out of the sole, up
  const double uy = fx;
  const Point sole{p.ankle.x - s.ankle_height * ux, p.ankle.y - s.ankle_height * uy};
  p.heel = {sole.x - s.heel * fx, sole.y - s.heel * fy};
  p.ball = {sole.x + s.ball * fx, sole.y + s.ball * fy};
  p.tip = {p.ball.x + s.toe * std::cos(o.toes), p.ball.y + s.toe * std::sin(o.toes)};
  return p;
}

bool JointLimits::contains(const LegAngles& a) const {
  return a.hip >= minimum.hip && a.hip <= maximum.hip && a.knee >= minimum.knee &&
         a.knee <= maximum.knee && a.ankle >= minimum.ankle && a.ankle <= maximum.ankle &&
         a.toe >= minimum.toe && a.toe <= maximum.toe;
}

LegAngles JointLimits::clamp(const LegAngles& a) const {
  return {std::clamp(a.hip, minimum.hip, maximum.hip),
          std::clamp(a.knee, minimum.knee, maximum.knee),
          std::clamp(a.ankle, minimum.ankle, maximum.ankle),
          std::clamp(a.toe, minimum.toe, maximum.toe)};
}

}  // namespace fuzzygait::rig

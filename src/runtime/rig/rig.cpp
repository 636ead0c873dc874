#include "fuzzygait/rig/rig.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "runtime/common/format.hpp"
#include "runtime/rig/trigonometry.hpp"

namespace fuzzygait::rig {
namespace {

using common::number_text;

}  // namespace

Segments segments_from_stature(double stature) {
  if (!std::isfinite(stature) || stature < 0.5 || stature > 3.0) {
    throw std::invalid_argument("stature must be between 0.5 and 3.0 m, got " +
                                number_text(stature));
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
                                  number_text(low) + " and " + number_text(high) + " m, got " +
                                  number_text(value));
    }
  };
  check("thigh", s.thigh, 0.05, 1.5);
  check("shank", s.shank, 0.05, 1.5);
  check("ankle_height", s.ankle_height, 0.005, 0.3);
  check("heel", s.heel, 0.0, 0.3);
  check("ball", s.ball, 0.01, 0.5);
  check("toe", s.toe, 0.0, 0.3);
}

LegTrig trig(const LegOrientation& o) {
  return detail::leg_trig(o);
}

LegPoints forward_kinematics(const Segments& s, Point hip, double pelvis_tilt,
                             const LegAngles& angles) {
  return forward_kinematics(s, hip, trig(orientation(pelvis_tilt, angles)));
}

void validate(const JointLimits& limits) {
  const double turn = 2.0 * std::numbers::pi;
  auto check = [&](const char* joint, double low, double high) {
    if (!(low >= -turn && high <= turn && low <= high)) {
      throw std::invalid_argument(std::string("joint limits of the ") + joint +
                                  " must be finite, within a turn, minimum <= maximum; got " +
                                  number_text(degrees(low)) + " to " + number_text(degrees(high)) +
                                  " deg");
    }
  };
  check("hip", limits.minimum.hip, limits.maximum.hip);
  check("knee", limits.minimum.knee, limits.maximum.knee);
  check("ankle", limits.minimum.ankle, limits.maximum.ankle);
  check("toe", limits.minimum.toe, limits.maximum.toe);
}

bool JointLimits::contains(const LegAngles& a) const {
  return a.hip >= minimum.hip && a.hip <= maximum.hip && a.knee >= minimum.knee &&
         a.knee <= maximum.knee && a.ankle >= minimum.ankle && a.ankle <= maximum.ankle &&
         a.toe >= minimum.toe && a.toe <= maximum.toe;
}

}  // namespace fuzzygait::rig

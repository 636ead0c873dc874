// How we measure a walk (docs/measuring.md): realism against normative curves,
// contact quality, timing, and smoothness (velocity jumps at phase switches, angular acceleration
// and jerk). Works on a Motion, recorded live or read back from a walk CSV, so every figure
// comes from a command anyone can run.
#pragma once

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::eval {

inline constexpr int kCycleSamples = 51;       // 0..100 % of the gait cycle in 2 % steps
inline constexpr double kTravelWindow = 0.05;  // s: the span the body's travel is measured over

// Mean and one standard deviation over the gait cycle, degrees, sampled at kCycleSamples.
struct Curve {
  std::array<double, kCycleSamples> mean{};
  std::array<double, kCycleSamples> sd{};
};

// Normative sagittal curves (e.g. Schwartz et al. 2008): hip, knee, ankle, pelvic tilt, and
// the thigh's inclination (hip minus pelvic tilt), which is what we compare.
struct Normative {
  std::string name;
  Curve hip;
  Curve knee;
  Curve ankle;
  Curve pelvis_tilt;
  Curve thigh;
  // The ankle's zero is the source's own, a constant away from the clinical one (Bovi et al.
  // 2011): its curve is compared in shape, the RMSE and the 2 SD band after removing the
  // difference of the means.
  bool ankle_offset_unknown = false;
};

struct JointScore {
  double rmse = 0.0;        // degrees
  double pearson = 0.0;     // correlation of the mean curves
  double within_2sd = 0.0;  // share of samples inside mean +/- 2 SD, percent
  // RMS angular acceleration over the mean cycle, deg/s^2, of the walk and of the reference
  // played at the walk's cycle time: how vigorously the joint moves against how people move it.
  double acceleration_rms = 0.0;
  double reference_acceleration_rms = 0.0;
  // How many times as hard as people the joint moves (a reference under 1 deg/s^2 counts as 1).
  double acceleration_ratio() const {
    return acceleration_rms / std::max(reference_acceleration_rms, 1.0);
  }
};

// Smoothness of one joint over a walk, from frame-to-frame finite differences of its angle.
struct JointSmoothness {
  double rms_acceleration = 0.0;  // deg/s^2
  double rms_jerk = 0.0;          // deg/s^3
  double max_jerk = 0.0;          // deg/s^3, the largest |jerk|
};

// Angular acceleration and jerk of the hip, knee, ankle and toe (gait::Joint order), both legs
// pooled, over the frames from `first` on. Throws std::invalid_argument when fewer than four
// frames remain or the frame rate is not positive.
std::array<JointSmoothness, 4> joint_smoothness(const Motion& motion, std::size_t first = 0);

// RMS angular acceleration (deg/s^2) of a mean cycle curve played once every `cycle_time`
// seconds: periodic second differences over the cycle's samples (0 % and 100 % are one point).
double cycle_acceleration_rms(const Curve& curve, double cycle_time);

struct GaitReport {
  int cycles = 0;               // complete left cycles measured
  double cycle_time = 0.0;      // s
  double cycle_time_sd = 0.0;   // s, between cycles: regularity
  double cadence = 0.0;         // steps per minute
  double speed = 0.0;           // m/s, pelvis
  double stance_percent = 0.0;  // left foot in contact, share of the cycle
  double step_length = 0.0;     // m, heel to heel at successive heel strikes
  double step_length_sd = 0.0;
  std::optional<double> step_error_percent;  // against the command; none without one
  double knee_peak = 0.0;                    // degrees, swing
  double knee_peak_percent = 0.0;            // where in the cycle
  double thigh_range = 0.0;                  // degrees, max - min of the mean curve
  double pelvis_vertical_range = 0.0;        // m, mean cycle
  // Body travel over the measured cycles, from the pelvis's motion over 50 ms (a central
  // difference over kTravelWindow): its forward speed against its cycle's mean speed, lowest and
  // highest, and the fastest it rises (m/s).
  double pelvis_speed_ratio_min = 0.0;
  double pelvis_speed_ratio_max = 0.0;
  double pelvis_rise_speed = 0.0;
  // Features of the mean cycle (degrees): how far the thigh swings past where it lands (its
  // largest inclination in the second half of the cycle over its inclination at contact), the
  // knee's flexion in loading response (largest in the first 30 %) and the ankle's push off
  // (its lowest from 40 to 80 %).
  double thigh_overshoot = 0.0;
  double knee_loading_peak = 0.0;
  double ankle_push_off = 0.0;
  double max_slip = 0.0;           // m per frame, foot points in contact
  double max_penetration = 0.0;    // m below the ground, any foot point
  double min_toe_clearance = 0.0;  // m, mid-swing (middle 60 % of swing)
  // m: the highest a heel rose and came down again within one contact (a heel that lifts after
  // foot flat and drops back before its real heel-off, a flutter people do not show); 0 if none.
  double max_heel_bounce = 0.0;
  double max_velocity_jump = 0.0;  // deg/s, largest change of a joint's velocity at a phase switch
  double typical_velocity_change = 0.0;  // deg/s, 99th percentile of frame-to-frame changes
  // Angular acceleration and jerk of hip, knee, ankle and toe from the first measured cycle on.
  std::array<JointSmoothness, 4> smoothness{};
  // Mean curves of the left leg over the cycle (degrees): thigh inclination, knee, ankle, toe.
  Curve thigh;
  Curve knee;
  Curve ankle;
  Curve toe;
  std::optional<JointScore> thigh_score;
  std::optional<JointScore> knee_score;
  std::optional<JointScore> ankle_score;
};

// Measures the walk over its complete left cycles: for a walker's motion those after the first
// (the start from standing), for captured motion every one. `reference` adds the realism scores;
// `commanded_step` the step error. Throws std::invalid_argument when there are fewer than two
// such cycles, or fewer than one in captured motion (a clip may hold no more).
GaitReport evaluate(const Motion& motion, const terrain::Terrain& terrain,
                    const Normative* reference = nullptr,
                    std::optional<double> commanded_step = std::nullopt);

// The contact bounds of the acceptance (docs/measuring.md) that the walk misses, one
// phrase each with its figure and bound ("foot slip 4.27 mm a frame (bound 1 mm)"): slip under
// 1 mm a frame, penetration under 1 mm, mid-swing toe clearance at least 5 mm, and, with a
// commanded step, a step error of at most 3 %. Empty when the walk meets them all.
std::vector<std::string> missed_contact_bounds(const GaitReport& report);

// The report as a table people read, and as JSON.
std::string to_text(const GaitReport& report);
std::string to_json(const GaitReport& report);

// The frames where a foot's strikes begin (begins_strike): the strikes that part evaluate()'s gait
// cycles.
std::vector<std::size_t> heel_strikes(const Motion& motion, rig::Side side);

// Where the swing knee flexion peaks: the largest mean value (degrees) in the second half of the
// cycle, and where (percent of the cycle); 0 at 0 % when no value there is above 0.
struct CurvePeak {
  double percent = 0.0;
  double value = 0.0;
};
CurvePeak swing_peak(const Curve& knee);

// Resamples a periodic series to kCycleSamples points over [begin, end] frames.
std::array<double, kCycleSamples> resample_cycle(const std::vector<double>& values,
                                                 std::size_t begin, std::size_t end);

}  // namespace fuzzygait::eval

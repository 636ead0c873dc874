// The smoothness measures of eval::evaluate: angular acceleration and jerk from the frames, and
// the RMS acceleration of a mean cycle, checked on motions whose derivatives are known exactly.
#include "fuzzygait/eval/evaluation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzzygait/io/normative.hpp"
#include "fuzzygait/terrain/terrain.hpp"
#include "support/walks.hpp"

namespace fuzzygait {
namespace {

constexpr double kPi = std::numbers::pi;

// `seconds` of frames at `fps` where every joint of both legs follows angle(joint, t) (radians).
template <class Angle>
eval::Motion synthetic(double fps, double seconds, Angle angle) {
  eval::Motion m;
  m.fps = fps;
  m.segments = rig::segments_from_stature(1.75);
  const int frames = static_cast<int>(std::lround(seconds * fps)) + 1;
  for (int i = 0; i < frames; ++i) {
    eval::Frame f;
    f.time = i / fps;
    for (rig::LegAngles& a : f.pose.legs) {
      a = {angle(0, f.time), angle(1, f.time), angle(2, f.time), angle(3, f.time)};
    }
    m.frames.push_back(f);
  }
  return m;
}

TEST(JointSmoothness, SineHasItsAnalyticAccelerationAndJerk) {
  // Hip: 20 deg amplitude at 1 Hz; knee: constant velocity; ankle: still; toe: 5 deg at 2 Hz.
  const double hip_amplitude = 20.0;
  const double toe_amplitude = 5.0;
  const eval::Motion m = synthetic(240.0, 4.0, [&](int joint, double t) {
    switch (joint) {
      case 0:
        return rig::radians(hip_amplitude * std::sin(2.0 * kPi * t));
      case 1:
        return rig::radians(10.0 + 30.0 * t);
      case 2:
        return rig::radians(5.0);
      default:
        return rig::radians(toe_amplitude * std::sin(4.0 * kPi * t));
    }
  });
  const auto s = eval::joint_smoothness(m);
  const double w = 2.0 * kPi;
  // RMS of A w^2 sin over whole periods: A w^2 / sqrt 2; jerk A w^3 / sqrt 2, peak A w^3.
  EXPECT_NEAR(s[0].rms_acceleration, hip_amplitude * w * w / std::sqrt(2.0),
              0.002 * hip_amplitude * w * w);
  EXPECT_NEAR(s[0].rms_jerk, hip_amplitude * w * w * w / std::sqrt(2.0),
              0.005 * hip_amplitude * w * w * w);
  EXPECT_NEAR(s[0].max_jerk, hip_amplitude * w * w * w, 0.005 * hip_amplitude * w * w * w);
  // A straight line and a constant have none (up to the rounding of degrees).
  EXPECT_LT(s[1].rms_acceleration, 1e-6);
  EXPECT_LT(s[1].max_jerk, 1e-3);
  EXPECT_EQ(s[2].rms_acceleration, 0.0);
  EXPECT_EQ(s[2].max_jerk, 0.0);
  // Twice the frequency: four times the acceleration, eight times the jerk per degree.
  const double w2 = 2.0 * w;
  EXPECT_NEAR(s[3].rms_acceleration, toe_amplitude * w2 * w2 / std::sqrt(2.0),
              0.005 * toe_amplitude * w2 * w2);
  EXPECT_NEAR(s[3].rms_jerk, toe_amplitude * w2 * w2 * w2 / std::sqrt(2.0),
              0.01 * toe_amplitude * w2 * w2 * w2);
}

TEST(JointSmoothness, AKinkShowsAsAJerkSpike) {
  // The knee's velocity jumps from 0 to 100 deg/s at t = 1 s: a smooth walk has no such thing.
  const eval::Motion m = synthetic(120.0, 2.0, [](int joint, double t) {
    return joint == 1 ? rig::radians(t > 1.0 ? 100.0 * (t - 1.0) : 0.0) : 0.0;
  });
  const auto s = eval::joint_smoothness(m);
  // One frame carries the whole velocity change: 100 deg/s in 1/120 s.
  EXPECT_NEAR(s[1].max_jerk, 100.0 * 120.0 * 120.0, 1.0);
  EXPECT_EQ(s[0].max_jerk, 0.0);
}

TEST(JointSmoothness, MeasuresFromTheFirstFrameGiven) {
  const eval::Motion m = synthetic(100.0, 2.0, [](int joint, double t) {
    return joint == 0 && t < 0.5 ? rig::radians(40.0 * std::sin(20.0 * t)) : 0.0;
  });
  EXPECT_GT(eval::joint_smoothness(m)[0].rms_acceleration, 1000.0);
  EXPECT_EQ(eval::joint_smoothness(m, 60)[0].rms_acceleration, 0.0);
}

TEST(JointSmoothness, RefusesTooFewFramesAndNoFrameRate) {
  eval::Motion m = synthetic(60.0, 0.05, [](int, double) { return 0.0; });  // 4 frames
  EXPECT_NO_THROW(eval::joint_smoothness(m));
  EXPECT_THROW(eval::joint_smoothness(m, 1), std::invalid_argument);
  m.fps = 0.0;
  EXPECT_THROW(eval::joint_smoothness(m), std::invalid_argument);
}

TEST(CycleAcceleration, SineOverTheCycle) {
  eval::Curve c;
  for (int k = 0; k < eval::kCycleSamples; ++k) {
    c.mean[static_cast<std::size_t>(k)] =
        30.0 * std::sin(2.0 * kPi * k / (eval::kCycleSamples - 1));
  }
  const double cycle = 1.1;
  const double w = 2.0 * kPi / cycle;
  // Second differences of 50 samples a period fall 0.13 % short of the derivative.
  EXPECT_NEAR(eval::cycle_acceleration_rms(c, cycle), 30.0 * w * w / std::sqrt(2.0),
              0.003 * 30.0 * w * w);
  // Played twice as fast, four times the acceleration.
  EXPECT_NEAR(eval::cycle_acceleration_rms(c, cycle / 2.0),
              4.0 * eval::cycle_acceleration_rms(c, cycle), 1e-9);
}

TEST(CycleAcceleration, TheWalkReportsItBesidePeoples) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::Walker walker = test::make_walker(ground);
  const eval::Motion motion = eval::record(walker, 12.0, 120.0);
  const eval::Normative reference = io::load_normative("schwartz2008_free");
  const eval::GaitReport r = eval::evaluate(motion, ground, &reference, 0.70);
  ASSERT_TRUE(r.knee_score.has_value());
  EXPECT_DOUBLE_EQ(r.knee_score->acceleration_rms,
                   eval::cycle_acceleration_rms(r.knee, r.cycle_time));
  EXPECT_DOUBLE_EQ(r.knee_score->reference_acceleration_rms,
                   eval::cycle_acceleration_rms(reference.knee, r.cycle_time));
  // People's mean knee curve at this cadence: about 1,900 deg/s^2 (Schwartz 2008, free speed).
  EXPECT_GT(r.knee_score->reference_acceleration_rms, 1500.0);
  EXPECT_LT(r.knee_score->reference_acceleration_rms, 2500.0);
  // The frame-by-frame figures are there for every joint, finite and non-zero.
  for (const eval::JointSmoothness& s : r.smoothness) {
    EXPECT_TRUE(std::isfinite(s.rms_jerk));
    EXPECT_GT(s.rms_acceleration, 0.0);
    EXPECT_GT(s.rms_jerk, 0.0);
    EXPECT_GE(s.max_jerk, s.rms_jerk);
  }
  const std::string text = eval::to_text(r);
  EXPECT_NE(text.find("knee   acceleration RMS"), std::string::npos) << text;
  const std::string json = eval::to_json(r);
  EXPECT_NE(json.find("\"rms_jerk_deg_per_s3\""), std::string::npos);
  EXPECT_NE(json.find("\"reference_acceleration_rms_deg_per_s2\""), std::string::npos);
}

// Without a commanded step there is no step error: the report says so rather than showing 0 %.
TEST(StepError, OnlyAgainstACommandedStep) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::Walker walker = test::make_walker(ground);
  const eval::Motion motion = eval::record(walker, 8.0, 60.0);
  const eval::GaitReport without = eval::evaluate(motion, ground);
  EXPECT_FALSE(without.step_error_percent.has_value());
  EXPECT_NE(eval::to_text(without).find("step error                   (no commanded step given)"),
            std::string::npos)
      << eval::to_text(without);
  EXPECT_NE(eval::to_json(without).find("\"step_error_percent\": null"), std::string::npos);

  // A command 10 % longer than the walk's steps: an error of 1 - 1/1.1 of the command.
  const double command = 1.1 * without.step_length;
  const eval::GaitReport with = eval::evaluate(motion, ground, nullptr, command);
  ASSERT_TRUE(with.step_error_percent.has_value());
  EXPECT_NEAR(*with.step_error_percent, 100.0 * (1.0 - 1.0 / 1.1), 1e-9);
  EXPECT_NE(eval::to_text(with).find("step error"), std::string::npos);
}

}  // namespace
// A heel that rises and drops back within one contact is a bounce; the real heel-off, which
// stays up until the foot leaves, is not.
TEST(HeelBounce, ARiseAndFallWithinOneContactIsMeasured) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::Walker walker = test::make_walker(ground);
  const eval::Motion walked = eval::record(walker, 12.0, 120.0);
  eval::Motion motion = walked;
  const double before = eval::evaluate(motion, ground).max_heel_bounce;
  // The first run of 16 left-contact frames with the heel down, from the third second on.
  std::size_t first = 0;
  std::size_t run = 0;
  for (std::size_t i = 360; i < motion.frames.size() && run < 16; ++i) {
    const eval::Frame& f = motion.frames[i];
    run = f.contact[0] && f.points[0].heel.y < 0.002 ? run + 1 : 0;
    first = i + 1 - run;
  }
  ASSERT_EQ(run, 16u);
  // A 6 mm tent over its middle frames, on the ground again at both ends.
  const double peak = 0.006 + before;
  for (std::size_t k = 1; k < 15; ++k) {
    const double up = peak * (1.0 - std::abs(static_cast<double>(k) - 7.5) / 7.5);
    motion.frames[first + k].points[0].heel.y =
        std::max(motion.frames[first + k].points[0].heel.y, up);
  }
  const eval::GaitReport r = eval::evaluate(motion, ground);
  EXPECT_NEAR(r.max_heel_bounce, peak * (1.0 - 0.5 / 7.5), 1e-12);
  EXPECT_NE(eval::to_text(r).find("max heel bounce in stance"), std::string::npos);
  EXPECT_NE(eval::to_json(r).find("\"max_heel_bounce_m\""), std::string::npos);
  // A heel raised 50 mm over the last frames of that contact, never down again before the foot
  // leaves: a heel-off, not a bounce.
  eval::Motion lifted = walked;
  std::size_t end = first + 16;
  while (end < lifted.frames.size() && lifted.frames[end].contact[0])
    ++end;
  ASSERT_LT(end, lifted.frames.size());
  for (std::size_t i = end - 8; i < end; ++i)
    lifted.frames[i].points[0].heel.y += 0.05;
  EXPECT_EQ(eval::evaluate(lifted, ground).max_heel_bounce, before);
}

// Each contact bound of the acceptance is judged on its own figure, at its edge, and named with
// the figure and the bound; the step error only against a commanded step.
TEST(ContactBounds, NamesEachMissedBoundWithItsFigure) {
  eval::GaitReport r;
  r.max_slip = 0.00099;
  r.max_penetration = 0.0;
  r.min_toe_clearance = 0.005;
  EXPECT_TRUE(eval::missed_contact_bounds(r).empty());
  r.step_error_percent = 3.0;
  EXPECT_TRUE(eval::missed_contact_bounds(r).empty());
  r.max_slip = 0.001;
  r.max_penetration = 0.0012;
  r.min_toe_clearance = 0.0049;
  r.step_error_percent = 3.04;
  const std::vector<std::string> missed = eval::missed_contact_bounds(r);
  ASSERT_EQ(missed.size(), 4u);
  EXPECT_EQ(missed[0], "foot slip 1.00 mm a frame (bound 1 mm)");
  EXPECT_EQ(missed[1], "penetration 1.20 mm (bound 1 mm)");
  EXPECT_EQ(missed[2], "toe clearance 4.90 mm (bound 5 mm)");
  EXPECT_EQ(missed[3], "step error 3.04 % (bound 3 %)");
}

}  // namespace fuzzygait

// Walking by speed: a walker asked for a speed takes the step people take at it (the set's stride
// relation) at the cadence that makes the speed, reaches people's five speeds (Bovi et al. 2011's
// adults) at their cadence and step, keeps its feet planted across speeds and statures, and
// changes speed mid-walk at the set's acceleration without a slip or a pop.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzzygait/eval/evaluation.hpp"
#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/gait/crowd.hpp"
#include "fuzzygait/io/normative.hpp"
#include "support/walks.hpp"

using namespace fuzzygait;

namespace {

using test::default_set;

gait::Walker walker_at(const terrain::Terrain& ground, double speed, double stature,
                       const gait::ControllerSet& set = default_set()) {
  gait::WalkerOptions o;
  o.segments = rig::segments_from_stature(stature);
  o.speed = speed;
  return gait::Walker(set, o, ground);
}

std::string label(double speed, double stature) {
  return "speed " + std::to_string(speed) + " m/s, stature " + std::to_string(stature) + " m";
}

// Bovi et al.'s adults at each of their five speeds, as a 1.75 m adult: the speed within 3 %,
// the cadence and step within one SD of theirs, the curves as close to that speed's as the set
// walks them today (thigh 4.2-7.4, knee 6.6-9.9 deg RMSE: docs/walk.md, "Speed"), the feet
// planted.
TEST(Speed, PeoplesFiveSpeedsAtTheirCadenceAndStep) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  for (const io::GaitParameters& p : io::level_speeds()) {
    const double speed = p.speed_per_height.mean * 1.75;
    gait::Walker w = walker_at(ground, speed, 1.75);
    const double step = w.step_length();
    const eval::Normative people = io::load_normative(p.curves);
    const eval::GaitReport r = eval::evaluate(eval::record(w, 13.0, 120.0), ground, &people, step);
    const std::string at = p.task + " " + label(speed, 1.75);
    EXPECT_NEAR(r.speed, speed, 0.03 * speed) << at;
    EXPECT_NEAR(r.cadence, p.cadence.mean, p.cadence.sd) << at;
    EXPECT_NEAR(r.step_length, p.step_length.mean, p.step_length.sd) << at;
    ASSERT_TRUE(r.thigh_score && r.knee_score) << at;
    EXPECT_LE(r.thigh_score->rmse, 7.5) << at;
    EXPECT_GE(r.thigh_score->pearson, 0.95) << at;
    EXPECT_LE(r.knee_score->rmse, 10.0) << at;
    EXPECT_GE(r.knee_score->pearson, 0.90) << at;
    EXPECT_LT(r.max_slip, 0.001) << at;
    EXPECT_LE(r.step_error_percent.value(), 3.0) << at;
    std::printf(
        "%-8s %.2f m/s: speed %.3f cadence %.1f (people %.1f +- %.1f) step %.3f (%.3f +- "
        "%.3f) stance %.1f (%.1f) thigh %.2f r %.3f knee %.2f r %.3f slip %.2f mm\n",
        p.task.c_str(), speed, r.speed, r.cadence, p.cadence.mean, p.cadence.sd, r.step_length,
        p.step_length.mean, p.step_length.sd, r.stance_percent, p.stance.mean, r.thigh_score->rmse,
        r.thigh_score->pearson, r.knee_score->rmse, r.knee_score->pearson, 1000.0 * r.max_slip);
  }
}

// The contact bounds from the slowest speed to the fastest each stature walks (the speed grid of
// the issue, 0.6-2.1 m/s, within what the legs take), each within 3 % of the speed asked.
TEST(Speed, FeetStayPlantedAcrossSpeedsAndStatures) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  for (const double stature : {1.50, 1.75, 2.00}) {
    gait::Walker probe = walker_at(ground, 1.2, stature);
    for (const double asked : {0.6, 1.0, 1.5, 2.1}) {
      const double speed = std::clamp(asked, probe.min_speed(), probe.max_speed());
      gait::Walker w = walker_at(ground, speed, stature);
      const double step = w.step_length();
      const eval::GaitReport r =
          eval::evaluate(eval::record(w, 13.0, 120.0), ground, nullptr, step);
      const std::string at = label(speed, stature);
      EXPECT_NEAR(r.speed, speed, 0.03 * speed) << at;
      EXPECT_LT(r.max_slip, 0.001) << at;
      EXPECT_LT(r.max_penetration, 0.001) << at;
      EXPECT_LE(r.step_error_percent.value(), 3.0) << at;
      EXPECT_GE(r.cycles, 5) << at;
      std::printf(
          "%s: speed %.3f step %.3f cadence %.1f slip %.2f mm clearance %.1f mm step "
          "error %.1f %% cycles %d\n",
          at.c_str(), r.speed, r.step_length, r.cadence, 1000.0 * r.max_slip,
          1000.0 * r.min_toe_clearance, r.step_error_percent.value(), r.cycles);
    }
  }
}

// Speeding up from a slow walk to a brisk one and back: the commanded speed moves at the set's
// acceleration, the steps follow it, the feet stay planted through the change, and no joint's
// velocity jumps at a phase switch by more than in a steady walk at the fastest speed reached.
// (That one's jumps are 1.8 times its 99th percentile of changes: the controllers' switches,
// played faster, are more abrupt; docs/walk.md, "Speed".)
TEST(Speed, ChangesMidWalkAtTheSetsAcceleration) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::Walker w = walker_at(ground, 0.9, 1.75);
  const double accel = default_set().acceleration;
  eval::Motion motion;
  motion.fps = 120.0;
  motion.segments = rig::segments_from_stature(1.75);
  double previous = w.state().speed;
  double fastest_change = 0.0;
  for (int frame = 0; frame < 120 * 16; ++frame) {
    const double t = frame / 120.0;
    if (frame == 120 * 4) {
      EXPECT_DOUBLE_EQ(w.set_speed(1.7), 1.7);
    }
    if (frame == 120 * 10) {
      EXPECT_DOUBLE_EQ(w.set_speed(1.1), 1.1);
    }
    motion.frames.push_back(eval::capture_frame(w, t));
    ASSERT_TRUE(w.advance(1.0 / 120.0));
    fastest_change = std::max(fastest_change, std::abs(w.state().speed - previous) * 120.0);
    previous = w.state().speed;
    if (frame == 120 * 4 + 59) {
      EXPECT_NEAR(w.state().speed, 0.9 + 0.5 * accel, 1e-9);  // half a second after the change
    }
    if (frame == 120 * 9) {
      EXPECT_DOUBLE_EQ(w.state().speed, 1.7);
      EXPECT_NEAR(w.step_length(),
                  default_set().step_at_pace(gait::Walker::pace(1.7, motion.segments)) *
                      motion.segments.leg_length(),
                  1e-12);
    }
  }
  EXPECT_LE(fastest_change, accel * (1.0 + 1e-9));
  EXPECT_DOUBLE_EQ(w.state().speed, 1.1);
  const eval::GaitReport r = eval::evaluate(motion, ground);
  EXPECT_LT(r.max_slip, 0.001);
  EXPECT_LT(r.max_penetration, 0.001);
  gait::Walker steady = walker_at(ground, 1.7, 1.75);
  const eval::GaitReport fast = eval::evaluate(eval::record(steady, 13.0, 120.0), ground);
  EXPECT_LE(r.max_velocity_jump, 1.1 * fast.max_velocity_jump);
  std::printf(
      "speed change: slip %.2f mm, velocity jump %.1f deg/s per frame (steady at 1.7 m/s: "
      "jump %.1f, 99th percentile %.1f)\n",
      1000.0 * r.max_slip, r.max_velocity_jump, fast.max_velocity_jump,
      fast.typical_velocity_change);
}

TEST(Speed, RangeAndBadRequests) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::Walker w = walker_at(ground, 1.2, 1.75);
  EXPECT_LT(w.min_speed(), 0.7);
  EXPECT_GT(w.max_speed(), 2.0);
  EXPECT_DOUBLE_EQ(w.speed(), 1.2);
  EXPECT_DOUBLE_EQ(w.set_speed(100.0), w.max_speed());
  EXPECT_DOUBLE_EQ(w.set_speed(0.0), w.min_speed());
  EXPECT_TRUE(std::isnan(w.set_speed(std::numeric_limits<double>::quiet_NaN())));
  EXPECT_DOUBLE_EQ(w.speed(), w.min_speed());
  // Walked by step length, the speed is that step at the set's cadence.
  EXPECT_DOUBLE_EQ(w.set_step_length(0.7), 0.7);
  EXPECT_DOUBLE_EQ(w.speed(), 0.7 * default_set().cadence / 60.0);
  EXPECT_DOUBLE_EQ(w.step_length(), 0.7);

  gait::WalkerOptions o;
  o.speed = 9.0;
  try {
    gait::Walker too_fast(default_set(), o, ground);
    ADD_FAILURE() << "a 9 m/s walk was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("speed must be between"), std::string::npos) << e.what();
  }
  gait::ControllerSet no_stride = default_set();
  no_stride.stride.reset();
  o.speed = 1.2;
  try {
    gait::Walker without(no_stride, o, ground);
    ADD_FAILURE() << "a walk by speed was taken without a stride relation";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no stride relation"), std::string::npos) << e.what();
  }
  o.speed = 0.0;
  gait::Walker by_step(no_stride, o, ground);
  EXPECT_TRUE(std::isnan(by_step.set_speed(1.2)));
  EXPECT_TRUE(std::isnan(by_step.min_speed()));
  EXPECT_DOUBLE_EQ(by_step.step_length(), o.step_length);
}

// A crowd's character asked for a speed walks bit for bit as the same walker alone.
TEST(Speed, ACrowdsCharacterWalksAsAlone) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::WalkerOptions o;
  o.segments = rig::segments_from_stature(1.8);
  o.speed = 1.0;
  const std::vector<gait::WalkerOptions> characters = {o, o};
  gait::Crowd crowd(default_set(), ground, characters);
  gait::Walker alone(default_set(), o, ground);
  EXPECT_DOUBLE_EQ(crowd.set_speed(1, 1.6), 1.6);
  EXPECT_TRUE(std::isnan(crowd.set_speed(2, 1.6)));
  alone.set_speed(1.6);
  for (int i = 0; i < 600; ++i) {
    crowd.advance(1.0 / 60.0);
    alone.advance(1.0 / 60.0);
  }
  EXPECT_EQ(test::state_difference(crowd[1].state(), alone.state()), "");
  EXPECT_NE(test::state_difference(crowd[0].state(), alone.state()), "");
}

}  // namespace

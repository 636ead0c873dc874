// The walk's acceptance bounds (level walking issue): realism against Schwartz et al. 2008 at
// free speed, contact quality across steps and body sizes, curves that change with step length
// as people's do, smooth phase switches, and recovery from awkward starts.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "fuzzygait/eval/evaluation.hpp"
#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/eval/recovery.hpp"
#include "fuzzygait/io/normative.hpp"
#include "support/walks.hpp"

using namespace fuzzygait;

namespace {

using test::default_set;
using test::make_walker;

eval::GaitReport walk(double step, double stature, const eval::Normative* reference,
                      const gait::ControllerSet& set = default_set(), double seconds = 13.0) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::Walker walker = make_walker(ground, step, stature, {}, set);
  const eval::Motion motion = eval::record(walker, seconds, 120.0);
  return eval::evaluate(motion, ground, reference, step);
}

void expect_sound_contact(const eval::GaitReport& r, const std::string& label) {
  EXPECT_LT(r.max_slip, 0.001) << label;
  EXPECT_LT(r.max_penetration, 0.001) << label;
  EXPECT_GE(r.min_toe_clearance, 0.005) << label;
  EXPECT_LE(r.step_error_percent.value(), 3.0) << label;
  EXPECT_GE(r.cycles, 8) << label;
  EXPECT_LT(r.cycle_time_sd, 0.02) << label;
}

TEST(Acceptance, DefaultWalkMatchesNormalGait) {
  const eval::Normative reference = io::load_normative("schwartz2008_free");
  const eval::GaitReport r = walk(0.70, 1.75, &reference);
  ASSERT_TRUE(r.thigh_score.has_value());
  ASSERT_TRUE(r.knee_score.has_value());
  ASSERT_TRUE(r.ankle_score.has_value());
  EXPECT_LE(r.thigh_score->rmse, 6.0);
  EXPECT_LE(r.knee_score->rmse, 8.0);
  EXPECT_LE(r.ankle_score->rmse, 6.0);
  EXPECT_GE(r.thigh_score->pearson, 0.90);
  EXPECT_GE(r.knee_score->pearson, 0.90);
  EXPECT_GE(r.ankle_score->pearson, 0.75);
  EXPECT_GE(r.stance_percent, 57.0);
  EXPECT_LE(r.stance_percent, 65.0);
  EXPECT_GE(r.knee_peak, 55.0);
  EXPECT_LE(r.knee_peak, 70.0);
  EXPECT_GE(r.knee_peak_percent, 68.0);
  EXPECT_LE(r.knee_peak_percent, 78.0);
  expect_sound_contact(r, "default");
}

TEST(Acceptance, NoVelocityJumpAtPhaseSwitches) {
  const eval::GaitReport r = walk(0.70, 1.75, nullptr);
  EXPECT_GE(r.cycles, 8);
  // Where a phase hands a joint to another controller (or to the ground), its velocity changes
  // from one frame to the next by at most 1.5 times the typical change elsewhere in the walk
  // (the 99th percentile of the frame-to-frame changes).
  EXPECT_LE(r.max_velocity_jump, 1.5 * r.typical_velocity_change);
}

class StepAndStature : public ::testing::TestWithParam<std::tuple<double, double>> {};

TEST_P(StepAndStature, ContactIsSound) {
  const auto [step, stature] = GetParam();
  expect_sound_contact(walk(step, stature, nullptr),
                       "step " + std::to_string(step) + " stature " + std::to_string(stature));
}

INSTANTIATE_TEST_SUITE_P(Grid, StepAndStature,
                         ::testing::Combine(::testing::Values(0.50, 0.60, 0.70, 0.85),
                                            ::testing::Values(1.50, 1.75, 2.00)));

// The shortest step the walker takes with the default set (Walker::min_step_length, 0.46 leg
// lengths) meets the contact bounds too, for every stature of the grid: the refusal below it is
// where the walk breaks down, not a margin kept for safety's sake (at 0.45 leg lengths the feet
// slide 60-80 mm a frame).
TEST(Acceptance, ShortestAcceptedStepIsSound) {
  for (double stature : {1.50, 1.75, 2.00}) {
    const double step =
        gait::Walker::min_step_length(default_set(), rig::segments_from_stature(stature));
    expect_sound_contact(walk(step, stature, nullptr), "stature " + std::to_string(stature));
  }
}

// The styles' shortest steps (their manifests' shortest_step_leg_lengths) are where their walks
// stop breaking down: from there up, slip stays within a few millimetres a frame and the step
// within 10 % of the command. They miss the default's tighter bounds at some steps (docs/walk.md,
// "Step lengths"), but none slides like a walk below its shortest step.
TEST(Acceptance, StylesHoldTogetherFromTheirShortestStep) {
  for (const char* name : {"energetic", "heavy", "cautious"}) {
    const gait::ControllerSet set = gait::ControllerSet::builtin(name);
    for (double stature : {1.50, 1.75, 2.00}) {
      const rig::Segments segments = rig::segments_from_stature(stature);
      const double shortest = gait::Walker::min_step_length(set, segments);
      for (double step : {shortest, 0.5 * (shortest + gait::Walker::max_step_length(segments))}) {
        const eval::GaitReport r = walk(step, stature, nullptr, set, 20.0);
        const std::string label = std::string(name) + " stature " + std::to_string(stature) +
                                  " step " + std::to_string(step);
        EXPECT_LT(r.max_slip, 0.005) << label;
        EXPECT_LT(r.max_penetration, 0.001) << label;
        EXPECT_LE(r.step_error_percent.value(), 10.0) << label;
        EXPECT_GE(r.cycles, 8) << label;
      }
    }
  }
}

TEST(Acceptance, CurvesChangeWithStepLengthAsPeoplesDo) {
  // Schwartz et al.: thigh range and peak knee flexion grow from slow to fast walking.
  const eval::GaitReport short_steps = walk(0.55, 1.75, nullptr);
  const eval::GaitReport normal = walk(0.70, 1.75, nullptr);
  const eval::GaitReport long_steps = walk(0.85, 1.75, nullptr);
  EXPECT_LT(short_steps.thigh_range, normal.thigh_range);
  EXPECT_LT(normal.thigh_range, long_steps.thigh_range);
  EXPECT_LT(short_steps.knee_peak, normal.knee_peak);
  EXPECT_LT(normal.knee_peak, long_steps.knee_peak);
}

// The joint angles of both legs, left then right.
std::array<double, 8> leg_angles(const std::array<rig::LegAngles, 2>& legs) {
  std::array<double, 8> out{};
  for (std::size_t k = 0; k < 2; ++k) {
    const rig::LegAngles& a = legs[k];
    out[4 * k] = a.hip;
    out[4 * k + 1] = a.knee;
    out[4 * k + 2] = a.ankle;
    out[4 * k + 3] = a.toe;
  }
  return out;
}

// 500 seeded random starts within the joint limits, checked at every time step, not only every
// frame (what happens between frames shows in a game too; eval::walk_from_random_start): no NaN,
// nothing below the ground, joints within their limits, no pop of the pelvis, and steady steps of
// the commanded length from the fourth step on (the first touchdown is not a step).
TEST(Acceptance, RecoversFromAwkwardStarts) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  const rig::JointLimits limits{};
  const std::array<double, 8> lowest = leg_angles({limits.minimum, limits.minimum});
  const std::array<double, 8> highest = leg_angles({limits.maximum, limits.maximum});
  const gait::WalkerState default_state = make_walker(ground).state();
  const std::array<double, 8> default_start =
      leg_angles({default_state.legs[0].angles, default_state.legs[1].angles});
  constexpr std::uint64_t kSeeds = 500;
  const gait::WalkerOptions options;  // 0.70 m steps, 1.75 m tall
  // The largest excess (radians) past any hip, knee or ankle limit, and the pelvis's largest move
  // in one time step (m): no pop, whatever the start.
  double worst_excess = 0.0;
  double largest_pelvis_move = 0.0;
  constexpr int kReported = 5;
  std::set<std::array<double, 8>> starts;
  int outside_limits = 0;
  int unsettled = 0;
  for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
    const eval::RecoveryReport r =
        eval::walk_from_random_start(default_set(), options, seed, ground);
    // The start itself, before the first step: random angles within the joint limits.
    const std::array<double, 8> angles = leg_angles(r.start);
    starts.insert(angles);
    EXPECT_NE(angles, default_start) << "seed " << seed << " starts from the default pose";
    for (std::size_t j = 0; j < angles.size(); ++j) {
      const double highest_here = highest[j] + 1e-9;
      if ((angles[j] < lowest[j] - 1e-9 || angles[j] > highest_here) &&
          ++outside_limits <= kReported) {
        ADD_FAILURE() << "seed " << seed << ": angle " << j << " (leg " << j / 4 << ") is "
                      << angles[j] << " rad, outside [" << lowest[j] << ", " << highest_here << "]";
      }
    }
    ASSERT_TRUE(r.sound()) << "seed " << seed << ": " << r.failure;
    worst_excess = std::max(worst_excess, r.worst_limit_excess);
    largest_pelvis_move = std::max(largest_pelvis_move, r.largest_pelvis_move);
    if (r.unsettled_steps(options.step_length) > 0 && ++unsettled <= kReported) {
      ADD_FAILURE() << "seed " << seed << " did not settle: " << r.strikes.size() << " steps";
    }
  }
  EXPECT_EQ(outside_limits, 0) << "start angles outside the joint limits";
  // A flat foot's ankle can pass its limit by a fraction of a degree for a time step.
  EXPECT_LT(rig::degrees(worst_excess), 0.5) << "deg past the hip, knee or ankle limits";
  // Walking moves the pelvis about 5 mm a time step; a fast vault out of a crouch, 60 mm. A pop
  // (the chain snapping onto a foot put down far away) moved it 0.3-0.8 m.
  EXPECT_LT(largest_pelvis_move, 0.075) << "m, the pelvis's largest move in a time step";
  EXPECT_EQ(unsettled, 0) << "of " << kSeeds << " starts did not settle";
  // Every seed its own start (seeds are hashed one-to-one into the generator's state).
  EXPECT_EQ(starts.size(), kSeeds) << "distinct starts of " << kSeeds;
}

// The styles from the same 500 awkward starts: finite and above the ground at every time step,
// no pop of the pelvis, and walking on (none stuck in a crouch).
TEST(Acceptance, StylesStayAboveTheGroundFromAwkwardStarts) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  for (const char* name : {"energetic", "heavy", "cautious"}) {
    const gait::ControllerSet set = gait::ControllerSet::builtin(name);
    const gait::WalkerOptions options;
    int unsettled = 0;
    for (std::uint64_t seed = 0; seed < 500; ++seed) {
      const eval::RecoveryReport r = eval::walk_from_random_start(set, options, seed, ground);
      ASSERT_TRUE(r.sound()) << name << " seed " << seed << ": " << r.failure;
      EXPECT_LT(r.largest_pelvis_move, 0.1) << name << " seed " << seed << ", m in a time step";
      // The slowest style takes 11 steps in 8 s; a walker stuck in a crouch took one.
      EXPECT_GE(r.strikes.size(), 8u) << name << " seed " << seed << " stopped stepping";
      if (r.unsettled_steps(options.step_length) > 0) ++unsettled;
    }
    // The default's bound (every start settles within three steps) less one start: heavy's
    // seed 263 hops on both forefeet for two seconds and settles a step late.
    EXPECT_LE(unsettled, 1) << name << ": starts not settled within three steps";
  }
}

// A style is only controller data: walked with the same options as the default, it must differ
// from it the way an animator expects, by a margin people can see.
struct StyleFigures {
  double cadence;       // steps per minute
  double swing_time;    // s
  double stance;        // % of the cycle
  double knee_peak;     // deg
  double pelvis_range;  // m
};

StyleFigures style(const std::string& name) {
  const gait::ControllerSet set = gait::ControllerSet::builtin(name);
  // 18 s: at least 10 cycles for the slow styles too (cautious, 1.4 s a cycle: 11).
  const eval::GaitReport r = walk(0.70, 1.75, nullptr, set, 18.0);
  EXPECT_GE(r.cycles, 10) << name;
  EXPECT_LT(r.max_slip, 0.001) << name;
  EXPECT_LT(r.max_penetration, 0.001) << name;
  EXPECT_GE(r.min_toe_clearance, 0.005) << name;
  // Cautious: 3.6 %, short of its 0.70 m steps.
  EXPECT_LE(r.step_error_percent.value(), 4.0) << name;
  EXPECT_LT(r.cycle_time_sd, 0.02) << name;
  return {r.cadence, r.cycle_time * (1.0 - r.stance_percent / 100.0), r.stance_percent, r.knee_peak,
          r.pelvis_vertical_range};
}

TEST(Styles, DifferFromTheDefaultInTheExpectedDirections) {
  const StyleFigures normal = style("default");
  const StyleFigures energetic = style("energetic");
  const StyleFigures heavy = style("heavy");
  const StyleFigures cautious = style("cautious");
  // Energetic: quicker steps and a quicker swing.
  EXPECT_GT(energetic.cadence, normal.cadence + 10.0);
  EXPECT_LT(energetic.swing_time, normal.swing_time - 0.03);
  EXPECT_GE(energetic.knee_peak, normal.knee_peak);
  // Heavy: slower steps, a lower knee, a flatter path of the pelvis.
  EXPECT_LT(heavy.cadence, normal.cadence - 5.0);
  EXPECT_LT(heavy.knee_peak, normal.knee_peak - 3.0);
  EXPECT_LT(heavy.pelvis_range, normal.pelvis_range - 0.005);
  // Cautious or tired: slower still, longer on both feet, little knee lift.
  EXPECT_LT(cautious.cadence, heavy.cadence - 5.0);
  EXPECT_GT(cautious.stance, normal.stance + 3.0);
  EXPECT_GT(cautious.swing_time, normal.swing_time + 0.03);
  EXPECT_LT(cautious.knee_peak, normal.knee_peak - 3.0);
}

}  // namespace

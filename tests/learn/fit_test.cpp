// Training data and fits, on walks the walker made itself, where the truth is known: the data
// measure the walk as the walker measured it, the walker's own controllers replayed along it
// retrace it, and fits started from other values find the values that walked.
#include "fuzzygait/learn/fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/learn/network.hpp"
#include "fuzzygait/learn/training.hpp"
#include "fuzzygait/learn/tune.hpp"
#include "support/walks.hpp"

namespace fuzzygait {
namespace {

constexpr double kStep = 1.0 / 240.0;

// A walker's walk sampled at every time step, and its state after each step.
struct Recorded {
  eval::Motion motion;
  std::vector<gait::WalkerState> states;  // states[n]: after n steps
};

Recorded walk(const gait::ControllerSet& set, double seconds, double step = 0.70) {
  gait::WalkerOptions o;
  o.step_length = step;
  static const terrain::Terrain flat = terrain::Terrain::flat();
  gait::Walker walker(set, o, flat);
  Recorded r;
  r.motion.fps = 1.0 / kStep;
  r.motion.segments = walker.segments();
  const auto steps = static_cast<std::size_t>(seconds / kStep);
  for (std::size_t n = 0; n <= steps; ++n) {
    if (n > 0) walker.advance(kStep);
    r.motion.frames.push_back(eval::capture_frame(walker, static_cast<double>(n) * kStep));
    r.states.push_back(walker.state());
  }
  return r;
}

learn::TrainingClip data_of(const Recorded& r, const gait::ControllerSet& set, double step = 0.70) {
  return learn::training_data(r.motion, terrain::Terrain::flat(), step, set, {.time_step = kStep});
}

std::size_t weight(const learn::SetNetwork& network, const std::string& name) {
  const std::size_t i = network.find(name);
  EXPECT_LT(i, network.size()) << name;
  return i;
}

TEST(TrainingData, MeasuresASwingAsTheWalkerMeasuredIt) {
  const gait::ControllerSet& set = test::default_set();
  const Recorded r = walk(set, 4.0);
  const learn::TrainingClip data = data_of(r, set);
  ASSERT_EQ(data.steps.size(), r.states.size());
  std::size_t swings = 0;
  for (std::size_t n = 0; n + 1 < data.steps.size(); ++n) {
    for (std::size_t leg = 0; leg < 2; ++leg) {
      const learn::LegStep& s = data.steps[n][leg];
      // The walker measures frame n at the start of step n + 1.
      const gait::LegState& walker = r.states[n + 1].legs[leg];
      ASSERT_EQ(s.phase == gait::LegPhase::Swing, r.motion.frames[n].contact[leg] == false);
      if (!s.known || s.phase != gait::LegPhase::Swing) continue;
      ++swings;
      ASSERT_NEAR(s.metrics[static_cast<std::size_t>(gait::Metric::Delta)], walker.delta, 1e-9)
          << "step " << n << " leg " << leg;
      if (walker.phase == gait::Phase::Swing) {  // (a strike in step n + 1 starts a new sweep)
        ASSERT_NEAR(s.sweep_start, walker.sweep_start, 1e-12);
        ASSERT_NEAR(s.sweep_end, walker.sweep_end, 1e-9);
      }
      EXPECT_DOUBLE_EQ(s.metrics[static_cast<std::size_t>(gait::Metric::Knee)],
                       rig::degrees(r.states[n].legs[leg].angles.knee));
      EXPECT_TRUE(learn::driven(s, gait::Joint::Knee));
    }
  }
  EXPECT_GT(swings, 600u);
}

TEST(TrainingData, TellsWhoDrivesAPlantedLeg) {
  const gait::ControllerSet& set = test::default_set();
  const Recorded r = walk(set, 4.0);
  const learn::TrainingClip data = data_of(r, set);
  std::size_t carrying = 0;
  std::size_t planted_not_carrying = 0;
  std::array<std::size_t, 4> feet{};
  for (std::size_t n = 0; n < data.steps.size(); ++n) {
    for (std::size_t leg = 0; leg < 2; ++leg) {
      const learn::LegStep& s = data.steps[n][leg];
      if (!s.known || s.phase != gait::LegPhase::Stance) continue;
      ++feet[static_cast<std::size_t>(s.foot)];
      // The leg the walker let carry the body is the one the data say carries.
      if (s.carrying) {
        ++carrying;
        EXPECT_EQ(r.states[n].lead, static_cast<int>(leg)) << "step " << n;
      } else {
        ++planted_not_carrying;
      }
      EXPECT_EQ(learn::driven(s, gait::Joint::Hip), s.carrying);
      EXPECT_EQ(learn::driven(s, gait::Joint::Ankle),
                s.foot == learn::FootContact::Heel || s.foot == learn::FootContact::Ball);
    }
  }
  EXPECT_GT(carrying, 400u);
  EXPECT_GT(planted_not_carrying, 20u);
  EXPECT_GT(feet[static_cast<std::size_t>(learn::FootContact::Heel)], 10u);
  EXPECT_GT(feet[static_cast<std::size_t>(learn::FootContact::Flat)], 100u);
  EXPECT_GT(feet[static_cast<std::size_t>(learn::FootContact::Ball)], 50u);
}

TEST(TrainingData, RefusesWhatCannotBeMeasured) {
  const gait::ControllerSet& set = test::default_set();
  eval::Motion empty;
  empty.fps = 120.0;
  EXPECT_THROW(learn::training_data(empty, terrain::Terrain::flat(), 0.7, set),
               std::invalid_argument);
  const Recorded r = walk(set, 0.5);
  EXPECT_THROW(learn::training_data(r.motion, terrain::Terrain::flat(), 0.0, set),
               std::invalid_argument);
  EXPECT_THROW(
      learn::training_data(r.motion, terrain::Terrain::flat(), 0.7, set, {.time_step = -1.0}),
      std::invalid_argument);
}

// The walker's own controllers, replayed along its walk, retrace the thigh (in swing to rounding;
// in stance its sweep begins where the chain closed after the strike, a hair off the walker's),
// and the other joints closely (the clearance reflex and the ground's rules touch them now and
// then).
TEST(Replay, TheWalkersOwnControllersRetraceItsWalk) {
  const gait::ControllerSet& set = test::default_set();
  const Recorded r = walk(set, 5.0);
  const std::vector<learn::TrainingClip> data = {data_of(r, set)};
  const learn::SetNetwork network(set);
  const std::array<double, 4> alone = learn::replay_rmse(network, data, network.values(), false);
  EXPECT_LT(alone[0], 0.1) << "hip";
  EXPECT_LT(alone[1], 1.0) << "knee";
  EXPECT_LT(alone[2], 1.0) << "ankle";
  // Other values retrace it worse: the replay depends on the weights.
  std::vector<double> other = network.values();
  other[network.find("swing_hip.velocity.fast")] *= 0.8;
  other[network.find("swing_knee.velocity.flex_fast")] *= 0.8;
  const std::array<double, 4> off = learn::replay_rmse(network, data, other, false);
  EXPECT_GT(off[0], 10.0 * alone[0] + 0.5);
  EXPECT_GT(off[1], alone[1] + 0.5);
}

// The set that walked differs from the default in its swinging thigh and knee; fits from the
// default find its values.
class Recovery : public ::testing::Test {
 protected:
  void SetUp() override {
    const learn::SetNetwork base(test::default_set());
    truth_ = base.values();
    truth_[weight(base, "swing_hip.velocity.slow")] = 6.2;
    truth_[weight(base, "swing_hip.velocity.fast")] = 11.5;
    truth_[weight(base, "swing_knee.velocity.flex_fast")] = 760.0;
    truth_[weight(base, "swing_knee.velocity.extend_fast")] = -700.0;
    truth_set_ = base.apply(truth_);
    data_ = {data_of(walk(truth_set_, 4.0), truth_set_)};
  }
  std::vector<double> truth_;
  gait::ControllerSet truth_set_;
  std::vector<learn::TrainingClip> data_;
};

TEST_F(Recovery, ATrajectoryFitFindsTheSwingValuesThatWalked) {
  const learn::SetNetwork network(test::default_set());
  learn::FitOptions o;
  o.prior = 0.0;
  o.max_iterations = 50;
  const std::vector<std::size_t> hip = network.slot_weights(0);
  std::vector<std::size_t> free;
  for (std::size_t i : hip) {
    if (network.weight(i).kind == learn::WeightKind::Output) free.push_back(i);
  }
  const learn::FitResult r =
      learn::fit_weights(network, data_, network.values(), free, learn::FitData::Trajectories,
                         {true, false, false, false}, o);
  EXPECT_LT(r.final_cost, 1e-2 * r.initial_cost);
  for (const char* name : {"swing_hip.velocity.slow", "swing_hip.velocity.fast"}) {
    const std::size_t i = weight(network, name);
    EXPECT_NEAR(r.weights[i], truth_[i], 1e-3 * std::abs(truth_[i])) << name;
  }
}

TEST_F(Recovery, APerFrameFitComesCloseAndTheKneeFitFindsItsValues) {
  const learn::SetNetwork network(test::default_set());
  learn::FitOptions o;
  o.prior = 0.0;
  std::vector<std::size_t> free;
  for (const int slot : {0, 1}) {
    for (std::size_t i : network.slot_weights(slot)) {
      if (network.weight(i).kind == learn::WeightKind::Output) free.push_back(i);
    }
  }
  const learn::FitResult commands =
      learn::fit_weights(network, data_, network.values(), free, learn::FitData::Commands, {}, o);
  const learn::FitResult knee =
      learn::fit_weights(network, data_, commands.weights, free, learn::FitData::Trajectories,
                         {true, true, false, false}, o);
  for (const char* name : {"swing_hip.velocity.slow", "swing_hip.velocity.fast",
                           "swing_knee.velocity.flex_fast", "swing_knee.velocity.extend_fast"}) {
    const std::size_t i = weight(network, name);
    const double start_error = std::abs(network.values()[i] - truth_[i]);
    EXPECT_LT(std::abs(commands.weights[i] - truth_[i]), 0.5 * start_error) << name;
    EXPECT_NEAR(knee.weights[i], truth_[i], 0.02 * std::abs(truth_[i])) << name;
  }
}

// Starting far off, with every weight of the swing free, the readability terms hold: knots in
// order a gap apart, words kept.
TEST_F(Recovery, FitsKeepKnotsInOrderAndWordsTheirPromises) {
  const learn::SetNetwork network(test::default_set());
  learn::FitOptions o;
  std::vector<double> start = network.values();
  for (double& v : start)
    v *= 1.3;
  start[network.inertia_index()] = 0.02;
  start = learn::ordered(network, start, o.knot_gap);
  std::vector<std::size_t> every;
  for (std::size_t i = 0; i + 1 < network.size(); ++i)
    every.push_back(i);
  const learn::FitResult r =
      learn::fit_weights(network, data_, start, every, learn::FitData::Commands, {}, o);
  const std::vector<double> w = learn::ordered(network, r.weights, o.knot_gap);
  for (std::size_t i = 0; i < network.size(); ++i) {
    if (network.weight(i).kind != learn::WeightKind::Knot) continue;
    EXPECT_LT(network.knot_below(i, w), w[i]) << network.weight(i).name;
    // The fit itself kept them apart: ordering moved them by little.
    EXPECT_NEAR(w[i], r.weights[i], 0.01 * network.range(i)) << network.weight(i).name;
  }
  const gait::ControllerSet set = network.apply(w);
  EXPECT_LT(learn::word_penalty(set), 0.05);
}

TEST(Fit, RefusesWhatItCannotFit) {
  const learn::SetNetwork network(test::default_set());
  const std::vector<learn::TrainingClip> none;
  EXPECT_THROW(
      learn::fit_weights(network, none, network.values(), {}, learn::FitData::Commands, {}, {}),
      std::invalid_argument);
  const Recorded r = walk(test::default_set(), 2.0);
  const std::vector<learn::TrainingClip> data = {data_of(r, test::default_set())};
  const std::vector<double> short_start(3, 0.0);
  EXPECT_THROW(learn::fit_weights(network, data, short_start, {}, learn::FitData::Commands, {}, {}),
               std::invalid_argument);
  const std::vector<std::size_t> beyond = {network.size()};
  EXPECT_THROW(
      learn::fit_weights(network, data, network.values(), beyond, learn::FitData::Commands, {}, {}),
      std::invalid_argument);
}

TEST(Fit, StopsWhenAskedKeepingTheWeightsReached) {
  const learn::SetNetwork network(test::default_set());
  const Recorded r = walk(test::default_set(), 3.0);
  const std::vector<learn::TrainingClip> data = {data_of(r, test::default_set())};
  std::vector<double> start = network.values();
  start[network.find("swing_hip.velocity.fast")] = 10.0;
  learn::FitOptions o;
  int reports = 0;
  o.progress = [&reports](const learn::FitProgress&) { ++reports; };
  o.stop = [&reports] { return reports >= 2; };
  const std::vector<std::size_t> free = {network.find("swing_hip.velocity.fast")};
  const learn::FitResult f = learn::fit_weights(
      network, data, start, free, learn::FitData::Trajectories, {true, false, false, false}, o);
  EXPECT_TRUE(f.stopped);
  EXPECT_EQ(reports, 2);
  EXPECT_NE(f.weights[free[0]], 10.0);
}

}  // namespace
}  // namespace fuzzygait

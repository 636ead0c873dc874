// Learning: CMA-ES on functions whose minimum is known, the set's parameters (round trip,
// rounding), the penalty for words that stop meaning what they say, the walk cost's terms (held
// to recorded bits; each weight pricing what it names, and refused out of range), a short tune
// that must not make the set worse, and the polish of the rounded values.
#include "fuzzygait/learn/tune.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fuzzygait/eval/evaluation.hpp"
#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/io/normative.hpp"
#include "fuzzygait/learn/cmaes.hpp"
#include "support/bits.hpp"
#include "support/walks.hpp"

namespace fuzzygait {
namespace {

double sphere(const std::vector<double>& x) {
  double s = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i)
    s += (x[i] - 0.5 * static_cast<double>(i)) * (x[i] - 0.5 * static_cast<double>(i));
  return s;
}

double rosenbrock(const std::vector<double>& x) {
  double s = 0.0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    s += 100.0 * std::pow(x[i + 1] - x[i] * x[i], 2) + std::pow(1.0 - x[i], 2);
  }
  return s;
}

TEST(Cmaes, FindsTheMinimumOfASphere) {
  learn::CmaesOptions o;
  o.max_generations = 300;
  o.sigma = 1.0;
  const learn::CmaesResult r = learn::minimize(sphere, std::vector<double>(6, 3.0), o);
  EXPECT_LT(r.best_cost, 1e-10);
  for (std::size_t i = 0; i < r.best.size(); ++i)
    EXPECT_NEAR(r.best[i], 0.5 * static_cast<double>(i), 1e-4);
  EXPECT_GT(r.evaluations, 0);
}

TEST(Cmaes, FollowsRosenbrocksValley) {
  learn::CmaesOptions o;
  o.max_generations = 2000;
  o.sigma = 0.5;
  const learn::CmaesResult r = learn::minimize(rosenbrock, {-1.2, 1.0, -0.5, 0.8}, o);
  EXPECT_LT(r.best_cost, 1e-8);
  for (double v : r.best)
    EXPECT_NEAR(v, 1.0, 1e-3);
}

TEST(Cmaes, SameSeedSameResultWhateverTheThreads) {
  learn::CmaesOptions o;
  o.max_generations = 40;
  o.seed = 9;
  const learn::CmaesResult a = learn::minimize(rosenbrock, {0.0, 0.0, 0.0}, o);
  o.threads = 2;
  const learn::CmaesResult b = learn::minimize(rosenbrock, {0.0, 0.0, 0.0}, o);
  EXPECT_EQ(a.best, b.best);
  EXPECT_EQ(a.best_cost, b.best_cost);
  o.seed = 10;
  const learn::CmaesResult c = learn::minimize(rosenbrock, {0.0, 0.0, 0.0}, o);
  EXPECT_NE(a.best, c.best);
}

TEST(Cmaes, StopsAtTheTarget) {
  learn::CmaesOptions o;
  o.max_generations = 1000;
  o.target = 1e-2;
  const learn::CmaesResult r = learn::minimize(sphere, std::vector<double>(3, 2.0), o);
  EXPECT_LT(r.best_cost, 1e-2);
  EXPECT_GT(r.best_cost, 1e-8);  // stopped early, not run to the end
}

// Every controller's output for a grid of metric values.
std::vector<double> outputs(const gait::ControllerSet& set) {
  std::vector<double> out;
  for (const gait::Controller& c : set.controllers) {
    fuzzy::Workspace w = c.make_workspace();
    for (double delta = -1.0; delta <= 1.5; delta += 0.125) {
      for (double angle = -20.0; angle <= 70.0; angle += 10.0) {
        gait::MetricValues m{};
        m.fill(angle);
        m[static_cast<std::size_t>(gait::Metric::Delta)] = delta;
        m[static_cast<std::size_t>(gait::Metric::OtherDelta)] = -delta;
        out.push_back(c.evaluate(m, w));
      }
    }
  }
  return out;
}

TEST(SetParameters, ApplyingTheStartGivesTheSameSet) {
  const gait::ControllerSet& base = test::default_set();
  const learn::SetParameters p(base);
  EXPECT_GT(p.size(), 30u);
  // The same values through the parameters' scaling: equal but for the last bits.
  const gait::ControllerSet same = p.apply(p.values());
  const std::vector<double> a = outputs(same);
  const std::vector<double> b = outputs(base);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    ASSERT_NEAR(a[i], b[i], 1e-9 * (1.0 + std::abs(b[i]))) << i;
  EXPECT_NEAR(same.inertia, base.inertia, 1e-15);
  // The shipped values have three significant digits: rounding keeps them.
  EXPECT_EQ(outputs(p.rounded(p.values(), 3)), outputs(base));
  // A change moves the outputs, and rounding to one digit moves them too.
  std::vector<double> v = p.values();
  v[0] += 0.5;
  EXPECT_NE(outputs(p.apply(v)), outputs(base));
  EXPECT_NE(outputs(p.rounded(p.values(), 1)), outputs(base));
}

TEST(SetParameters, InertiaNeverGoesBelowItsMinimum) {
  const learn::SetParameters p(test::default_set(), 0.02);
  std::vector<double> v = p.values();
  v.back() = 0.0;  // the inertia is the last value: no time constant at all
  EXPECT_EQ(p.apply(v).inertia, 0.02);
  v.back() = -0.01;  // values are magnitudes
  EXPECT_EQ(p.apply(v).inertia, 0.02);
}

// A value the search drove to nan makes no controller set (gait::Controller refuses it); the
// tuner prices such a candidate above any that walks, instead of ending in a worker thread.
TEST(SetParameters, ANanValueMakesNoSet) {
  const learn::SetParameters p(test::default_set());
  std::vector<double> v = p.values();
  v[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(p.apply(v), std::invalid_argument);
  EXPECT_THROW(p.rounded(v, 3), std::invalid_argument);
}

TEST(WordPenalty, ShippedSetsKeepTheirWordsAndABrokenWordCosts) {
  for (const std::string& name : gait::ControllerSet::builtin_names()) {
    EXPECT_LT(learn::word_penalty(gait::ControllerSet::builtin(name)), 1.0) << name;
  }
  // Every value three times as large: a "hold" that moves, a "slow" as fast as a "fast".
  const gait::ControllerSet& base = test::default_set();
  const learn::SetParameters p(base);
  std::vector<double> v = p.values();
  for (double& x : v)
    x *= 3.0;
  EXPECT_GT(learn::word_penalty(p.apply(v)), learn::word_penalty(base) + 1.0);
}

TEST(WalkCost, WordsCostSteeplyPastTheShippedSetsBound) {
  // No walks: the cost is the words' alone, 10 a unit, and 100 more a unit past 0.9.
  const learn::TuneOptions o;
  ASSERT_EQ(o.word_penalty_max, 0.9);
  const learn::SetParameters p(test::default_set());
  for (const double factor : {1.0, 1.3, 3.0}) {
    std::vector<double> v = p.values();
    for (double& x : v)
      x *= factor;
    const gait::ControllerSet set = p.apply(v);
    const double words = learn::word_penalty(set);
    EXPECT_DOUBLE_EQ(learn::walk_cost(set, o), 10.0 * words + 100.0 * std::max(0.0, words - 0.9))
        << factor;
    if (factor == 3.0) {
      EXPECT_GT(words, 0.9);  // the steep part is exercised
    }
  }
}

TEST(WalkCost, TheGridWalksTheWholeAcceptanceGrid) {
  const eval::Normative free = io::load_normative("schwartz2008_free");
  const eval::Normative slow = io::load_normative("schwartz2008_slow");
  const eval::Normative fast = io::load_normative("schwartz2008_fast");
  const std::vector<learn::WalkCondition> grid = learn::grid_conditions(free, slow, fast);
  std::set<std::pair<double, double>> walked;
  for (const learn::WalkCondition& c : grid)
    walked.insert({c.step_length, c.stature});
  for (const double step : {0.50, 0.60, 0.70, 0.85}) {
    for (const double stature : {1.50, 1.75, 2.00}) {
      EXPECT_EQ(walked.count({step, stature}), 1u) << step << " m at " << stature << " m";
    }
  }
  EXPECT_EQ(walked.count({0.55, 1.75}), 1u);
  EXPECT_EQ(grid.size(), 13u);
  EXPECT_EQ(grid.front().reference, &free);
  EXPECT_TRUE(grid.front().enforce_bounds);
}

TEST(WalkCost, TheAccelerationLimitCostsOnlyWhenSet) {
  const eval::Normative free = io::load_normative("schwartz2008_free");
  learn::TuneOptions o;
  o.conditions = {learn::main_condition(free)};
  std::string report;
  const double unlimited = learn::walk_cost(test::default_set(), o, &report);
  EXPECT_NE(report.find("acceleration x"), std::string::npos) << report;
  o.acceleration_ratio_max = 100.0;
  EXPECT_EQ(learn::walk_cost(test::default_set(), o), unlimited);
  // The default's thigh and knee move about 3.7 and 2.9 times as hard as people's: a limit of
  // 1 costs 10 per unit over, about 46.
  o.acceleration_ratio_max = 1.0;
  const double limited = learn::walk_cost(test::default_set(), o);
  EXPECT_GT(limited - unlimited, 40.0);
  EXPECT_LT(limited - unlimited, 60.0);
}

// The normative curves of the recorded costs, loaded once: their conditions point at them.
struct References {
  eval::Normative free = io::load_normative("schwartz2008_free");
  eval::Normative slow = io::load_normative("schwartz2008_slow");
  eval::Normative fast = io::load_normative("schwartz2008_fast");
};

const References& references() {
  static const References r;
  return r;
}

// The default set with every parameter (velocities, inertia, knots) times `factor`.
gait::ControllerSet scaled_default(double factor) {
  const learn::SetParameters p(test::default_set());
  std::vector<double> v = p.values();
  for (double& x : v)
    x *= factor;
  return p.apply(v);
}

// The whole acceptance grid and two random starts, walked 6 s instead of 10: long enough for
// every walk of the default set.
learn::TuneOptions grid_options() {
  learn::TuneOptions o;
  o.conditions = learn::grid_conditions(references().free, references().slow, references().fast);
  o.recovery_seeds = learn::recovery_seeds(2);
  o.duration = 6.0;
  return o;
}

// Bounds that a set off its tune crosses, so that the terms priced above them count too.
learn::TuneOptions strained(learn::TuneOptions o) {
  o.acceleration_ratio_max = 2.0;
  o.heel_bounce_max = 0.01;
  o.pelvis_range_min = 20.0;
  o.pelvis_range_max = 60.0;
  return o;
}

struct CostCase {
  const char* name;
  gait::ControllerSet set;
  learn::TuneOptions options;
  double recorded;  // its walk_cost() as recorded (GCC 12, x86-64)
};

// Between them, these walks give every term of the cost a part: the default set under the
// default bounds, sets slower (x0.7) and faster (x1.5) than their tune under strained bounds
// (words past their bound, unsettled random starts, toes scuffing, the knee peaking early and
// late, slip, ...), a set whose slowest walks do not fit in 6 s, and a wild one (x10) that
// falls over from its random starts.
const std::vector<CostCase>& cost_cases() {
  static const std::vector<CostCase> cases = [] {
    learn::TuneOptions main_walk;
    main_walk.conditions = {learn::main_condition(references().free)};
    learn::TuneOptions wild = main_walk;
    wild.recovery_seeds = learn::recovery_seeds(2);
    return std::vector<CostCase>{
        {"default set, no walks", test::default_set(), learn::TuneOptions{}, 0x1.0555555555555p+3},
        {"default set, main walk", test::default_set(), main_walk, 0x1.f09dfb21fe122p+5},
        {"default set, grid", test::default_set(), grid_options(), 0x1.0cdc0f5f434f7p+7},
        {"slower set, strained grid", scaled_default(0.7), strained(grid_options()),
         0x1.dcbd445ffe114p+12},
        {"faster set, strained grid", scaled_default(1.5), strained(grid_options()),
         0x1.0c642c68aa446p+13},
        {"cautious set, grid", gait::ControllerSet::builtin("cautious"), grid_options(),
         0x1.a50ae592ad2e1p+12},
        {"wild set, main walk", scaled_default(10.0), wild, 0x1.99e0d890ff932p+14},
    };
  }();
  return cases;
}

// The cost's weights became named fields without changing what it computes: each case costs the
// bits recorded from the cost with its weights written inline. A change that alters the cost on
// purpose records new bits and says why.
TEST(WalkCost, DefaultWeightsCostTheRecordedBits) {
  for (const CostCase& c : cost_cases()) {
    const double cost = learn::walk_cost(c.set, c.options);
    char bits[64];
    std::snprintf(bits, sizeof bits, "%a", cost);
    EXPECT_TRUE(test::same_bits(cost, c.recorded)) << c.name << ": " << bits;
  }
}

// Every field of CostWeights, named as validate() names it.
struct WeightField {
  const char* name;
  double learn::CostWeights::*field;
};
constexpr WeightField kWeightFields[] = {
    {"words", &learn::CostWeights::words},
    {"words_over_bound", &learn::CostWeights::words_over_bound},
    {"word_unit", &learn::CostWeights::word_unit},
    {"unsound_start", &learn::CostWeights::unsound_start},
    {"unsettled_step", &learn::CostWeights::unsettled_step},
    {"failed_walk", &learn::CostWeights::failed_walk},
    {"step_error", &learn::CostWeights::step_error},
    {"step_error_over_bound", &learn::CostWeights::step_error_over_bound},
    {"toe_scuff", &learn::CostWeights::toe_scuff},
    {"toe_clearance_wanted", &learn::CostWeights::toe_clearance_wanted},
    {"cycle_time_sd", &learn::CostWeights::cycle_time_sd},
    {"step_length_sd", &learn::CostWeights::step_length_sd},
    {"stance_outside_range", &learn::CostWeights::stance_outside_range},
    {"pelvis_outside_range", &learn::CostWeights::pelvis_outside_range},
    {"cycle_time_outside_range", &learn::CostWeights::cycle_time_outside_range},
    {"velocity_jump", &learn::CostWeights::velocity_jump},
    {"velocity_jump_ratio_free", &learn::CostWeights::velocity_jump_ratio_free},
    {"slip", &learn::CostWeights::slip},
    {"slip_free", &learn::CostWeights::slip_free},
    {"slip_over_bound", &learn::CostWeights::slip_over_bound},
    {"penetration", &learn::CostWeights::penetration},
    {"heel_bounce_over_bound", &learn::CostWeights::heel_bounce_over_bound},
    {"curve_rmse", &learn::CostWeights::curve_rmse},
    {"thigh_knee_uncorrelated", &learn::CostWeights::thigh_knee_uncorrelated},
    {"ankle_uncorrelated", &learn::CostWeights::ankle_uncorrelated},
    {"curve_rmse_over_bound", &learn::CostWeights::curve_rmse_over_bound},
    {"acceleration_over_bound", &learn::CostWeights::acceleration_over_bound},
    {"knee_peak_outside_range", &learn::CostWeights::knee_peak_outside_range},
    {"knee_peak_timing_outside_range", &learn::CostWeights::knee_peak_timing_outside_range},
    {"toe_off_neutral", &learn::CostWeights::toe_off_neutral},
    {"anchor", &learn::CostWeights::anchor},
};
static_assert(std::size(kWeightFields) * sizeof(double) == sizeof(learn::CostWeights),
              "the table lists every field of CostWeights");

// The fields that are thresholds or units rather than prices, and those of them that divide
// (which validate() refuses at 0, as it does a failed walk that costs nothing).
bool is_threshold(const std::string& name) {
  return name == "word_unit" || name == "toe_clearance_wanted" ||
         name == "velocity_jump_ratio_free" || name == "slip_free";
}
bool must_be_positive(const std::string& name) {
  return name == "word_unit" || name == "toe_clearance_wanted" || name == "failed_walk";
}

double cost_with(const CostCase& c, double learn::CostWeights::*field, double value) {
  learn::TuneOptions o = c.options;
  o.weights.*field = value;
  return learn::walk_cost(c.set, o);
}

// Doubling a weight doubles the term it prices and 0 removes it, whatever the other terms:
// walk_cost is linear in each weight. Each weight is checked on the first recorded case where
// its term shows, and every weight's term shows in one.
TEST(WalkCost, EachWeightScalesItsOwnTermAlone) {
  std::vector<double> at_defaults;
  for (const CostCase& c : cost_cases())
    at_defaults.push_back(learn::walk_cost(c.set, c.options));
  for (const WeightField& f : kWeightFields) {
    // (The anchor, 0 by default, prices nothing without TuneOptions::anchor: its own test.)
    if (is_threshold(f.name) || std::string(f.name) == "failed_walk" ||
        std::string(f.name) == "anchor") {
      continue;  // below
    }
    // The walks' penetration is rounding error (under 1e-15 m): a large weight shows it.
    const double weight =
        std::string(f.name) == "penetration" ? 1e15 : learn::CostWeights{}.*f.field;
    bool shown = false;
    for (std::size_t k = 0; k < cost_cases().size(); ++k) {
      const CostCase& c = cost_cases()[k];
      const double without = cost_with(c, f.field, 0.0);
      const double with =
          weight == learn::CostWeights{}.*f.field ? at_defaults[k] : cost_with(c, f.field, weight);
      const double term = with - without;
      EXPECT_GE(term, 0.0) << f.name << " on " << c.name;
      if (!(term > 1e-6 * std::abs(with))) continue;
      const double doubled = cost_with(c, f.field, 2.0 * weight);
      EXPECT_NEAR(doubled - without, 2.0 * term, 1e-9 * std::abs(doubled))
          << f.name << " on " << c.name;
      shown = true;
      break;
    }
    EXPECT_TRUE(shown) << f.name << " prices nothing in the recorded cases";
  }
}

// The anchor's pull: weight times the squared distance, in SetParameters' scaled units, of the
// set's values from the anchor set's; nothing without an anchor or with the set itself.
TEST(WalkCost, TheAnchorPullsTowardItsSet) {
  const CostCase& main = cost_cases()[1];
  const learn::SetParameters p(main.set, main.options.minimum_inertia);
  std::vector<double> moved = p.values();
  moved[0] += 0.5;  // the first output, half a scaled unit
  moved[3] -= 1.5;
  const gait::ControllerSet other = p.apply(moved);
  learn::TuneOptions o = main.options;
  o.weights.anchor = 4.0;
  EXPECT_EQ(learn::walk_cost(main.set, o), main.recorded);  // no anchor set: no pull
  o.anchor = &main.set;
  EXPECT_EQ(learn::walk_cost(main.set, o), main.recorded);  // at the anchor: no pull
  o.anchor = &other;
  EXPECT_NEAR(learn::walk_cost(main.set, o) - main.recorded, 4.0 * (0.25 + 2.25), 1e-9);
  o.weights.anchor = -1.0;
  EXPECT_THROW(learn::walk_cost(main.set, o), std::invalid_argument);
}

// Walks the main condition as walk_cost() does and measures it.
eval::GaitReport main_walk_report(const gait::ControllerSet& set) {
  const learn::TuneOptions o;
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::Walker walker = test::make_walker(ground, 0.70, 1.75, {}, set);
  const eval::Motion motion = eval::record(walker, o.duration, o.fps);
  return eval::evaluate(motion, ground, &references().free, 0.70);
}

// On the default set's main walk (realism weight 1), each weight charges what its name says, in
// the unit its comment gives, and each threshold moves where its charge begins.
TEST(WalkCost, WeightsChargeWhatTheyName) {
  const CostCase& main = cost_cases()[1];
  ASSERT_EQ(std::string(main.name), "default set, main walk");
  ASSERT_EQ(main.options.conditions.size(), 1u);
  const eval::GaitReport r = main_walk_report(main.set);
  const learn::CostWeights w;
  using W = learn::CostWeights;
  // The cost less the same cost with `field` at 0: the term `field` prices, at `options`.
  auto term = [&main](double W::*field, learn::TuneOptions options) {
    const double with = learn::walk_cost(main.set, options);
    options.weights.*field = 0.0;
    return with - learn::walk_cost(main.set, options);
  };
  auto with_weights = [&main](const learn::CostWeights& weights) {
    learn::TuneOptions o = main.options;
    o.weights = weights;
    return o;
  };
  const double tolerance = 1e-9 * main.recorded;
  EXPECT_NEAR(term(&W::step_error, main.options), 2.0 * r.step_error_percent.value(), tolerance);
  EXPECT_NEAR(term(&W::curve_rmse, main.options),
              2.0 * (r.thigh_score->rmse + r.knee_score->rmse + r.ankle_score->rmse), tolerance);
  EXPECT_NEAR(term(&W::ankle_uncorrelated, main.options), 20.0 * (1.0 - r.ankle_score->pearson),
              tolerance);
  // The main walk's toes clear the ground by over 40 mm: asked for 50 mm, they fall short.
  ASSERT_GT(r.min_toe_clearance, w.toe_clearance_wanted);
  EXPECT_EQ(term(&W::toe_scuff, main.options), 0.0);
  learn::CostWeights wanting = w;
  wanting.toe_clearance_wanted = 0.05;
  EXPECT_NEAR(term(&W::toe_scuff, with_weights(wanting)),
              200.0 * (0.05 - r.min_toe_clearance) / 0.05, tolerance);
  // Its slip (0.33 mm a frame) is under the free 0.5 mm; with none free, all of it costs.
  ASSERT_LT(r.max_slip, w.slip_free);
  EXPECT_EQ(term(&W::slip, main.options), 0.0);
  learn::CostWeights strict = w;
  strict.slip_free = 0.0;
  EXPECT_NEAR(term(&W::slip, with_weights(strict)), 2000.0 * r.max_slip, tolerance);
  // Its velocity jumps are under 1.2 typical changes; with no ratio free, all of it costs.
  const double jump_ratio = r.max_velocity_jump / std::max(r.typical_velocity_change, 1.0);
  ASSERT_LT(jump_ratio, w.velocity_jump_ratio_free);
  EXPECT_EQ(term(&W::velocity_jump, main.options), 0.0);
  strict.velocity_jump_ratio_free = 0.0;
  EXPECT_NEAR(term(&W::velocity_jump, with_weights(strict)), 10.0 * jump_ratio, tolerance);
  // The knee peaks at 72 % of the cycle, inside 69-77 %; a window ending at 50 % charges the
  // 22 % it is late by.
  ASSERT_EQ(r.knee_peak_percent, 72.0);
  EXPECT_EQ(term(&W::knee_peak_timing_outside_range, main.options), 0.0);
  learn::TuneOptions early = main.options;
  early.knee_peak_percent_min = 40.0;
  early.knee_peak_percent_max = 50.0;
  EXPECT_NEAR(term(&W::knee_peak_timing_outside_range, early), 22.0, tolerance);
}

// The words are counted in units of word_unit of each output's range: a coarser unit counts a
// broken word as less, and walk_cost() charges the count in the unit it is given.
TEST(WalkCost, TheWordUnitScalesTheWordPenalty) {
  const gait::ControllerSet set = scaled_default(1.5);
  learn::TuneOptions o;  // no walks: the words alone
  const double words = learn::word_penalty(set);
  EXPECT_EQ(learn::word_penalty(set, o.weights), words);
  o.weights.word_unit = 0.04;
  const double coarse = learn::word_penalty(set, o.weights);
  EXPECT_LT(coarse, words);
  EXPECT_GT(coarse, 0.0);
  o.word_penalty_max = 1e9;
  EXPECT_EQ(learn::walk_cost(set, o), 10.0 * coarse);
  // A finer unit lets a "stay" or "hold" move less for free and counts each broken word as more.
  const gait::ControllerSet& base = test::default_set();
  learn::CostWeights half = o.weights;
  half.word_unit = 0.01;
  EXPECT_GT(learn::word_penalty(base, half), learn::word_penalty(base));
}

TEST(CostWeights, ValidateNamesTheWeightOutOfRange) {
  for (const WeightField& f : kWeightFields) {
    for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity(), -1.0, 0.0}) {
      learn::TuneOptions o;
      o.weights.*f.field = bad;
      if (bad == 0.0 && !must_be_positive(f.name)) {
        EXPECT_NO_THROW(learn::validate(o)) << f.name << " = 0";
        continue;
      }
      try {
        learn::validate(o);
        ADD_FAILURE() << f.name << " = " << bad << " passed";
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("weights." + std::string(f.name) + " "),
                  std::string::npos)
            << e.what();
      }
      EXPECT_THROW(learn::walk_cost(test::default_set(), o), std::invalid_argument) << f.name;
    }
  }
}

// A tune of a few generations on the main walk against `reference` (which must outlive the
// options), small steps: quick enough for a unit test.
learn::TuneOptions short_tune(const eval::Normative& reference, int generations,
                              std::uint64_t seed) {
  learn::TuneOptions o;
  o.conditions = {learn::main_condition(reference)};
  o.generations = generations;
  o.threads = 2;
  o.seed = seed;
  o.sigma = 0.05;
  return o;
}

TEST(Tune, AShortTuneNeverEndsWorseThanItsStart) {
  const eval::Normative free = io::load_normative("schwartz2008_free");
  const learn::TuneOptions o = short_tune(free, 4, 3);
  const double start = learn::walk_cost(test::default_set(), o);
  const learn::TuneResult r = learn::tune(test::default_set(), o);
  EXPECT_LE(r.cost, start);
  EXPECT_EQ(r.cost, learn::walk_cost(r.set, o));
  EXPECT_GT(r.evaluations, 4);
  // Deterministic for a seed.
  const learn::TuneResult again = learn::tune(test::default_set(), o);
  EXPECT_EQ(again.cost, r.cost);
  EXPECT_EQ(outputs(again.rounded), outputs(r.rounded));
}

TEST(Tune, PolishingImprovesTheRoundedValuesItWritesOut) {
  const eval::Normative free = io::load_normative("schwartz2008_free");
  learn::TuneOptions o = short_tune(free, 2, 2);
  o.polish_generations = 3;
  o.digits = 3;
  // A start away from the optimum, its values already three digits.
  const learn::SetParameters p(test::default_set());
  std::vector<double> v = p.values();
  v[0] += 0.5;
  const gait::ControllerSet start = p.rounded(v, o.digits);
  learn::TuneOptions unpolished = o;
  unpolished.polish_generations = 0;
  const learn::TuneResult tuned = learn::tune(start, unpolished);
  std::vector<int> generations;
  o.progress = [&generations](int generation, double) { generations.push_back(generation); };
  const learn::TuneResult r = learn::tune(start, o);
  // The polish's generations are counted on from the tune's.
  EXPECT_EQ(generations, (std::vector<int>{1, 2, 3, 4, 5}));
  // Polishing starts from the tuned values rounded, never ends worse than them, and here
  // improves on them.
  const double rounded_cost = learn::walk_cost(tuned.rounded, o);
  EXPECT_LE(r.cost, rounded_cost);
  EXPECT_NE(outputs(r.set), outputs(tuned.rounded));
  // The cost is that of the set returned, whose values are the rounded ones written out.
  EXPECT_EQ(r.cost, learn::walk_cost(r.set, o));
  EXPECT_EQ(outputs(r.rounded), outputs(r.set));
  const learn::SetParameters polished(r.set);
  EXPECT_EQ(outputs(polished.rounded(polished.values(), o.digits)), outputs(r.set));
  EXPECT_GT(r.evaluations, tuned.evaluations);
}

TEST(TuneOptions, OutOfRangeFieldsAreNamed) {
  const learn::TuneOptions good;
  EXPECT_NO_THROW(learn::validate(good));
  const double nan = std::nan("");
  struct Case {
    void (*change)(learn::TuneOptions&, double);
    double value;
    const char* field;
  };
  const Case cases[] = {
      {[](learn::TuneOptions& o, double v) { o.sigma = v; }, nan, "sigma"},
      {[](learn::TuneOptions& o, double v) { o.sigma = v; }, 0.0, "sigma"},
      {[](learn::TuneOptions& o, double v) { o.duration = v; }, 1e308, "duration"},
      {[](learn::TuneOptions& o, double v) { o.duration = v; }, 0.0, "duration"},
      {[](learn::TuneOptions& o, double v) { o.cycle_time_min = v; }, nan, "cycle time range"},
      {[](learn::TuneOptions& o, double v) { o.cycle_time_max = v; }, 0.5, "cycle time range"},
      {[](learn::TuneOptions& o, double v) { o.stance_min = v; }, 80.0, "stance range"},
      {[](learn::TuneOptions& o, double v) { o.knee_peak_max = v; }, 1e308, "knee peak range"},
      {[](learn::TuneOptions& o, double v) { o.knee_peak_percent_min = v; }, nan,
       "knee peak timing range"},
      {[](learn::TuneOptions& o, double v) { o.knee_peak_percent_max = v; }, 60.0,
       "knee peak timing range"},
      {[](learn::TuneOptions& o, double v) { o.knee_peak_percent_max = v; }, 101.0,
       "knee peak timing range"},
      {[](learn::TuneOptions& o, double v) { o.pelvis_range_max = v; }, -10.0, "pelvis range"},
      {[](learn::TuneOptions& o, double v) { o.minimum_inertia = v; }, -1.0, "minimum inertia"},
      {[](learn::TuneOptions& o, double v) { o.acceleration_ratio_max = v; }, nan,
       "acceleration ratio"},
      {[](learn::TuneOptions& o, double v) { o.heel_bounce_max = v; }, -0.001, "heel bounce"},
      {[](learn::TuneOptions& o, double v) { o.polish_generations = static_cast<int>(v); }, -5.0,
       "polish generations"},
  };
  for (const Case& c : cases) {
    learn::TuneOptions o;
    c.change(o, c.value);
    try {
      learn::validate(o);
      ADD_FAILURE() << c.field << " = " << c.value << " passed";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(c.field), std::string::npos) << e.what();
    }
    // The objective and the tuner refuse them too, before walking.
    EXPECT_THROW(learn::walk_cost(test::default_set(), o), std::invalid_argument) << c.field;
  }
}

TEST(WalkCost, CountsTheWalksThatFailed) {
  // One second is too short for two gait cycles: each condition fails and is counted.
  learn::TuneOptions o;
  o.duration = 1.0;
  o.conditions = {learn::main_condition(io::load_normative("schwartz2008_free"))};
  int failed = -1;
  std::string report;
  EXPECT_EQ(learn::walk_cost(test::default_set(), o, &report, &failed),
            10.0 * learn::word_penalty(test::default_set()) + 1000.0);
  EXPECT_EQ(failed, 1);
  EXPECT_NE(report.find("failed"), std::string::npos);
  // A failed walk costs weights.failed_walk.
  o.weights.failed_walk = 250.0;
  EXPECT_EQ(learn::walk_cost(test::default_set(), o),
            10.0 * learn::word_penalty(test::default_set()) + 250.0);
  o.duration = 10.0;
  learn::walk_cost(test::default_set(), o, nullptr, &failed);
  EXPECT_EQ(failed, 0);
}

}  // namespace
}  // namespace fuzzygait

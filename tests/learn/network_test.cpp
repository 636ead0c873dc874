// The controller set as a network: with doubles it answers the walker's controllers bit for bit
// (on every metric a walk asks them, every shipped set), its dual-number derivatives equal central
// differences, and its weights go back into the set's FLL as the peaks and values they name.
#include "fuzzygait/learn/network.hpp"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "runtime/gait/walker_stages.hpp"
#include "support/bits.hpp"
#include "support/controller_sets.hpp"
#include "support/walks.hpp"

namespace fuzzygait {
namespace {

// Every slot's answer through the network and through the walker's controller, for every metric
// vector the walker asks during a walk (a random start too, which visits odd corners).
TEST(SetNetwork, AnswersTheWalkersControllersBitForBitThroughAWalk) {
  for (const std::string& name : test::shipped_set_names()) {
    SCOPED_TRACE(name);
    const gait::ControllerSet set = gait::ControllerSet::builtin(name);
    const learn::SetNetwork network(set);
    const std::vector<double>& w = network.values();
    std::size_t compared = 0;
    std::size_t differ = 0;
    const gait::detail::ControllerBackend backend{[&](int controller, const gait::MetricValues& m) {
      fuzzy::Workspace none;
      const double walker =
          set.controllers.at(static_cast<std::size_t>(controller)).evaluate(m, none);
      if (controller < gait::kSlotCount) {
        ++compared;
        if (!test::same_bits(network.evaluate(controller, w.data(), m), walker)) ++differ;
      }
      return walker;
    }};
    const terrain::Terrain flat = terrain::Terrain::flat();
    for (const bool random : {false, true}) {
      gait::WalkerOptions o;
      o.start.random = random;
      o.start.seed = 7;
      gait::Walker walker = gait::detail::WalkerStages::make_walker(set, o, flat, &backend);
      walker.advance(4.0);
    }
    EXPECT_GT(compared, 8000u);
    EXPECT_EQ(differ, 0u);
  }
}

// Beyond the walk: a grid over and past every input's range, the knots themselves included.
TEST(SetNetwork, AnswersTheControllersOnAGridOfInputs) {
  const gait::ControllerSet& set = test::default_set();
  const learn::SetNetwork network(set);
  for (int s = 0; s < gait::kSlotCount; ++s) {
    const gait::Controller& c = set.controllers[static_cast<std::size_t>(s)];
    fuzzy::Workspace none;
    std::vector<std::vector<double>> values(c.input_count());
    for (std::size_t i = 0; i < c.input_count(); ++i) {
      const fuzzy::InputVariable& v = c.engine().inputs[i];
      for (int k = -10; k <= 50; ++k)
        values[i].push_back(v.minimum + (v.maximum - v.minimum) * k / 40.0);
      for (const fuzzy::Term& t : v.terms)
        values[i].push_back(t.parameters[1]);
    }
    if (values.size() == 1) values.push_back({0.0});
    for (double a : values[0]) {
      for (double b : values[1]) {
        gait::MetricValues m{};
        m[static_cast<std::size_t>(c.input(0))] = a;
        if (c.input_count() == 2) m[static_cast<std::size_t>(c.input(1))] = b;
        ASSERT_TRUE(
            test::same_bits(network.evaluate(s, network.values().data(), m), c.evaluate(m, none)))
            << gait::slot_name(s) << " at " << a << ", " << b;
      }
    }
  }
}

// d(output)/d(weight) by dual numbers against central differences, every slot of the default
// set, at inputs between the knots (where the output is smooth in the weights).
TEST(SetNetwork, DualNumberDerivativesEqualCentralDifferences) {
  using Jet = ceres::Jet<double, 16>;
  const gait::ControllerSet& set = test::default_set();
  const learn::SetNetwork network(set);
  const std::vector<double>& base = network.values();
  std::size_t checked = 0;
  for (int s = 0; s < gait::kSlotCount; ++s) {
    const std::vector<std::size_t>& mine = network.slot_weights(s);
    ASSERT_LE(mine.size(), 16u) << gait::slot_name(s);
    const gait::Controller& c = set.controllers[static_cast<std::size_t>(s)];
    for (int sample = 0; sample < 12; ++sample) {
      // Inputs at odd fractions of each range: never on a knot.
      std::array<double, 2> x{};
      for (std::size_t i = 0; i < c.input_count(); ++i) {
        const fuzzy::InputVariable& v = c.engine().inputs[i];
        x[i] =
            v.minimum + (v.maximum - v.minimum) *
                            std::fmod(0.137 + 0.291 * sample + 0.173 * static_cast<double>(i), 1.0);
      }
      std::vector<Jet> w(base.size());
      for (std::size_t i = 0; i < base.size(); ++i)
        w[i] = Jet(base[i]);
      for (std::size_t k = 0; k < mine.size(); ++k)
        w[mine[k]].v[static_cast<int>(k)] = 1.0;
      const Jet out = network.evaluate(s, w.data(), Jet(x[0]), Jet(x[1]));
      for (std::size_t k = 0; k < mine.size(); ++k) {
        const double step = 1e-6 * network.range(mine[k]);
        std::vector<double> up = base;
        std::vector<double> down = base;
        up[mine[k]] += step;
        down[mine[k]] -= step;
        const double numeric = (network.evaluate(s, up.data(), x[0], x[1]) -
                                network.evaluate(s, down.data(), x[0], x[1])) /
                               (2.0 * step);
        const double scale = std::max(1.0, std::abs(numeric));
        EXPECT_NEAR(out.v[static_cast<int>(k)], numeric, 1e-6 * scale)
            << network.weight(mine[k]).name << " at " << x[0] << ", " << x[1];
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 500u);
}

TEST(SetNetwork, NamesItsWeightsAfterTheWordsTheyMove) {
  const learn::SetNetwork network(test::default_set());
  const std::size_t flex = network.find("swing_knee.velocity.flex_fast");
  ASSERT_LT(flex, network.size());
  EXPECT_EQ(network.weight(flex).kind, learn::WeightKind::Output);
  EXPECT_EQ(network.values()[flex], 880.0);
  const std::size_t center = network.find("swing_hip.delta.center");
  ASSERT_LT(center, network.size());
  EXPECT_EQ(network.weight(center).kind, learn::WeightKind::Knot);
  EXPECT_EQ(network.values()[center], 0.828);
  EXPECT_EQ(network.knot_below(center, network.values()), -1.0);
  EXPECT_EQ(network.knot_above(center, network.values()), 0.884);
  EXPECT_EQ(network.weight(network.inertia_index()).name, "inertia");
  EXPECT_EQ(network.values()[network.inertia_index()], 0.02);
  // The ends of a range are not weights: "start" at -1 and "past" at 1.5 stay.
  EXPECT_EQ(network.find("swing_hip.delta.start"), network.size());
  EXPECT_EQ(network.find("swing_hip.delta.past"), network.size());
}

TEST(SetNetwork, WritesItsWeightsBackAsTheWordsPeaksAndValues) {
  const gait::ControllerSet& base = test::default_set();
  const learn::SetNetwork network(base);
  std::vector<double> w = network.values();
  w[network.find("swing_hip.delta.center")] = 0.5;
  w[network.find("swing_knee.velocity.flex_fast")] = 700.0;
  w[network.inertia_index()] = 0.03;
  const gait::ControllerSet set = network.apply(w);
  EXPECT_EQ(set.inertia, 0.03);
  const fuzzy::Engine& hip = set.at(gait::LegPhase::Swing, gait::Joint::Hip).engine();
  const fuzzy::InputVariable& delta = hip.inputs[0];
  EXPECT_EQ(delta.terms[1].parameters, (std::vector<double>{-1.0, 0.5, 0.884}));
  EXPECT_EQ(delta.terms[0].parameters[2], 0.5);
  EXPECT_EQ(delta.terms[2].parameters[0], 0.5);
  EXPECT_EQ(set.at(gait::LegPhase::Swing, gait::Joint::Knee)
                .engine()
                .outputs[0]
                .find_term("flex_fast")
                ->parameters[0],
            700.0);
  // Read back, the written set is the network's weights.
  EXPECT_EQ(learn::SetNetwork(set).values(), w);
  // Everything else is the base's, the terrain files included.
  EXPECT_EQ(fuzzy::write_fll(set.at(gait::LegPhase::Stance, gait::Joint::Ankle).engine()),
            fuzzy::write_fll(base.at(gait::LegPhase::Stance, gait::Joint::Ankle).engine()));
  EXPECT_EQ(set.terrain_controllers.size(), base.terrain_controllers.size());
  EXPECT_EQ(network.apply(network.values()).controllers.size(), base.controllers.size());
}

TEST(SetNetwork, RefusesWeightsThatMakeNoSet) {
  const learn::SetNetwork network(test::default_set());
  std::vector<double> w = network.values();
  EXPECT_THROW(network.apply(std::vector<double>(w.begin(), w.end() - 1)), std::invalid_argument);
  std::vector<double> crossed = w;
  crossed[network.find("swing_hip.delta.center")] = 0.9;  // past "end" at 0.884
  try {
    network.apply(crossed);
    ADD_FAILURE() << "knots out of order were taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("swing_hip.delta.center"), std::string::npos) << e.what();
  }
  std::vector<double> nan = w;
  nan[0] = std::nan("");
  EXPECT_THROW(network.apply(nan), std::invalid_argument);
  std::vector<double> sluggish = w;
  sluggish[network.inertia_index()] = 5.0;
  EXPECT_THROW(network.apply(sluggish), std::invalid_argument);
}

TEST(SetNetwork, RefusesAControllerThatIsNotAPartition) {
  gait::ControllerSet set = test::default_set();
  fuzzy::Engine engine = set.controllers[1].engine();
  engine.rule_blocks[0].conjunction = fuzzy::TNorm::BoundedDifference;
  set.controllers[1] = gait::Controller(engine, "somewhere/swing_knee.fll");
  try {
    learn::SetNetwork network(set);
    ADD_FAILURE() << "a controller off the partition shape was taken";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("somewhere/swing_knee.fll"), std::string::npos) << what;
    EXPECT_NE(what.find("swing_knee"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace fuzzygait

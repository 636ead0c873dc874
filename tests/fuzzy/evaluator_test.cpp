// The compiled evaluator: fuzzylite's semantics in the corners, thread safety, and no
// allocation while evaluating.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <thread>

#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "support/allocation_counter.hpp"

using namespace fuzzygait::fuzzy;

namespace {

Engine engine_with(const std::string& output_extra, const std::string& block) {
  return read_fll(R"(Engine: e
InputVariable: in
  range: 0 1
  lock-range: true
  term: low Triangle 0 0 0.5
  term: mid Triangle 0 0.5 1
  term: high Triangle 0.5 1 1
OutputVariable: out
  range: 0 10
  aggregation: Maximum
  defuzzifier: WeightedAverage Automatic
  default: -1
  term: small Constant 1
  term: medium Constant 5
  term: large Constant 9
)" + output_extra +
                  "RuleBlock: b\n" + block);
}

double run(const Evaluator& e, Workspace& w, double x) {
  double out = 0.0;
  e.evaluate(std::span<const double>(&x, 1), std::span<double>(&out, 1), w);
  return out;
}

TEST(Evaluator, TakagiSugenoWeightedAverage) {
  const Evaluator e(engine_with("",
                                "  rule: if in is low then out is small\n"
                                "  rule: if in is mid then out is medium\n"
                                "  rule: if in is high then out is large\n"));
  Workspace w = e.make_workspace();
  EXPECT_DOUBLE_EQ(run(e, w, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(run(e, w, 0.25), 3.0);  // 0.5*1 + 0.5*5
  EXPECT_DOUBLE_EQ(run(e, w, 0.75), 7.0);
  EXPECT_DOUBLE_EQ(run(e, w, 7.0), 9.0);  // lock-range clamps the input to 1
}

TEST(Evaluator, DefaultAndLockPrevious) {
  const std::string rules = "  rule: if in is low then out is small\n";
  const Evaluator plain(engine_with("", rules));
  Workspace w = plain.make_workspace();
  EXPECT_DOUBLE_EQ(run(plain, w, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(run(plain, w, 0.9), -1.0);  // nothing fires: default

  const Evaluator locked(engine_with("  lock-previous: true\n", rules));
  Workspace lw = locked.make_workspace();
  EXPECT_DOUBLE_EQ(run(locked, lw, 0.9), -1.0);  // no previous value yet
  EXPECT_DOUBLE_EQ(run(locked, lw, 0.25), 1.0);
  EXPECT_DOUBLE_EQ(run(locked, lw, 0.9), 1.0);  // keeps the last valid value
  lw.reset();
  EXPECT_DOUBLE_EQ(run(locked, lw, 0.9), -1.0);
}

TEST(Evaluator, ActivationMethods) {
  const std::string rules =
      "  rule: if in is low then out is small\n"
      "  rule: if in is mid then out is medium\n"
      "  rule: if in is high then out is large\n";
  auto with = [&](const std::string& activation) {
    return Evaluator(engine_with("", "  activation: " + activation + "\n" + rules));
  };
  const Evaluator highest = with("Highest 1");
  Workspace w = highest.make_workspace();
  EXPECT_DOUBLE_EQ(run(highest, w, 0.4), 5.0);  // mid (0.8) beats low (0.2)
  const Evaluator lowest = with("Lowest 1");
  Workspace lw = lowest.make_workspace();
  EXPECT_DOUBLE_EQ(run(lowest, lw, 0.4), 1.0);
  const Evaluator first = with("First 1 0");
  Workspace fw = first.make_workspace();
  EXPECT_DOUBLE_EQ(run(first, fw, 0.4), 1.0);
  const Evaluator last = with("Last 1 0");
  Workspace tw = last.make_workspace();
  EXPECT_DOUBLE_EQ(run(last, tw, 0.4), 5.0);
  const Evaluator threshold = with("Threshold >= 0.5");
  Workspace thw = threshold.make_workspace();
  EXPECT_DOUBLE_EQ(run(threshold, thw, 0.4), 5.0);
  const Evaluator proportional = with("Proportional");
  Workspace pw = proportional.make_workspace();
  EXPECT_DOUBLE_EQ(run(proportional, pw, 0.4), 0.2 * 1 + 0.8 * 5);
}

TEST(Evaluator, HedgesAndWeights) {
  const Evaluator e(engine_with("",
                                "  rule: if in is very low then out is small with 0.5\n"
                                "  rule: if in is not low then out is large\n"));
  Workspace w = e.make_workspace();
  // low(0.25) = 0.5: very -> 0.25, weight -> 0.125; not low -> 0.5.
  EXPECT_DOUBLE_EQ(run(e, w, 0.25), (0.125 * 1 + 0.5 * 9) / (0.125 + 0.5));
}

TEST(Evaluator, RejectsEnginesItCannotEvaluate) {
  const Engine e = engine_with("", "  rule: if in is low and in is mid then out is small\n");
  try {
    Evaluator evaluator(e);
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("no conjunction"), std::string::npos);
  }
}

TEST(Evaluator, ConstAndThreadSafeWithOwnWorkspaces) {
  const Engine engine = read_fll(R"(Engine: mamdani
InputVariable: a
  range: 0 1
  term: low Triangle 0 0 1
  term: high Triangle 0 1 1
InputVariable: b
  range: 0 1
  term: low Gaussian 0 0.3
  term: high Gaussian 1 0.3
OutputVariable: y
  range: 0 1
  aggregation: Maximum
  defuzzifier: Centroid 200
  term: low Trapezoid 0 0 0.2 0.6
  term: high Bell 0.8 0.2 2
RuleBlock: r
  conjunction: Minimum
  disjunction: Maximum
  implication: Minimum
  rule: if a is low and b is high then y is low
  rule: if a is high or b is low then y is high
)");
  const Evaluator evaluator(engine);
  std::vector<double> inputs;
  for (int i = 0; i < 200; ++i) {
    inputs.push_back(i / 199.0);
    inputs.push_back(std::fmod(i * 0.37, 1.0));
  }
  std::vector<double> expected(200);
  Workspace w = evaluator.make_workspace();
  evaluator.evaluate_batch(inputs, expected, w);
  std::vector<std::vector<double>> results(4, std::vector<double>(200));
  std::vector<std::thread> threads;
  for (auto& r : results) {
    threads.emplace_back([&evaluator, &inputs, &r]() {
      Workspace own = evaluator.make_workspace();
      for (int k = 0; k < 20; ++k)
        evaluator.evaluate_batch(inputs, r, own);
    });
  }
  for (auto& t : threads)
    t.join();
  for (const auto& r : results) {
    for (std::size_t i = 0; i < r.size(); ++i)
      EXPECT_EQ(r[i], expected[i]);  // bit-identical
  }
}

TEST(Evaluator, DoesNotAllocateWhileEvaluating) {
  const Engine engine = read_fll(R"(Engine: f
InputVariable: a
  range: 0 1
  term: low Discrete 0 1 1 0
  term: high Function x * a
OutputVariable: y
  range: 0 1
  aggregation: Maximum
  defuzzifier: Centroid 100
  term: low Triangle 0 0 1
  term: high Triangle 0 1 1
OutputVariable: z
  range: 0 1
  defuzzifier: WeightedAverage Automatic
  term: one Linear 0.5 0.25
RuleBlock: r
  activation: Highest 2
  implication: AlgebraicProduct
  rule: if a is low then y is low and z is one
  rule: if a is somewhat high then y is high
)");
  const Evaluator evaluator(engine);
  Workspace w = evaluator.make_workspace();
  std::vector<double> out(2);
  const long before = fuzzygait::testing::allocation_count();
  for (int i = 0; i <= 100; ++i) {
    const double a = i / 100.0;
    evaluator.evaluate(std::span<const double>(&a, 1), out, w);
  }
  EXPECT_EQ(fuzzygait::testing::allocation_count(), before);
}

}  // namespace

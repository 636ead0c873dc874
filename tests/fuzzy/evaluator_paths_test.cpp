// The evaluator's fast paths and their fallbacks against libfuzzylite, bit for bit: engines made
// to reach each of them (sparse and deferred aggregation, sums of weighted defuzzifiers kept as
// rules fire, reduced tolerant comparisons) and the cases that must leave them (NaN and negative
// memberships and degrees, infinite ranges, terms that read variables).
#include <fl/Headers.h>
#include <gtest/gtest.h>

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "support/fuzzylite_compare.hpp"

namespace {

using namespace fuzzygait::fuzzy;

// Evaluates both engines on the same rows, in order, and expects the same bits everywhere.
void expect_fuzzylite_bits(const std::string& fll) {
  const std::unique_ptr<fl::Engine> reference(fl::FllImporter().fromString(fll));
  const Engine engine = read_fll(fll);
  const Evaluator evaluator(engine);
  Workspace workspace = evaluator.make_workspace();
  std::vector<double> values = {kNaN, -kInfinity, kInfinity, -0.25, 1.25, 0.0, 1.0};
  for (int i = 0; i <= 60; ++i)
    values.push_back(i / 60.0);
  fuzzygait::test::FuzzyliteComparison c;
  c.label = engine.name;
  for (const InputVariable& v : engine.inputs) {
    c.inputs.push_back(v.name);
    c.values.push_back(values);
  }
  for (const OutputVariable& v : engine.outputs)
    c.outputs.push_back(v.name);
  c.max_reported = 5;
  fuzzygait::test::expect_fuzzylite_outputs(
      *reference, c, [&](std::span<const double> inputs, std::span<double> outputs) {
        evaluator.evaluate(inputs, outputs, workspace);
      });
}

constexpr const char* kInput = R"(InputVariable: a
  range: 0 1
  term: low Triangle 0 0 0.6
  term: mid Trapezoid 0.2 0.4 0.6 0.8
  term: high Ramp 0.4 1
)";

// Every integral defuzzifier over terms with narrow supports: Minimum and AlgebraicProduct
// implications with Maximum aggregation visit only the terms' own samples.
TEST(EvaluatorPaths, SparseAggregation) {
  std::string fll = std::string("Engine: sparse\n") + kInput;
  const char* kinds[] = {"Centroid 101", "Bisector 99", "MeanOfMaximum 301", "SmallestOfMaximum 57",
                         "LargestOfMaximum 57"};
  for (int k = 0; k < 5; ++k) {
    fll += "OutputVariable: y" + std::to_string(k) + R"(
  range: -1 3
  aggregation: Maximum
  defuzzifier: )" +
           kinds[k] + R"(
  term: small Triangle -1 -0.5 0
  term: plateau Trapezoid 0 0.5 1.5 2
  term: spike Spike 2.5 0.2
  term: gap Rectangle 1.0 1.2 0.7
)";
  }
  for (const char* implication : {"Minimum", "AlgebraicProduct"}) {
    std::string rules =
        fll + "RuleBlock: rules\n  conjunction: Minimum\n  implication: " + implication + "\n";
    for (int k = 0; k < 5; ++k) {
      const std::string y = "y" + std::to_string(k);
      rules += "  rule: if a is low then " + y + " is small\n";
      rules += "  rule: if a is mid then " + y + " is plateau with 0.8\n";
      rules += "  rule: if a is high then " + y + " is spike\n";
      rules += "  rule: if a is very mid then " + y + " is gap\n";
    }
    expect_fuzzylite_bits(rules);
  }
}

// Memberships and degrees that are negative, above one or NaN, and aggregations other than
// Maximum: the evaluator must leave its sparse paths and still match.
TEST(EvaluatorPaths, NegativeAndNanMembershipsAndDegrees) {
  std::string fll = std::string("Engine: irregular\n") + kInput;
  const char* aggregations[] = {"Maximum",     "UnboundedSum",  "BoundedSum",
                                "EinsteinSum", "NormalizedSum", "AlgebraicSum"};
  const char* kinds[] = {"Centroid 100",          "Bisector 100",         "MeanOfMaximum 100",
                         "SmallestOfMaximum 100", "LargestOfMaximum 100", "Centroid 33"};
  for (int k = 0; k < 6; ++k) {
    fll += "OutputVariable: y" + std::to_string(k) +
           "\n  range: 0 1\n  aggregation: " + aggregations[k] + "\n  defuzzifier: " + kinds[k] +
           R"(
  term: negative Triangle 0 0.3 0.6 -0.5
  term: logarithm Function log(x - 0.4)
  term: reads Function a * x
  term: tall Trapezoid 0.5 0.6 0.7 0.8 2
)";
  }
  for (const char* implication : {"Minimum", "AlgebraicProduct", "EinsteinProduct"}) {
    std::string rules = fll + "RuleBlock: rules\n  implication: " + implication + "\n";
    for (int k = 0; k < 6; ++k) {
      const std::string y = "y" + std::to_string(k);
      rules += "  rule: if a is low then " + y + " is tall with 2\n";
      rules += "  rule: if a is somewhat not high then " + y + " is negative with 3\n";
      rules += "  rule: if a is mid then " + y + " is logarithm\n";
      rules += "  rule: if a is high then " + y + " is reads\n";
    }
    expect_fuzzylite_bits(rules);
  }
}

// Weighted defuzzifiers summing as rules fire, next to ones that keep the activated terms (a
// term reading an output, a chained rule reading an output), with hedged conclusions, both
// readings of the terms, lock-previous and lock-range.
TEST(EvaluatorPaths, WeightedSumsAsRulesFire) {
  const std::string fll = std::string("Engine: weighted\n") + kInput + R"(InputVariable: b
  range: 0 1
  lock-range: true
  term: low Ramp 1 0
  term: high Ramp 0 1
OutputVariable: constant
  range: 0 10
  lock-previous: true
  defuzzifier: WeightedAverage TakagiSugeno
  term: c1 Constant 1
  term: c2 Constant 5
  term: linear Linear 2 -3 1
  term: function Function sin(a) + x
OutputVariable: tsukamoto
  range: 0 1
  lock-range: true
  defuzzifier: WeightedSum Automatic
  term: ramp Ramp 0.2 0.9
  term: sigmoid Sigmoid 0.5 12
  term: s SShape 0.1 0.8
  term: concave Concave 0.6 0.9
OutputVariable: reader
  range: 0 10
  defuzzifier: WeightedAverage TakagiSugeno
  term: previous Function constant + x
OutputVariable: chained
  range: 0 10
  defuzzifier: WeightedAverage Automatic
  term: c Constant 3
  term: d Constant 7
RuleBlock: rules
  conjunction: AlgebraicProduct
  disjunction: Maximum
  rule: if a is low and b is high then constant is c1 and tsukamoto is very ramp
  rule: if a is mid or b is low then constant is linear and tsukamoto is sigmoid and reader is previous
  rule: if a is high then constant is extremely function and tsukamoto is s and chained is c
  rule: if a is very high and b is somewhat high then constant is c2 and tsukamoto is concave with 0.5
  rule: if chained is c then chained is d
)";
  expect_fuzzylite_bits(fll);
}

}  // namespace

// Micro-benchmarks of the fuzzy Evaluator on small engines typical of gait controllers, so that
// a performance regression shows without fuzzylite. Each iteration is one evaluation; the
// inputs sweep the input ranges so that every rule fires somewhere.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/fll.hpp"

namespace {

using namespace fuzzygait::fuzzy;

// One input, three rules, constant consequents: the cheapest useful controller.
constexpr const char* kTakagiSugeno3 = R"(Engine: takagi_sugeno_3
InputVariable: stride
  range: 0 1
  lock-range: true
  term: short Triangle 0 0 0.5
  term: medium Triangle 0 0.5 1
  term: long Triangle 0.5 1 1
OutputVariable: lean
  range: 0 1
  lock-range: false
  aggregation: none
  defuzzifier: WeightedAverage TakagiSugeno
  default: nan
  term: little Constant 0.2
  term: some Constant 0.5
  term: much Constant 0.8
RuleBlock: rules
  conjunction: none
  disjunction: none
  implication: none
  activation: General
  rule: if stride is short then lean is little
  rule: if stride is medium then lean is some
  rule: if stride is long then lean is much
)";

// One input, three rules, Min/Max inference and a centroid over 200 samples.
constexpr const char* kMamdani3Centroid200 = R"(Engine: mamdani_3_centroid_200
InputVariable: speed
  range: 0 1
  lock-range: false
  term: slow Triangle 0 0.25 0.5
  term: medium Triangle 0.25 0.5 0.75
  term: fast Triangle 0.5 0.75 1
OutputVariable: stride
  range: 0 1
  lock-range: false
  aggregation: Maximum
  defuzzifier: Centroid 200
  default: nan
  term: short Triangle 0 0.25 0.5
  term: medium Triangle 0.25 0.5 0.75
  term: long Triangle 0.5 0.75 1
RuleBlock: rules
  conjunction: none
  disjunction: none
  implication: Minimum
  activation: General
  rule: if speed is slow then stride is long
  rule: if speed is medium then stride is medium
  rule: if speed is fast then stride is short
)";

// Two inputs combined with and/or, mixed shapes, centroid over 100 samples.
constexpr const char* kMamdani2Inputs = R"(Engine: mamdani_2_inputs
InputVariable: slope
  range: 0 1
  lock-range: false
  term: flat Triangle 0 0 1
  term: steep Triangle 0 1 1
InputVariable: load
  range: 0 1
  lock-range: false
  term: light Gaussian 0 0.3
  term: heavy Gaussian 1 0.3
OutputVariable: effort
  range: 0 1
  lock-range: false
  aggregation: Maximum
  defuzzifier: Centroid 100
  default: nan
  term: low Trapezoid 0 0 0.2 0.6
  term: medium Triangle 0.3 0.5 0.7
  term: high Bell 0.8 0.2 2
RuleBlock: rules
  conjunction: Minimum
  disjunction: Maximum
  implication: Minimum
  activation: General
  rule: if slope is flat and load is light then effort is low
  rule: if slope is flat and load is heavy then effort is medium
  rule: if slope is steep or load is heavy then effort is high
)";

void evaluate_sweep(benchmark::State& state, const char* fll) {
  const Evaluator evaluator(read_fll(fll));
  Workspace workspace = evaluator.make_workspace();
  const std::size_t n_in = evaluator.input_count();
  constexpr std::size_t kRows = 1024;
  std::vector<double> rows(kRows * n_in);
  for (std::size_t r = 0; r < kRows; ++r) {
    for (std::size_t i = 0; i < n_in; ++i) {
      // Different irrational strides per input cover the input space evenly.
      const double t = std::fmod(
          static_cast<double>(r) * (0.6180339887 + 0.4142135624 * static_cast<double>(i)), 1.0);
      rows[r * n_in + i] = evaluator.input_minimum(i) +
                           t * (evaluator.input_maximum(i) - evaluator.input_minimum(i));
    }
  }
  std::vector<double> outputs(evaluator.output_count());
  std::size_t row = 0;
  for (auto _ : state) {
    evaluator.evaluate(std::span<const double>(rows.data() + row * n_in, n_in), outputs, workspace);
    benchmark::DoNotOptimize(outputs.data());
    benchmark::ClobberMemory();
    row = (row + 1) % kRows;
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_TakagiSugeno3Rules(benchmark::State& state) {
  evaluate_sweep(state, kTakagiSugeno3);
}
void BM_Mamdani3RulesCentroid200(benchmark::State& state) {
  evaluate_sweep(state, kMamdani3Centroid200);
}
void BM_Mamdani2Inputs(benchmark::State& state) {
  evaluate_sweep(state, kMamdani2Inputs);
}

BENCHMARK(BM_TakagiSugeno3Rules);
BENCHMARK(BM_Mamdani3RulesCentroid200);
BENCHMARK(BM_Mamdani2Inputs);

}  // namespace

BENCHMARK_MAIN();

// libFuzzer target for the FLL reader, fuzzygait::fuzzy::read_fll.
//
// Contract: any bytes either parse or are refused with a ParseError naming the source; a
// crash, a hang, a sanitizer report or any other exception is a bug. An engine that parses
// writes and reads back to an equal engine and writes the same text again (a lossless round
// trip), and when it has no problems it compiles and evaluates deterministically: the same
// inputs on a fresh, a reset and a batch workspace, and on the engine read back, give
// bit-identical outputs.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_check.hpp"
#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/fll.hpp"

namespace {

using namespace fuzzygait::fuzzy;
using fuzzygait::fuzz::check_names_source;
using fuzzygait::fuzz::fail;

constexpr std::string_view kSource = "fuzz.fll";

// Membership samples an evaluation may take before the target skips evaluating, so that
// legitimately expensive engines (a resolution near the reader's limit times many rules) keep
// the fuzzer fast instead of being reported as hangs.
constexpr double kEvaluationBudget = 2e6;

double evaluation_cost(const Engine& engine) {
  double cost = 0.0;
  for (const RuleBlock& block : engine.rule_blocks) {
    for (const Rule& rule : block.rules) {
      cost += static_cast<double>(rule.propositions.size());
      for (const Proposition& conclusion : rule.conclusions) {
        const OutputVariable* output = engine.find_output(conclusion.variable);
        const Term* term = output ? output->find_term(conclusion.term) : nullptr;
        const double per_sample = 1.0 + (term ? static_cast<double>(term->formula.size()) : 0.0);
        const bool integral = output && output->defuzzifier && output->defuzzifier->is_integral();
        cost += per_sample * (integral ? output->defuzzifier->resolution : 1.0);
      }
    }
  }
  return cost;
}

// Values each input takes in turn: the range's ends and middle, NaN, out of range, infinities.
std::vector<double> probe_values(const InputVariable& input) {
  const double span =
      std::isfinite(input.maximum - input.minimum) ? input.maximum - input.minimum + 1.0 : 1.0;
  return {input.minimum,
          input.maximum,
          0.5 * (input.minimum + input.maximum),
          kNaN,
          input.minimum - span,
          input.maximum + span,
          -kInfinity,
          kInfinity,
          0.0};
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

std::string join(const std::vector<double>& values) {
  std::string out;
  for (double v : values)
    out += format_scalar(v) + " ";
  return out;
}

Engine check_round_trip(const Engine& engine) {
  std::string written;
  try {
    written = write_fll(engine);
  } catch (const std::exception& e) {
    fail("write_fll refused an engine that read_fll accepted", e.what());
  }
  Engine again;
  try {
    again = read_fll(written, "round-trip.fll");
  } catch (const std::exception& e) {
    fail("read_fll refused what write_fll wrote", std::string(e.what()) + "\n" + written);
  }
  if (!(again == engine)) fail("the engine read back differs", written);
  const std::string rewritten = write_fll(again);
  if (rewritten != written) fail("the text written twice differs", written + "\n--\n" + rewritten);
  return again;
}

// Evaluates rows of probe inputs; returns the outputs.
std::vector<double> check_evaluation(const Engine& engine) {
  const Evaluator evaluator(engine);  // throwing here (problems() was empty) is a bug
  const std::size_t input_count = evaluator.input_count();
  const std::size_t output_count = evaluator.output_count();
  constexpr std::size_t kRows = 9;
  std::vector<double> inputs(kRows * input_count);
  for (std::size_t i = 0; i < input_count; ++i) {
    const std::vector<double> values = probe_values(engine.inputs[i]);
    for (std::size_t row = 0; row < kRows; ++row) {
      inputs[row * input_count + i] = values[(row + i) % values.size()];
    }
  }
  auto run_rows = [&](Workspace& workspace) {
    std::vector<double> outputs(kRows * output_count);
    for (std::size_t row = 0; row < kRows; ++row) {
      evaluator.evaluate(std::span<const double>(inputs).subspan(row * input_count, input_count),
                         std::span<double>(outputs).subspan(row * output_count, output_count),
                         workspace);
    }
    return outputs;
  };
  Workspace workspace = evaluator.make_workspace();
  const std::vector<double> fresh = run_rows(workspace);
  workspace.reset();
  const std::vector<double> reset = run_rows(workspace);
  if (!same_bits(fresh, reset)) {
    fail("a reset workspace evaluates differently from a fresh one",
         join(fresh) + "\n" + join(reset));
  }
  workspace.reset();
  std::vector<double> batch(kRows * output_count);
  evaluator.evaluate_batch(inputs, batch, workspace);
  if (!same_bits(fresh, batch)) {
    fail("evaluate_batch differs from evaluate row by row", join(fresh) + "\n" + join(batch));
  }
  // Membership probes reach every term, including those no rule uses.
  for (std::size_t i = 0; i < input_count; ++i) {
    for (std::size_t t = 0; t < evaluator.input_term_count(i); ++t) {
      for (double x : {evaluator.input_minimum(i), evaluator.input_maximum(i), kNaN}) {
        evaluator.input_membership(i, t, x, workspace);
      }
    }
  }
  for (std::size_t o = 0; o < output_count; ++o) {
    for (std::size_t t = 0; t < evaluator.output_term_count(o); ++t) {
      for (double x : {evaluator.output_minimum(o), evaluator.output_maximum(o), kNaN}) {
        evaluator.output_membership(o, t, x, workspace);
      }
    }
  }
  return fresh;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  Engine engine;
  try {
    engine = read_fll(text, kSource);
  } catch (const ParseError& e) {
    check_names_source(e, kSource);
    const auto lines = std::count(text.begin(), text.end(), '\n') + 1;
    if (e.line() < 1 || e.line() > lines) fail("a ParseError names no line of the text", e.what());
    return 0;
  } catch (const std::exception& e) {
    fail("read_fll threw something other than a ParseError", e.what());
  }
  const Engine again = check_round_trip(engine);
  std::vector<std::string> problems;
  try {
    problems = engine.problems();
  } catch (const std::exception& e) {
    fail("Engine::problems threw", e.what());
  }
  if (!problems.empty() || evaluation_cost(engine) > kEvaluationBudget) return 0;
  try {
    const std::vector<double> outputs = check_evaluation(engine);
    const std::vector<double> outputs_again = check_evaluation(again);
    if (!same_bits(outputs, outputs_again)) {
      fail("the engine read back evaluates differently",
           join(outputs) + "\n" + join(outputs_again));
    }
  } catch (const std::exception& e) {
    fail("compiling or evaluating an engine without problems threw", e.what());
  }
  return 0;
}

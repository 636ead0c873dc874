// Differential test against libfuzzylite itself: random engines covering the whole FLL language
// are loaded from the same text into fuzzylite (fl::FllImporter) and fuzzygait (read_fll), then
// evaluated row after row on one engine object each (both keep state between rows), and must
// agree within 1e-6 (NaN equals NaN, infinities match in sign). fuzzylite must also read
// fuzzygait's write_fll of each engine as it reads the original text. The run reports how many
// values were compared, the worst difference and how many values were not bit-identical.
//
// FUZZYGAIT_DIFFERENTIAL_ENGINES sets how many engines run (2000 by default, 500 in sanitizer
// builds); FUZZYGAIT_DIFFERENTIAL_ONLY=<index> runs a single one, to reproduce a failure.
#include <fl/Headers.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "random_engine.hpp"
#include "support/bits.hpp"

namespace {

using fuzzygait::fuzzy::Engine;
using fuzzygait::fuzzy::Evaluator;
using fuzzygait::fuzzy::Workspace;
using fuzzygait::fuzzy::testing::RandomEngine;

#ifndef FUZZYGAIT_DIFFERENTIAL_DEFAULT_ENGINES
#define FUZZYGAIT_DIFFERENTIAL_DEFAULT_ENGINES 2000
#endif
constexpr std::size_t kDefaultEngines = FUZZYGAIT_DIFFERENTIAL_DEFAULT_ENGINES;
// Enough engines to use every feature of the language at least once.
constexpr std::size_t kCoverageEngines = 400;
constexpr std::size_t kRows = 40;
constexpr std::uint64_t kFirstSeed = 0x5eedf0221e000000ULL;
constexpr double kAgreement = 1e-6;
constexpr std::size_t kMaxFailingEngines = 5;
constexpr std::size_t kMaxReportedRows = 5;

std::optional<std::size_t> environment(const char* name) {
  const char* text = std::getenv(name);
  if (text == nullptr || *text == '\0') return std::nullopt;
  return static_cast<std::size_t>(std::strtoull(text, nullptr, 10));
}

bool agree(double expected, double actual) {
  if (std::isnan(expected) || std::isnan(actual)) {
    return std::isnan(expected) && std::isnan(actual);
  }
  if (std::isinf(expected) || std::isinf(actual)) return expected == actual;
  return std::abs(expected - actual) <= kAgreement;
}

// Same bits, but any NaN equals any NaN (payloads and signs of NaN carry no meaning here).
using fuzzygait::test::same_bits;

std::string text(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

struct Tally {
  std::size_t engines = 0;
  std::size_t rows = 0;
  std::size_t values = 0;
  std::size_t numbers = 0;  // values fuzzylite gives that are not NaN
  std::size_t not_identical = 0;
  std::size_t failing_engines = 0;
  double worst = 0.0;
  std::map<std::string, std::size_t> features;
  std::map<std::string, std::size_t> types;
};

// fuzzylite's engine read from FLL text; nullptr, after reporting why, when fuzzylite cannot
// import it or drops one of its rules (its importer keeps rules it cannot load, unloaded).
std::unique_ptr<fl::Engine> import_into_fuzzylite(const std::string& fll, const std::string& what) {
  std::unique_ptr<fl::Engine> engine;
  try {
    engine.reset(fl::FllImporter().fromString(fll));
  } catch (const std::exception& error) {
    ADD_FAILURE() << what << ": fuzzylite cannot import it: " << error.what();
    return nullptr;
  }
  for (std::size_t b = 0; b < engine->numberOfRuleBlocks(); ++b) {
    const fl::RuleBlock* block = engine->getRuleBlock(b);
    for (std::size_t r = 0; r < block->numberOfRules(); ++r) {
      if (!block->getRule(r)->isLoaded()) {
        ADD_FAILURE() << what << ": fuzzylite cannot load rule '" << block->getRule(r)->getText()
                      << "'";
        return nullptr;
      }
    }
  }
  return engine;
}

// One row through a fuzzylite engine; false, after reporting why, when fuzzylite throws.
bool process(fl::Engine& engine, std::span<const double> row, const std::string& what) {
  for (std::size_t i = 0; i < row.size(); ++i) {
    engine.getInputVariable(i)->setValue(row[i]);
  }
  try {
    engine.process();
  } catch (const std::exception& error) {
    ADD_FAILURE() << what << ": fuzzylite throws: " << error.what();
    return false;
  }
  return true;
}

// Compares one random engine in both libraries; false when they disagree or one cannot load it.
// Also checks that fuzzylite reads fuzzygait's write_fll of the engine as the original text.
bool compare_engine(std::size_t index, Tally& tally) {
  const std::uint64_t seed = kFirstSeed + index;
  const RandomEngine generated = fuzzygait::fuzzy::testing::random_engine(seed);
  const std::string label = "engine " + std::to_string(index) + " (seed " + std::to_string(seed) +
                            ", FUZZYGAIT_DIFFERENTIAL_ONLY=" + std::to_string(index) + ")";
  SCOPED_TRACE("\n--- FLL of " + label + " ---\n" + generated.fll + "-----------");
  ++tally.engines;
  for (const std::string& feature : generated.features) {
    ++tally.features[feature];
  }

  const std::unique_ptr<fl::Engine> oracle = import_into_fuzzylite(generated.fll, label);
  if (!oracle) return false;
  Engine engine;
  try {
    engine = fuzzygait::fuzzy::read_fll(generated.fll, label);
  } catch (const std::exception& error) {
    ADD_FAILURE() << label << ": fuzzygait cannot read it: " << error.what();
    return false;
  }
  const std::vector<std::string> problems = engine.problems();
  if (!problems.empty()) {
    ADD_FAILURE() << label << ": fuzzygait reports '" << problems.front() << "'";
    return false;
  }
  std::string oracle_type;
  oracle->type(&oracle_type);
  ++tally.types[oracle_type];
  EXPECT_EQ(std::string(name(engine.type())), oracle_type) << label;
  const std::string written = fuzzygait::fuzzy::write_fll(engine);
  const std::unique_ptr<fl::Engine> rewritten =
      import_into_fuzzylite(written, label + " written by write_fll");
  if (!rewritten) return false;

  const std::size_t input_count = engine.inputs.size();
  const std::size_t output_count = engine.outputs.size();
  if (input_count != oracle->numberOfInputVariables() ||
      output_count != oracle->numberOfOutputVariables()) {
    ADD_FAILURE() << label << ": the libraries read different variables";
    return false;
  }
  const Evaluator evaluator(engine);
  Workspace workspace = evaluator.make_workspace();
  const std::vector<double> rows =
      fuzzygait::fuzzy::testing::random_rows(generated, kRows, seed ^ 0x9e3779b97f4a7c15ULL);
  std::vector<double> outputs(output_count);
  std::ostringstream mismatches;
  std::size_t mismatched_rows = 0;
  bool rewritten_agrees = true;
  for (std::size_t r = 0; r < kRows; ++r) {
    const std::span<const double> row(rows.data() + r * input_count, input_count);
    const std::string where = label + " row " + std::to_string(r);
    if (!process(*oracle, row, where) || !process(*rewritten, row, where + " (write_fll)")) {
      return false;
    }
    evaluator.evaluate(row, outputs, workspace);
    ++tally.rows;
    bool row_agrees = true;
    for (std::size_t o = 0; o < output_count; ++o) {
      const double expected = oracle->getOutputVariable(o)->getValue();
      const double actual = outputs[o];
      ++tally.values;
      if (!std::isnan(expected)) ++tally.numbers;
      if (!same_bits(expected, actual)) ++tally.not_identical;
      if (std::isfinite(expected) && std::isfinite(actual)) {
        tally.worst = std::max(tally.worst, std::abs(expected - actual));
      }
      if (!agree(expected, actual)) {
        row_agrees = false;
        if (mismatched_rows < kMaxReportedRows) {
          mismatches << "\n  row " << r << " " << engine.outputs[o].name << ": fuzzylite "
                     << text(expected) << ", fuzzygait " << text(actual);
        }
      }
      const double reread = rewritten->getOutputVariable(o)->getValue();
      if (rewritten_agrees && !same_bits(expected, reread)) {
        rewritten_agrees = false;
        ADD_FAILURE() << where << " " << engine.outputs[o].name << ": fuzzylite gives "
                      << text(expected) << " for the text and " << text(reread)
                      << " for fuzzygait's write_fll of it:\n"
                      << written;
      }
    }
    if (!row_agrees) {
      if (mismatched_rows < kMaxReportedRows) {
        mismatches << "\n    inputs:";
        for (const double value : row) {
          mismatches << " " << text(value);
        }
      }
      ++mismatched_rows;
    }
  }
  if (mismatched_rows > 0) {
    ADD_FAILURE() << label << ": " << mismatched_rows << " of " << kRows
                  << " rows disagree (first ones below)" << mismatches.str();
    return false;
  }
  return rewritten_agrees;
}

// Adds "prefix" + name for every name of a space-separated list.
void add_features(std::vector<std::string>& out, const std::string& prefix,
                  std::string_view names) {
  std::size_t start = 0;
  while (start < names.size()) {
    const std::size_t end = std::min(names.find(' ', start), names.size());
    out.push_back(prefix + std::string(names.substr(start, end - start)));
    start = end + 1;
  }
}

// Features every run of at least kCoverageEngines engines uses at least once.
std::vector<std::string> required_features() {
  constexpr std::string_view kShapes =
      "Bell Binary Concave Constant Cosine Discrete Function Gaussian GaussianProduct Linear "
      "PiShape Ramp Rectangle SShape Sigmoid SigmoidDifference SigmoidProduct Spike Trapezoid "
      "Triangle ZShape";
  constexpr std::string_view kTNorms =
      "AlgebraicProduct BoundedDifference DrasticProduct EinsteinProduct HamacherProduct Minimum "
      "NilpotentMinimum";
  constexpr std::string_view kSNorms =
      "AlgebraicSum BoundedSum DrasticSum EinsteinSum HamacherSum Maximum NilpotentMaximum "
      "NormalizedSum UnboundedSum";
  constexpr std::string_view kHedges = "any not extremely seldom somewhat very";
  std::vector<std::string> out;
  add_features(out, "input-term:", kShapes);
  add_features(out, "output-term:", kShapes);
  add_features(out, "conjunction:", kTNorms);
  add_features(out, "implication:", kTNorms);
  add_features(out, "disjunction:", kSNorms);
  add_features(out, "aggregation:", kSNorms);
  add_features(out, "hedge:", kHedges);
  add_features(out, "consequent-hedge:", kHedges);
  add_features(out, "activation:", "General none Proportional Threshold First Last Highest Lowest");
  add_features(out, "activation:Threshold ", "< <= == != >= >");
  add_features(out, "defuzzifier:",
               "Centroid Bisector SmallestOfMaximum MeanOfMaximum LargestOfMaximum "
               "WeightedAverage WeightedSum");
  add_features(out, "weighted-type:", "Automatic TakagiSugeno Tsukamoto");
  add_features(out, "flavour:", "Mamdani Larsen TakagiSugeno Tsukamoto InverseTsukamoto Hybrid");
  add_features(out, "function:",
               "reads-x reads-input reads-output acos asin atan ceil cos cosh exp abs fabs floor "
               "log log10 round sin sinh sqrt tan tanh log1p acosh asinh atanh min max pow atan2 "
               "fmod gt ge eq neq le lt");
  add_features(out, "function:operator", "~ ! + - * / % ^ and or");
  add_features(out, "",
               "term:height term:unsorted rule:weight antecedent:and-or antecedent:parentheses "
               "antecedent:output-variable consequent:several consequent:same-output "
               "rule-blocks:several rules:none rules:shared-propositions disabled:input "
               "disabled:output disabled:rule-block lock-range:input lock-range:output "
               "lock-previous default:number range:inverted range:infinite "
               "variables:interleaved weighted:automatic-mixed legacy:activation-tnorm "
               "legacy:accumulation legacy:lock-valid comment");
  return out;
}

TEST(Differential, RandomEnginesAgreeWithFuzzylite) {
  std::size_t first = 0;
  std::size_t count = environment("FUZZYGAIT_DIFFERENTIAL_ENGINES").value_or(kDefaultEngines);
  if (const std::optional<std::size_t> only = environment("FUZZYGAIT_DIFFERENTIAL_ONLY")) {
    first = *only;
    count = 1;
  }
  fl::fuzzylite::setLogging(false);  // its warnings about fuzzylite 5 keys the engines use
  Tally tally;
  for (std::size_t index = first; index < first + count; ++index) {
    if (!compare_engine(index, tally) && ++tally.failing_engines >= kMaxFailingEngines) {
      ADD_FAILURE() << "stopped after " << kMaxFailingEngines << " failing engines";
      break;
    }
  }

  std::printf(
      "[differential] %zu engines, %zu rows, %zu output values (%zu not NaN) compared with "
      "fuzzylite %s\n"
      "[differential] worst absolute difference %.3g; %zu values not bit-identical\n",
      tally.engines, tally.rows, tally.values, tally.numbers, fl::fuzzylite::version().c_str(),
      tally.worst, tally.not_identical);
  std::printf("[differential] engine types:");
  for (const auto& [type, engines] : tally.types) {
    std::printf(" %s %zu;", type.c_str(), engines);
  }
  std::printf("\n");
  RecordProperty("engines", static_cast<int>(tally.engines));
  RecordProperty("values", static_cast<int>(tally.values));
  RecordProperty("not_bit_identical", static_cast<int>(tally.not_identical));

  if (first == 0 && count >= kCoverageEngines) {
    for (const std::string& feature : required_features()) {
      EXPECT_GT(tally.features[feature], 0u) << "no random engine used " << feature;
    }
    for (const char* type :
         {"Mamdani", "Larsen", "Takagi-Sugeno", "Tsukamoto", "Inverse Tsukamoto", "Hybrid"}) {
      EXPECT_GT(tally.types[type], 0u) << "no random engine of type " << type;
    }
  }
}

// Fixed seeds reproduce a failure anywhere: the generator draws from SplitMix64 (pinned here
// to its published reference values) and nothing else.
TEST(Differential, GeneratorIsDeterministic) {
  fuzzygait::fuzzy::testing::Random random(1234567);
  EXPECT_EQ(random.next(), 6457827717110365317ULL);
  EXPECT_EQ(random.next(), 3203168211198807973ULL);
  EXPECT_EQ(random.next(), 9817491932198370423ULL);
  for (const std::uint64_t seed : {std::uint64_t{1}, std::uint64_t{42}, kFirstSeed}) {
    const RandomEngine a = fuzzygait::fuzzy::testing::random_engine(seed);
    const RandomEngine b = fuzzygait::fuzzy::testing::random_engine(seed);
    EXPECT_EQ(a.fll, b.fll);
    const std::vector<double> rows_a = fuzzygait::fuzzy::testing::random_rows(a, 10, seed);
    const std::vector<double> rows_b = fuzzygait::fuzzy::testing::random_rows(b, 10, seed);
    ASSERT_EQ(rows_a.size(), rows_b.size());
    for (std::size_t i = 0; i < rows_a.size(); ++i) {
      EXPECT_TRUE(same_bits(rows_a[i], rows_b[i]));
    }
  }
}

// Evaluates one input value in both libraries; {fuzzylite, fuzzygait} for the first output.
std::pair<double, double> evaluate_both(const std::string& fll, double input) {
  const std::unique_ptr<fl::Engine> oracle(fl::FllImporter().fromString(fll));
  oracle->getInputVariable(0)->setValue(input);
  oracle->process();
  const Evaluator evaluator(fuzzygait::fuzzy::read_fll(fll));
  Workspace workspace = evaluator.make_workspace();
  std::vector<double> outputs(evaluator.output_count());
  evaluator.evaluate(std::span<const double>(&input, 1), outputs, workspace);
  return {oracle->getOutputVariable(0)->getValue(), outputs[0]};
}

// fuzzylite 6 infers an Automatic weighted defuzzifier's type from the Activated wrapper of the
// first term (WeightedAverage::defuzzify), which is never a Constant, Linear or Function: every
// term is read as Tsukamoto does, even after a Constant.
TEST(Differential, AutomaticWeightedTypeReadsEveryTermAsTsukamoto) {
  const std::string fll = R"(Engine: automatic
InputVariable: a
  range: 0 1
  term: low Triangle 0 0 1
  term: high Triangle 0 1 1
OutputVariable: y
  range: 0 1
  defuzzifier: WeightedAverage Automatic
  term: constant Constant 0.3
  term: ramp Ramp 0 0.5
RuleBlock: rules
  rule: if a is low then y is constant
  rule: if a is high then y is ramp
)";
  // low 0.8 and high 0.2: the ramp reaches 0.2 at 0.1 (its membership at 0.2 would be 0.4).
  const auto [fuzzylite, fuzzygait] = evaluate_both(fll, 0.2);
  EXPECT_DOUBLE_EQ(fuzzylite, 0.8 * 0.3 + 0.2 * 0.1);
  EXPECT_TRUE(same_bits(fuzzylite, fuzzygait)) << fuzzylite << " " << fuzzygait;
}

// fuzzylite resolves a Function term's variables while it reads the term, so write_fll puts a
// variable after those its formulas read, even an input after an output.
TEST(Differential, FuzzyliteReadsWriteFllOfFunctionsReadingLaterVariables) {
  const std::string fll = R"(Engine: ordered
OutputVariable: y
  range: 0 1
  lock-range: true
  defuzzifier: WeightedAverage TakagiSugeno
  default: 0.5
  lock-previous: true
  term: half Constant 0.5
InputVariable: a
  range: 0 1
  term: near Function 1 - fabs(x - y)
RuleBlock: rules
  rule: if a is near then y is half
)";
  const Engine engine = fuzzygait::fuzzy::read_fll(fll);
  const std::string written = fuzzygait::fuzzy::write_fll(engine);
  EXPECT_LT(written.find("OutputVariable: y"), written.find("InputVariable: a")) << written;
  for (const double input : {0.25, 0.75}) {
    const auto [original, fuzzygait] = evaluate_both(fll, input);
    const auto [rewritten, again] = evaluate_both(written, input);
    EXPECT_TRUE(same_bits(original, rewritten)) << original << " " << rewritten;
    EXPECT_TRUE(same_bits(original, fuzzygait)) << original << " " << fuzzygait;
  }
}

// Engines that fuzzylite loads but cannot process (it throws from Engine::process) are refused
// up front by fuzzygait: Engine::problems() names what is missing and Evaluator throws.
TEST(Differential, EnginesFuzzyliteCannotProcessAreRejected) {
  struct Case {
    const char* what;
    const char* output;  // the output variable's aggregation and defuzzifier lines
    const char* block;   // the rule block's operators and its rule
  };
  const Case cases[] = {
      {"'and' without a conjunction", "  aggregation: Maximum\n  defuzzifier: Centroid 100\n",
       "  disjunction: Maximum\n  implication: Minimum\n"
       "  rule: if a is low and a is high then y is small\n"},
      {"'or' without a disjunction", "  aggregation: Maximum\n  defuzzifier: Centroid 100\n",
       "  conjunction: Minimum\n  implication: Minimum\n"
       "  rule: if a is low or a is high then y is small\n"},
      {"an integral output without implication",
       "  aggregation: Maximum\n  defuzzifier: Bisector 100\n",
       "  conjunction: Minimum\n  rule: if a is low then y is small\n"},
      {"an integral output without aggregation", "  aggregation: none\n  defuzzifier: Centroid\n",
       "  implication: Minimum\n  rule: if a is low then y is small\n"},
      {"an output without defuzzifier", "  aggregation: Maximum\n  defuzzifier: none\n",
       "  implication: Minimum\n  rule: if a is high then y is small\n"},
  };
  for (const Case& c : cases) {
    const std::string fll = std::string(R"(Engine: invalid
InputVariable: a
  range: 0 1
  term: low Triangle 0 0 1
  term: high Triangle 0 1 1
OutputVariable: y
  range: 0 1
)") + c.output + "  term: small Triangle 0 0.25 0.5\nRuleBlock: rules\n" +
                            c.block;
    SCOPED_TRACE(std::string(c.what) + "\n" + fll);

    std::unique_ptr<fl::Engine> oracle(fl::FllImporter().fromString(fll));
    ASSERT_TRUE(oracle->getRuleBlock(0)->getRule(0)->isLoaded());
    oracle->getInputVariable(0)->setValue(0.5);
    EXPECT_THROW(oracle->process(), fl::Exception);

    const Engine engine = fuzzygait::fuzzy::read_fll(fll);
    EXPECT_FALSE(engine.problems().empty());
    EXPECT_THROW(Evaluator evaluator(engine), std::invalid_argument);
  }
}

}  // namespace

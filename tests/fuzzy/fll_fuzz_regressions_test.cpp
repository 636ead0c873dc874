// Regressions found by fuzzing the FLL reader (fuzz/fll_reader_fuzzer.cpp): each input once
// crashed or broke the lossless round trip; it is now refused with a clear error or handled.
// The inputs themselves are also kept in fuzz/corpus/fll/crash_*.fll.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/fll.hpp"

using namespace fuzzygait::fuzzy;
using ::testing::HasSubstr;

namespace {

std::string error_of(const std::string& text) {
  try {
    read_fll(text, "fuzz.fll");
  } catch (const ParseError& e) {
    return e.what();
  }
  return "no error";
}

// Reads, writes and reads again: the engine and its text must survive unchanged.
void expect_lossless_round_trip(const std::string& text) {
  const Engine engine = read_fll(text, "fuzz.fll");
  const std::string written = write_fll(engine);
  const Engine again = read_fll(written, "written.fll");
  EXPECT_EQ(again, engine) << written;
  EXPECT_EQ(write_fll(again), written);
}

// Evaluation indexed before the first point: the shape's binary search cannot order nan.
TEST(FllFuzzRegressions, DiscretePointsNeedNumericX) {
  EXPECT_THAT(error_of("Engine: e\nInputVariable: in\n  term: odd Discrete nan 1\n"),
              HasSubstr("fuzz.fll:3: term 'odd' (Discrete): x0 is nan"));
  EXPECT_THAT(error_of("Engine: e\nInputVariable: in\n  term: odd Discrete 0 1 nan 1\n"),
              HasSubstr("x1 is nan"));
}

// write_fll refused the engine name read_fll had accepted.
TEST(FllFuzzRegressions, CarriageReturnInsideALineIsRefused) {
  EXPECT_THAT(error_of("Engine: a\rb\n"), HasSubstr("fuzz.fll:1: carriage return inside the line"));
  EXPECT_THAT(error_of("Engine: e\nInputVariable: in\n  description: first\rsecond\n"),
              HasSubstr("fuzz.fll:3: carriage return"));
  // Windows line endings, with or without a comment, stay fine.
  const std::string unix_text = "Engine: e\nInputVariable: in\n  range: 0 1\n";
  const std::string windows_text = "Engine: e\r\nInputVariable: in # comment\r\n  range: 0 1\r\n";
  EXPECT_EQ(read_fll(windows_text), read_fll(unix_text));
}

// A resolution of 10^9 made the workspace allocate 16 GB and each evaluation take minutes.
TEST(FllFuzzRegressions, ResolutionHasAnUpperLimit) {
  EXPECT_THAT(error_of("Engine: e\nOutputVariable: out\n  defuzzifier: Centroid 1000000000\n"),
              HasSubstr("fuzz.fll:3: defuzzifier resolution must be from 1 to 1000000, found "
                        "'1000000000'"));
  const Engine at_limit = read_fll(
      "Engine: e\nOutputVariable: out\n  aggregation: Maximum\n"
      "  defuzzifier: Centroid 1000000\n");
  EXPECT_TRUE(at_limit.problems().empty());
  Engine built = at_limit;
  built.outputs[0].defuzzifier->resolution = Defuzzifier::kMaxResolution + 1;
  ASSERT_EQ(built.problems().size(), 1u);
  EXPECT_THAT(built.problems()[0], HasSubstr("resolution of 1000001; it must be from 1 to"));
  EXPECT_THROW(Evaluator{built}, std::invalid_argument);
}

// A variable named 'and' defined after a rule block turned that block's connectives into
// propositions when the written file was read back.
TEST(FllFuzzRegressions, VariablesCannotBeNamedLikeConnectives) {
  const std::string rules =
      "Engine: e\nInputVariable: a\n  term: t Triangle 0 1 2\nOutputVariable: o\n"
      "  defuzzifier: WeightedAverage\n  term: c Constant 1\nRuleBlock: b\n"
      "  conjunction: Minimum\n  rule: if a is t and a is t then o is c\n";
  EXPECT_THAT(error_of(rules + "InputVariable: and\n"),
              HasSubstr("fuzz.fll:10: input variable name 'and' is a rule connective"));
  EXPECT_THAT(error_of(rules + "OutputVariable: or\n"),
              HasSubstr("fuzz.fll:10: output variable name 'or' is a rule connective"));
}

// Names that are also formula functions or operators ("max", "min", "or") moved when the
// antecedent, written without the reader's parentheses, went through infix-to-postfix again.
TEST(FllFuzzRegressions, FormulaFunctionNamesInRulesRoundTrip) {
  const std::string text =
      "Engine: e\n"
      "InputVariable: speed\n  term: max Triangle 0 1 1\n  term: or Triangle 0 0 1\n"
      "InputVariable: max\n  term: t Triangle 0 1 1\n  term: min Triangle 0 1 1\n"
      "OutputVariable: o\n  defuzzifier: WeightedAverage\n  term: c Constant 1\n"
      "RuleBlock: b\n  conjunction: Minimum\n  disjunction: Maximum\n"
      "  rule: if ((max) is t) or (speed is or) and ((max) is (min)) then o is c\n";
  const Engine engine = read_fll(text);
  EXPECT_EQ(engine.rule_blocks[0].rules[0].text(),
            "if (max) is t or speed is (or) and (max) is (min) then o is c");
  expect_lossless_round_trip(text);
}

// "-0" was written as "0": the engine read back compared equal (-0 == 0) but evaluated
// differently, here a locked range clamping to the minimum's zero.
TEST(FllFuzzRegressions, NegativeZeroSurvivesTheRoundTrip) {
  EXPECT_EQ(format_scalar(-0.0), "-0");
  EXPECT_EQ(format_scalar(0.0), "0");
  const std::string text =
      "Engine: e\nInputVariable: in\n  range: 0 1\n  term: t Triangle 0 0.5 1\n"
      "OutputVariable: out\n  range: -0e308 1\n  lock-range: true\n  aggregation: Maximum\n"
      "  defuzzifier: Centroid 3\n  default: -1\n  term: t Sigmoid 0.5 -0\n"
      "RuleBlock: b\n  implication: Minimum\n  rule: if in is t then out is t with -0\n";
  expect_lossless_round_trip(text);
  const Engine again = read_fll(write_fll(read_fll(text)));
  EXPECT_TRUE(std::signbit(again.outputs[0].minimum));
  EXPECT_TRUE(std::signbit(again.outputs[0].terms[0].parameters[1]));
  EXPECT_TRUE(std::signbit(again.rule_blocks[0].rules[0].weight));
  const Evaluator evaluator(again);
  Workspace workspace = evaluator.make_workspace();
  const double input = 0.5;
  double output = 1.0;
  evaluator.evaluate({&input, 1}, {&output, 1}, workspace);
  EXPECT_EQ(output, 0.0);  // the default, clamped to the range's -0
  EXPECT_TRUE(std::signbit(output));
}

}  // namespace

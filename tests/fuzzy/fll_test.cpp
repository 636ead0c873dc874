// FLL reading and writing: the language's corners, and clear errors on bad files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "fuzzygait/fuzzy/fll.hpp"

using namespace fuzzygait::fuzzy;
using ::testing::HasSubstr;

namespace {

const char* kSmall = R"(Engine: small
description: a small engine
InputVariable: in
  enabled: true
  range: 0 1
  lock-range: true
  term: low Triangle 0 0 0.5   # comment after a term
  term: high Triangle 0.5 1 1 0.75
OutputVariable: out
  enabled: true
  range: -1 1
  lock-range: false
  aggregation: Maximum
  defuzzifier: Centroid 200
  default: nan
  lock-previous: true
  term: neg Ramp 0 -1
  term: pos Ramp 0 1
RuleBlock: main
  enabled: true
  conjunction: Minimum
  disjunction: Maximum
  implication: AlgebraicProduct
  activation: Highest 2
  rule: if in is low then out is neg
  rule: if in is very high or in is not low then out is pos with 0.5
)";

std::string error_of(const std::string& text) {
  try {
    read_fll(text, "bad.fll");
  } catch (const ParseError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Fll, ReadsEveryField) {
  const Engine e = read_fll(kSmall);
  EXPECT_EQ(e.name, "small");
  EXPECT_EQ(e.description, "a small engine");
  ASSERT_EQ(e.inputs.size(), 1u);
  EXPECT_TRUE(e.inputs[0].lock_range);
  ASSERT_EQ(e.inputs[0].terms.size(), 2u);
  EXPECT_EQ(e.inputs[0].terms[1].height, 0.75);
  EXPECT_EQ(e.inputs[0].terms[1].parameters, (std::vector<double>{0.5, 1, 1}));
  const OutputVariable& out = e.outputs.at(0);
  EXPECT_EQ(out.aggregation, SNorm::Maximum);
  ASSERT_TRUE(out.defuzzifier.has_value());
  EXPECT_EQ(out.defuzzifier->kind, Defuzzifier::Kind::Centroid);
  EXPECT_EQ(out.defuzzifier->resolution, 200);
  EXPECT_TRUE(std::isnan(out.default_value));
  EXPECT_TRUE(out.lock_previous);
  const RuleBlock& b = e.rule_blocks.at(0);
  EXPECT_EQ(b.implication, TNorm::AlgebraicProduct);
  EXPECT_EQ(b.activation.kind, Activation::Kind::Highest);
  EXPECT_EQ(b.activation.number_of_rules, 2);
  ASSERT_EQ(b.rules.size(), 2u);
  EXPECT_EQ(b.rules[1].weight, 0.5);
  EXPECT_EQ(b.rules[1].text(), "if in is very high or in is not low then out is pos with 0.5");
  EXPECT_EQ(e.type(), EngineType::Larsen);
  EXPECT_TRUE(e.problems().empty());
}

TEST(Fll, RoundTripIsLossless) {
  Engine e = read_fll(kSmall);
  e.inputs[0].terms[0].parameters[2] = 0.1 + 0.2;  // not representable in few decimals
  const Engine again = read_fll(write_fll(e));
  EXPECT_EQ(e, again);
  EXPECT_EQ(again.inputs[0].terms[0].parameters[2], 0.1 + 0.2);
}

TEST(Fll, RuleTextKeepsParenthesesThatMatter) {
  const std::string text = std::string(kSmall) +
                           "  rule: if (in is low or in is high) and in is low then out is neg\n"
                           "  rule: if in is low or (in is high or in is low) then out is pos\n";
  const Engine e = read_fll(text);
  const auto& rules = e.rule_blocks[0].rules;
  EXPECT_EQ(rules[2].text(), "if (in is low or in is high) and in is low then out is neg");
  EXPECT_EQ(rules[3].text(), "if in is low or (in is high or in is low) then out is pos");
  EXPECT_EQ(read_fll(write_fll(e)), e);
}

TEST(Fll, AnyHedgeAndChainedOutputs) {
  const std::string text =
      std::string(kSmall) + "  rule: if in is any and out is pos then out is somewhat neg\n";
  const Engine e = read_fll(text);
  const Rule& r = e.rule_blocks[0].rules.at(2);
  ASSERT_EQ(r.propositions.size(), 2u);
  EXPECT_EQ(r.propositions[0].hedges, std::vector<Hedge>{Hedge::Any});
  EXPECT_TRUE(r.propositions[0].term.empty());
  EXPECT_TRUE(r.propositions[1].output);
  EXPECT_EQ(r.conclusions[0].hedges, std::vector<Hedge>{Hedge::Somewhat});
}

TEST(Fll, ObsoleteKeysOfFuzzylite5AreUnderstood) {
  std::string text = kSmall;
  text.replace(text.find("aggregation:"), 12, "accumulation:");
  text.replace(text.find("implication: AlgebraicProduct"), 29, "activation: AlgebraicProduct");
  text.replace(text.find("activation: Highest 2"), 21, "lock-valid: true");
  EXPECT_THAT(error_of(text), HasSubstr("bad.fll:24: unknown key 'lock-valid' in RuleBlock"));
  text.replace(text.find("lock-valid: true"), 16, "enabled: true");
  const Engine e = read_fll(text);
  EXPECT_EQ(e.outputs[0].aggregation, SNorm::Maximum);
  EXPECT_EQ(e.rule_blocks[0].implication, TNorm::AlgebraicProduct);
}

struct BadCase {
  std::string from;
  std::string to;
  std::string expected;
};

class BadFll : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadFll, NamesFileLineAndProblem) {
  std::string text = kSmall;
  const BadCase& c = GetParam();
  const std::size_t at = text.find(c.from);
  ASSERT_NE(at, std::string::npos) << c.from;
  text.replace(at, c.from.size(), c.to);
  EXPECT_THAT(error_of(text), HasSubstr(c.expected));
}

INSTANTIATE_TEST_SUITE_P(
    Errors, BadFll,
    ::testing::Values(
        BadCase{"range: 0 1", "range: 0", "bad.fll:5: range must be two numbers"},
        BadCase{"range: 0 1", "range: 0 one", "bad.fll:5: range maximum must be a number"},
        BadCase{"lock-range: true", "lock-range: yes", "bad.fll:6: 'lock-range' must be true"},
        BadCase{"low Triangle 0 0 0.5", "low Triangle 0 0",
                "bad.fll:7: term 'low' (Triangle): needs 3 parameters"},
        BadCase{"low Triangle 0 0 0.5", "low Triangle 0 0 0.5 1 2", "found 5"},
        BadCase{"low Triangle 0 0 0.5", "low Triangel 0 0 0.5",
                "bad.fll:7: unknown term shape 'Triangel'"},
        BadCase{"low Triangle 0 0 0.5", "low Triangle 0 x 0.5", "parameter 2 'x' is not a number"},
        BadCase{"term: high", "term: low", "bad.fll:8: term 'low' is defined twice in 'in'"},
        BadCase{"Centroid 200", "Centroid 0", "bad.fll:14: defuzzifier resolution must be"},
        BadCase{"Centroid 200", "Centroid 2.5", "resolution must be a whole number"},
        BadCase{"Centroid 200", "Centroyd", "bad.fll:14: unknown defuzzifier 'Centroyd'"},
        BadCase{"aggregation: Maximum", "aggregation: Max", "unknown S-norm 'Max'"},
        BadCase{"conjunction: Minimum", "conjunction: Min", "bad.fll:21: unknown T-norm 'Min'"},
        BadCase{"Highest 2", "Highest", "activation 'Highest' must read"},
        BadCase{"then out is neg", "then out is negative",
                "bad.fll:25: rule 'if in is low then out is negative': 'negative' is neither"},
        BadCase{"if in is low then", "if in is lo then", "'lo' is neither a hedge nor a term"},
        BadCase{"if in is low then", "if inn is low then", "expected an input or output variable"},
        BadCase{"if in is low then out is neg", "if in is low out is neg", "has no 'then'"},
        BadCase{"with 0.5", "with half", "the weight after 'with' must be a number"},
        BadCase{"with 0.5", "with 0.5 0.6", "unexpected '0.6' after the weight"},
        BadCase{"in is very high or", "in is very high", "does not combine into one"},
        BadCase{"InputVariable: in", "InputVariable: in put", "name 'in put' must be letters"},
        BadCase{"OutputVariable: out", "OutputVariable: in", "variable 'in' is defined twice"},
        BadCase{"  enabled: true\n  range: -1", "  colour: red\n  range: -1",
                "bad.fll:10: unknown key 'colour' in OutputVariable 'out'"},
        BadCase{"Engine: small", "Engine: small\nrange: 0 1",
                "bad.fll:2: 'range' must belong to an InputVariable"},
        BadCase{"description: a small engine", "description a small engine",
                "bad.fll:2: expected 'key: value'"}));

TEST(Fll, ProblemsAreReportedNotHidden) {
  std::string text = kSmall;
  text.replace(text.find("conjunction: Minimum"), 20, "conjunction: none");
  text += "  rule: if in is low and in is high then out is neg\n";
  const Engine e = read_fll(text);
  ASSERT_EQ(e.problems().size(), 1u);
  EXPECT_THAT(e.problems()[0], HasSubstr("has rules with 'and' but no conjunction"));
}

TEST(Fll, DiscreteMustBeSorted) {
  std::string text = kSmall;
  text.replace(text.find("low Triangle 0 0 0.5"), 20, "low Discrete 0 1 0.5 0 0.25 1");
  EXPECT_THAT(error_of(text), HasSubstr("points must be sorted by x"));
}

TEST(Fll, WriterRefusesWhatFllCannotHold) {
  Engine e = read_fll(kSmall);
  e.description = "two\nlines";
  EXPECT_THROW(write_fll(e), std::invalid_argument);
}

TEST(Fll, ScalarsReadLikeFuzzylite) {
  EXPECT_EQ(parse_scalar("1e3"), 1000.0);
  EXPECT_EQ(parse_scalar("+2.5"), 2.5);
  EXPECT_EQ(parse_scalar(".5"), 0.5);
  EXPECT_TRUE(std::isnan(*parse_scalar("nan")));
  EXPECT_EQ(parse_scalar("-inf"), -HUGE_VAL);
  EXPECT_FALSE(parse_scalar("infinity"));
  EXPECT_FALSE(parse_scalar("0x10"));
  EXPECT_FALSE(parse_scalar("1.5m"));
  EXPECT_EQ(format_scalar(0.1), "0.1");
  EXPECT_EQ(format_scalar(-HUGE_VAL), "-inf");
}

// `text` ("bad.fll") is read by default, as fuzzylite reads it, and refused under `strict` with
// an error holding `error`.
void expect_read_unless(const std::string& text, const FllOptions& strict,
                        const std::string& error) {
  EXPECT_NO_THROW(read_fll(text, "bad.fll")) << text << "\nfuzzylite reads it, and so do we";
  try {
    read_fll(text, "bad.fll", strict);
    ADD_FAILURE() << error << ": was read";
  } catch (const ParseError& e) {
    EXPECT_THAT(e.what(), HasSubstr(error));
  }
}

TEST(Fll, FiniteNumbersRefusesNanAndInfinityWhereverANumberIs) {
  const FllOptions finite{.finite_numbers = true};
  EXPECT_NO_THROW(read_fll(
      std::string(kSmall).replace(std::string(kSmall).find("default: nan"), 12, "default: 0"),
      "ok.fll", finite));
  struct Case {
    std::string from, to, error;
  };
  const Case cases[] = {
      {"default: nan", "default: nan",
       "bad.fll:15: default must be a finite number here, found 'nan'"},
      {"range: 0 1", "range: 0 inf", "bad.fll:5: range maximum must be a finite number here"},
      {"range: -1 1", "range: -inf 1", "bad.fll:11: range minimum must be a finite number"},
      {"low Triangle 0 0 0.5", "low Triangle 0 nan 0.5",
       "bad.fll:7: term 'low' parameter 'vertexB' must be a finite number here, found 'nan'"},
      {"high Triangle 0.5 1 1 0.75", "high Triangle 0.5 1 1 inf",
       "bad.fll:8: term 'high' height must be a finite number"},
      {"neg Ramp 0 -1", "neg Discrete 0 0 1 nan", "bad.fll:17: term 'neg' parameter 4 must"},
      {"with 0.5", "with nan", "bad.fll:26: rule weight must be a finite number here"},
      {"Highest 2", "Threshold >= inf", "bad.fll:24: threshold must be a finite number"},
      {"neg Ramp 0 -1", "neg Function 2 * nan",
       "bad.fll:17: a constant in the formula of term 'neg' must be a finite number here"},
      // Left out, a range is -inf to inf and an output's default nan: named at the variable.
      {"  range: 0 1\n", "", "bad.fll:3: input variable 'in' needs a 'range: minimum maximum'"},
      {"  default: nan\n", "", "bad.fll:9: output variable 'out' needs a 'default:'"},
  };
  for (const Case& c : cases) {
    std::string text = kSmall;
    if (c.from.find("default: nan") == std::string::npos) {
      text.replace(text.find("default: nan"), 12, "default: 0");
    }
    text.replace(text.find(c.from), c.from.size(), c.to);
    expect_read_unless(text, finite, c.error);
  }
}

// A term whose points are out of order is read as fuzzylite reads it, and refused, naming the
// line and the term, under FllOptions::ordered_points (`fuzzygait fuzzy check`).
TEST(Fll, OrderedPointsRefusesATermWhosePointsAreOutOfOrder) {
  const FllOptions ordered{.ordered_points = true};
  EXPECT_NO_THROW(read_fll(kSmall, "ok.fll", ordered));
  struct Case {
    std::string from, to, error;
  };
  const Case cases[] = {
      {"low Triangle 0 0 0.5", "low Triangle 0.9 5 1.29",
       "bad.fll:7: term 'low' (Triangle): 'vertexB' 5 is past 'vertexC' 1.29; its points must "
       "be in order (in 'in')"},
      {"low Triangle 0 0 0.5", "low Trapezoid 0 0.2 0.1 0.5",
       "bad.fll:7: term 'low' (Trapezoid): 'vertexB' 0.2 is past 'vertexC' 0.1"},
      {"high Triangle 0.5 1 1 0.75", "high PiShape 0.6 0.5 1 1",
       "bad.fll:8: term 'high' (PiShape): 'bottomLeft' 0.6 is past 'topLeft' 0.5"},
      {"neg Ramp 0 -1", "neg Rectangle 0 -1",
       "bad.fll:17: term 'neg' (Rectangle): 'start' 0 is past 'end' -1"},
  };
  for (const Case& c : cases) {
    std::string text = kSmall;
    text.replace(text.find(c.from), c.from.size(), c.to);
    expect_read_unless(text, ordered, c.error);
  }
  // Points that meet are in order (a shoulder), and a Ramp's direction is its own.
  std::string shoulder = kSmall;
  shoulder.replace(shoulder.find("0 0 0.5"), 7, "0 0.5 0.5");
  EXPECT_NO_THROW(read_fll(shoulder, "ok.fll", ordered));
}

TEST(Fll, AnEmptyFileOrADirectoryIsAnError) {
  // Not an empty engine that every check then passes: a truncated copy or a wrong path.
  EXPECT_THAT(error_of(""), HasSubstr("bad.fll:1: no engine: the text is empty"));
  EXPECT_THAT(error_of("  \n# only a comment\n\n"), HasSubstr("the text is empty"));
  EXPECT_EQ(error_of("Engine: named\n"), "no error");  // a name is an engine, if a bare one
  const std::filesystem::path directory =
      std::filesystem::temp_directory_path() / "fuzzygait_fll_test_directory.fll";
  std::filesystem::create_directories(directory);
  try {
    read_fll_file(directory);
    ADD_FAILURE() << "read a directory";
  } catch (const ParseError& e) {
    EXPECT_THAT(e.what(), HasSubstr("is a directory"));
  }
  std::filesystem::remove(directory);
}

}  // namespace

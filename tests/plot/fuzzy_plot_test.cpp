// Drawings of fuzzy engines: a curve and a label per term, the input-output curve or surface,
// deterministic output; and `fuzzygait fuzzy plot` end to end.
#include "fuzzygait/plot/fuzzy_plot.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "fuzzygait/fuzzy/fll.hpp"
#include "plot/xml_check.hpp"
#include "support/program.hpp"
#include "support/text.hpp"

using fuzzygait::fuzzy::Engine;
using fuzzygait::fuzzy::read_fll;
using fuzzygait::fuzzy::read_fll_file;
using fuzzygait::plot::EnginePlotOptions;
using fuzzygait::plot::plot_engine;
using fuzzygait::test::check_xml;
using fuzzygait::test::count;
using fuzzygait::test::keep;
using fuzzygait::test::ProgramRun;
using fuzzygait::test::read_text;
using fuzzygait::test::run_program;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

const std::filesystem::path kEaseInOut =
    std::filesystem::path(FUZZYGAIT_SOURCE_DIR) / "controllers/paper/ease_in_out.fll";
const std::filesystem::path kExamples = FUZZYLITE_EXAMPLES_DIR;

// Term curves and Constant stems are the only lines drawn 1.9 pixels wide.
std::size_t term_curves(const std::string& svg) {
  return count(svg, "stroke-width=\"1.9\"");
}

std::size_t term_count(const Engine& engine) {
  std::size_t n = 0;
  for (const auto& v : engine.inputs)
    n += v.terms.size();
  for (const auto& v : engine.outputs)
    n += v.terms.size();
  return n;
}

}  // namespace

TEST(FuzzyPlot, EaseInOutHasACurveAndALabelPerTermAndTheOutputCurve) {
  const Engine engine = read_fll_file(kEaseInOut);
  const std::string svg = plot_engine(engine).svg();
  EXPECT_EQ(check_xml(svg), "");
  EXPECT_EQ(term_curves(svg), term_count(engine));
  for (const char* name : {"start", "center", "end", "stay", "slow", "fast"}) {
    EXPECT_THAT(svg, HasSubstr(std::string(">") + name + "</text>")) << name;
  }
  EXPECT_THAT(svg, HasSubstr(">input: alpha</text>"));
  EXPECT_THAT(svg, HasSubstr(">output: velocity</text>"));
  EXPECT_THAT(svg, HasSubstr(">velocity against alpha</text>"));
  EXPECT_THAT(svg, HasSubstr("rule: if alpha is start then velocity is slow"));
  EXPECT_THAT(svg, HasSubstr("Takagi-Sugeno engine"));
  EXPECT_EQ(count(svg, "<image "), 0u);
  keep(svg, "ease_in_out.svg");
}

TEST(FuzzyPlot, IsDeterministic) {
  const Engine engine = read_fll_file(kEaseInOut);
  EXPECT_EQ(plot_engine(engine).svg(), plot_engine(engine).svg());
}

TEST(FuzzyPlot, TwoInputsGiveOneSurfacePerOutput) {
  const Engine engine = read_fll(R"(Engine: two
InputVariable: a
  range: 0 1
  term: low Triangle 0 0 1
  term: high Triangle 0 1 1
InputVariable: b
  range: 0 10
  term: low Trapezoid 0 0 2 8
  term: high Trapezoid 2 8 10 10
OutputVariable: mamdani
  range: 0 1
  aggregation: Maximum
  defuzzifier: Centroid 50
  default: nan
  term: small Triangle 0 0.25 0.5
  term: large Triangle 0.5 0.75 1
OutputVariable: sugeno
  range: 0 1
  defuzzifier: WeightedAverage TakagiSugeno
  default: nan
  term: small Constant 0.1
  term: large Linear 0.5 0.05 0
RuleBlock: rules
  conjunction: Minimum
  disjunction: Maximum
  implication: Minimum
  rule: if a is low and b is low then mamdani is small and sugeno is small
  rule: if a is high or b is high then mamdani is large and sugeno is large
)");
  const std::string svg = plot_engine(engine, {.surface_samples = 21}).svg();
  EXPECT_EQ(check_xml(svg), "");
  EXPECT_EQ(count(svg, "<image "), 2u);
  EXPECT_EQ(count(svg, "<linearGradient "), 2u);
  EXPECT_THAT(svg, HasSubstr(">mamdani over a and b</text>"));
  EXPECT_THAT(svg, HasSubstr(">sugeno over a and b</text>"));
  // The output with a Linear term lists its terms as formulas instead of membership curves.
  EXPECT_THAT(svg, HasSubstr(">large = 0.5 a + 0.05 b</text>"));
  EXPECT_THAT(svg, HasSubstr(">small = 0.1</text>"));
  EXPECT_EQ(term_curves(svg), 2u + 2u + 2u);
}

TEST(FuzzyPlot, MoreThanTwoInputsGetTermsAndANote) {
  const Engine engine = read_fll(R"(Engine: three
InputVariable: a
  range: 0 1
  term: t Triangle 0 0.5 1
InputVariable: b
  range: 0 1
  term: t Triangle 0 0.5 1
InputVariable: c
  range: 0 1
  term: t Triangle 0 0.5 1
OutputVariable: out
  range: 0 1
  defuzzifier: WeightedAverage TakagiSugeno
  term: k Constant 0.5
RuleBlock:
  conjunction: Minimum
  rule: if a is t and b is t and c is t then out is k
)");
  const std::string svg = plot_engine(engine).svg();
  EXPECT_EQ(check_xml(svg), "");
  EXPECT_THAT(svg, HasSubstr("This engine has 3 inputs"));
  EXPECT_THAT(svg, Not(HasSubstr(" against ")));
  EXPECT_EQ(count(svg, "<image "), 0u);
  EXPECT_EQ(term_curves(svg), 4u);
}

TEST(FuzzyPlot, EngineThatCannotBeEvaluatedStillShowsItsTerms) {
  const Engine engine = read_fll(R"(Engine: unfinished
InputVariable: a
  range: 0 1
  term: low Ramp 1 0
  term: high Ramp 0 1
OutputVariable: out
  range: 0 1
  defuzzifier: Centroid 100
  term: small Triangle 0 0.25 0.5
RuleBlock:
  implication: Minimum
  rule: if a is low then out is small
)");
  ASSERT_FALSE(engine.problems().empty());
  const std::string svg = plot_engine(engine).svg();
  EXPECT_EQ(check_xml(svg), "");
  EXPECT_THAT(svg, HasSubstr("Not evaluated"));
  EXPECT_THAT(svg, HasSubstr("no aggregation"));
  EXPECT_EQ(term_curves(svg), 3u);
  EXPECT_THAT(svg, Not(HasSubstr(" against ")));
}

TEST(FuzzyPlot, NamesAreEscapedAndInfiniteRangesFollowTheTerms) {
  const Engine engine = read_fll(R"(Engine: a&b
description: <quoted> "text"
InputVariable: in
  range: -inf inf
  term: low Triangle -3 -1 1
  term: high Triangle -1 1 3
OutputVariable: out
  range: 0 1
  defuzzifier: WeightedAverage TakagiSugeno
  term: k Constant 0.5
  term: j Constant 0.7
RuleBlock:
  rule: if in is low then out is k
  rule: if in is high then out is j
)");
  const std::string svg = plot_engine(engine).svg();
  EXPECT_EQ(check_xml(svg), "");
  EXPECT_THAT(svg, HasSubstr(">a&amp;b</text>"));
  EXPECT_THAT(svg, HasSubstr("&lt;quoted&gt; &quot;text&quot;"));
  EXPECT_THAT(svg, HasSubstr(">out against in</text>"));
  EXPECT_THAT(svg, Not(HasSubstr("inf")));
}

TEST(FuzzyPlot, RejectsBadOptions) {
  const Engine engine = read_fll_file(kEaseInOut);
  EXPECT_THROW(plot_engine(engine, {.curve_samples = 1}), std::invalid_argument);
  EXPECT_THROW(plot_engine(engine, {.surface_samples = 1}), std::invalid_argument);
  EXPECT_THROW(plot_engine(engine, {.columns = 0}), std::invalid_argument);
}

TEST(FuzzyPlot, FuzzyliteExamples) {
  // (FUZZYGAIT_REQUIRE_FUZZYLITE stops the configuration instead when they are missing.)
  if (!std::filesystem::exists(kExamples / "mamdani/AllTerms.fll")) {
    GTEST_SKIP() << "fuzzylite's examples are not installed";
  }
  for (const char* name :
       {"mamdani/AllTerms.fll", "mamdani/SimpleDimmer.fll", "hybrid/tipper.fll",
        "takagi-sugeno/approximation.fll", "mamdani/Laundry.fll", "tsukamoto/tsukamoto.fll"}) {
    SCOPED_TRACE(name);
    const Engine engine = read_fll_file(kExamples / name);
    const std::string svg = plot_engine(engine, {.surface_samples = 21}).svg();
    EXPECT_EQ(check_xml(svg), "");
    std::size_t drawn = 0;  // Linear and Function terms are written out, not drawn
    for (const auto& v : engine.inputs)
      drawn += v.terms.size();
    for (const auto& v : engine.outputs) {
      for (const auto& t : v.terms) {
        drawn += t.kind != fuzzygait::fuzzy::TermKind::Linear &&
                 t.kind != fuzzygait::fuzzy::TermKind::Function;
      }
    }
    EXPECT_EQ(term_curves(svg), drawn);
    for (const auto& v : engine.inputs) {
      for (const auto& t : v.terms)
        EXPECT_THAT(svg, HasSubstr(">" + t.name + "</text>"));
    }
  }
}

// ---------------------------------------------------------------------------------------------
// The command line.

TEST(FuzzyPlotCommand, PlotsTheEaseInOutController) {
  const std::filesystem::path out = std::filesystem::path(::testing::TempDir()) / "ease_cli.svg";
  std::filesystem::remove(out);
  const ProgramRun result = run_program("fuzzy plot \"" + kEaseInOut.string() + "\" -o \"" +
                                        out.string() + "\" --grid 11 --samples 101");
  ASSERT_EQ(result.status, 0) << result.output;
  const std::string svg = read_text(out);
  EXPECT_EQ(check_xml(svg), "");
  EXPECT_THAT(svg, HasSubstr(">velocity against alpha</text>"));
  EXPECT_EQ(
      svg,
      plot_engine(read_fll_file(kEaseInOut), {.curve_samples = 101, .surface_samples = 11}).svg());
  if (std::system("xmllint --version > /dev/null 2>&1") == 0) {
    EXPECT_EQ(std::system(("xmllint --noout \"" + out.string() + "\"").c_str()), 0);
  }
}

TEST(FuzzyPlotCommand, WritesToStandardOutputWithoutAFile) {
  const ProgramRun result = run_program("fuzzy plot \"" + kEaseInOut.string() + "\"");
  ASSERT_EQ(result.status, 0) << result.output;
  EXPECT_EQ(check_xml(result.output), "");
}

TEST(FuzzyPlotCommand, HelpDescribesIt) {
  const ProgramRun fuzzy = run_program("fuzzy --help");
  EXPECT_THAT(fuzzy.output, HasSubstr("plot"));
  const ProgramRun plot = run_program("fuzzy plot --help");
  EXPECT_EQ(plot.status, 0);
  EXPECT_THAT(plot.output, HasSubstr("SVG"));
  EXPECT_THAT(plot.output, HasSubstr("--grid"));
  EXPECT_THAT(plot.output, HasSubstr("--samples"));
  EXPECT_THAT(plot.output, HasSubstr("-o,--output"));
}

TEST(FuzzyPlotCommand, ReportsErrors) {
  const ProgramRun missing = run_program("fuzzy plot /nonexistent/engine.fll -o /dev/null");
  EXPECT_EQ(missing.status, 1);
  EXPECT_THAT(missing.output, HasSubstr("error"));
  const ProgramRun bad_grid = run_program("fuzzy plot \"" + kEaseInOut.string() + "\" --grid 1");
  EXPECT_NE(bad_grid.status, 0);
  EXPECT_THAT(bad_grid.output, HasSubstr("--grid"));
}

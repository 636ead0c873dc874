// The evaluator's shortcuts against the code they stand for: shapes computed with reduced
// tolerant comparisons must give the templated shapes' bits.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/shapes.hpp"
#include "support/bits.hpp"

using namespace fuzzygait::fuzzy;

namespace {

using fuzzygait::test::same_bits;

// The evaluator computes Triangle, Trapezoid and Ramp with the tolerant comparisons reduced to
// one subtraction each; they must give the templated shapes' bits everywhere, at and around the
// tolerance, at infinities and at NaN.
TEST(Evaluator, LinearShapesGiveTheTemplatedShapesBits) {
  const std::vector<double> corners = {-kInfinity, -1.0, -1e-6,      0.0, 5e-7,     1e-6,
                                       0.5,        1.0,  1.0 + 1e-7, 2.0, kInfinity};
  const std::vector<double> heights = {1.0, 0.5, -2.0};
  Engine engine;
  engine.name = "shapes";
  InputVariable input;
  input.name = "x";
  auto add = [&input](TermKind kind, std::vector<double> parameters, double height) {
    input.terms.push_back({"t" + std::to_string(input.terms.size()), kind, parameters, height, ""});
  };
  for (double h : heights) {
    for (double a : corners) {
      for (double b : corners) {
        add(TermKind::Ramp, {a, b}, h);
        for (double c : corners)
          add(TermKind::Triangle, {a, b, c}, h);
      }
    }
  }
  const std::vector<double> few = {-kInfinity, -1.0, 0.0, 1e-6, 1.0, kInfinity};
  for (double a : few) {
    for (double b : few) {
      for (double c : few) {
        for (double d : few)
          add(TermKind::Trapezoid, {a, b, c, d}, 0.5);
      }
    }
  }
  engine.inputs.push_back(input);
  OutputVariable output;
  output.name = "y";
  output.defuzzifier =
      Defuzzifier{Defuzzifier::Kind::WeightedAverage, 100, Defuzzifier::WeightedType::Automatic};
  output.terms.push_back({"c", TermKind::Constant, {1.0}, 1.0, ""});
  engine.outputs.push_back(output);

  std::vector<double> xs = {kNaN, -kInfinity, kInfinity};
  for (double corner : corners) {
    for (double offset : {0.0, 1e-7, 5e-7, 9.99e-7, 1e-6, 1.01e-6, 2e-6, 0.25}) {
      xs.push_back(corner + offset);
      xs.push_back(corner - offset);
    }
  }
  const Evaluator evaluator(engine);
  Workspace w = evaluator.make_workspace();
  std::size_t mismatches = 0;
  for (std::size_t t = 0; t < input.terms.size(); ++t) {
    const Term& term = input.terms[t];
    const std::vector<double>& p = term.parameters;
    for (double x : xs) {
      double expected = 0.0;
      switch (term.kind) {
        case TermKind::Triangle:
          expected = shapes::triangle(x, p[0], p[1], p[2], term.height);
          break;
        case TermKind::Trapezoid:
          expected = shapes::trapezoid(x, p[0], p[1], p[2], p[3], term.height);
          break;
        default:
          expected = shapes::ramp(x, p[0], p[1], term.height);
          break;
      }
      const double actual = evaluator.input_membership(0, t, x, w);
      if (!same_bits(expected, actual) && ++mismatches <= 10) {
        ADD_FAILURE() << term.name << " " << shape_info(term.kind).name << " "
                      << term.parameter_text() << " h=" << term.height << " at x=" << x
                      << ": expected " << expected << ", got " << actual;
      }
    }
  }
  EXPECT_EQ(mismatches, 0u);
}

}  // namespace

// fuzzylite's formula language: precedence, associativity, functions and errors.
#include <gtest/gtest.h>

#include <cmath>

#include "fuzzygait/fuzzy/formula.hpp"

using namespace fuzzygait::fuzzy;

namespace {

double eval(const std::string& text, std::vector<double> values = {}) {
  const FormulaProgram p = compile_formula(text);
  values.resize(p.variables.size(), 0.0);
  std::vector<double> stack(p.stack_size);
  return evaluate_formula(p, values.data(), stack.data());
}

TEST(Formula, PrecedenceAndAssociativity) {
  EXPECT_DOUBLE_EQ(eval("1 + 2 * 3"), 7.0);
  EXPECT_DOUBLE_EQ(eval("(1 + 2) * 3"), 9.0);
  EXPECT_DOUBLE_EQ(eval("2 ^ 3 ^ 2"), 512.0);  // right associative
  EXPECT_DOUBLE_EQ(eval("8 - 4 - 2"), 2.0);    // left associative
  EXPECT_DOUBLE_EQ(eval("7 % 4"), 3.0);
  EXPECT_DOUBLE_EQ(eval("~3 + 5"), 2.0);
  EXPECT_DOUBLE_EQ(eval("!0"), 1.0);
}

TEST(Formula, FunctionsAndComparisons) {
  EXPECT_DOUBLE_EQ(eval("max(1, 2) + min(3, 4)"), 5.0);
  EXPECT_DOUBLE_EQ(eval("pow(2, 10)"), 1024.0);
  EXPECT_DOUBLE_EQ(eval("atan2(1, 1)"), std::atan2(1.0, 1.0));
  EXPECT_DOUBLE_EQ(eval("gt(2, 1) + lt(2, 1) + eq(1, 1.0000001)"), 2.0);
  EXPECT_DOUBLE_EQ(eval("round(2.5) + round(~2.5)"), 0.0);
  EXPECT_DOUBLE_EQ(eval("sin(0) + cos(0) + sqrt(16)"), 5.0);
  EXPECT_DOUBLE_EQ(eval("1 and 1"), 1.0);
  EXPECT_DOUBLE_EQ(eval("0 or 0"), 0.0);
}

TEST(Formula, Variables) {
  const FormulaProgram p = compile_formula("x*x + speed - x");
  EXPECT_EQ(p.variables, (std::vector<std::string>{"x", "speed"}));
  EXPECT_DOUBLE_EQ(eval("x*x + speed - x", {3.0, 10.0}), 16.0);
}

TEST(Formula, Errors) {
  EXPECT_THROW(compile_formula(""), std::invalid_argument);
  EXPECT_THROW(compile_formula("(1 + 2"), std::invalid_argument);
  EXPECT_THROW(compile_formula("1 + 2)"), std::invalid_argument);
  EXPECT_THROW(compile_formula("1 +"), std::invalid_argument);
  EXPECT_THROW(compile_formula("1 2"), std::invalid_argument);
  EXPECT_THROW(compile_formula("-1"), std::invalid_argument);  // '-' is binary; '~' negates
  EXPECT_THROW(compile_formula("max(1)"), std::invalid_argument);
}

TEST(Formula, PostfixOfRuleAntecedents) {
  EXPECT_EQ(
      to_postfix("a is x or b is y and c is z"),
      (std::vector<std::string>{"a", "is", "x", "b", "is", "y", "c", "is", "z", "and", "or"}));
}

}  // namespace

// fuzzylite's formula language (Function terms): infix arithmetic, comparison and logic over
// the engine's variables and `x`, parsed with the same shunting-yard rules as fuzzylite and
// compiled into a flat postfix program.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fuzzygait::fuzzy {

// fuzzylite's infix-to-postfix conversion (operators spaced out, functions and parentheses
// resolved). Also used for rule antecedents, where `and` and `or` are the operators.
// Throws std::invalid_argument on mismatched parentheses.
std::vector<std::string> to_postfix(std::string_view infix);

struct FormulaInstruction {
  enum class Kind : std::uint8_t { Constant, Variable, Unary, Binary };
  Kind kind;
  std::uint8_t function;  // index into the formula function table for Unary/Binary
  std::uint32_t slot;     // Variable: index into FormulaProgram::variables
  double value;           // Constant
};

struct FormulaProgram {
  std::string text;
  std::vector<FormulaInstruction> code;  // postfix
  std::vector<std::string> variables;    // distinct names referenced, in order of first use
  std::size_t stack_size = 0;            // deepest evaluation stack
};

// Parses a formula; throws std::invalid_argument naming the problem.
FormulaProgram compile_formula(std::string_view infix);

// Evaluates with `values[i]` bound to `program.variables[i]`; `stack` has program.stack_size
// doubles of scratch.
double evaluate_formula(const FormulaProgram& program, const double* values, double* stack);

// Names of the unary and binary functions and operators the language knows.
bool is_formula_function(std::string_view name);

}  // namespace fuzzygait::fuzzy

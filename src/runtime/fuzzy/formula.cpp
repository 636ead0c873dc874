#include "fuzzygait/fuzzy/formula.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "fuzzygait/fuzzy/compare.hpp"
#include "fuzzygait/fuzzy/term.hpp"

namespace fuzzygait::fuzzy {
namespace {

enum class Fn : std::uint8_t {
  // operators
  LogicalNot,
  Negate,
  Power,
  Multiply,
  Divide,
  Modulo,
  Add,
  Subtract,
  LogicalAnd,
  LogicalOr,
  // functions
  Gt,
  Ge,
  Eq,
  Neq,
  Le,
  Lt,
  Min,
  Max,
  Acos,
  Asin,
  Atan,
  Ceil,
  Cos,
  Cosh,
  Exp,
  Abs,
  Fabs,
  Floor,
  Log,
  Log10,
  Round,
  Sin,
  Sinh,
  Sqrt,
  Tan,
  Tanh,
  Log1p,
  Acosh,
  Asinh,
  Atanh,
  Pow,
  Atan2,
  Fmod,
};

struct Element {
  std::string_view name;
  Fn fn;
  bool is_operator;
  int arity;
  int precedence;
  int associativity;  // -1 left, 1 right
};

// fuzzylite's FunctionFactory, with its precedences and associativities. One element a line
// (clang-format would pack two), so the table reads as a table.
// clang-format off
constexpr std::array<Element, 43> kElements = {{
    {"!", Fn::LogicalNot, true, 1, 100, 1},
    {"~", Fn::Negate, true, 1, 100, 1},
    {"^", Fn::Power, true, 2, 90, 1},
    {"*", Fn::Multiply, true, 2, 80, -1},
    {"/", Fn::Divide, true, 2, 80, -1},
    {"%", Fn::Modulo, true, 2, 80, -1},
    {"+", Fn::Add, true, 2, 70, -1},
    {"-", Fn::Subtract, true, 2, 70, -1},
    {"and", Fn::LogicalAnd, true, 2, 60, -1},
    {"or", Fn::LogicalOr, true, 2, 50, -1},
    {"gt", Fn::Gt, false, 2, 0, -1},
    {"ge", Fn::Ge, false, 2, 0, -1},
    {"eq", Fn::Eq, false, 2, 0, -1},
    {"neq", Fn::Neq, false, 2, 0, -1},
    {"le", Fn::Le, false, 2, 0, -1},
    {"lt", Fn::Lt, false, 2, 0, -1},
    {"min", Fn::Min, false, 2, 0, -1},
    {"max", Fn::Max, false, 2, 0, -1},
    {"acos", Fn::Acos, false, 1, 0, -1},
    {"asin", Fn::Asin, false, 1, 0, -1},
    {"atan", Fn::Atan, false, 1, 0, -1},
    {"ceil", Fn::Ceil, false, 1, 0, -1},
    {"cos", Fn::Cos, false, 1, 0, -1},
    {"cosh", Fn::Cosh, false, 1, 0, -1},
    {"exp", Fn::Exp, false, 1, 0, -1},
    {"abs", Fn::Abs, false, 1, 0, -1},
    {"fabs", Fn::Fabs, false, 1, 0, -1},
    {"floor", Fn::Floor, false, 1, 0, -1},
    {"log", Fn::Log, false, 1, 0, -1},
    {"log10", Fn::Log10, false, 1, 0, -1},
    {"round", Fn::Round, false, 1, 0, -1},
    {"sin", Fn::Sin, false, 1, 0, -1},
    {"sinh", Fn::Sinh, false, 1, 0, -1},
    {"sqrt", Fn::Sqrt, false, 1, 0, -1},
    {"tan", Fn::Tan, false, 1, 0, -1},
    {"tanh", Fn::Tanh, false, 1, 0, -1},
    {"log1p", Fn::Log1p, false, 1, 0, -1},
    {"acosh", Fn::Acosh, false, 1, 0, -1},
    {"asinh", Fn::Asinh, false, 1, 0, -1},
    {"atanh", Fn::Atanh, false, 1, 0, -1},
    {"pow", Fn::Pow, false, 2, 0, -1},
    {"atan2", Fn::Atan2, false, 2, 0, -1},
    {"fmod", Fn::Fmod, false, 2, 0, -1},
}};
// clang-format on

const Element* find_element(std::string_view token) {
  for (const Element& e : kElements) {
    if (e.name == token) return &e;
  }
  return nullptr;
}

// fuzzylite's Function::space: surrounds parentheses, commas and the symbol operators with
// blanks, then splits on blanks.
std::vector<std::string> tokenize(std::string_view formula) {
  std::vector<std::string> tokens;
  std::string current;
  auto flush = [&]() {
    if (!current.empty()) tokens.push_back(std::move(current));
    current.clear();
  };
  for (char c : formula) {
    switch (c) {
      case '(':
      case ')':
      case ',':
      case '!':
      case '~':
      case '^':
      case '*':
      case '/':
      case '%':
      case '+':
      case '-':
        flush();
        tokens.emplace_back(1, c);
        break;
      case ' ':
      case '\t':
      case '\n':
      case '\r':
      case '\v':
      case '\f':
        flush();
        break;
      default:
        current += c;
    }
  }
  flush();
  return tokens;
}

std::invalid_argument parentheses_error(std::string_view formula) {
  return std::invalid_argument("mismatching parentheses in '" + std::string(formula) + "'");
}

double round_half_away(double x) {
  return x > 0.0 ? std::floor(x + 0.5) : std::ceil(x - 0.5);
}

double call(Fn fn, double a, double b) {
  switch (fn) {
    case Fn::LogicalNot:
      return is_eq(a, 1.0) ? 0.0 : 1.0;
    case Fn::Negate:
      return -a;
    case Fn::Power:
    case Fn::Pow:
      return std::pow(a, b);
    case Fn::Multiply:
      return a * b;
    case Fn::Divide:
      return a / b;
    case Fn::Modulo:
    case Fn::Fmod:
      return std::fmod(a, b);
    case Fn::Add:
      return a + b;
    case Fn::Subtract:
      return a - b;
    case Fn::LogicalAnd:
      return (is_eq(a, 1.0) && is_eq(b, 1.0)) ? 1.0 : 0.0;
    case Fn::LogicalOr:
      return (is_eq(a, 1.0) || is_eq(b, 1.0)) ? 1.0 : 0.0;
    case Fn::Gt:
      return is_gt(a, b);
    case Fn::Ge:
      return is_ge(a, b);
    case Fn::Eq:
      return is_eq(a, b);
    case Fn::Neq:
      return !is_eq(a, b);
    case Fn::Le:
      return is_le(a, b);
    case Fn::Lt:
      return is_lt(a, b);
    case Fn::Min:
      return nan_min(a, b);
    case Fn::Max:
      return nan_max(a, b);
    case Fn::Acos:
      return std::acos(a);
    case Fn::Asin:
      return std::asin(a);
    case Fn::Atan:
      return std::atan(a);
    case Fn::Ceil:
      return std::ceil(a);
    case Fn::Cos:
      return std::cos(a);
    case Fn::Cosh:
      return std::cosh(a);
    case Fn::Exp:
      return std::exp(a);
    case Fn::Abs:
    case Fn::Fabs:
      return std::fabs(a);
    case Fn::Floor:
      return std::floor(a);
    case Fn::Log:
      return std::log(a);
    case Fn::Log10:
      return std::log10(a);
    case Fn::Round:
      return round_half_away(a);
    case Fn::Sin:
      return std::sin(a);
    case Fn::Sinh:
      return std::sinh(a);
    case Fn::Sqrt:
      return std::sqrt(a);
    case Fn::Tan:
      return std::tan(a);
    case Fn::Tanh:
      return std::tanh(a);
    case Fn::Log1p:
      return std::log1p(a);
    case Fn::Acosh:
      return std::acosh(a);
    case Fn::Asinh:
      return std::asinh(a);
    case Fn::Atanh:
      return std::atanh(a);
    case Fn::Atan2:
      return std::atan2(a, b);
  }
  return std::nan("");
}

}  // namespace

bool is_formula_function(std::string_view name) {
  return find_element(name) != nullptr;
}

std::vector<std::string> to_postfix(std::string_view infix) {
  std::vector<std::string> queue;
  std::vector<std::string> stack;
  for (std::string& token : tokenize(infix)) {
    const Element* element = find_element(token);
    const bool parenthesis_or_comma = token == "(" || token == ")" || token == ",";
    if (!element && !parenthesis_or_comma) {
      queue.push_back(std::move(token));
    } else if (element && !element->is_operator) {
      stack.push_back(std::move(token));
    } else if (token == ",") {
      while (!stack.empty() && stack.back() != "(") {
        queue.push_back(std::move(stack.back()));
        stack.pop_back();
      }
      if (stack.empty()) throw parentheses_error(infix);
    } else if (element) {
      for (;;) {
        const Element* top = stack.empty() ? nullptr : find_element(stack.back());
        if (!top) break;
        if ((element->associativity < 0 && element->precedence == top->precedence) ||
            element->precedence < top->precedence) {
          queue.push_back(std::move(stack.back()));
          stack.pop_back();
        } else {
          break;
        }
      }
      stack.push_back(std::move(token));
    } else if (token == "(") {
      stack.push_back(std::move(token));
    } else {  // ")"
      while (!stack.empty() && stack.back() != "(") {
        queue.push_back(std::move(stack.back()));
        stack.pop_back();
      }
      if (stack.empty()) throw parentheses_error(infix);
      stack.pop_back();
      if (!stack.empty()) {
        const Element* top = find_element(stack.back());
        if (top && !top->is_operator) {
          queue.push_back(std::move(stack.back()));
          stack.pop_back();
        }
      }
    }
  }
  while (!stack.empty()) {
    if (stack.back() == "(" || stack.back() == ")") throw parentheses_error(infix);
    queue.push_back(std::move(stack.back()));
    stack.pop_back();
  }
  return queue;
}

FormulaProgram compile_formula(std::string_view infix) {
  FormulaProgram program;
  program.text = std::string(infix);
  if (infix.find_first_not_of(" \t\r\n") == std::string_view::npos) {
    throw std::invalid_argument("the formula is empty");
  }
  std::size_t depth = 0;
  for (const std::string& token : to_postfix(infix)) {
    FormulaInstruction instruction{};
    if (const Element* element = find_element(token)) {
      if (static_cast<std::size_t>(element->arity) > depth) {
        throw std::invalid_argument(std::string(element->is_operator ? "operator" : "function") +
                                    " '" + token + "' needs " + std::to_string(element->arity) +
                                    " operand" + (element->arity == 1 ? "" : "s") + " but has " +
                                    std::to_string(depth) + " in '" + program.text + "'");
      }
      instruction.kind =
          element->arity == 1 ? FormulaInstruction::Kind::Unary : FormulaInstruction::Kind::Binary;
      instruction.function = static_cast<std::uint8_t>(element->fn);
      depth -= static_cast<std::size_t>(element->arity - 1);
    } else if (const std::optional<double> value = parse_scalar(token)) {
      instruction.kind = FormulaInstruction::Kind::Constant;
      instruction.value = *value;
      ++depth;
    } else {
      instruction.kind = FormulaInstruction::Kind::Variable;
      const auto found = std::find(program.variables.begin(), program.variables.end(), token);
      instruction.slot = static_cast<std::uint32_t>(found - program.variables.begin());
      if (found == program.variables.end()) program.variables.push_back(token);
      ++depth;
    }
    program.stack_size = std::max(program.stack_size, depth);
    program.code.push_back(instruction);
  }
  if (depth != 1) {
    throw std::invalid_argument("ill-formed formula '" + program.text + "'");
  }
  return program;
}

double evaluate_formula(const FormulaProgram& program, const double* values, double* stack) {
  std::size_t top = 0;
  for (const FormulaInstruction& instruction : program.code) {
    switch (instruction.kind) {
      case FormulaInstruction::Kind::Constant:
        stack[top++] = instruction.value;
        break;
      case FormulaInstruction::Kind::Variable:
        stack[top++] = values[instruction.slot];
        break;
      case FormulaInstruction::Kind::Unary:
        stack[top - 1] = call(static_cast<Fn>(instruction.function), stack[top - 1], 0.0);
        break;
      case FormulaInstruction::Kind::Binary:
        stack[top - 2] =
            call(static_cast<Fn>(instruction.function), stack[top - 2], stack[top - 1]);
        --top;
        break;
    }
  }
  return stack[0];
}

}  // namespace fuzzygait::fuzzy

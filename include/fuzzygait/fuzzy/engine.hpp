// The editable fuzzy model, mirroring fuzzylite's FLL language: an Engine holds input and
// output variables and rule blocks. It is plain data an artist or a tool edits; compile it into
// an Evaluator to run it.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fuzzygait/fuzzy/operators.hpp"
#include "fuzzygait/fuzzy/term.hpp"

namespace fuzzygait::fuzzy {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct InputVariable {
  std::string name;
  std::string description;
  bool enabled = true;
  double minimum = -kInfinity;
  double maximum = kInfinity;
  bool lock_range = false;  // clamp incoming values to [minimum, maximum]
  std::vector<Term> terms;

  const Term* find_term(std::string_view term_name) const;
  bool operator==(const InputVariable& other) const;  // NaN equals NaN
};

struct Defuzzifier {
  enum class Kind : std::uint8_t {
    Bisector,
    Centroid,
    LargestOfMaximum,
    MeanOfMaximum,
    SmallestOfMaximum,
    WeightedAverage,
    WeightedSum,
  };
  // How a weighted defuzzifier reads a term. Automatic reads every term as Tsukamoto does, which
  // for Constant, Linear and Function terms is their value (fuzzylite 6 infers the type from the
  // activated wrapper, never a Constant, so Automatic always means Tsukamoto).
  enum class WeightedType : std::uint8_t { Automatic, TakagiSugeno, Tsukamoto };

  // Most samples an integral defuzzifier takes: each evaluation costs resolution times the
  // activated terms, and the workspace holds three arrays of up to twice this size (Bisector
  // samples from both ends).
  static constexpr int kMaxResolution = 1'000'000;

  Kind kind = Kind::Centroid;
  int resolution = 100;  // samples across the range, integral defuzzifiers
  WeightedType type = WeightedType::Automatic;

  bool is_integral() const { return kind < Kind::WeightedAverage; }
  bool operator==(const Defuzzifier&) const = default;
};

std::string_view name(Defuzzifier::Kind kind);
std::string_view name(Defuzzifier::WeightedType type);
std::optional<Defuzzifier::Kind> defuzzifier_from_name(std::string_view text);
std::optional<Defuzzifier::WeightedType> weighted_type_from_name(std::string_view text);

struct OutputVariable {
  std::string name;
  std::string description;
  bool enabled = true;
  double minimum = -kInfinity;
  double maximum = kInfinity;
  bool lock_range = false;
  SNorm aggregation = SNorm::None;
  std::optional<Defuzzifier> defuzzifier;
  double default_value = kNaN;  // value when no rule fires
  bool lock_previous = false;   // when no rule fires, keep the last valid value instead
  std::vector<Term> terms;

  const Term* find_term(std::string_view term_name) const;
  bool operator==(const OutputVariable& other) const;  // NaN equals NaN
};

struct Activation {
  enum class Kind : std::uint8_t {
    None,  // written as "none"; evaluates as General
    General,
    Proportional,
    Threshold,
    First,
    Last,
    Highest,
    Lowest,
  };
  enum class Comparison : std::uint8_t {
    Less,
    LessOrEqual,
    Equal,
    NotEqual,
    GreaterOrEqual,
    Greater
  };

  Kind kind = Kind::General;
  int number_of_rules = 1;                             // First, Last, Highest, Lowest
  double threshold = 0.0;                              // First, Last, Threshold
  Comparison comparison = Comparison::GreaterOrEqual;  // Threshold

  std::string text() const;  // FLL text, e.g. "Threshold >= 0.5"
  bool operator==(const Activation& other) const;
};
std::optional<Activation::Kind> activation_from_name(std::string_view text);
std::optional<Activation::Comparison> comparison_from_name(std::string_view text);

// "variable is [hedges] term", or "variable is [hedges] any" (then `term` is empty).
struct Proposition {
  std::string variable;
  bool output = false;        // refers to an output variable (chained engines)
  std::vector<Hedge> hedges;  // in reading order; applied last-to-first
  std::string term;
  bool operator==(const Proposition&) const = default;
};

struct Rule {
  // Antecedent in postfix: each entry is a proposition index, or kAnd / kOr.
  static constexpr int kAnd = -1;
  static constexpr int kOr = -2;
  std::vector<Proposition> propositions;
  std::vector<int> antecedent;
  std::vector<Proposition> conclusions;
  double weight = 1.0;

  std::string text() const;  // normalised FLL text: "if ... then ... [with w]"
  bool operator==(const Rule& other) const;
};

struct RuleBlock {
  std::string name;
  std::string description;
  bool enabled = true;
  TNorm conjunction = TNorm::None;
  SNorm disjunction = SNorm::None;
  TNorm implication = TNorm::None;
  Activation activation;
  std::vector<Rule> rules;
  bool operator==(const RuleBlock&) const = default;
};

enum class EngineType : std::uint8_t {
  Unknown,
  Mamdani,
  Larsen,
  TakagiSugeno,
  Tsukamoto,
  InverseTsukamoto,
  Hybrid,
};
std::string_view name(EngineType type);

struct Engine {
  std::string name;
  std::string description;
  std::vector<InputVariable> inputs;
  std::vector<OutputVariable> outputs;
  std::vector<RuleBlock> rule_blocks;

  const InputVariable* find_input(std::string_view variable_name) const;
  const OutputVariable* find_output(std::string_view variable_name) const;
  // fuzzylite's classification of the inference the engine performs.
  EngineType type() const;
  // Problems that stop the engine from being evaluated, one sentence each; empty when ready.
  std::vector<std::string> problems() const;
  // Its numbers that are nan or infinite (ranges, term parameters and heights, defaults, rule
  // weights), one phrase each naming where. fuzzylite evaluates such engines; a joint controller
  // refuses them (gait::Controller).
  std::vector<std::string> non_finite_numbers() const;
  bool operator==(const Engine&) const = default;
};

// Parses rule text against the engine's variables and terms, with fuzzylite's grammar:
// "if A is [hedges] t [and|or ...] then B is [hedges] u [and ...] [with weight]".
// Throws std::invalid_argument with a message naming the unexpected word.
Rule parse_rule(std::string_view text, const Engine& engine);

}  // namespace fuzzygait::fuzzy

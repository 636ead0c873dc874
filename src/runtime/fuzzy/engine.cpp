#include "fuzzygait/fuzzy/engine.hpp"

#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "fuzzygait/fuzzy/compare.hpp"
#include "fuzzygait/fuzzy/formula.hpp"
#include "text.hpp"

namespace fuzzygait::fuzzy {
namespace {

// The element of `list` with that name (variables, terms), or nullptr.
template <class Named>
const Named* find_named(const std::vector<Named>& list, std::string_view name) {
  for (const Named& item : list) {
    if (item.name == name) return &item;
  }
  return nullptr;
}

template <class Enum, std::size_t N>
std::optional<Enum> lookup(const std::array<std::string_view, N>& names, std::string_view text) {
  for (std::size_t i = 0; i < N; ++i) {
    if (names[i] == text) return static_cast<Enum>(i);
  }
  return std::nullopt;
}

constexpr std::array<std::string_view, 8> kTNormNames = {
    "none",           "AlgebraicProduct", "BoundedDifference",
    "DrasticProduct", "EinsteinProduct",  "HamacherProduct",
    "Minimum",        "NilpotentMinimum"};
constexpr std::array<std::string_view, 10> kSNormNames = {
    "none",        "AlgebraicSum", "BoundedSum",       "DrasticSum",    "EinsteinSum",
    "HamacherSum", "Maximum",      "NilpotentMaximum", "NormalizedSum", "UnboundedSum"};
constexpr std::array<std::string_view, 6> kHedgeNames = {"any",    "extremely", "not",
                                                         "seldom", "somewhat",  "very"};
constexpr std::array<std::string_view, 7> kDefuzzifierNames = {
    "Bisector",          "Centroid",        "LargestOfMaximum", "MeanOfMaximum",
    "SmallestOfMaximum", "WeightedAverage", "WeightedSum"};
constexpr std::array<std::string_view, 3> kWeightedTypeNames = {"Automatic", "TakagiSugeno",
                                                                "Tsukamoto"};
constexpr std::array<std::string_view, 8> kActivationNames = {
    "none", "General", "Proportional", "Threshold", "First", "Last", "Highest", "Lowest"};
constexpr std::array<std::string_view, 6> kComparisonNames = {"<", "<=", "==", "!=", ">=", ">"};

// Rule text splits into words on any white space.
constexpr std::string_view kWordSeparators = " \t\n\r\v\f";

// In an antecedent, which goes through the formula language's infix-to-postfix conversion, a
// name that is also a function or operator of that language ("max", "and") is parenthesised
// so that it stays in place when read back.
std::string proposition_text(const Proposition& p, bool antecedent) {
  auto word = [antecedent](const std::string& name) {
    return antecedent && is_formula_function(name) ? "(" + name + ")" : name;
  };
  std::string out = word(p.variable) + " is";
  for (Hedge h : p.hedges) {
    out += ' ';
    out += name(h);
  }
  if (!p.term.empty()) out += " " + word(p.term);
  return out;
}

bool has_term(const Engine& engine, const Proposition& p) {
  if (p.output) {
    const OutputVariable* v = engine.find_output(p.variable);
    return v && v->find_term(p.term);
  }
  const InputVariable* v = engine.find_input(p.variable);
  return v && v->find_term(p.term);
}

}  // namespace

std::string_view name(TNorm norm) {
  return kTNormNames.at(static_cast<std::size_t>(norm));
}
std::string_view name(SNorm norm) {
  return kSNormNames.at(static_cast<std::size_t>(norm));
}
std::string_view name(Hedge hedge) {
  return kHedgeNames.at(static_cast<std::size_t>(hedge));
}
std::optional<TNorm> tnorm_from_name(std::string_view text) {
  return lookup<TNorm>(kTNormNames, text);
}
std::optional<SNorm> snorm_from_name(std::string_view text) {
  return lookup<SNorm>(kSNormNames, text);
}
std::optional<Hedge> hedge_from_name(std::string_view text) {
  return lookup<Hedge>(kHedgeNames, text);
}
std::string_view name(Defuzzifier::Kind kind) {
  return kDefuzzifierNames.at(static_cast<std::size_t>(kind));
}
std::string_view name(Defuzzifier::WeightedType type) {
  return kWeightedTypeNames.at(static_cast<std::size_t>(type));
}
std::optional<Defuzzifier::Kind> defuzzifier_from_name(std::string_view text) {
  return lookup<Defuzzifier::Kind>(kDefuzzifierNames, text);
}
std::optional<Defuzzifier::WeightedType> weighted_type_from_name(std::string_view text) {
  return lookup<Defuzzifier::WeightedType>(kWeightedTypeNames, text);
}
std::optional<Activation::Kind> activation_from_name(std::string_view text) {
  return lookup<Activation::Kind>(kActivationNames, text);
}
std::optional<Activation::Comparison> comparison_from_name(std::string_view text) {
  return lookup<Activation::Comparison>(kComparisonNames, text);
}

std::string_view name(EngineType type) {
  static constexpr std::array<std::string_view, 7> kNames = {
      "Unknown", "Mamdani", "Larsen", "Takagi-Sugeno", "Tsukamoto", "Inverse Tsukamoto", "Hybrid"};
  return kNames.at(static_cast<std::size_t>(type));
}

std::string Activation::text() const {
  std::string out(kActivationNames.at(static_cast<std::size_t>(kind)));
  switch (kind) {
    case Kind::Threshold:
      out += " " + std::string(kComparisonNames.at(static_cast<std::size_t>(comparison))) + " " +
             format_scalar(threshold);
      break;
    case Kind::First:
    case Kind::Last:
      out += " " + std::to_string(number_of_rules) + " " + format_scalar(threshold);
      break;
    case Kind::Highest:
    case Kind::Lowest:
      out += " " + std::to_string(number_of_rules);
      break;
    default:
      break;
  }
  return out;
}

bool Activation::operator==(const Activation& other) const {
  return kind == other.kind && number_of_rules == other.number_of_rules &&
         is_same_value(threshold, other.threshold) && comparison == other.comparison;
}

const Term* InputVariable::find_term(std::string_view term_name) const {
  return find_named(terms, term_name);
}

const Term* OutputVariable::find_term(std::string_view term_name) const {
  return find_named(terms, term_name);
}

bool InputVariable::operator==(const InputVariable& other) const {
  return name == other.name && description == other.description && enabled == other.enabled &&
         is_same_value(minimum, other.minimum) && is_same_value(maximum, other.maximum) &&
         lock_range == other.lock_range && terms == other.terms;
}

bool OutputVariable::operator==(const OutputVariable& other) const {
  return name == other.name && description == other.description && enabled == other.enabled &&
         is_same_value(minimum, other.minimum) && is_same_value(maximum, other.maximum) &&
         lock_range == other.lock_range && aggregation == other.aggregation &&
         defuzzifier == other.defuzzifier && is_same_value(default_value, other.default_value) &&
         lock_previous == other.lock_previous && terms == other.terms;
}

bool Rule::operator==(const Rule& other) const {
  return propositions == other.propositions && antecedent == other.antecedent &&
         conclusions == other.conclusions && is_same_value(weight, other.weight);
}

std::string Rule::text() const {
  // Rebuild infix from postfix; parenthesise where the parse would otherwise change the tree
  // (`and` binds tighter than `or`, both associate to the left).
  struct Node {
    std::string text;
    int precedence;  // 2 proposition, 1 and, 0 or
  };
  std::vector<Node> stack;
  for (int token : antecedent) {
    if (token >= 0) {
      stack.push_back(
          {proposition_text(propositions.at(static_cast<std::size_t>(token)), true), 2});
      continue;
    }
    const int precedence = token == kAnd ? 1 : 0;
    Node right = std::move(stack.back());
    stack.pop_back();
    Node left = std::move(stack.back());
    stack.pop_back();
    if (left.precedence < precedence) left.text = "(" + left.text + ")";
    if (right.precedence <= precedence) right.text = "(" + right.text + ")";
    stack.push_back({left.text + (token == kAnd ? " and " : " or ") + right.text, precedence});
  }
  std::string out = "if " + (stack.empty() ? std::string() : stack.back().text) + " then ";
  for (std::size_t i = 0; i < conclusions.size(); ++i) {
    if (i > 0) out += " and ";
    out += proposition_text(conclusions[i], false);
  }
  if (!(weight == 1.0)) out += " with " + format_scalar(weight);
  return out;
}

const InputVariable* Engine::find_input(std::string_view variable_name) const {
  return find_named(inputs, variable_name);
}

const OutputVariable* Engine::find_output(std::string_view variable_name) const {
  return find_named(outputs, variable_name);
}

EngineType Engine::type() const {
  if (outputs.empty()) return EngineType::Unknown;
  bool mamdani = true;
  for (const OutputVariable& v : outputs) {
    mamdani = mamdani && v.defuzzifier && v.defuzzifier->is_integral();
  }
  if (mamdani) {
    bool larsen = !rule_blocks.empty();
    for (const RuleBlock& b : rule_blocks)
      larsen = larsen && b.implication == TNorm::AlgebraicProduct;
    return larsen ? EngineType::Larsen : EngineType::Mamdani;
  }
  auto weighted_all = [this](Defuzzifier::WeightedType wanted, auto term_ok) {
    for (const OutputVariable& v : outputs) {
      if (!v.defuzzifier || v.defuzzifier->is_integral()) return false;
      if (v.defuzzifier->type != Defuzzifier::WeightedType::Automatic &&
          v.defuzzifier->type != wanted) {
        return false;
      }
      for (const Term& t : v.terms) {
        if (!term_ok(t)) return false;
      }
    }
    return true;
  };
  auto takagi_sugeno_term = [](const Term& t) {
    return t.kind == TermKind::Constant || t.kind == TermKind::Linear ||
           t.kind == TermKind::Function;
  };
  if (weighted_all(Defuzzifier::WeightedType::TakagiSugeno, takagi_sugeno_term)) {
    return EngineType::TakagiSugeno;
  }
  if (weighted_all(Defuzzifier::WeightedType::Tsukamoto,
                   [](const Term& t) { return shape_info(t.kind).monotonic; })) {
    return EngineType::Tsukamoto;
  }
  bool all_weighted = true;
  bool all_defuzzified = true;
  for (const OutputVariable& v : outputs) {
    all_weighted = all_weighted && v.defuzzifier && !v.defuzzifier->is_integral();
    all_defuzzified = all_defuzzified && v.defuzzifier.has_value();
  }
  if (all_weighted) return EngineType::InverseTsukamoto;
  if (all_defuzzified) return EngineType::Hybrid;
  return EngineType::Unknown;
}

std::vector<std::string> Engine::non_finite_numbers() const {
  std::vector<std::string> out;
  auto check = [&out](const std::string& where, double value) {
    if (!std::isfinite(value)) out.push_back(where + " is " + format_scalar(value));
  };
  auto check_variable = [&](const char* kind, const std::string& variable_name, double minimum,
                            double maximum, const std::vector<Term>& terms) {
    const std::string variable = std::string(kind) + " '" + variable_name + "'";
    check(variable + " range minimum", minimum);
    check(variable + " range maximum", maximum);
    for (const Term& t : terms) {
      for (std::size_t i = 0; i < t.parameters.size(); ++i) {
        check(variable + " term '" + t.name + "' parameter " + parameter_label(t, i),
              t.parameters[i]);
      }
      check(variable + " term '" + t.name + "' height", t.height);
      for (const double constant : formula_constants(t))
        check(variable + " term '" + t.name + "' formula constant", constant);
    }
  };
  for (const InputVariable& v : inputs)
    check_variable("input", v.name, v.minimum, v.maximum, v.terms);
  for (const OutputVariable& v : outputs) {
    check_variable("output", v.name, v.minimum, v.maximum, v.terms);
    check("output '" + v.name + "' default", v.default_value);
  }
  for (const RuleBlock& b : rule_blocks) {
    check("rule block '" + b.name + "' activation threshold", b.activation.threshold);
    for (const Rule& r : b.rules)
      check("the weight of rule '" + r.text() + "'", r.weight);
  }
  return out;
}

std::vector<std::string> Engine::problems() const {
  std::vector<std::string> out;
  for (const OutputVariable& v : outputs) {
    if (!v.defuzzifier) out.push_back("output variable '" + v.name + "' has no defuzzifier");
    if (v.defuzzifier && v.defuzzifier->is_integral()) {
      if (v.aggregation == SNorm::None) {
        out.push_back("output variable '" + v.name + "' has an integral defuzzifier (" +
                      std::string(fuzzy::name(v.defuzzifier->kind)) + ") but no aggregation");
      }
      if (v.defuzzifier->resolution < 1 ||
          v.defuzzifier->resolution > Defuzzifier::kMaxResolution) {
        out.push_back("output variable '" + v.name + "' has a defuzzifier resolution of " +
                      std::to_string(v.defuzzifier->resolution) + "; it must be from 1 to " +
                      std::to_string(Defuzzifier::kMaxResolution));
      }
    }
  }
  auto check_terms = [&](const std::string& variable, const std::vector<Term>& terms) {
    for (const Term& t : terms) {
      if (t.kind != TermKind::Function) continue;
      for (const std::string& symbol : compile_formula(t.formula).variables) {
        if (symbol != "x" && !find_input(symbol) && !find_output(symbol)) {
          out.push_back("term '" + t.name + "' of '" + variable + "' uses unknown variable '" +
                        symbol + "' in its formula");
        }
      }
    }
  };
  for (const InputVariable& v : inputs)
    check_terms(v.name, v.terms);
  for (const OutputVariable& v : outputs)
    check_terms(v.name, v.terms);
  for (std::size_t b = 0; b < rule_blocks.size(); ++b) {
    const RuleBlock& block = rule_blocks[b];
    const std::string where =
        "rule block " + std::to_string(b + 1) + (block.name.empty() ? "" : " '" + block.name + "'");
    bool needs_conjunction = false;
    bool needs_disjunction = false;
    bool needs_implication = false;
    for (const Rule& rule : block.rules) {
      for (int token : rule.antecedent) {
        needs_conjunction = needs_conjunction || token == Rule::kAnd;
        needs_disjunction = needs_disjunction || token == Rule::kOr;
      }
      for (const Proposition& p : rule.propositions) {
        const bool any = !p.hedges.empty() && p.hedges.back() == Hedge::Any;
        if (!any && !has_term(*this, p)) {
          out.push_back(where + ": rule '" + rule.text() + "' refers to unknown '" + p.variable +
                        " is " + p.term + "'");
        }
      }
      for (const Proposition& p : rule.conclusions) {
        const OutputVariable* v = find_output(p.variable);
        if (!v || !v->find_term(p.term)) {
          out.push_back(where + ": rule '" + rule.text() + "' concludes unknown '" + p.variable +
                        " is " + p.term + "'");
        } else if (v->defuzzifier && v->defuzzifier->is_integral()) {
          needs_implication = true;
        }
      }
    }
    if (needs_conjunction && block.conjunction == TNorm::None) {
      out.push_back(where + " has rules with 'and' but no conjunction");
    }
    if (needs_disjunction && block.disjunction == SNorm::None) {
      out.push_back(where + " has rules with 'or' but no disjunction");
    }
    if (needs_implication && block.implication == TNorm::None) {
      out.push_back(where + " concludes into integral-defuzzified outputs but has no implication");
    }
    const Activation& a = block.activation;
    const bool counted = a.kind == Activation::Kind::First || a.kind == Activation::Kind::Last ||
                         a.kind == Activation::Kind::Highest || a.kind == Activation::Kind::Lowest;
    if (counted && a.number_of_rules < 0) {
      out.push_back(where + ": activation " + a.text() + " needs a number of rules >= 0");
    }
  }
  return out;
}

Rule parse_rule(std::string_view text, const Engine& engine) {
  const std::string_view body = text.substr(0, text.find('#'));
  const std::string quoted = "'" + std::string(text) + "'";
  enum class State { None, If, Then, With, End };
  State state = State::None;
  std::string antecedent_text;
  std::vector<std::string_view> consequent_words;
  Rule rule;
  for (std::string_view word : split_words(body, kWordSeparators)) {
    switch (state) {
      case State::None:
        if (word != "if") {
          throw std::invalid_argument("rule " + quoted + " must start with 'if', found '" +
                                      std::string(word) + "'");
        }
        state = State::If;
        break;
      case State::If:
        if (word == "then") {
          state = State::Then;
        } else {
          antecedent_text += std::string(word) + " ";
        }
        break;
      case State::Then:
        if (word == "with") {
          state = State::With;
        } else {
          consequent_words.push_back(word);
        }
        break;
      case State::With: {
        const std::optional<double> weight = parse_scalar(word);
        if (!weight) {
          throw std::invalid_argument("rule " + quoted + ": the weight after 'with' must be a " +
                                      "number, found '" + std::string(word) + "'");
        }
        rule.weight = *weight;
        state = State::End;
        break;
      }
      case State::End:
        throw std::invalid_argument("rule " + quoted + ": unexpected '" + std::string(word) +
                                    "' after the weight");
    }
  }
  if (state == State::None) throw std::invalid_argument("empty rule");
  if (state == State::If) throw std::invalid_argument("rule " + quoted + " has no 'then'");
  if (state == State::With) {
    throw std::invalid_argument("rule " + quoted + " has 'with' but no weight");
  }
  if (split_words(antecedent_text, kWordSeparators).empty()) {
    throw std::invalid_argument("rule " + quoted + " has nothing between 'if' and 'then'");
  }

  // Antecedent: fuzzylite's state machine over the postfix form.
  enum : int { kVariable = 1, kIs = 2, kHedge = 4, kTerm = 8, kAndOr = 16 };
  int expect = kVariable;
  int depth = 0;
  Proposition* current = nullptr;
  std::string last;
  auto fail = [&](const std::string& what) {
    throw std::invalid_argument("rule " + quoted + ": " + what);
  };
  for (const std::string& token : to_postfix(antecedent_text)) {
    last = token;
    if (expect & kVariable) {
      const bool input = engine.find_input(token) != nullptr;
      const bool output = !input && engine.find_output(token) != nullptr;
      if (input || output) {
        rule.propositions.push_back(Proposition{token, output, {}, {}});
        current = &rule.propositions.back();
        rule.antecedent.push_back(static_cast<int>(rule.propositions.size()) - 1);
        ++depth;
        expect = kIs;
        continue;
      }
    }
    if ((expect & kIs) && token == "is") {
      expect = kHedge | kTerm;
      continue;
    }
    if (expect & kHedge) {
      if (const std::optional<Hedge> hedge = hedge_from_name(token)) {
        current->hedges.push_back(*hedge);
        expect = *hedge == Hedge::Any ? (kVariable | kAndOr) : (kHedge | kTerm);
        continue;
      }
    }
    if (expect & kTerm) {
      const bool known = current->output
                             ? engine.find_output(current->variable)->find_term(token) != nullptr
                             : engine.find_input(current->variable)->find_term(token) != nullptr;
      if (known) {
        current->term = token;
        expect = kVariable | kAndOr;
        continue;
      }
    }
    if ((expect & kAndOr) && (token == "and" || token == "or")) {
      if (depth < 2) fail("'" + token + "' needs two operands");
      rule.antecedent.push_back(token == "and" ? Rule::kAnd : Rule::kOr);
      --depth;
      expect = kVariable | kAndOr;
      continue;
    }
    if (expect & (kVariable | kAndOr)) {
      fail("expected an input or output variable, 'and' or 'or' but found '" + token + "'");
    }
    if (expect & kIs) fail("expected 'is' but found '" + token + "'");
    fail("'" + token + "' is neither a hedge nor a term of '" + current->variable + "'");
  }
  if (!(expect & (kVariable | kAndOr))) {
    if (expect & kIs) fail("expected 'is' after '" + last + "'");
    fail("expected a hedge or a term after '" + last + "'");
  }
  if (depth != 1) fail("the antecedent does not combine into one expression (missing 'and'/'or')");

  // Consequent: "output is [hedges] term [and ...]".
  enum : int { kOutput = 1, kIsWord = 2, kHedgeWord = 4, kTermWord = 8, kAnd = 16 };
  expect = kOutput;
  Proposition* conclusion = nullptr;
  std::string previous;
  for (std::string_view word_view : consequent_words) {
    const std::string word(word_view);
    previous = word;
    if (expect & kOutput) {
      if (engine.find_output(word)) {
        rule.conclusions.push_back(Proposition{word, true, {}, {}});
        conclusion = &rule.conclusions.back();
        expect = kIsWord;
        continue;
      }
      fail("expected an output variable after 'then' or 'and' but found '" + word + "'");
    }
    if ((expect & kIsWord) && word == "is") {
      expect = kHedgeWord | kTermWord;
      continue;
    }
    if (expect & kHedgeWord) {
      if (const std::optional<Hedge> hedge = hedge_from_name(word)) {
        conclusion->hedges.push_back(*hedge);
        continue;
      }
    }
    if ((expect & kTermWord) && engine.find_output(conclusion->variable)->find_term(word)) {
      conclusion->term = word;
      expect = kAnd;
      continue;
    }
    if ((expect & kAnd) && word == "and") {
      expect = kOutput;
      continue;
    }
    if (expect & kIsWord) fail("expected 'is' but found '" + word + "'");
    if (expect & kAnd) fail("expected 'and' or 'with' but found '" + word + "'");
    fail("'" + word + "' is neither a hedge nor a term of '" + conclusion->variable + "'");
  }
  if (expect != kAnd) {
    if (consequent_words.empty()) fail("nothing follows 'then'");
    if (expect & kOutput) fail("expected an output variable after '" + previous + "'");
    if (expect & kIsWord) fail("expected 'is' after '" + previous + "'");
    fail("expected a hedge or a term after '" + previous + "'");
  }
  return rule;
}

}  // namespace fuzzygait::fuzzy

#include "fuzzygait/fuzzy/fll.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <unordered_set>

#include "fuzzygait/fuzzy/formula.hpp"
#include "text.hpp"

namespace fuzzygait::fuzzy {
namespace {

std::string_view trim(std::string_view text) {
  const char* blanks = " \t\r\n\v\f";
  const std::size_t first = text.find_first_not_of(blanks);
  if (first == std::string_view::npos) return {};
  const std::size_t last = text.find_last_not_of(blanks);
  return text.substr(first, last - first + 1);
}

// Values split into words on spaces and tabs.
constexpr std::string_view kWordSeparators = " \t";

bool valid_name(std::string_view name) {
  if (name.empty()) return false;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '.';
    if (!ok) return false;
  }
  return true;
}

struct Entry {
  int line;
  std::string key;
  std::string value;
};

class Reader {
 public:
  Reader(std::string_view source, const FllOptions& options) : source_(source), options_(options) {}

  Engine read(std::string_view text) {
    std::vector<Entry> block;
    int number = 0;
    bool any_entry = false;
    std::size_t start = 0;
    while (start <= text.size()) {
      std::size_t end = text.find('\n', start);
      if (end == std::string_view::npos) end = text.size();
      std::string_view line = text.substr(start, end - start);
      start = end + 1;
      ++number;
      line = trim(line.substr(0, line.find('#')));
      if (line.empty()) continue;
      // A '\r' that does not end the line would end up inside a name or a description, which
      // no FLL file can hold: refuse it rather than guess what was meant.
      if (line.find('\r') != std::string_view::npos) {
        fail(number, "carriage return inside the line (lines end with '\\n' or '\\r\\n')");
      }
      const std::size_t colon = line.find(':');
      if (colon == std::string_view::npos) {
        fail(number, "expected 'key: value', found '" + std::string(line) + "'");
      }
      any_entry = true;
      Entry entry{number, std::string(trim(line.substr(0, colon))),
                  std::string(trim(line.substr(colon + 1)))};
      if (entry.key == "Engine") {
        engine_.name = entry.value;
        continue;
      }
      if (entry.key == "description" && block.empty()) {
        engine_.description = entry.value;
        continue;
      }
      if (entry.key == "InputVariable" || entry.key == "OutputVariable" ||
          entry.key == "RuleBlock") {
        process(block);
        block.clear();
      } else if (block.empty()) {
        fail(number,
             "'" + entry.key + "' must belong to an InputVariable, OutputVariable or RuleBlock");
      }
      block.push_back(std::move(entry));
    }
    // An empty file is a mistake (a truncated copy, the wrong path), not an engine.
    if (!any_entry) fail(1, "no engine: the text is empty (or only comments)");
    process(block);
    return std::move(engine_);
  }

 private:
  [[noreturn]] void fail(int line, const std::string& message) const {
    throw ParseError(source_, line, message);
  }

  bool boolean(const Entry& e) const {
    if (e.value == "true") return true;
    if (e.value == "false") return false;
    fail(e.line, "'" + e.key + "' must be true or false, found '" + e.value + "'");
  }

  double scalar(const Entry& e, std::string_view text, const std::string& what) const {
    const std::optional<double> v = parse_scalar(text);
    if (!v) fail(e.line, what + " must be a number, found '" + std::string(text) + "'");
    finite(e, *v, what);
    return *v;
  }

  // Under FllOptions::finite_numbers, a number that is nan or infinite is an error.
  void finite(const Entry& e, double value, const std::string& what) const {
    if (options_.finite_numbers && !std::isfinite(value)) {
      fail(e.line, what + " must be a finite number here, found '" + format_scalar(value) + "'");
    }
  }

  int count(const Entry& e, std::string_view text, const std::string& what) const {
    const double v = scalar(e, text, what);
    if (!(v == std::floor(v)) || v < -1e9 || v > 1e9) {
      fail(e.line, what + " must be a whole number, found '" + std::string(text) + "'");
    }
    return static_cast<int>(v);
  }

  std::string name(const Entry& e, const std::string& what) const {
    if (!valid_name(e.value)) {
      fail(e.line,
           what + " name '" + e.value + "' must be letters, digits, '_' or '.', and not empty");
    }
    // Rules read 'and' and 'or' as connectives, so no rule could name such a variable, and the
    // rule parser would take every connective for it.
    if (e.value == "and" || e.value == "or") {
      fail(e.line, what + " name '" + e.value + "' is a rule connective ('and', 'or')");
    }
    return e.value;
  }

  void range(const Entry& e, double& minimum, double& maximum) const {
    const std::vector<std::string_view> w = split_words(e.value, kWordSeparators);
    if (w.size() != 2) fail(e.line, "range must be two numbers 'minimum maximum'");
    minimum = scalar(e, w[0], "range minimum");
    maximum = scalar(e, w[1], "range maximum");
  }

  // Name sets rather than scans of the engine, so that checking a variable or term name for a
  // duplicate does not grow with the names before it (rules still find their variables and
  // terms by scanning the engine).
  void unique_variable(const Entry& e, const std::string& variable) {
    if (!variable_names_.insert(variable).second) {
      fail(e.line, "variable '" + variable + "' is defined twice");
    }
  }

  Term term(const Entry& e, std::unordered_set<std::string>& existing,
            const std::string& variable) const {
    const std::vector<std::string_view> w = split_words(e.value, kWordSeparators);
    if (w.size() < 2) fail(e.line, "a term needs 'name Shape parameters', found '" + e.value + "'");
    const std::string term_name(w[0]);
    if (!valid_name(term_name)) {
      fail(e.line, "term name '" + term_name + "' must be letters, digits, '_' or '.'");
    }
    if (!existing.insert(term_name).second) {
      fail(e.line, "term '" + term_name + "' is defined twice in '" + variable + "'");
    }
    const std::optional<TermKind> kind = term_kind_from_name(w[1]);
    if (!kind) fail(e.line, "unknown term shape '" + std::string(w[1]) + "'");
    const std::size_t rest =
        w.size() > 2 ? static_cast<std::size_t>(w[2].data() - e.value.data()) : e.value.size();
    Term made;
    try {
      made = make_term(term_name, *kind, std::string_view(e.value).substr(rest));
    } catch (const std::invalid_argument& error) {
      fail(e.line, error.what());
    }
    for (std::size_t i = 0; i < made.parameters.size(); ++i) {
      finite(e, made.parameters[i],
             "term '" + term_name + "' parameter " + parameter_label(made, i));
    }
    finite(e, made.height, "term '" + term_name + "' height");
    if (options_.ordered_points) {
      if (const std::string disorder = points_out_of_order(made); !disorder.empty()) {
        fail(e.line, disorder + " (in '" + variable + "')");
      }
    }
    for (const double constant : formula_constants(made))
      finite(e, constant, "a constant in the formula of term '" + term_name + "'");
    return made;
  }

  void process(const std::vector<Entry>& block) {
    if (block.empty()) return;
    const std::string& tag = block.front().key;
    if (tag == "InputVariable") {
      input(block);
    } else if (tag == "OutputVariable") {
      output(block);
    } else {
      rule_block(block);
    }
  }

  // Under FllOptions::finite_numbers, a variable must give the numbers whose defaults are not
  // finite (a range of -inf to inf, an output's default of nan): named at the variable's line.
  template <class Variable>
  void absent_numbers(const Entry& header, const char* kind, const Variable& v,
                      bool no_default) const {
    if (!options_.finite_numbers) return;
    if (!std::isfinite(v.minimum)) {
      fail(header.line, std::string(kind) + " variable '" + v.name +
                            "' needs a 'range: minimum maximum' here (its numbers must be finite)");
    }
    if (no_default) {
      fail(header.line, std::string(kind) + " variable '" + v.name +
                            "' needs a 'default:' here (its numbers must be finite)");
    }
  }

  // The keys input and output variables share; false for any other key.
  template <class Variable>
  bool variable_key(const Entry& e, Variable& v, std::unordered_set<std::string>& term_names) {
    if (e.key == "description") {
      v.description = e.value;
    } else if (e.key == "enabled") {
      v.enabled = boolean(e);
    } else if (e.key == "range") {
      range(e, v.minimum, v.maximum);
    } else if (e.key == "lock-range") {
      v.lock_range = boolean(e);
    } else if (e.key == "term") {
      v.terms.push_back(term(e, term_names, v.name));
    } else {
      return false;
    }
    return true;
  }

  void input(const std::vector<Entry>& block) {
    InputVariable v;
    std::unordered_set<std::string> term_names;
    v.name = name(block.front(), "input variable");
    unique_variable(block.front(), v.name);
    for (std::size_t i = 1; i < block.size(); ++i) {
      const Entry& e = block[i];
      if (!variable_key(e, v, term_names)) {
        fail(e.line, "unknown key '" + e.key + "' in InputVariable '" + v.name + "'");
      }
    }
    absent_numbers(block.front(), "input", v, false);
    engine_.inputs.push_back(std::move(v));
  }

  void output(const std::vector<Entry>& block) {
    OutputVariable v;
    std::unordered_set<std::string> term_names;
    v.name = name(block.front(), "output variable");
    unique_variable(block.front(), v.name);
    for (std::size_t i = 1; i < block.size(); ++i) {
      const Entry& e = block[i];
      if (variable_key(e, v, term_names)) continue;
      if (e.key == "default") {
        v.default_value = scalar(e, e.value, "default");
      } else if (e.key == "lock-previous" || e.key == "lock-valid") {
        v.lock_previous = boolean(e);
      } else if (e.key == "aggregation" || e.key == "accumulation") {
        const std::optional<SNorm> s = snorm_from_name(e.value);
        if (!s) fail(e.line, "unknown S-norm '" + e.value + "' for aggregation");
        v.aggregation = *s;
      } else if (e.key == "defuzzifier") {
        v.defuzzifier = defuzzifier(e);
      } else {
        fail(e.line, "unknown key '" + e.key + "' in OutputVariable '" + v.name + "'");
      }
    }
    absent_numbers(block.front(), "output", v, !std::isfinite(v.default_value));
    engine_.outputs.push_back(std::move(v));
  }

  std::optional<Defuzzifier> defuzzifier(const Entry& e) const {
    const std::vector<std::string_view> w = split_words(e.value, kWordSeparators);
    if (w.empty()) fail(e.line, "defuzzifier is empty (write 'none' for no defuzzifier)");
    if (w[0] == "none" && w.size() == 1) return std::nullopt;
    const std::optional<Defuzzifier::Kind> kind = defuzzifier_from_name(w[0]);
    if (!kind) fail(e.line, "unknown defuzzifier '" + std::string(w[0]) + "'");
    if (w.size() > 2) fail(e.line, "too many parameters for defuzzifier '" + e.value + "'");
    Defuzzifier d;
    d.kind = *kind;
    if (w.size() == 2) {
      if (d.is_integral()) {
        d.resolution = count(e, w[1], "defuzzifier resolution");
        if (d.resolution < 1 || d.resolution > Defuzzifier::kMaxResolution) {
          fail(e.line, "defuzzifier resolution must be from 1 to " +
                           std::to_string(Defuzzifier::kMaxResolution) + ", found '" +
                           std::string(w[1]) + "'");
        }
      } else {
        const std::optional<Defuzzifier::WeightedType> type = weighted_type_from_name(w[1]);
        if (!type) {
          fail(e.line,
               "weighted defuzzifier type must be Automatic, TakagiSugeno or "
               "Tsukamoto, found '" +
                   std::string(w[1]) + "'");
        }
        d.type = *type;
      }
    }
    return d;
  }

  Activation activation(const Entry& e) const {
    const std::vector<std::string_view> w = split_words(e.value, kWordSeparators);
    if (w.empty()) fail(e.line, "activation is empty (write 'General' or 'none')");
    const std::optional<Activation::Kind> kind = activation_from_name(w[0]);
    if (!kind) fail(e.line, "unknown activation method '" + std::string(w[0]) + "'");
    Activation a;
    a.kind = *kind;
    const std::size_t parameters = w.size() - 1;
    auto expect = [&](std::size_t allowed_a, std::size_t allowed_b, const char* form) {
      if (parameters != allowed_a && parameters != allowed_b) {
        fail(e.line, "activation '" + e.value + "' must read '" + form + "'");
      }
    };
    switch (a.kind) {
      case Activation::Kind::None:
        expect(0, 0, "none");
        break;
      case Activation::Kind::General:
        expect(0, 0, "General");
        break;
      case Activation::Kind::Proportional:
        expect(0, 0, "Proportional");
        break;
      case Activation::Kind::Threshold:
        expect(0, 2, "Threshold [< | <= | == | != | >= | >] value");
        if (parameters == 2) {
          const std::optional<Activation::Comparison> c = comparison_from_name(w[1]);
          if (!c) fail(e.line, "unknown comparison '" + std::string(w[1]) + "' in Threshold");
          a.comparison = *c;
          a.threshold = scalar(e, w[2], "threshold");
        }
        break;
      case Activation::Kind::First:
      case Activation::Kind::Last:
        expect(0, 2, "First|Last [rules threshold]");
        if (parameters == 2) {
          a.number_of_rules = count(e, w[1], "number of rules");
          a.threshold = scalar(e, w[2], "threshold");
        }
        break;
      case Activation::Kind::Highest:
      case Activation::Kind::Lowest:
        expect(1, 1, "Highest|Lowest rules");
        a.number_of_rules = count(e, w[1], "number of rules");
        break;
    }
    return a;
  }

  void rule_block(const std::vector<Entry>& block) {
    RuleBlock b;
    b.name = block.front().value;
    for (std::size_t i = 1; i < block.size(); ++i) {
      const Entry& e = block[i];
      if (e.key == "description") {
        b.description = e.value;
      } else if (e.key == "enabled") {
        b.enabled = boolean(e);
      } else if (e.key == "conjunction" || e.key == "implication") {
        const std::optional<TNorm> t = tnorm_from_name(e.value);
        if (!t) fail(e.line, "unknown T-norm '" + e.value + "' for " + e.key);
        (e.key == "conjunction" ? b.conjunction : b.implication) = *t;
      } else if (e.key == "disjunction") {
        const std::optional<SNorm> s = snorm_from_name(e.value);
        if (!s) fail(e.line, "unknown S-norm '" + e.value + "' for disjunction");
        b.disjunction = *s;
      } else if (e.key == "activation") {
        // fuzzylite 5 wrote the implication T-norm under this key.
        const std::optional<TNorm> t = tnorm_from_name(e.value);
        if (t && *t != TNorm::None) {
          b.implication = *t;
        } else {
          b.activation = activation(e);
        }
      } else if (e.key == "rule") {
        try {
          b.rules.push_back(parse_rule(e.value, engine_));
        } catch (const std::invalid_argument& error) {
          fail(e.line, error.what());
        }
        finite(e, b.rules.back().weight, "rule weight");
      } else {
        fail(e.line, "unknown key '" + e.key + "' in RuleBlock '" + b.name + "'");
      }
    }
    engine_.rule_blocks.push_back(std::move(b));
  }

  std::string source_;
  FllOptions options_;
  Engine engine_;
  std::unordered_set<std::string> variable_names_;
};

void check_line(const std::string& text, const std::string& what) {
  if (text.find_first_of("#\n\r") != std::string::npos) {
    throw std::invalid_argument(what + " '" + text +
                                "' cannot be written to FLL: it holds '#' or "
                                "a line break");
  }
}

std::string range_text(double minimum, double maximum) {
  return format_scalar(minimum) + " " + format_scalar(maximum);
}

// The other variables that a variable's Function terms read.
std::vector<std::string> formula_reads(const std::string& variable,
                                       const std::vector<Term>& terms) {
  std::vector<std::string> out;
  for (const Term& t : terms) {
    if (t.kind != TermKind::Function) continue;
    try {
      for (const std::string& symbol : compile_formula(t.formula).variables) {
        if (symbol != variable) out.push_back(symbol);
      }
    } catch (const std::invalid_argument&) {
      // An unparsable formula reads nothing; the reader reports it.
    }
  }
  return out;
}

}  // namespace

ParseError::ParseError(std::string source, int line, const std::string& message)
    : std::runtime_error(source + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " +
                         message),
      source_(std::move(source)),
      line_(line) {}

Engine read_fll(std::string_view text, std::string_view source, const FllOptions& options) {
  return Reader(source, options).read(text);
}

std::string read_text_file(const std::filesystem::path& path) {
  // A directory opens as a stream that reads nothing.
  if (std::filesystem::is_directory(path)) {
    throw ParseError(path.string(), 0, "is a directory, not a file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ParseError(path.string(), 0, "cannot open the file");
  std::ostringstream content;
  content << in.rdbuf();
  return content.str();
}

Engine read_fll_file(const std::filesystem::path& path, const FllOptions& options) {
  return read_fll(read_text_file(path), path.string(), options);
}

std::string write_fll(const Engine& engine) {
  std::ostringstream out;
  check_line(engine.name, "engine name");
  out << "Engine: " << engine.name << "\n";
  if (!engine.description.empty()) {
    check_line(engine.description, "description");
    out << "description: " << engine.description << "\n";
  }
  auto terms = [&out](const std::vector<Term>& list) {
    for (const Term& t : list) {
      check_line(t.formula, "formula");
      out << "  term: " << t.name << " " << shape_info(t.kind).name;
      const std::string parameters = t.parameter_text();
      if (!parameters.empty()) out << " " << parameters;
      out << "\n";
    }
  };
  auto header = [&out](const char* tag, const std::string& name, const std::string& description,
                       bool enabled, double minimum, double maximum, bool lock_range) {
    check_line(name, "variable name");
    out << tag << ": " << name << "\n";
    if (!description.empty()) {
      check_line(description, "description");
      out << "  description: " << description << "\n";
    }
    out << "  enabled: " << (enabled ? "true" : "false") << "\n";
    out << "  range: " << range_text(minimum, maximum) << "\n";
    out << "  lock-range: " << (lock_range ? "true" : "false") << "\n";
  };
  auto input = [&](const InputVariable& v) {
    header("InputVariable", v.name, v.description, v.enabled, v.minimum, v.maximum, v.lock_range);
    terms(v.terms);
  };
  auto output = [&](const OutputVariable& v) {
    header("OutputVariable", v.name, v.description, v.enabled, v.minimum, v.maximum, v.lock_range);
    out << "  aggregation: " << name(v.aggregation) << "\n";
    out << "  defuzzifier: ";
    if (!v.defuzzifier) {
      out << "none";
    } else if (v.defuzzifier->is_integral()) {
      out << name(v.defuzzifier->kind) << " " << v.defuzzifier->resolution;
    } else {
      out << name(v.defuzzifier->kind) << " " << name(v.defuzzifier->type);
    }
    out << "\n";
    out << "  default: " << format_scalar(v.default_value) << "\n";
    out << "  lock-previous: " << (v.lock_previous ? "true" : "false") << "\n";
    terms(v.terms);
  };
  // fuzzylite resolves a Function term's variables as it reads the term, so a variable goes after
  // the variables its formulas read (when no cycle forbids it); inputs keep their order, and so
  // do outputs.
  std::vector<std::string> written;
  auto ready = [&](const std::string& variable, const std::vector<Term>& list) {
    for (const std::string& symbol : formula_reads(variable, list)) {
      const bool known = engine.find_input(symbol) || engine.find_output(symbol);
      if (known && std::find(written.begin(), written.end(), symbol) == written.end()) {
        return false;
      }
    }
    return true;
  };
  std::size_t next_input = 0;
  std::size_t next_output = 0;
  while (next_input < engine.inputs.size() || next_output < engine.outputs.size()) {
    const bool inputs_left = next_input < engine.inputs.size();
    const bool output_ready =
        next_output < engine.outputs.size() &&
        ready(engine.outputs[next_output].name, engine.outputs[next_output].terms);
    if (inputs_left &&
        (ready(engine.inputs[next_input].name, engine.inputs[next_input].terms) || !output_ready)) {
      input(engine.inputs[next_input]);
      written.push_back(engine.inputs[next_input++].name);
    } else {
      output(engine.outputs[next_output]);
      written.push_back(engine.outputs[next_output++].name);
    }
  }
  for (const RuleBlock& b : engine.rule_blocks) {
    check_line(b.name, "rule block name");
    out << "RuleBlock: " << b.name << "\n";
    if (!b.description.empty()) {
      check_line(b.description, "description");
      out << "  description: " << b.description << "\n";
    }
    out << "  enabled: " << (b.enabled ? "true" : "false") << "\n";
    out << "  conjunction: " << name(b.conjunction) << "\n";
    out << "  disjunction: " << name(b.disjunction) << "\n";
    out << "  implication: " << name(b.implication) << "\n";
    out << "  activation: " << b.activation.text() << "\n";
    for (const Rule& r : b.rules)
      out << "  rule: " << r.text() << "\n";
  }
  return out.str();
}

}  // namespace fuzzygait::fuzzy

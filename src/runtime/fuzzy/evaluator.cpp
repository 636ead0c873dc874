#include "fuzzygait/fuzzy/evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fuzzygait/compiler.hpp"
#include "fuzzygait/fuzzy/shapes.hpp"

namespace fuzzygait::fuzzy {
namespace {

// fuzzylite's Op::bound: NaN passes through.
double bound(double x, double minimum, double maximum) {
  if (x > maximum) return maximum;
  if (x < minimum) return minimum;
  return x;
}

bool activates(const Activation& a, double degree) {
  switch (a.comparison) {
    case Activation::Comparison::Less:
      return is_lt(degree, a.threshold);
    case Activation::Comparison::LessOrEqual:
      return is_le(degree, a.threshold);
    case Activation::Comparison::Equal:
      return is_eq(degree, a.threshold);
    case Activation::Comparison::NotEqual:
      return !is_eq(degree, a.threshold);
    case Activation::Comparison::GreaterOrEqual:
      return is_ge(degree, a.threshold);
    case Activation::Comparison::Greater:
      return is_gt(degree, a.threshold);
  }
  return false;
}

// Output terms sampled once over their grid, at most (8 bytes each); beyond, terms are sampled
// during each evaluation.
constexpr std::size_t kMaxGridValues = std::size_t{1} << 22;

// One activated term over the grid: implied[i] = implication(y[i], degree), then
// mu[i] = aggregation(mu[i], implied[i]), sample by sample with the operators' exact formulas.
// One loop per operator keeps the dispatch out of the sample loop.
template <TNorm kImplication>
void imply(const double* y, double degree, std::size_t n, double* implied) {
  for (std::size_t i = 0; i < n; ++i)
    implied[i] = apply(kImplication, y[i], degree);
}

template <SNorm kAggregation>
void accumulate(const double* implied, std::size_t n, double* mu) {
  for (std::size_t i = 0; i < n; ++i)
    mu[i] = apply(kAggregation, mu[i], implied[i]);
}

void imply(TNorm implication, const double* y, double degree, std::size_t n, double* implied) {
  if (implication == TNorm::Minimum && !std::isnan(degree)) {  // nan_min, see aggregate()
    for (std::size_t i = 0; i < n; ++i)
      implied[i] = y[i] < degree ? y[i] : degree;
    return;
  }
  switch (implication) {
    case TNorm::None:
      return imply<TNorm::None>(y, degree, n, implied);
    case TNorm::AlgebraicProduct:
      return imply<TNorm::AlgebraicProduct>(y, degree, n, implied);
    case TNorm::BoundedDifference:
      return imply<TNorm::BoundedDifference>(y, degree, n, implied);
    case TNorm::DrasticProduct:
      return imply<TNorm::DrasticProduct>(y, degree, n, implied);
    case TNorm::EinsteinProduct:
      return imply<TNorm::EinsteinProduct>(y, degree, n, implied);
    case TNorm::HamacherProduct:
      return imply<TNorm::HamacherProduct>(y, degree, n, implied);
    case TNorm::Minimum:
      return imply<TNorm::Minimum>(y, degree, n, implied);
    case TNorm::NilpotentMinimum:
      return imply<TNorm::NilpotentMinimum>(y, degree, n, implied);
  }
}

void accumulate(SNorm aggregation, const double* implied, std::size_t n, double* mu) {
  switch (aggregation) {
    case SNorm::None:
      return accumulate<SNorm::None>(implied, n, mu);
    case SNorm::AlgebraicSum:
      return accumulate<SNorm::AlgebraicSum>(implied, n, mu);
    case SNorm::BoundedSum:
      return accumulate<SNorm::BoundedSum>(implied, n, mu);
    case SNorm::DrasticSum:
      return accumulate<SNorm::DrasticSum>(implied, n, mu);
    case SNorm::EinsteinSum:
      return accumulate<SNorm::EinsteinSum>(implied, n, mu);
    case SNorm::HamacherSum:
      return accumulate<SNorm::HamacherSum>(implied, n, mu);
    case SNorm::Maximum:
      return accumulate<SNorm::Maximum>(implied, n, mu);
    case SNorm::NilpotentMaximum:
      return accumulate<SNorm::NilpotentMaximum>(implied, n, mu);
    case SNorm::NormalizedSum:
      return accumulate<SNorm::NormalizedSum>(implied, n, mu);
    case SNorm::UnboundedSum:
      return accumulate<SNorm::UnboundedSum>(implied, n, mu);
  }
}

// The linear shapes with fuzzylite's tolerant comparisons reduced to one subtraction each,
// exact when x and the parameters are not NaN (infinities included): is_lt(x, a) is
// a - x >= kTolerance, is_gt(x, a) is x - a >= kTolerance, is_eq(x, a) is
// !(|x - a| >= kTolerance), and is_le / is_ge are the negations of is_gt / is_lt.
bool tolerant_lt(double x, double a) {
  return a - x >= kTolerance;
}
bool tolerant_gt(double x, double a) {
  return x - a >= kTolerance;
}

double triangle(double x, const double* p, double h) {
  if (std::isnan(x)) return kNaN;
  const double a = p[0];
  const double b = p[1];
  const double c = p[2];
  if (tolerant_lt(x, a) || tolerant_gt(x, c)) return h * 0.0;
  if (!(std::abs(x - b) >= kTolerance)) return h * 1.0;
  if (x < b) return a == -kInfinity ? h * 1.0 : h * (x - a) / (b - a);
  return c == kInfinity ? h * 1.0 : h * (c - x) / (c - b);
}

double trapezoid(double x, const double* p, double h) {
  if (std::isnan(x)) return kNaN;
  const double a = p[0];
  const double b = p[1];
  const double c = p[2];
  const double d = p[3];
  if (tolerant_lt(x, a) || tolerant_gt(x, d)) return h * 0.0;
  if (tolerant_lt(x, b)) return a == -kInfinity ? h * 1.0 : h * nan_min(1.0, (x - a) / (b - a));
  if (!tolerant_gt(x, c)) return h * 1.0;
  if (tolerant_lt(x, d)) return d == kInfinity ? h * 1.0 : h * (d - x) / (d - c);
  return d == kInfinity ? h * 1.0 : h * 0.0;
}

double ramp(double x, const double* p, double h) {
  if (std::isnan(x)) return kNaN;
  const double start = p[0];
  const double end = p[1];
  if (is_eq(start, end)) return h * 0.0;
  if (is_lt(start, end)) {
    if (!tolerant_gt(x, start)) return h * 0.0;
    if (!tolerant_lt(x, end)) return h * 1.0;
    return h * (x - start) / (end - start);
  }
  if (!tolerant_lt(x, start)) return h * 0.0;
  if (!tolerant_gt(x, end)) return h * 1.0;
  return h * (start - x) / (start - end);
}

// The connectives of antecedents, with the usual ones inline.
double conjoin(TNorm norm, double a, double b) {
  if (norm == TNorm::Minimum) return nan_min(a, b);
  if (norm == TNorm::AlgebraicProduct) return a * b;
  return apply(norm, a, b);
}
double disjoin(SNorm norm, double a, double b) {
  return norm == SNorm::Maximum ? nan_max(a, b) : apply(norm, a, b);
}

// Hedges apply last to first: "very not x" is very(not(x)).
double apply_hedges(const Hedge* hedges, std::uint32_t count, double value) {
  while (count > 0)
    value = apply(hedges[--count], value);
  return value;
}

// For i in [first, last): visit(i, max(mu[i], implication(y[i], degree))), with Minimum
// implication or else AlgebraicProduct, as selects the compiler vectorises. The caller makes sure
// they equal fuzzylite's operators: when b is not NaN, nan_min(a, b) is a < b ? a : b and
// nan_max(a, b) is a > b ? a : b.
template <class Visit>
FUZZYGAIT_ALWAYS_INLINE void max_with_implied(TNorm implication, const double* y, double degree,
                                              const double* mu, std::size_t first, std::size_t last,
                                              Visit visit) {
  if (implication == TNorm::Minimum) {
    for (std::size_t i = first; i < last; ++i) {
      const double implied = y[i] < degree ? y[i] : degree;
      visit(i, mu[i] > implied ? mu[i] : implied);
    }
  } else {
    for (std::size_t i = first; i < last; ++i) {
      const double implied = y[i] * degree;
      visit(i, mu[i] > implied ? mu[i] : implied);
    }
  }
}

// Zeroes mu[0, n) outside [first, last) (first <= last, so an empty range zeroes everything).
void zero_outside(double* mu, std::size_t first, std::size_t last, std::size_t n) {
  std::fill(mu, mu + first, 0.0);
  std::fill(mu + last, mu + n, 0.0);
}

bool all_finite(const double* values, std::size_t n) {
  bool finite = true;
  for (std::size_t i = 0; i < n; ++i)
    finite &= std::isfinite(values[i]);
  return finite;
}

}  // namespace

void Workspace::reset() {
  std::fill(input_values_.begin(), input_values_.end(), kNaN);
  std::fill(output_values_.begin(), output_values_.end(), kNaN);
  std::fill(previous_values_.begin(), previous_values_.end(), kNaN);
  std::fill(activated_count_.begin(), activated_count_.end(), 0u);
}

Evaluator::Evaluator(const Engine& engine) {
  const std::vector<std::string> problems = engine.problems();
  if (!problems.empty()) {
    std::string all = "engine '" + engine.name + "' cannot be evaluated: ";
    for (std::size_t i = 0; i < problems.size(); ++i)
      all += (i ? "; " : "") + problems[i];
    throw std::invalid_argument(all);
  }
  auto add_terms = [this, &engine](const std::vector<Term>& terms, std::size_t variable) {
    const auto first = static_cast<std::uint32_t>(terms_.size());
    for (const Term& t : terms) {
      CompiledTerm c{};
      c.kind = t.kind;
      c.variable = static_cast<std::uint32_t>(variable);
      c.parameters_not_nan = std::none_of(t.parameters.begin(), t.parameters.end(),
                                          [](double p) { return std::isnan(p); });
      c.height = t.height;
      c.parameters = static_cast<std::uint32_t>(parameters_.size());
      c.count = static_cast<std::uint32_t>(t.kind == TermKind::Discrete ? t.parameters.size() / 2
                                                                        : t.parameters.size());
      parameters_.insert(parameters_.end(), t.parameters.begin(), t.parameters.end());
      if (t.kind == TermKind::Function) {
        CompiledFormula f{compile_formula(t.formula), {}};
        for (const std::string& symbol : f.program.variables) {
          std::int32_t binding = kX;
          if (symbol != "x") {
            for (std::size_t i = 0; i < engine.inputs.size(); ++i) {
              if (engine.inputs[i].name == symbol) binding = static_cast<std::int32_t>(i);
            }
            for (std::size_t i = 0; i < engine.outputs.size(); ++i) {
              if (engine.outputs[i].name == symbol) binding = -static_cast<std::int32_t>(i) - 1;
            }
          }
          f.bindings.push_back(binding);
        }
        formula_values_size_ = std::max(formula_values_size_, f.bindings.size());
        formula_stack_size_ = std::max(formula_stack_size_, f.program.stack_size);
        c.formula = static_cast<std::int32_t>(formulas_.size());
        formulas_.push_back(std::move(f));
      }
      terms_.push_back(c);
    }
    return first;
  };
  for (const InputVariable& v : engine.inputs) {
    const std::uint32_t first = add_terms(v.terms, inputs_.size());
    inputs_.push_back({v.name, v.minimum, v.maximum, v.enabled, v.lock_range, first,
                       static_cast<std::uint32_t>(v.terms.size())});
  }
  for (const OutputVariable& v : engine.outputs) {
    const std::uint32_t first = add_terms(v.terms, outputs_.size());
    CompiledOutput o{};
    o.name = v.name;
    o.minimum = v.minimum;
    o.maximum = v.maximum;
    o.enabled = v.enabled;
    o.lock_range = v.lock_range;
    o.aggregation = v.aggregation;
    o.defuzzifier = *v.defuzzifier;
    o.default_value = v.default_value;
    o.lock_previous = v.lock_previous;
    o.first_term = first;
    o.term_count = static_cast<std::uint32_t>(v.terms.size());
    outputs_.push_back(std::move(o));
  }

  auto variable_index = [&engine](const Proposition& p) -> std::uint32_t {
    if (p.output) {
      for (std::size_t i = 0; i < engine.outputs.size(); ++i) {
        if (engine.outputs[i].name == p.variable) return static_cast<std::uint32_t>(i);
      }
    }
    for (std::size_t i = 0; i < engine.inputs.size(); ++i) {
      if (engine.inputs[i].name == p.variable) return static_cast<std::uint32_t>(i);
    }
    throw std::logic_error("unknown variable " + p.variable);
  };
  auto compile_proposition = [&](const Proposition& p) {
    CompiledProposition c{};
    c.output = p.output;
    c.variable = variable_index(p);
    c.hedges = static_cast<std::uint32_t>(hedges_.size());
    c.hedge_count = static_cast<std::uint32_t>(p.hedges.size());
    hedges_.insert(hedges_.end(), p.hedges.begin(), p.hedges.end());
    c.term = -1;
    if (!p.term.empty()) {
      const std::uint32_t first =
          p.output ? outputs_[c.variable].first_term : inputs_[c.variable].first_term;
      const std::vector<Term>& terms =
          p.output ? engine.outputs[c.variable].terms : engine.inputs[c.variable].terms;
      for (std::size_t t = 0; t < terms.size(); ++t) {
        if (terms[t].name == p.term) c.term = static_cast<std::int32_t>(first + t);
      }
    }
    c.variable_enabled =
        p.output ? engine.outputs[c.variable].enabled : engine.inputs[c.variable].enabled;
    return c;
  };

  std::vector<std::size_t> capacity(outputs_.size(), 0);
  std::vector<bool> fuzzified(terms_.size(), false);
  for (const RuleBlock& b : engine.rule_blocks) {
    CompiledBlock block{b.enabled,
                        b.conjunction,
                        b.disjunction,
                        b.implication,
                        b.activation,
                        static_cast<std::uint32_t>(rules_.size()),
                        static_cast<std::uint32_t>(b.rules.size())};
    max_block_rules_ = std::max(max_block_rules_, b.rules.size());
    for (const Rule& r : b.rules) {
      CompiledRule rule{};
      rule.weight = r.weight;
      rule.antecedent = static_cast<std::uint32_t>(antecedent_.size());
      rule.antecedent_length = static_cast<std::uint32_t>(r.antecedent.size());
      // Input propositions read values computed once per evaluation: an unhedged one its
      // term's membership, any other a slot shared by its equals. Output propositions
      // (chained engines) read the activations so far, so they are evaluated in rule order.
      std::vector<std::int32_t> tokens;
      for (const Proposition& p : r.propositions) {
        const CompiledProposition c = compile_proposition(p);
        const auto index = static_cast<std::int32_t>(propositions_.size());
        propositions_.push_back(c);
        if (c.output) {
          tokens.push_back(kOutputProposition - index);
        } else if (c.variable_enabled && c.hedge_count == 0) {
          tokens.push_back(c.term);
        } else {
          auto same = [this, &c](std::uint32_t other) {
            const CompiledProposition& o = propositions_[other];
            return o.variable == c.variable && o.term == c.term &&
                   o.variable_enabled == c.variable_enabled && o.hedge_count == c.hedge_count &&
                   std::equal(hedges_.begin() + o.hedges,
                              hedges_.begin() + o.hedges + o.hedge_count,
                              hedges_.begin() + c.hedges);
          };
          const auto slot = static_cast<std::size_t>(
              std::find_if(hedged_propositions_.begin(), hedged_propositions_.end(), same) -
              hedged_propositions_.begin());
          if (slot == hedged_propositions_.size()) {
            hedged_propositions_.push_back(static_cast<std::uint32_t>(index));
          }
          tokens.push_back(static_cast<std::int32_t>(terms_.size() + slot));
        }
        if (!c.output && c.term >= 0 && !fuzzified[static_cast<std::size_t>(c.term)]) {
          fuzzified[static_cast<std::size_t>(c.term)] = true;
          fuzzified_terms_.push_back(static_cast<std::uint32_t>(c.term));
        }
      }
      std::size_t depth = 0;
      for (int token : r.antecedent) {
        antecedent_.push_back(token >= 0 ? tokens[static_cast<std::size_t>(token)] : token);
        depth = token >= 0 ? depth + 1 : depth - 1;
        stack_size_ = std::max(stack_size_, depth);
      }
      // v0 v1 op v2 op ...: folds from the left without a stack.
      const std::int32_t* code = antecedent_.data() + rule.antecedent;
      rule.left_deep = rule.antecedent_length % 2 == 1;
      for (std::uint32_t i = 0; i < rule.antecedent_length; ++i) {
        rule.left_deep =
            rule.left_deep &&
            (i % 2 == 1 || i == 0 ? code[i] >= 0 : code[i] == Rule::kAnd || code[i] == Rule::kOr);
      }
      rule.conclusions = static_cast<std::uint32_t>(conclusions_.size());
      rule.conclusion_count = static_cast<std::uint32_t>(r.conclusions.size());
      for (const Proposition& p : r.conclusions) {
        CompiledProposition c = compile_proposition(p);
        ++capacity[c.variable];
        conclusions_.push_back(c);
      }
      rules_.push_back(rule);
    }
    blocks_.push_back(block);
  }
  std::size_t offset = 0;
  for (std::size_t o = 0; o < outputs_.size(); ++o) {
    outputs_[o].activated_offset = static_cast<std::uint32_t>(offset);
    offset += capacity[o];
  }
  activated_total_ = offset;
  for (std::size_t i = 0; i < outputs_.size(); ++i) {
    CompiledOutput& o = outputs_[i];
    o.eager = !o.defuzzifier.is_integral();
    for (std::uint32_t t = o.first_term; t < o.first_term + o.term_count; ++t) {
      if (terms_[t].formula < 0) continue;
      for (std::int32_t b : formulas_[static_cast<std::size_t>(terms_[t].formula)].bindings) {
        o.eager = o.eager && (b == kX || b >= 0);
      }
    }
    for (const CompiledProposition& p : propositions_) {
      o.eager = o.eager && !(p.output && p.variable == i);
    }
  }
  sample_grids();
}

// The positions an integral defuzzifier samples, and the membership there of every output term
// that depends on x alone: the same expressions as fuzzylite's sample loops, computed once.
void Evaluator::sample_grids() {
  for (CompiledOutput& o : outputs_) {
    if (!o.defuzzifier.is_integral() || !std::isfinite(o.minimum + o.maximum)) continue;
    const int resolution = o.defuzzifier.resolution;
    const double dx = (o.maximum - o.minimum) / resolution;
    o.grid = static_cast<std::int32_t>(grid_x_.size());
    for (int i = 0; i < resolution; ++i)
      grid_x_.push_back(o.minimum + (i + 0.5) * dx);
    if (o.defuzzifier.kind == Defuzzifier::Kind::Bisector) {
      for (int i = 0; i < resolution; ++i)
        grid_x_.push_back(o.maximum - (i + 0.5) * dx);
    }
    o.grid_size = static_cast<std::uint32_t>(grid_x_.size() - static_cast<std::size_t>(o.grid));
    max_grid_size_ = std::max<std::size_t>(max_grid_size_, o.grid_size);
  }
  Workspace scratch = make_workspace();
  for (const CompiledOutput& o : outputs_) {
    if (o.grid < 0) continue;
    const double* x = grid_x_.data() + o.grid;
    for (std::uint32_t t = o.first_term; t < o.first_term + o.term_count; ++t) {
      CompiledTerm& term = terms_[t];
      bool reads_variables = term.kind == TermKind::Linear;
      if (term.kind == TermKind::Function) {
        for (std::int32_t b : formulas_[static_cast<std::size_t>(term.formula)].bindings) {
          reads_variables |= b != kX;
        }
      }
      if (reads_variables || grid_values_.size() + o.grid_size > kMaxGridValues) continue;
      term.grid_values = static_cast<std::int32_t>(grid_values_.size());
      for (std::uint32_t i = 0; i < o.grid_size; ++i) {
        grid_values_.push_back(membership(term, x[i], scratch));
      }
      const double* values = grid_values_.data() + term.grid_values;
      term.grid_values_finite = all_finite(values, o.grid_size);
      term.grid_values_nonnegative =
          term.grid_values_finite &&
          std::all_of(values, values + o.grid_size, [](double y) { return y >= 0.0; });
      std::uint32_t first = 0;
      std::uint32_t last = o.grid_size;
      while (first < last && values[first] == 0.0)
        ++first;
      while (last > first && values[last - 1] == 0.0)
        --last;
      term.grid_first = first;
      term.grid_last = last;
    }
  }
}

Workspace Evaluator::make_workspace() const {
  Workspace w;
  w.input_values_.assign(inputs_.size(), kNaN);
  w.output_values_.assign(outputs_.size(), kNaN);
  w.previous_values_.assign(outputs_.size(), kNaN);
  w.activated_.resize(activated_total_);
  w.activated_count_.assign(outputs_.size(), 0);
  w.weighted_sums_.assign(outputs_.size(), {0.0, 0.0});
  w.rule_degrees_.assign(max_block_rules_, 0.0);
  w.heap_.assign(max_block_rules_, 0);
  w.stack_.assign(stack_size_, 0.0);
  w.formula_values_.assign(formula_values_size_, 0.0);
  w.formula_stack_.assign(std::max<std::size_t>(formula_stack_size_, 1), 0.0);
  w.proposition_values_.assign(terms_.size() + hedged_propositions_.size(), 0.0);
  w.samples_.assign(max_grid_size_, 0.0);
  w.term_samples_.assign(max_grid_size_, 0.0);
  w.implied_.assign(max_grid_size_, 0.0);
  return w;
}

// A Linear term: its coefficients times the input values, then its constant if it has one.
FUZZYGAIT_ALWAYS_INLINE double Evaluator::linear(const CompiledTerm& t, const Workspace& w) const {
  const double* p = parameters_.data() + t.parameters;
  const double* inputs = w.input_values_.data();
  const std::size_t n = inputs_.size();
  const std::size_t products = std::min<std::size_t>(n, t.count);
  double result = 0.0;
  for (std::size_t i = 0; i < products; ++i)
    result += p[i] * inputs[i];
  if (t.count > n) result += p[t.count - 1];
  return result;
}

// The common linear shapes inline, every other through general_membership().
FUZZYGAIT_ALWAYS_INLINE double Evaluator::fuzzify(const CompiledTerm& t, double x,
                                                  Workspace& w) const {
  if (t.parameters_not_nan) {  // else the templated shapes, NaN parameters and all
    const double* p = parameters_.data() + t.parameters;
    switch (t.kind) {
      case TermKind::Triangle:
        return triangle(x, p, t.height);
      case TermKind::Trapezoid:
        return trapezoid(x, p, t.height);
      case TermKind::Ramp:
        return ramp(x, p, t.height);
      default:
        break;
    }
  }
  return general_membership(t, x, w);
}

double Evaluator::membership(const CompiledTerm& t, double x, Workspace& w) const {
  return fuzzify(t, x, w);
}

double Evaluator::general_membership(const CompiledTerm& t, double x, Workspace& w) const {
  const double* p = parameters_.data() + t.parameters;
  const double h = t.height;
  switch (t.kind) {
    case TermKind::Bell:
      return shapes::bell(x, p[0], p[1], p[2], h);
    case TermKind::Binary:
      return shapes::binary(x, p[0], p[1], h);
    case TermKind::Concave:
      return shapes::concave(x, p[0], p[1], h);
    case TermKind::Constant:
      return p[0];
    case TermKind::Cosine:
      return shapes::cosine(x, p[0], p[1], h);
    case TermKind::Discrete:
      return shapes::discrete(x, p, t.count, h);
    case TermKind::Function: {
      const CompiledFormula& f = formulas_[static_cast<std::size_t>(t.formula)];
      for (std::size_t i = 0; i < f.bindings.size(); ++i) {
        const std::int32_t b = f.bindings[i];
        w.formula_values_[i] = b == kX  ? x
                               : b >= 0 ? w.input_values_[static_cast<std::size_t>(b)]
                                        : w.output_values_[static_cast<std::size_t>(-b - 1)];
      }
      return evaluate_formula(f.program, w.formula_values_.data(), w.formula_stack_.data());
    }
    case TermKind::Gaussian:
      return shapes::gaussian(x, p[0], p[1], h);
    case TermKind::GaussianProduct:
      return shapes::gaussian_product(x, p[0], p[1], p[2], p[3], h);
    case TermKind::Linear:
      return linear(t, w);
    case TermKind::PiShape:
      return shapes::pi_shape(x, p[0], p[1], p[2], p[3], h);
    case TermKind::Ramp:
      return shapes::ramp(x, p[0], p[1], h);
    case TermKind::Rectangle:
      return shapes::rectangle(x, p[0], p[1], h);
    case TermKind::SShape:
      return shapes::s_shape(x, p[0], p[1], h);
    case TermKind::Sigmoid:
      return shapes::sigmoid(x, p[0], p[1], h);
    case TermKind::SigmoidDifference:
      return shapes::sigmoid_difference(x, p[0], p[1], p[2], p[3], h);
    case TermKind::SigmoidProduct:
      return shapes::sigmoid_product(x, p[0], p[1], p[2], p[3], h);
    case TermKind::Spike:
      return shapes::spike(x, p[0], p[1], h);
    case TermKind::Trapezoid:
      return shapes::trapezoid(x, p[0], p[1], p[2], p[3], h);
    case TermKind::Triangle:
      return shapes::triangle(x, p[0], p[1], p[2], h);
    case TermKind::ZShape:
      return shapes::z_shape(x, p[0], p[1], h);
  }
  return kNaN;
}

double Evaluator::tsukamoto(const CompiledTerm& t, double w, double minimum, double maximum,
                            Workspace& ws) const {
  const double* p = parameters_.data() + t.parameters;
  switch (t.kind) {
    case TermKind::Concave:
      return shapes::concave_inverse(w, p[0], p[1], t.height);
    case TermKind::Ramp:
      return shapes::ramp_inverse(w, p[0], p[1]);
    case TermKind::Sigmoid:
      return shapes::sigmoid_inverse(w, p[0], p[1], minimum, maximum);
    case TermKind::SShape:
      return shapes::s_shape_inverse(w, p[0], p[1], t.height);
    case TermKind::ZShape:
      return shapes::z_shape_inverse(w, p[0], p[1], t.height);
    default:
      return membership(t, w, ws);
  }
}

double Evaluator::input_membership(std::size_t input, std::size_t term, double x,
                                   Workspace& workspace) const {
  return membership(terms_.at(inputs_.at(input).first_term + term), x, workspace);
}

double Evaluator::output_membership(std::size_t output, std::size_t term, double x,
                                    Workspace& workspace) const {
  return membership(terms_.at(outputs_.at(output).first_term + term), x, workspace);
}

double Evaluator::fuzzy_output_degree(std::uint32_t output, std::int32_t term,
                                      const Workspace& w) const {
  const CompiledOutput& o = outputs_[output];
  const Workspace::Activated* a = w.activated_.data() + o.activated_offset;
  const std::uint32_t n = w.activated_count_[output];
  double result = 0.0;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (static_cast<std::int32_t>(a[i].term) != term) continue;
    result = o.aggregation != SNorm::None ? apply(o.aggregation, result, a[i].degree)
                                          : result + a[i].degree;
  }
  return result;
}

double Evaluator::proposition(const CompiledProposition& p, Workspace& w) const {
  if (!p.variable_enabled) return 0.0;
  const Hedge* hedges = hedges_.data() + p.hedges;
  std::uint32_t count = p.hedge_count;
  double result;
  if (count > 0 && hedges[count - 1] == Hedge::Any) {
    result = 1.0;
    --count;
  } else if (p.output) {
    result = fuzzy_output_degree(p.variable, p.term, w);
  } else {
    result = w.proposition_values_[static_cast<std::size_t>(p.term)];
  }
  return apply_hedges(hedges, count, result);
}

double Evaluator::antecedent(const CompiledRule& rule, const CompiledBlock& block,
                             Workspace& w) const {
  const std::int32_t* code = antecedent_.data() + rule.antecedent;
  const double* values = w.proposition_values_.data();
  double* stack = w.stack_.data();
  std::size_t top = 0;
  for (std::uint32_t i = 0; i < rule.antecedent_length; ++i) {
    const std::int32_t token = code[i];
    if (token >= 0) {
      stack[top++] = values[token];
    } else if (token == Rule::kAnd || token == Rule::kOr) {
      const double right = stack[--top];
      const double left = stack[top - 1];
      stack[top - 1] = token == Rule::kAnd ? conjoin(block.conjunction, left, right)
                                           : disjoin(block.disjunction, left, right);
    } else {
      stack[top++] =
          proposition(propositions_[static_cast<std::size_t>(kOutputProposition - token)], w);
    }
  }
  return rule.weight * stack[0];
}

// Hot paths are forced inline into the rule loops: a call per rule or conclusion would cost more
// than the work.

// The rule's activation degree (fuzzylite's Rule::activationDegree): a left-deep antecedent
// folds its proposition values without a stack, any other runs its postfix program.
FUZZYGAIT_ALWAYS_INLINE double Evaluator::activation_degree(const CompiledRule& rule,
                                                            const CompiledBlock& block,
                                                            Workspace& w) const {
  if (!rule.left_deep) return antecedent(rule, block, w);
  const std::int32_t* code = antecedent_.data() + rule.antecedent;
  const double* values = w.proposition_values_.data();
  double degree = values[code[0]];
  for (std::uint32_t i = 1; i < rule.antecedent_length; i += 2) {
    const double value = values[code[i]];
    degree = code[i + 1] == Rule::kAnd ? conjoin(block.conjunction, degree, value)
                                       : disjoin(block.disjunction, degree, value);
  }
  return rule.weight * degree;
}

// Hedges of a conclusion, last to first; rare, so kept out of the rule loops.
FUZZYGAIT_NOINLINE double Evaluator::hedge(const CompiledProposition& p, double degree) const {
  return apply_hedges(hedges_.data() + p.hedges, p.hedge_count, degree);
}

// Adds the rule's conclusions with the activation degree (fuzzylite's Rule::trigger): to the
// activated terms of the output, or at once to the sums of an eager weighted defuzzifier.
FUZZYGAIT_ALWAYS_INLINE void Evaluator::trigger(const CompiledRule& rule, double degree,
                                                TNorm implication, Workspace& w) const {
  if (!(degree >= kTolerance)) return;  // !is_gt(degree, 0.0), NaN included
  const CompiledProposition* conclusion = conclusions_.data() + rule.conclusions;
  const CompiledProposition* const end = conclusion + rule.conclusion_count;
  for (; conclusion != end; ++conclusion) {
    if (!conclusion->variable_enabled) continue;
    // fuzzylite hedges the degree in place, so a hedge also reaches later conclusions.
    if (conclusion->hedge_count > 0) degree = hedge(*conclusion, degree);
    const CompiledOutput& o = outputs_[conclusion->variable];
    std::uint32_t& count = w.activated_count_[conclusion->variable];
    if (o.eager) {
      Workspace::WeightedSums& sums = w.weighted_sums_[conclusion->variable];
      if (count == 0) sums = {0.0, 0.0};
      const CompiledTerm& t = terms_[static_cast<std::size_t>(conclusion->term)];
      // Constant and Linear are read alike by both kinds of weighted defuzzifier.
      const double z = t.kind == TermKind::Constant ? parameters_[t.parameters]
                       : t.kind == TermKind::Linear ? linear(t, w)
                                                    : weighted_value(o, t, degree, w);
      sums.sum += degree * z;
      sums.weights += degree;
    } else {
      w.activated_[o.activated_offset + count] = {static_cast<std::uint32_t>(conclusion->term),
                                                  degree, implication};
    }
    ++count;
  }
}

// General activation, fuzzylite's default: every rule fires with its activation degree.
FUZZYGAIT_ALWAYS_INLINE void Evaluator::activate_general(const CompiledBlock& block,
                                                         Workspace& w) const {
  const CompiledRule* rules = rules_.data() + block.first_rule;
  const std::uint32_t n = block.rule_count;
  for (const CompiledRule* rule = rules; rule != rules + n; ++rule) {
    trigger(*rule, activation_degree(*rule, block, w), block.implication, w);
  }
}

void Evaluator::activate(const CompiledBlock& block, Workspace& w) const {
  const CompiledRule* rules = rules_.data() + block.first_rule;
  const std::uint32_t n = block.rule_count;
  const Activation& a = block.activation;
  double* degrees = w.rule_degrees_.data();
  switch (a.kind) {
    case Activation::Kind::None:
    case Activation::Kind::General:
      activate_general(block, w);
      return;
    case Activation::Kind::Proportional: {
      double sum = 0.0;
      for (std::uint32_t r = 0; r < n; ++r) {
        degrees[r] = activation_degree(rules[r], block, w);
        sum += degrees[r];
      }
      for (std::uint32_t r = 0; r < n; ++r)
        trigger(rules[r], degrees[r] / sum, block.implication, w);
      return;
    }
    case Activation::Kind::Threshold:
      for (std::uint32_t r = 0; r < n; ++r) {
        const double d = activation_degree(rules[r], block, w);
        if (activates(a, d)) trigger(rules[r], d, block.implication, w);
      }
      return;
    case Activation::Kind::First:
    case Activation::Kind::Last: {
      int activated = 0;
      for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t r = a.kind == Activation::Kind::First ? i : n - 1 - i;
        const double d = activation_degree(rules[r], block, w);
        if (activated < a.number_of_rules && is_gt(d, 0.0) && is_ge(d, a.threshold)) {
          trigger(rules[r], d, block.implication, w);
          ++activated;
        }
      }
      return;
    }
    case Activation::Kind::Highest:
    case Activation::Kind::Lowest: {
      // std::priority_queue's exact order (push_heap / pop_heap), so ties break as in fuzzylite.
      const bool highest = a.kind == Activation::Kind::Highest;
      auto before = [degrees, highest](std::uint32_t x, std::uint32_t y) {
        return highest ? degrees[x] < degrees[y] : degrees[x] > degrees[y];
      };
      std::uint32_t* heap = w.heap_.data();
      std::uint32_t size = 0;
      for (std::uint32_t r = 0; r < n; ++r) {
        degrees[r] = activation_degree(rules[r], block, w);
        if (is_gt(degrees[r], 0.0)) {
          heap[size++] = r;
          std::push_heap(heap, heap + size, before);
        }
      }
      int activated = 0;
      while (size > 0 && activated++ < a.number_of_rules) {
        const std::uint32_t r = heap[0];
        trigger(rules[r], degrees[r], block.implication, w);
        std::pop_heap(heap, heap + size, before);
        --size;
      }
      return;
    }
  }
}

// mu over the output's grid: every activated term, in order, through its implication and the
// aggregation, as fuzzylite's Aggregated::membership computes it at each sample. Returns the
// samples outside which mu is zero; only those inside are written.
//
// While every term and degree so far was finite and >= 0, mu is too, and with Minimum or
// AlgebraicProduct implication and Maximum aggregation a term changes mu only where the term is
// not zero: elsewhere mu = max(mu, +-0) keeps its value, at most turning +0 into -0, which no
// defuzzifier tells apart. So such terms only visit their own samples.
Evaluator::Aggregate Evaluator::aggregate(const CompiledOutput& o, bool defer_last,
                                          Workspace& w) const {
  const std::size_t n = o.grid_size;
  const double* x = grid_x_.data() + o.grid;
  double* mu = w.samples_.data();
  std::size_t first = 0;  // [first, last) holds every sample written so far
  std::size_t last = 0;
  bool sparse = true;  // mu is finite and >= 0, and zero outside [first, last)
  const Workspace::Activated* activated = w.activated_.data() + o.activated_offset;
  const std::uint32_t count = w.activated_count_[static_cast<std::size_t>(&o - outputs_.data())];
  for (std::uint32_t k = 0; k < count; ++k) {
    const CompiledTerm& t = terms_[activated[k].term];
    const double degree = activated[k].degree;
    const TNorm implication = activated[k].implication;
    const bool max_of_implied =
        o.aggregation == SNorm::Maximum &&
        (implication == TNorm::Minimum || implication == TNorm::AlgebraicProduct);
    if (sparse && max_of_implied && t.grid_values_nonnegative && std::isfinite(degree) &&
        degree >= 0.0) {
      const std::size_t term_first = t.grid_first;
      const std::size_t term_last = t.grid_last;
      if (term_first == term_last) continue;
      if (first == last) {
        std::fill(mu + term_first, mu + term_last, 0.0);
        first = term_first;
        last = term_last;
      } else {
        if (term_first < first) std::fill(mu + term_first, mu + first, 0.0);
        if (term_last > last) std::fill(mu + last, mu + term_last, 0.0);
        first = std::min(first, term_first);
        last = std::max(last, term_last);
      }
      const double* y = grid_values_.data() + t.grid_values;
      if (defer_last && k + 1 == count) return {first, last, y, degree, implication};
      max_with_implied(implication, y, degree, mu, term_first, term_last,
                       [mu](std::size_t i, double aggregated) { mu[i] = aggregated; });
      continue;
    }
    if (sparse) {  // from here on, every sample
      zero_outside(mu, first, last, n);
      first = 0;
      last = n;
      sparse = false;
    }
    // No offset of -1 (a term sampled during evaluation): that pointer arithmetic is undefined.
    const double* y = t.grid_values < 0 ? nullptr : grid_values_.data() + t.grid_values;
    bool y_finite = t.grid_values_finite;
    if (t.grid_values < 0) {
      double* sampled = w.term_samples_.data();
      for (std::size_t i = 0; i < n; ++i)
        sampled[i] = membership(t, x[i], w);
      y = sampled;
      y_finite = false;
    }
    // Minimum with a degree that is not NaN, or the product of finite values, never gives NaN.
    if (o.aggregation == SNorm::Maximum &&
        ((implication == TNorm::Minimum && !std::isnan(degree)) ||
         (implication == TNorm::AlgebraicProduct && y_finite && std::isfinite(degree)))) {
      max_with_implied(implication, y, degree, mu, 0, n,
                       [mu](std::size_t i, double aggregated) { mu[i] = aggregated; });
    } else {
      imply(implication, y, degree, n, w.implied_.data());
      accumulate(o.aggregation, w.implied_.data(), n, mu);
    }
  }
  return {first, last};
}

double Evaluator::integral(const CompiledOutput& o, Workspace& w) const {
  if (o.grid < 0) return kNaN;  // the range is not finite
  const bool centroid = o.defuzzifier.kind == Defuzzifier::Kind::Centroid;
  const Aggregate nonzero = aggregate(o, centroid, w);
  double* mu = w.samples_.data();
  const double* x = grid_x_.data() + o.grid;
  const int resolution = o.defuzzifier.resolution;
  if (!centroid) zero_outside(mu, nonzero.first, nonzero.last, o.grid_size);  // read every sample
  switch (o.defuzzifier.kind) {
    case Defuzzifier::Kind::Bisector: {
      // Samples from both ends towards the middle: the right end has its own grid.
      const double* mu_right = mu + resolution;
      const double* x_right_grid = x + resolution;
      int counter = resolution;
      int left = 0;
      int right = 0;
      double left_area = 0.0;
      double right_area = 0.0;
      double x_left = o.minimum;
      double x_right = o.maximum;
      while (counter-- > 0) {
        if (is_le(left_area, right_area)) {
          x_left = x[left];
          left_area += mu[left];
          ++left;
        } else {
          x_right = x_right_grid[right];
          right_area += mu_right[right];
          ++right;
        }
      }
      return (left_area * x_right + right_area * x_left) / (left_area + right_area);
    }
    case Defuzzifier::Kind::Centroid: {
      // The sums stay sequential, in fuzzylite's order. Samples where mu is exactly zero add
      // nothing (x is finite, and sums that start at +0 never round to -0), so the zero ends of
      // the aggregate are skipped.
      std::size_t first = nonzero.first;
      std::size_t last = nonzero.last;
      double area = 0.0;
      double x_centroid = 0.0;
      if (nonzero.deferred != nullptr) {
        // The last term's implication and aggregation fill the wait on the sums' additions.
        max_with_implied(nonzero.deferred_implication, nonzero.deferred, nonzero.deferred_degree,
                         mu, first, last, [&](std::size_t i, double aggregated) {
                           x_centroid += aggregated * x[i];
                           area += aggregated;
                         });
        return x_centroid / area;
      }
      while (first < last && mu[first] == 0.0)
        ++first;
      while (last > first && mu[last - 1] == 0.0)
        --last;
      for (std::size_t i = first; i < last; ++i) {
        x_centroid += mu[i] * x[i];
        area += mu[i];
      }
      return x_centroid / area;
    }
    // y_max is never NaN (it starts at -1 and takes only values that compared greater), so
    // the tolerant comparisons of mu with it reduce as for the linear shapes:
    // is_gt(m, y_max) is m - y_max >= kTolerance, is_lt(m, y_max) is y_max - m >= kTolerance,
    // is_eq(m, y_max) is |m - y_max| < kTolerance || m == y_max, and is_ge is its negation of
    // is_lt with m == y_max for infinities; a NaN m fails them all, as in fuzzylite.
    case Defuzzifier::Kind::SmallestOfMaximum: {
      double y_max = -1.0;
      double x_smallest = o.minimum;
      for (int i = 0; i < resolution; ++i) {
        if (mu[i] - y_max >= kTolerance) {
          x_smallest = x[i];
          y_max = mu[i];
        }
      }
      return x_smallest;
    }
    case Defuzzifier::Kind::LargestOfMaximum: {
      double y_max = -1.0;
      double x_largest = o.maximum;
      for (int i = 0; i < resolution; ++i) {
        if (y_max - mu[i] < kTolerance || mu[i] == y_max) {
          y_max = mu[i];
          x_largest = x[i];
        }
      }
      return x_largest;
    }
    case Defuzzifier::Kind::MeanOfMaximum: {
      double y_max = -1.0;
      double x_smallest = o.minimum;
      double x_largest = o.maximum;
      bool same_plateau = false;
      for (int i = 0; i < resolution; ++i) {
        const double difference = mu[i] - y_max;
        if (difference >= kTolerance) {
          y_max = mu[i];
          x_smallest = x[i];
          x_largest = x[i];
          same_plateau = true;
        } else if (same_plateau && (std::abs(difference) < kTolerance || mu[i] == y_max)) {
          x_largest = x[i];
        } else if (y_max - mu[i] >= kTolerance) {
          same_plateau = false;
        }
      }
      return 0.5 * (x_largest + x_smallest);
    }
    default:
      return kNaN;
  }
}

// z of an activated term for the weighted defuzzifiers. Automatic reads every term as
// Tsukamoto does, as fuzzylite 6 does in effect: it infers the type from the first Activated
// wrapper, never a Constant, Linear or Function itself (WeightedAverage::defuzzify,
// WeightedSum::defuzzify). For those terms it is the same value.
FUZZYGAIT_NOINLINE double Evaluator::weighted_value(const CompiledOutput& o, const CompiledTerm& t,
                                                    double degree, Workspace& w) const {
  if (t.kind == TermKind::Constant) return parameters_[t.parameters];  // in both readings
  if (o.defuzzifier.type == Defuzzifier::WeightedType::TakagiSugeno) {
    return membership(t, degree, w);
  }
  return tsukamoto(t, degree, o.minimum, o.maximum, w);
}

double Evaluator::weighted(const CompiledOutput& o, Workspace& w) const {
  const bool average = o.defuzzifier.kind == Defuzzifier::Kind::WeightedAverage;
  const auto output = static_cast<std::size_t>(&o - outputs_.data());
  const Workspace::Activated* activated = w.activated_.data() + o.activated_offset;
  const std::uint32_t count = w.activated_count_[output];
  double sum = 0.0;
  double weights = 0.0;
  for (std::uint32_t k = 0; k < count; ++k) {
    const double degree = activated[k].degree;
    sum += degree * weighted_value(o, terms_[activated[k].term], degree, w);
    if (average) weights += degree;
  }
  return average ? sum / weights : sum;
}

FUZZYGAIT_ALWAYS_INLINE void Evaluator::defuzzify(std::uint32_t output, Workspace& w) const {
  const CompiledOutput& o = outputs_[output];
  if (!o.enabled) return;
  double& value = w.output_values_[output];
  double& previous = w.previous_values_[output];
  if (std::isfinite(value)) previous = value;
  double result;
  if (w.activated_count_[output] > 0) {
    if (o.eager) {
      const Workspace::WeightedSums& sums = w.weighted_sums_[output];
      result = o.defuzzifier.kind == Defuzzifier::Kind::WeightedAverage ? sums.sum / sums.weights
                                                                        : sums.sum;
    } else {
      result = o.defuzzifier.is_integral() ? integral(o, w) : weighted(o, w);
    }
  } else {
    result = (o.lock_previous && !std::isnan(previous)) ? previous : o.default_value;
  }
  value = o.lock_range ? bound(result, o.minimum, o.maximum) : result;
}

void Evaluator::evaluate(std::span<const double> inputs, std::span<double> outputs,
                         Workspace& w) const {
  double* input_values = w.input_values_.data();
  const std::size_t input_count = inputs_.size();
  for (std::size_t i = 0; i < input_count; ++i) {
    const CompiledInput& v = inputs_[i];
    input_values[i] = v.lock_range ? bound(inputs[i], v.minimum, v.maximum) : inputs[i];
  }
  // Inputs, and so their terms' memberships, stay fixed while the rule blocks activate.
  double* values = w.proposition_values_.data();
  for (std::uint32_t t : fuzzified_terms_) {
    const CompiledTerm& term = terms_[t];
    values[t] = fuzzify(term, input_values[term.variable], w);
  }
  std::size_t slot = terms_.size();
  for (std::uint32_t index : hedged_propositions_) {
    values[slot++] = proposition(propositions_[index], w);
  }
  for (const CompiledBlock& block : blocks_) {
    if (!block.enabled) continue;
    const Activation::Kind kind = block.activation.kind;
    if (kind == Activation::Kind::General || kind == Activation::Kind::None) {
      activate_general(block, w);
    } else {
      activate(block, w);
    }
  }
  const std::size_t output_count = outputs_.size();
  for (std::size_t o = 0; o < output_count; ++o) {
    defuzzify(static_cast<std::uint32_t>(o), w);
    outputs[o] = w.output_values_[o];
    w.activated_count_[o] = 0;  // empty for the next evaluation (make_workspace starts empty)
  }
}

void Evaluator::evaluate_batch(std::span<const double> inputs, std::span<double> outputs,
                               Workspace& w) const {
  const std::size_t n_in = inputs_.size();
  const std::size_t n_out = outputs_.size();
  const std::size_t rows =
      n_in == 0 ? outputs.size() / std::max<std::size_t>(n_out, 1) : inputs.size() / n_in;
  for (std::size_t r = 0; r < rows; ++r) {
    evaluate(inputs.subspan(r * n_in, n_in), outputs.subspan(r * n_out, n_out), w);
  }
}

}  // namespace fuzzygait::fuzzy

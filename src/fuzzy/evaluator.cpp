#include "fuzzygait/fuzzy/evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

bool takagi_sugeno_kind(TermKind kind) {
  return kind == TermKind::Constant || kind == TermKind::Linear || kind == TermKind::Function;
}

// Fills out[i] with the shape at x_i = minimum + (i + 0.5) dx. One loop per shape keeps the
// dispatch out of the sample loop.
template <class Shape>
void sample(double minimum, double dx, int n, double* out, Shape shape) {
  for (int i = 0; i < n; ++i) out[i] = shape(minimum + (i + 0.5) * dx);
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
    for (std::size_t i = 0; i < problems.size(); ++i) all += (i ? "; " : "") + problems[i];
    throw std::invalid_argument(all);
  }
  auto add_terms = [this, &engine](const std::vector<Term>& terms) {
    const auto first = static_cast<std::uint32_t>(terms_.size());
    for (const Term& t : terms) {
      CompiledTerm c{};
      c.kind = t.kind;
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
    const std::uint32_t first = add_terms(v.terms);
    inputs_.push_back({v.name, v.minimum, v.maximum, v.enabled, v.lock_range, first,
                       static_cast<std::uint32_t>(v.terms.size())});
  }
  for (const OutputVariable& v : engine.outputs) {
    const std::uint32_t first = add_terms(v.terms);
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
    if (o.defuzzifier.is_integral()) {
      max_resolution_ = std::max(max_resolution_, o.defuzzifier.resolution);
    }
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
      const std::uint32_t first = p.output ? outputs_[c.variable].first_term
                                           : inputs_[c.variable].first_term;
      const std::vector<Term>& terms =
          p.output ? engine.outputs[c.variable].terms : engine.inputs[c.variable].terms;
      for (std::size_t t = 0; t < terms.size(); ++t) {
        if (terms[t].name == p.term) c.term = static_cast<std::int32_t>(first + t);
      }
    }
    c.variable_enabled = p.output ? engine.outputs[c.variable].enabled
                                  : engine.inputs[c.variable].enabled;
    return c;
  };

  std::vector<std::size_t> capacity(outputs_.size(), 0);
  for (const RuleBlock& b : engine.rule_blocks) {
    CompiledBlock block{b.enabled,   b.conjunction, b.disjunction,
                        b.implication, b.activation, static_cast<std::uint32_t>(rules_.size()),
                        static_cast<std::uint32_t>(b.rules.size())};
    max_block_rules_ = std::max(max_block_rules_, b.rules.size());
    for (const Rule& r : b.rules) {
      CompiledRule rule{};
      rule.weight = r.weight;
      rule.antecedent = static_cast<std::uint32_t>(antecedent_.size());
      rule.antecedent_length = static_cast<std::uint32_t>(r.antecedent.size());
      const auto first_proposition = static_cast<std::int32_t>(propositions_.size());
      std::size_t depth = 0;
      for (int token : r.antecedent) {
        antecedent_.push_back(token >= 0 ? first_proposition + token : token);
        depth = token >= 0 ? depth + 1 : depth - 1;
        stack_size_ = std::max(stack_size_, depth);
      }
      for (const Proposition& p : r.propositions) propositions_.push_back(compile_proposition(p));
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
}

Workspace Evaluator::make_workspace() const {
  Workspace w;
  w.input_values_.assign(inputs_.size(), kNaN);
  w.output_values_.assign(outputs_.size(), kNaN);
  w.previous_values_.assign(outputs_.size(), kNaN);
  w.activated_.resize(activated_total_);
  w.activated_count_.assign(outputs_.size(), 0);
  w.rule_degrees_.assign(max_block_rules_, 0.0);
  w.heap_.assign(max_block_rules_, 0);
  w.stack_.assign(stack_size_, 0.0);
  w.formula_values_.assign(formula_values_size_, 0.0);
  w.formula_stack_.assign(std::max<std::size_t>(formula_stack_size_, 1), 0.0);
  w.samples_.assign(static_cast<std::size_t>(max_resolution_), 0.0);
  w.term_samples_.assign(static_cast<std::size_t>(max_resolution_), 0.0);
  return w;
}

double Evaluator::membership(const CompiledTerm& t, double x, Workspace& w) const {
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
        w.formula_values_[i] = b == kX   ? x
                               : b >= 0 ? w.input_values_[static_cast<std::size_t>(b)]
                                        : w.output_values_[static_cast<std::size_t>(-b - 1)];
      }
      return evaluate_formula(f.program, w.formula_values_.data(), w.formula_stack_.data());
    }
    case TermKind::Gaussian:
      return shapes::gaussian(x, p[0], p[1], h);
    case TermKind::GaussianProduct:
      return shapes::gaussian_product(x, p[0], p[1], p[2], p[3], h);
    case TermKind::Linear: {
      double result = 0.0;
      const std::size_t n = inputs_.size();
      for (std::size_t i = 0; i < n; ++i) {
        if (i < t.count) result += p[i] * w.input_values_[i];
      }
      if (t.count > n) result += p[t.count - 1];
      return result;
    }
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
    result = membership(terms_[static_cast<std::size_t>(p.term)], w.input_values_[p.variable], w);
  }
  while (count > 0) result = apply(hedges[--count], result);
  return result;
}

double Evaluator::antecedent(const CompiledRule& rule, const CompiledBlock& block,
                             Workspace& w) const {
  double* stack = w.stack_.data();
  std::size_t top = 0;
  const std::int32_t* code = antecedent_.data() + rule.antecedent;
  for (std::uint32_t i = 0; i < rule.antecedent_length; ++i) {
    const std::int32_t token = code[i];
    if (token >= 0) {
      stack[top++] = proposition(propositions_[static_cast<std::size_t>(token)], w);
    } else {
      const double right = stack[--top];
      const double left = stack[top - 1];
      stack[top - 1] = token == Rule::kAnd ? apply(block.conjunction, left, right)
                                           : apply(block.disjunction, left, right);
    }
  }
  return rule.weight * stack[0];
}

void Evaluator::trigger(const CompiledRule& rule, double degree, TNorm implication,
                        Workspace& w) const {
  if (!is_gt(degree, 0.0)) return;
  for (std::uint32_t c = 0; c < rule.conclusion_count; ++c) {
    const CompiledProposition& p = conclusions_[rule.conclusions + c];
    if (!p.variable_enabled) continue;
    // fuzzylite hedges the degree in place, so a hedge also reaches later conclusions.
    for (std::uint32_t h = p.hedge_count; h > 0; --h) degree = apply(hedges_[p.hedges + h - 1], degree);
    const CompiledOutput& o = outputs_[p.variable];
    w.activated_[o.activated_offset + w.activated_count_[p.variable]++] = {
        static_cast<std::uint32_t>(p.term), degree, implication};
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
      for (std::uint32_t r = 0; r < n; ++r) {
        trigger(rules[r], antecedent(rules[r], block, w), block.implication, w);
      }
      return;
    case Activation::Kind::Proportional: {
      double sum = 0.0;
      for (std::uint32_t r = 0; r < n; ++r) {
        degrees[r] = antecedent(rules[r], block, w);
        sum += degrees[r];
      }
      for (std::uint32_t r = 0; r < n; ++r) trigger(rules[r], degrees[r] / sum, block.implication, w);
      return;
    }
    case Activation::Kind::Threshold:
      for (std::uint32_t r = 0; r < n; ++r) {
        const double d = antecedent(rules[r], block, w);
        if (activates(a, d)) trigger(rules[r], d, block.implication, w);
      }
      return;
    case Activation::Kind::First:
    case Activation::Kind::Last: {
      int activated = 0;
      for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t r = a.kind == Activation::Kind::First ? i : n - 1 - i;
        const double d = antecedent(rules[r], block, w);
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
        degrees[r] = antecedent(rules[r], block, w);
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

void Evaluator::sample_aggregate(const CompiledOutput& o, double minimum, double dx,
                                 int resolution, Workspace& w) const {
  double* mu = w.samples_.data();
  double* y = w.term_samples_.data();
  std::fill(mu, mu + resolution, 0.0);
  const Workspace::Activated* activated = w.activated_.data() + o.activated_offset;
  const std::uint32_t count = w.activated_count_[&o - outputs_.data()];
  for (std::uint32_t k = 0; k < count; ++k) {
    const CompiledTerm& t = terms_[activated[k].term];
    const double* p = parameters_.data() + t.parameters;
    const double h = t.height;
    switch (t.kind) {
      case TermKind::Triangle:
        sample(minimum, dx, resolution, y,
               [&](double x) { return shapes::triangle(x, p[0], p[1], p[2], h); });
        break;
      case TermKind::Trapezoid:
        sample(minimum, dx, resolution, y,
               [&](double x) { return shapes::trapezoid(x, p[0], p[1], p[2], p[3], h); });
        break;
      case TermKind::Gaussian:
        sample(minimum, dx, resolution, y,
               [&](double x) { return shapes::gaussian(x, p[0], p[1], h); });
        break;
      case TermKind::Bell:
        sample(minimum, dx, resolution, y,
               [&](double x) { return shapes::bell(x, p[0], p[1], p[2], h); });
        break;
      default:
        sample(minimum, dx, resolution, y, [&](double x) { return membership(t, x, w); });
        break;
    }
    const double degree = activated[k].degree;
    const TNorm implication = activated[k].implication;
    const SNorm aggregation = o.aggregation;
    if (implication == TNorm::Minimum && aggregation == SNorm::Maximum) {
      for (int i = 0; i < resolution; ++i) mu[i] = nan_max(mu[i], nan_min(y[i], degree));
    } else if (implication == TNorm::AlgebraicProduct && aggregation == SNorm::Maximum) {
      for (int i = 0; i < resolution; ++i) mu[i] = nan_max(mu[i], y[i] * degree);
    } else {
      for (int i = 0; i < resolution; ++i) {
        mu[i] = apply(aggregation, mu[i], apply(implication, y[i], degree));
      }
    }
  }
}

double Evaluator::integral(const CompiledOutput& o, Workspace& w) const {
  const double minimum = o.minimum;
  const double maximum = o.maximum;
  if (!std::isfinite(minimum + maximum)) return kNaN;
  const int resolution = o.defuzzifier.resolution;
  const double dx = (maximum - minimum) / resolution;
  if (o.defuzzifier.kind == Defuzzifier::Kind::Bisector) {
    // Samples from both ends towards the middle: x values differ from the uniform grid.
    const Workspace::Activated* activated = w.activated_.data() + o.activated_offset;
    const std::uint32_t count = w.activated_count_[&o - outputs_.data()];
    auto aggregated = [&](double x) {
      double mu = 0.0;
      for (std::uint32_t k = 0; k < count; ++k) {
        mu = apply(o.aggregation, mu,
                   apply(activated[k].implication, membership(terms_[activated[k].term], x, w),
                         activated[k].degree));
      }
      return mu;
    };
    int counter = resolution;
    int left = 0;
    int right = 0;
    double left_area = 0.0;
    double right_area = 0.0;
    double x_left = minimum;
    double x_right = maximum;
    while (counter-- > 0) {
      if (is_le(left_area, right_area)) {
        x_left = minimum + (left + 0.5) * dx;
        left_area += aggregated(x_left);
        ++left;
      } else {
        x_right = maximum - (right + 0.5) * dx;
        right_area += aggregated(x_right);
        ++right;
      }
    }
    return (left_area * x_right + right_area * x_left) / (left_area + right_area);
  }
  sample_aggregate(o, minimum, dx, resolution, w);
  const double* mu = w.samples_.data();
  switch (o.defuzzifier.kind) {
    case Defuzzifier::Kind::Centroid: {
      double area = 0.0;
      double x_centroid = 0.0;
      for (int i = 0; i < resolution; ++i) {
        const double x = minimum + (i + 0.5) * dx;
        x_centroid += mu[i] * x;
        area += mu[i];
      }
      return x_centroid / area;
    }
    case Defuzzifier::Kind::SmallestOfMaximum: {
      double y_max = -1.0;
      double x_smallest = minimum;
      for (int i = 0; i < resolution; ++i) {
        if (is_gt(mu[i], y_max)) {
          x_smallest = minimum + (i + 0.5) * dx;
          y_max = mu[i];
        }
      }
      return x_smallest;
    }
    case Defuzzifier::Kind::LargestOfMaximum: {
      double y_max = -1.0;
      double x_largest = maximum;
      for (int i = 0; i < resolution; ++i) {
        if (is_ge(mu[i], y_max)) {
          y_max = mu[i];
          x_largest = minimum + (i + 0.5) * dx;
        }
      }
      return x_largest;
    }
    case Defuzzifier::Kind::MeanOfMaximum: {
      double y_max = -1.0;
      double x_smallest = minimum;
      double x_largest = maximum;
      bool same_plateau = false;
      for (int i = 0; i < resolution; ++i) {
        const double x = minimum + (i + 0.5) * dx;
        if (is_gt(mu[i], y_max)) {
          y_max = mu[i];
          x_smallest = x;
          x_largest = x;
          same_plateau = true;
        } else if (same_plateau && is_eq(mu[i], y_max)) {
          x_largest = x;
        } else if (is_lt(mu[i], y_max)) {
          same_plateau = false;
        }
      }
      return 0.5 * (x_largest + x_smallest);
    }
    default:
      return kNaN;
  }
}

double Evaluator::weighted(const CompiledOutput& o, Workspace& w) const {
  const Workspace::Activated* activated = w.activated_.data() + o.activated_offset;
  const std::uint32_t count = w.activated_count_[&o - outputs_.data()];
  Defuzzifier::WeightedType type = o.defuzzifier.type;
  if (type == Defuzzifier::WeightedType::Automatic) {
    type = takagi_sugeno_kind(terms_[activated[0].term].kind)
               ? Defuzzifier::WeightedType::TakagiSugeno
               : Defuzzifier::WeightedType::Tsukamoto;
  }
  const bool average = o.defuzzifier.kind == Defuzzifier::Kind::WeightedAverage;
  double sum = 0.0;
  double weights = 0.0;
  for (std::uint32_t k = 0; k < count; ++k) {
    const double degree = activated[k].degree;
    const CompiledTerm& t = terms_[activated[k].term];
    const double z = type == Defuzzifier::WeightedType::TakagiSugeno
                         ? membership(t, degree, w)
                         : tsukamoto(t, degree, o.minimum, o.maximum, w);
    sum += degree * z;
    if (average) weights += degree;
  }
  return average ? sum / weights : sum;
}

void Evaluator::defuzzify(std::uint32_t output, Workspace& w) const {
  const CompiledOutput& o = outputs_[output];
  if (!o.enabled) return;
  double& value = w.output_values_[output];
  double& previous = w.previous_values_[output];
  if (std::isfinite(value)) previous = value;
  double result;
  if (w.activated_count_[output] > 0) {
    result = o.defuzzifier.is_integral() ? integral(o, w) : weighted(o, w);
  } else {
    result = (o.lock_previous && !std::isnan(previous)) ? previous : o.default_value;
  }
  value = o.lock_range ? bound(result, o.minimum, o.maximum) : result;
}

void Evaluator::evaluate(std::span<const double> inputs, std::span<double> outputs,
                         Workspace& w) const {
  for (std::size_t i = 0; i < inputs_.size(); ++i) {
    const CompiledInput& v = inputs_[i];
    w.input_values_[i] = v.lock_range ? bound(inputs[i], v.minimum, v.maximum) : inputs[i];
  }
  std::fill(w.activated_count_.begin(), w.activated_count_.end(), 0u);
  for (const CompiledBlock& block : blocks_) {
    if (block.enabled) activate(block, w);
  }
  for (std::size_t o = 0; o < outputs_.size(); ++o) {
    defuzzify(static_cast<std::uint32_t>(o), w);
    outputs[o] = w.output_values_[o];
  }
}

void Evaluator::evaluate_batch(std::span<const double> inputs, std::span<double> outputs,
                               Workspace& w) const {
  const std::size_t n_in = inputs_.size();
  const std::size_t n_out = outputs_.size();
  const std::size_t rows = n_in == 0 ? outputs.size() / std::max<std::size_t>(n_out, 1)
                                     : inputs.size() / n_in;
  for (std::size_t r = 0; r < rows; ++r) {
    evaluate(inputs.subspan(r * n_in, n_in), outputs.subspan(r * n_out, n_out), w);
  }
}

}  // namespace fuzzygait::fuzzy

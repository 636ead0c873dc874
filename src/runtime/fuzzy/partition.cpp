#include "fuzzygait/fuzzy/partition.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace fuzzygait::fuzzy {
namespace {

bool fail(std::string* reason, const std::string& why) {
  if (reason) *reason = why;
  return false;
}

// Knots of an input whose Triangle terms form a strong partition over its locked range.
bool knots_of(const InputVariable& v, std::vector<double>& knots, std::string* reason) {
  if (!v.enabled) return fail(reason, "input '" + v.name + "' is disabled");
  if (!v.lock_range) return fail(reason, "input '" + v.name + "' does not lock its range");
  const std::size_t n = v.terms.size();
  if (n < 2) return fail(reason, "input '" + v.name + "' has fewer than two terms");
  knots.clear();
  for (const Term& t : v.terms) {
    if (t.kind != TermKind::Triangle || t.height != 1.0) {
      return fail(reason, "term '" + t.name + "' of '" + v.name + "' is not a unit Triangle");
    }
    knots.push_back(t.parameters[1]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::vector<double>& p = v.terms[i].parameters;
    if (i + 1 < n && !(knots[i] < knots[i + 1])) {
      return fail(reason, "terms of '" + v.name + "' are not ordered by their peaks");
    }
    const bool left_ok = i == 0 ? p[0] <= p[1] : p[0] == knots[i - 1];
    const bool right_ok = i + 1 == n ? p[2] >= p[1] : p[2] == knots[i + 1];
    if (!left_ok || !right_ok) {
      return fail(reason, "term '" + v.terms[i].name + "' of '" + v.name +
                              "' does not reach zero at the neighbouring peaks");
    }
  }
  if (v.minimum != knots.front() || v.maximum != knots.back()) {
    return fail(reason, "the range of '" + v.name + "' is not [first peak, last peak]");
  }
  return true;
}

}  // namespace

std::optional<PartitionController<double>> as_partition(const Engine& engine, std::string* reason) {
  PartitionController<double> c;
  const std::size_t inputs = engine.inputs.size();
  if (inputs < 1 || inputs > 2) {
    fail(reason, "a partition controller has one or two inputs");
    return std::nullopt;
  }
  for (std::size_t i = 0; i < inputs; ++i) {
    if (!knots_of(engine.inputs[i], c.knots[i], reason)) return std::nullopt;
  }
  if (engine.outputs.size() != 1) {
    fail(reason, "a partition controller has one output");
    return std::nullopt;
  }
  const OutputVariable& out = engine.outputs[0];
  const bool weighted_average = out.defuzzifier &&
                                out.defuzzifier->kind == Defuzzifier::Kind::WeightedAverage &&
                                out.defuzzifier->type != Defuzzifier::WeightedType::Tsukamoto;
  if (!out.enabled || out.lock_range || out.lock_previous || !weighted_average) {
    fail(reason, "the output must be enabled, unlocked, with a WeightedAverage defuzzifier");
    return std::nullopt;
  }
  for (const Term& t : out.terms) {
    if (t.kind != TermKind::Constant) {
      fail(reason, "output term '" + t.name + "' is not a Constant");
      return std::nullopt;
    }
  }
  c.default_value = out.default_value;
  if (engine.rule_blocks.size() != 1) {
    fail(reason, "a partition controller has one rule block");
    return std::nullopt;
  }
  const RuleBlock& block = engine.rule_blocks[0];
  const bool general = block.activation.kind == Activation::Kind::General ||
                       block.activation.kind == Activation::Kind::None;
  if (!block.enabled || !general) {
    fail(reason, "the rule block must be enabled with General activation");
    return std::nullopt;
  }
  if (inputs == 2) {
    if (block.conjunction == TNorm::AlgebraicProduct) {
      c.conjunction = Conjunction::Product;
    } else if (block.conjunction == TNorm::Minimum) {
      c.conjunction = Conjunction::Minimum;
    } else {
      fail(reason, "the conjunction must be AlgebraicProduct or Minimum");
      return std::nullopt;
    }
  }
  const std::size_t columns = inputs == 2 ? c.knots[1].size() : 1;
  const std::size_t cells = c.knots[0].size() * columns;
  if (block.rules.size() != cells) {
    fail(reason, "expected one rule per combination of terms (" + std::to_string(cells) + ")");
    return std::nullopt;
  }
  c.consequents.assign(cells, 0.0);
  for (std::size_t r = 0; r < cells; ++r) {
    const Rule& rule = block.rules[r];
    const std::size_t row = r / columns;
    const std::size_t column = r % columns;
    const std::vector<int> expected_code =
        inputs == 2 ? std::vector<int>{0, 1, Rule::kAnd} : std::vector<int>{0};
    bool ok = rule.weight == 1.0 && rule.antecedent == expected_code &&
              rule.conclusions.size() == 1 && rule.conclusions[0].hedges.empty();
    for (std::size_t i = 0; ok && i < inputs; ++i) {
      const Proposition& p = rule.propositions[i];
      const std::size_t term = i == 0 ? row : column;
      ok = !p.output && p.hedges.empty() && p.variable == engine.inputs[i].name &&
           p.term == engine.inputs[i].terms[term].name;
    }
    if (!ok) {
      fail(reason, "rule " + std::to_string(r + 1) + " is not 'if " + engine.inputs[0].name +
                       " is " + engine.inputs[0].terms[row].name +
                       (inputs == 2 ? " and " + engine.inputs[1].name + " is " +
                                          engine.inputs[1].terms[column].name
                                    : std::string()) +
                       " then ...' in row-major order");
      return std::nullopt;
    }
    c.consequents[r] = out.find_term(rule.conclusions[0].term)->parameters[0];
  }
  return c;
}

Engine with_partition(const Engine& base, const PartitionController<double>& controller) {
  std::string reason;
  if (!as_partition(base, &reason)) {
    throw std::invalid_argument("with_partition: the base engine is not of the partition shape: " +
                                reason);
  }
  Engine out = base;
  for (std::size_t i = 0; i < out.inputs.size(); ++i) {
    const std::vector<double>& k = controller.knots[i];
    InputVariable& v = out.inputs[i];
    if (k.size() != v.terms.size()) {
      throw std::invalid_argument("with_partition: input '" + v.name + "' has " +
                                  std::to_string(v.terms.size()) + " terms but " +
                                  std::to_string(k.size()) + " knots were given");
    }
    for (std::size_t t = 0; t < k.size(); ++t) {
      if (t + 1 < k.size() && !(k[t] < k[t + 1])) {
        throw std::invalid_argument("with_partition: knots of '" + v.name + "' must increase");
      }
      const double left = t == 0 ? k[0] - (k.size() > 1 ? k[1] - k[0] : 1.0) : k[t - 1];
      const double right = t + 1 == k.size() ? k[t] + (k[t] - k[t - 1]) : k[t + 1];
      v.terms[t].parameters = {left, k[t], right};
    }
    v.minimum = k.front();
    v.maximum = k.back();
  }
  OutputVariable& o = out.outputs[0];
  std::vector<bool> assigned(o.terms.size(), false);
  const std::vector<Rule>& rules = out.rule_blocks[0].rules;
  for (std::size_t r = 0; r < rules.size(); ++r) {
    for (std::size_t t = 0; t < o.terms.size(); ++t) {
      if (o.terms[t].name != rules[r].conclusions[0].term) continue;
      const double value = controller.consequents.at(r);
      if (assigned[t] && !(o.terms[t].parameters[0] == value)) {
        throw std::invalid_argument("with_partition: rules sharing output term '" +
                                    o.terms[t].name + "' were given different values");
      }
      o.terms[t].parameters = {value};
      assigned[t] = true;
    }
  }
  return out;
}

std::optional<PackedPartition> PackedPartition::pack(const PartitionController<double>& c) {
  PackedPartition p;
  const std::size_t inputs = c.input_count();
  for (std::size_t i = 0; i < inputs; ++i) {
    const std::vector<double>& knots = c.knots[i];
    if (knots.size() < 2 || knots.size() > kMaxKnots) return std::nullopt;
    // Increasing, as as_partition makes them: the batch form counts the knots below an input.
    for (std::size_t k = 1; k < knots.size(); ++k) {
      if (!(knots[k - 1] < knots[k])) return std::nullopt;
    }
    std::copy(knots.begin(), knots.end(), p.knots_[i].begin());
    p.counts_[i] = knots.size();
  }
  const std::size_t columns = inputs == 2 ? c.knots[1].size() : 1;
  if (c.consequents.size() != c.knots[0].size() * columns) return std::nullopt;
  for (std::size_t row = 0; row < c.knots[0].size(); ++row) {
    for (std::size_t column = 0; column < columns; ++column) {
      p.consequents_[inputs == 2 ? row * kMaxKnots + column : row] =
          c.consequents[row * columns + column];
    }
  }
  p.default_value_ = c.default_value;
  p.shape_ = inputs == 1                             ? Shape::OneInput
             : c.conjunction == Conjunction::Product ? Shape::Product
                                                     : Shape::Minimum;
  return p;
}

// The batch: the steps of evaluate_partition lane for lane, as selects instead of branches, so
// every lane gets the bits the scalar call gives (a rule that does not fire leaves the sums as
// they are; a NaN input gives the default).
struct PackedLanes {
  static void scalar(const PackedPartition& p, const double* x0, const double* x1, double* out,
                     std::size_t n) {
    const bool one_input = p.shape_ == PackedPartition::Shape::OneInput;
    for (std::size_t i = 0; i < n; ++i)
      out[i] = p.evaluate(x0[i], one_input ? 0.0 : x1[i]);
  }
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  // In GCC's vector extensions, four lanes: one AVX2 register. (Eight lanes of AVX-512, each
  // lane's consequent loaded on its own, took 10 ns a lane against 4.0 here and 6.6 scalar.)
  typedef double Real __attribute__((vector_size(32)));
  typedef std::int64_t Mask __attribute__((vector_size(32)));
  [[gnu::target("avx2")]] static void avx2(const PackedPartition& p, const double* x0,
                                           const double* x1, double* out, std::size_t n);
#endif
};

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>

namespace {

using Real = PackedLanes::Real;
using Mask = PackedLanes::Mask;

[[gnu::target("avx2"), gnu::always_inline]] inline Real broadcast(double value) {
  return Real{value, value, value, value};
}
[[gnu::target("avx2"), gnu::always_inline]] inline Mask broadcast_index(std::int64_t value) {
  return Mask{value, value, value, value};
}

// partition_degrees in every lane (x not NaN; a NaN lane's result is replaced by the default).
[[gnu::target("avx2"), gnu::always_inline]] inline void lane_degrees(const double* knots,
                                                                     std::size_t count, Real x,
                                                                     Mask& lower,
                                                                     Real& lower_degree,
                                                                     Real& upper_degree) {
  const Real one = broadcast(1.0);
  const Real tolerance = broadcast(kTolerance);
  // knots[i] <= x < knots[i + 1]: i counts the inner knots at or below x.
  Mask i = broadcast_index(0);
  Real left = broadcast(knots[0]);
  Real right = broadcast(knots[1]);
  for (std::size_t k = 1; k + 1 < count; ++k) {
    const Real knot = broadcast(knots[k]);
    const Mask at_or_above = x >= knot;  // -1 where true
    i -= at_or_above;
    left = at_or_above ? knot : left;
    right = at_or_above ? broadcast(knots[k + 1]) : right;
  }
  lower_degree = x - left < tolerance ? one : (right - x) / (right - left);
  upper_degree = right - x < tolerance ? one : (x - left) / (right - left);
  const Mask below = !(x > broadcast(knots[0]));
  const Mask above = !(x < broadcast(knots[count - 1]));
  lower_degree = (below | above) ? one : lower_degree;
  upper_degree = (below | above) ? broadcast(0.0) : upper_degree;
  lower = above ? broadcast_index(static_cast<std::int64_t>(count - 1)) : i;
  lower = below ? broadcast_index(0) : lower;
}

// A rule fires in each lane where its degree reaches the tolerance: its consequent (at rule[lane]
// in the table) weighted by the degree.
[[gnu::target("avx2"), gnu::always_inline]] inline void lane_fire(Real degree, Mask rule,
                                                                  const double* consequents,
                                                                  Real& sum, Real& weights) {
  const Mask fires = degree >= broadcast(kTolerance);
  // A masked gather: a lane that does not fire loads nothing (its index may lie past the table).
  const Real consequent = reinterpret_cast<Real>(
      _mm256_mask_i64gather_pd(_mm256_setzero_pd(), consequents, reinterpret_cast<__m256i>(rule),
                               reinterpret_cast<__m256d>(fires), 8));
  sum = fires ? sum + degree * consequent : sum;
  weights = fires ? weights + degree : weights;
}

// nan_min: a NaN degree (finite knots more than the largest double apart) yields to the other.
[[gnu::target("avx2"), gnu::always_inline]] inline Real lane_minimum(Real a, Real b) {
  return a != a ? b : (b != b ? a : (a < b ? a : b));
}

}  // namespace

void PackedLanes::avx2(const PackedPartition& p, const double* x0, const double* x1, double* out,
                       std::size_t n) {
  using Shape = PackedPartition::Shape;
  constexpr std::size_t kWidth = PackedPartition::kVectorLanes;
  static_assert(sizeof(Real) == kWidth * sizeof(double));
  const double* consequents = p.consequents_.data();
  const std::size_t whole = n - n % kWidth;
  for (std::size_t at = 0; at < whole; at += kWidth) {
    Real a;
    std::memcpy(&a, x0 + at, sizeof a);
    Mask a_lower;
    Real a_low;
    Real a_high;
    lane_degrees(p.knots_[0].data(), p.counts_[0], a, a_lower, a_low, a_high);
    Real sum = broadcast(0.0);
    Real weights = broadcast(0.0);
    Mask nan = a != a;
    if (p.shape_ == Shape::OneInput) {
      lane_fire(a_low, a_lower, consequents, sum, weights);
      lane_fire(a_high, a_lower + 1, consequents, sum, weights);
    } else {
      Real b;
      std::memcpy(&b, x1 + at, sizeof b);
      nan |= b != b;
      Mask b_lower;
      Real b_low;
      Real b_high;
      lane_degrees(p.knots_[1].data(), p.counts_[1], b, b_lower, b_low, b_high);
      const auto stride = static_cast<std::int64_t>(PackedPartition::kMaxKnots);
      const Mask rule = a_lower * stride + b_lower;
      if (p.shape_ == Shape::Product) {
        lane_fire(a_low * b_low, rule, consequents, sum, weights);
        lane_fire(a_low * b_high, rule + 1, consequents, sum, weights);
        lane_fire(a_high * b_low, rule + stride, consequents, sum, weights);
        lane_fire(a_high * b_high, rule + stride + 1, consequents, sum, weights);
      } else {
        lane_fire(lane_minimum(a_low, b_low), rule, consequents, sum, weights);
        lane_fire(lane_minimum(a_low, b_high), rule + 1, consequents, sum, weights);
        lane_fire(lane_minimum(a_high, b_low), rule + stride, consequents, sum, weights);
        lane_fire(lane_minimum(a_high, b_high), rule + stride + 1, consequents, sum, weights);
      }
    }
    const Real average = sum / weights;
    const Mask defined = (weights > broadcast(0.0)) & ~nan;
    const Real result = defined ? average : broadcast(p.default_value_);
    std::memcpy(out + at, &result, sizeof result);
  }
  scalar(p, x0 + whole, x1 != nullptr ? x1 + whole : nullptr, out + whole, n - whole);
}

bool PackedPartition::batch_in_vectors() {
  static const bool has_avx2 = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return has_avx2;
}

void PackedPartition::evaluate(const double* x0, const double* x1, double* out,
                               std::size_t n) const {
  if (batch_in_vectors()) {
    PackedLanes::avx2(*this, x0, x1, out, n);
  } else {
    PackedLanes::scalar(*this, x0, x1, out, n);
  }
}

#else

bool PackedPartition::batch_in_vectors() {
  return false;
}

void PackedPartition::evaluate(const double* x0, const double* x1, double* out,
                               std::size_t n) const {
  PackedLanes::scalar(*this, x0, x1, out, n);
}

#endif

}  // namespace fuzzygait::fuzzy

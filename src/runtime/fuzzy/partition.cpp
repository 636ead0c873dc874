#include "fuzzygait/fuzzy/partition.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "runtime/fuzzy/packed_batch.hpp"
#include "runtime/simd/cpu.hpp"

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

detail::PackedView detail::PackedPartitionAccess::view(const PackedPartition& p) {
  using Shape = PackedPartition::Shape;
  static_assert(PackedPartition::kMaxKnots == kPackedRowStride);
  PackedView v{};
  v.knots[0] = p.knots_[0].data();
  v.knots[1] = p.knots_[1].data();
  v.counts[0] = p.counts_[0];
  v.counts[1] = p.counts_[1];
  v.consequents = p.consequents_.data();
  v.default_value = p.default_value_;
  v.tolerance = kTolerance;
  v.shape = p.shape_ == Shape::OneInput  ? PackedShape::OneInput
            : p.shape_ == Shape::Product ? PackedShape::Product
                                         : PackedShape::Minimum;
  return v;
}

std::size_t detail::batch_vector_lanes() {
  if (simd::has_avx512()) return 8;
  if (simd::has_avx2()) return 4;
  return 1;
}

void detail::evaluate_batch(const PackedPartition& p, const double* x0, const double* x1,
                            double* out, std::size_t n) {
  const PackedView view = PackedPartitionAccess::view(p);
  const bool one_input = view.shape == PackedShape::OneInput;
  std::size_t done = 0;
  // Whole vectors of the lanes [done, done + count).
  [[maybe_unused]] auto in_vectors = [&](std::size_t width, auto kernel) {
    const std::size_t count = (n - done) / width * width;
    if (count == 0) return;
    kernel(view, x0 + done, one_input ? nullptr : x1 + done, out + done, count);
    done += count;
  };
#if defined(FUZZYGAIT_SIMD_AVX512)
  if (simd::has_avx512()) in_vectors(8, evaluate_packed_avx512);
#endif
#if defined(FUZZYGAIT_SIMD_AVX2)
  if (simd::has_avx2()) in_vectors(4, evaluate_packed_avx2);
#endif
  // The remaining lanes, and every lane without vectors: the scalar path is faster than the
  // lanes' selects one at a time.
  for (std::size_t i = done; i < n; ++i)
    out[i] = p.evaluate(x0[i], one_input ? 0.0 : x1[i]);
}

}  // namespace fuzzygait::fuzzy

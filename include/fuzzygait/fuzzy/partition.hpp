// The trainable core: a Takagi-Sugeno controller over one or two inputs whose terms form strong
// triangular partitions (each term a Triangle peaking at a knot and reaching zero at the
// neighbouring knots), one rule per combination of terms with a Constant consequent, product or
// minimum conjunction, and weighted-average defuzzification. It is the shape of every gait
// controller, and the fuzzy neural network of the paper (GARIC-style): its weights are the knots
// and the consequents, readable as FLL terms.
//
// Everything is templated on the scalar, so automatic differentiation (Ceres Jets, dual numbers)
// flows through evaluation; with double it is the controllers' fast path (a few nanoseconds).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/compare.hpp"
#include "fuzzygait/fuzzy/engine.hpp"
#include "fuzzygait/fuzzy/shapes.hpp"

namespace fuzzygait::fuzzy {

// Membership degrees of a strong triangular partition at x: at most two neighbouring terms are
// non-zero. Inputs are clamped to [knots.front(), knots.back()] (the variables lock their range).
template <class T>
struct PartitionDegrees {
  std::size_t lower = 0;  // index of the first non-zero term
  T lower_degree = T(1.0);
  T upper_degree = T(0.0);  // degree of term lower + 1 (zero when lower is the last term)
};

// Always inlined: the walker evaluates eight controllers a time step, and the call returned its
// result through memory (inlining it, with level ground's height, took a step from 405 to 383 ns).
template <class T>
[[gnu::always_inline]] inline PartitionDegrees<T> partition_degrees(const T* knots,
                                                                    std::size_t count, const T& x) {
  PartitionDegrees<T> d;
  if (count < 2 || !(x > knots[0])) return d;
  if (!(x < knots[count - 1])) {
    d.lower = count - 1;
    return d;
  }
  std::size_t i = 0;
  while (i + 2 < count && !(x < knots[i + 1]))
    ++i;
  // knots[i] <= x < knots[i + 1]: the neighbouring Triangle terms (shapes::triangle) come down
  // to these sides, a degree of 1 where x is within fuzzylite's tolerance of their peak
  // (is_eq(x, peak), which on this side of the peak is the difference below the tolerance).
  const T& left = knots[i];
  const T& right = knots[i + 1];
  d.lower = i;
  d.lower_degree = x - left < T(kTolerance) ? T(1.0) : T((right - x) / (right - left));
  d.upper_degree = right - x < T(kTolerance) ? T(1.0) : T((x - left) / (right - left));
  return d;
}

enum class Conjunction { Product, Minimum };

template <class T>
struct PartitionController {
  std::vector<T> knots[2];     // knots of input 0 and (optionally) input 1
  std::vector<T> consequents;  // row-major: term of input 0 major, term of input 1 minor
  Conjunction conjunction = Conjunction::Product;
  T default_value = T(kNaN);  // output when no rule fires (a NaN input)

  std::size_t input_count() const { return knots[1].empty() ? 1 : 2; }

  // Same result as the general Evaluator on the equivalent engine: rules fire when their degree
  // exceeds fuzzylite's tolerance, and sums run in rule order. Only the (at most four) rules
  // around the inputs can fire.
  T evaluate(const T& x0, const T& x1 = T(0.0)) const {
    const bool two_inputs = !knots[1].empty();
    if (detail::is_nan(x0) || (two_inputs && detail::is_nan(x1))) return default_value;
    const PartitionDegrees<T> a = partition_degrees(knots[0].data(), knots[0].size(), x0);
    T sum(0.0);
    T weights(0.0);
    // is_gt(degree, 0): for any degree, NaN included, the same as degree >= kTolerance.
    auto fire = [&](const T& degree, std::size_t rule) {
      if (!(degree >= T(kTolerance))) return;
      sum += degree * consequents[rule];
      weights += degree;
    };
    if (!two_inputs) {
      fire(a.lower_degree, a.lower);
      fire(a.upper_degree, a.lower + 1);
    } else {
      const PartitionDegrees<T> b = partition_degrees(knots[1].data(), knots[1].size(), x1);
      const std::size_t columns = knots[1].size();
      const std::size_t rule = a.lower * columns + b.lower;
      if (conjunction == Conjunction::Product) {
        fire(T(a.lower_degree * b.lower_degree), rule);
        fire(T(a.lower_degree * b.upper_degree), rule + 1);
        fire(T(a.upper_degree * b.lower_degree), rule + columns);
        fire(T(a.upper_degree * b.upper_degree), rule + columns + 1);
      } else {
        fire(nan_min(a.lower_degree, b.lower_degree), rule);
        fire(nan_min(a.lower_degree, b.upper_degree), rule + 1);
        fire(nan_min(a.upper_degree, b.lower_degree), rule + columns);
        fire(nan_min(a.upper_degree, b.upper_degree), rule + columns + 1);
      }
    }
    if (!(weights > T(0.0))) return default_value;
    return sum / weights;
  }
};

// Recognises an engine of the partition shape and extracts its knots and consequents: every
// input locks its range to [first knot, last knot] with Triangle terms peaking at the knots in
// order; one rule block, General activation, one output with WeightedAverage and Constant terms;
// exactly one rule "if a is A [and b is B] then out is C" per combination, no hedges, weight 1.
// Returns nullopt (and why, in `reason`) for any other engine.
std::optional<PartitionController<double>> as_partition(const Engine& engine,
                                                        std::string* reason = nullptr);

// Writes a partition controller back into FLL form with the given names, so that a fitted
// controller returns to the artist as readable rules. `base` supplies the names, descriptions and
// rule order (it must be of the partition shape); its knots and consequents are replaced.
Engine with_partition(const Engine& base, const PartitionController<double>& controller);

}  // namespace fuzzygait::fuzzy

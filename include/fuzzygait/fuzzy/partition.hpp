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
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fuzzygait/compiler.hpp"
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

// Always inlined: the walker evaluates eight controllers a time step.
template <class T>
FUZZYGAIT_ALWAYS_INLINE PartitionDegrees<T> partition_degrees(const T* knots, std::size_t count,
                                                              const T& x) {
  PartitionDegrees<T> d;
  if (count < 2 || !(x > knots[0])) return d;
  if (!(x < knots[count - 1])) {
    d.lower = count - 1;
    return d;
  }
  // x < knots[count - 1], so the search stops at count - 2 at the latest.
  std::size_t i = 0;
  while (!(x < knots[i + 1]))
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

// The rules around (x0, x1) fired and averaged, for every form of partition controller: the same
// result as the general Evaluator on the equivalent engine (rules fire when their degree exceeds
// fuzzylite's tolerance, sums run in rule order); only the (at most four) rules around the inputs
// can fire. Without two_inputs, knots1 and count1 are not read. The consequent of terms (i, j) is
// at consequents[i * row_stride + j].
template <class T>
FUZZYGAIT_ALWAYS_INLINE T evaluate_partition(bool two_inputs, const T* knots0, std::size_t count0,
                                             const T* knots1, std::size_t count1,
                                             const T* consequents, std::size_t row_stride,
                                             Conjunction conjunction, const T& default_value,
                                             const T& x0, const T& x1) {
  if (detail::is_nan(x0) || (two_inputs && detail::is_nan(x1))) return default_value;
  const PartitionDegrees<T> a = partition_degrees(knots0, count0, x0);
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
    const PartitionDegrees<T> b = partition_degrees(knots1, count1, x1);
    const std::size_t rule = a.lower * row_stride + b.lower;
    if (conjunction == Conjunction::Product) {
      fire(T(a.lower_degree * b.lower_degree), rule);
      fire(T(a.lower_degree * b.upper_degree), rule + 1);
      fire(T(a.upper_degree * b.lower_degree), rule + row_stride);
      fire(T(a.upper_degree * b.upper_degree), rule + row_stride + 1);
    } else {
      fire(nan_min(a.lower_degree, b.lower_degree), rule);
      fire(nan_min(a.lower_degree, b.upper_degree), rule + 1);
      fire(nan_min(a.upper_degree, b.lower_degree), rule + row_stride);
      fire(nan_min(a.upper_degree, b.upper_degree), rule + row_stride + 1);
    }
  }
  if (!(weights > T(0.0))) return default_value;
  return sum / weights;
}

template <class T>
struct PartitionController {
  std::vector<T> knots[2];     // knots of input 0 and (optionally) input 1
  std::vector<T> consequents;  // row-major: term of input 0 major, term of input 1 minor
  Conjunction conjunction = Conjunction::Product;
  T default_value = T(kNaN);  // output when no rule fires (a NaN input)

  std::size_t input_count() const { return knots[1].empty() ? 1 : 2; }

  T evaluate(const T& x0, const T& x1 = T(0.0)) const {
    return evaluate_partition(!knots[1].empty(), knots[0].data(), knots[0].size(), knots[1].data(),
                              knots[1].size(), consequents.data(),
                              knots[1].empty() ? 1 : knots[1].size(), conjunction, default_value,
                              x0, x1);
  }
};

namespace detail {
struct PackedPartitionAccess;
}

// A PartitionController<double> of at most kMaxKnots knots per input in one flat block, with its
// shape (one input, two with product or minimum) decided once, for the walker's eight calls a time
// step. The same evaluation (evaluate_partition), so the same bits as the controller it packs.
class PackedPartition {
 public:
  static constexpr std::size_t kMaxKnots = 8;

  // nullopt when an input has more than kMaxKnots knots or knots that do not increase (evaluate
  // the controller itself).
  static std::optional<PackedPartition> pack(const PartitionController<double>& controller);

  double evaluate(double x0, double x1 = 0.0) const {
    switch (shape_) {
      case Shape::OneInput:
        return evaluate_as(false, 1, Conjunction::Product, x0, x1);
      case Shape::Product:
        return evaluate_as(true, kMaxKnots, Conjunction::Product, x0, x1);
      case Shape::Minimum:
        return evaluate_as(true, kMaxKnots, Conjunction::Minimum, x0, x1);
    }
    return default_value_;
  }

 private:
  enum class Shape : std::uint8_t { OneInput, Product, Minimum };
  friend struct detail::PackedPartitionAccess;  // a crowd's batch (internal)

  // One straight path per shape (evaluate_partition is inlined with the constants).
  double evaluate_as(bool two_inputs, std::size_t row_stride, Conjunction conjunction, double x0,
                     double x1) const {
    return evaluate_partition(two_inputs, knots_[0].data(), counts_[0], knots_[1].data(),
                              counts_[1], consequents_.data(), row_stride, conjunction,
                              default_value_, x0, x1);
  }

  std::array<double, kMaxKnots> knots_[2]{};
  // Rows of kMaxKnots for two inputs, one row for one input.
  std::array<double, kMaxKnots * kMaxKnots> consequents_{};
  std::size_t counts_[2]{};
  double default_value_ = kNaN;
  Shape shape_ = Shape::OneInput;
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

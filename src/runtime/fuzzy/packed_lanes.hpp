// The packed controllers' batch kernel, written once over a lane type (simd/lanes.hpp): the steps
// of evaluate_partition lane for lane, as selects instead of branches, so that every lane gets the
// bits the scalar call gives (a rule that does not fire leaves the sums as they are; a NaN input
// gives the default). It reads a plain view of a PackedPartition and includes only lanes.hpp and
// the standard library, so that a translation unit compiled for AVX2 may instantiate it.
#pragma once

#include <cstddef>
#include <cstdint>

#include "fuzzygait/compiler.hpp"
#include "runtime/simd/lanes.hpp"

namespace fuzzygait::fuzzy::detail {

enum class PackedShape : std::uint8_t { OneInput, Product, Minimum };

// Rows of the consequents' table for two inputs (PackedPartition::kMaxKnots).
inline constexpr std::uint32_t kPackedRowStride = 8;

// A PackedPartition's data: increasing knots per input (at least two), the consequent of terms
// (i, j) at consequents[i * kPackedRowStride + j] (of term i at consequents[i] for one input).
struct PackedView {
  const double* knots[2];
  std::size_t counts[2];
  const double* consequents;
  double default_value;
  double tolerance;  // fuzzylite's: a rule fires from this degree on
  PackedShape shape;
};

template <class D>
struct LaneDegrees {
  typename D::Int lower;  // index of the first non-zero term
  D lower_degree;
  D upper_degree;  // of term lower + 1
};

// partition_degrees in every lane (a NaN lane's result is replaced by the default).
template <class D>
FUZZYGAIT_ALWAYS_INLINE LaneDegrees<D> lane_degrees(const double* knots, std::size_t count, D x,
                                                    D tolerance) {
  using Int = typename D::Int;
  // knots[i] <= x < knots[i + 1]: i counts the inner knots at or below x.
  Int i(0);
  D left(knots[0]);
  D right(knots[1]);
  for (std::size_t k = 1; k + 1 < count; ++k) {
    const D knot(knots[k]);
    const typename D::Mask at_or_above = x >= knot;
    i = i - as_int(at_or_above);  // -1 where set
    left = select(at_or_above, knot, left);
    right = select(at_or_above, D(knots[k + 1]), right);
  }
  LaneDegrees<D> d;
  d.lower_degree = select(x - left < tolerance, D(1.0), (right - x) / (right - left));
  d.upper_degree = select(right - x < tolerance, D(1.0), (x - left) / (right - left));
  // Outside (or at the ends of) the knots, or NaN: the first or last term alone.
  const typename D::Mask above_first = x > D(knots[0]);
  const typename D::Mask below_last = x < D(knots[count - 1]);
  const typename D::Mask inside = above_first & below_last;
  d.lower_degree = select(inside, d.lower_degree, D(1.0));
  d.upper_degree = select(inside, d.upper_degree, D(0.0));
  d.lower = select(below_last, i, Int(static_cast<std::int64_t>(count - 1)));
  d.lower = select(above_first, d.lower, Int(0));
  return d;
}

// A rule fires in each lane where its degree reaches the tolerance: its consequent (at rule[lane]
// in the table) weighted by the degree. A lane that does not fire loads nothing (its index may
// lie past the table).
template <class D>
FUZZYGAIT_ALWAYS_INLINE void lane_fire(D degree, typename D::Int rule, const double* consequents,
                                       D tolerance, D& sum, D& weights) {
  const typename D::Mask fires = degree >= tolerance;
  const D consequent = gather(consequents, rule, fires);
  sum = select(fires, sum + degree * consequent, sum);
  weights = select(fires, weights + degree, weights);
}

// nan_min: a NaN degree (finite knots more than the largest double apart) yields to the other.
template <class D>
FUZZYGAIT_ALWAYS_INLINE D lane_minimum(D a, D b) {
  return select(a != a, b, select(b != b, a, select(a < b, a, b)));
}

// out[i] = the controller at (x0[i], x1[i]) for i < n, n a multiple of D::kLanes. x1 is not read
// for one input.
template <class D>
void evaluate_packed_lanes(const PackedView& view, const double* x0, const double* x1, double* out,
                           std::size_t n) {
  using Int = typename D::Int;
  const PackedView p = view;  // a copy, which the stores to out cannot change
  const D tolerance(p.tolerance);
  for (std::size_t at = 0; at < n; at += D::kLanes) {
    const D a = D::load(x0 + at);
    const LaneDegrees<D> da = lane_degrees(p.knots[0], p.counts[0], a, tolerance);
    D sum(0.0);
    D weights(0.0);
    typename D::Mask ordered = a == a;  // not NaN
    if (p.shape == PackedShape::OneInput) {
      lane_fire(da.lower_degree, da.lower, p.consequents, tolerance, sum, weights);
      lane_fire(da.upper_degree, da.lower + 1, p.consequents, tolerance, sum, weights);
    } else {
      const D b = D::load(x1 + at);
      ordered = ordered & (b == b);
      const LaneDegrees<D> db = lane_degrees(p.knots[1], p.counts[1], b, tolerance);
      const Int rule = multiply_small<kPackedRowStride>(da.lower) + db.lower;
      const Int stride(kPackedRowStride);
      const double* c = p.consequents;
      if (p.shape == PackedShape::Product) {
        lane_fire(da.lower_degree * db.lower_degree, rule, c, tolerance, sum, weights);
        lane_fire(da.lower_degree * db.upper_degree, rule + 1, c, tolerance, sum, weights);
        lane_fire(da.upper_degree * db.lower_degree, rule + stride, c, tolerance, sum, weights);
        lane_fire(da.upper_degree * db.upper_degree, rule + stride + 1, c, tolerance, sum, weights);
      } else {
        lane_fire(lane_minimum(da.lower_degree, db.lower_degree), rule, c, tolerance, sum, weights);
        lane_fire(lane_minimum(da.lower_degree, db.upper_degree), rule + 1, c, tolerance, sum,
                  weights);
        lane_fire(lane_minimum(da.upper_degree, db.lower_degree), rule + stride, c, tolerance, sum,
                  weights);
        lane_fire(lane_minimum(da.upper_degree, db.upper_degree), rule + stride + 1, c, tolerance,
                  sum, weights);
      }
    }
    const D average = sum / weights;
    const typename D::Mask defined = (weights > D(0.0)) & ordered;
    store(out + at, select(defined, average, D(p.default_value)));
  }
}

// evaluate_packed_lanes with simd::avx2::Double4 (packed_lanes_avx2.cpp, compiled for AVX2): only
// where simd::has_avx2(), and n a multiple of 4.
void evaluate_packed_avx2(const PackedView& p, const double* x0, const double* x1, double* out,
                          std::size_t n);
// With simd::avx512::Double8 (packed_lanes_avx512.cpp): only where simd::has_avx512(), and n a
// multiple of 8.
void evaluate_packed_avx512(const PackedView& p, const double* x0, const double* x1, double* out,
                            std::size_t n);

}  // namespace fuzzygait::fuzzy::detail

// Every operation of the lane types (src/runtime/simd/lanes.hpp) applied to eight lanes of inputs,
// written once over a body, so that a test compares each body with the scalar one. Includes only
// lanes.hpp and the standard library: lanes_avx2.cpp and lanes_avx512.cpp, compiled for those
// instruction sets, instantiate it too.
#pragma once

#include <cstddef>
#include <cstdint>

#include "runtime/simd/lanes.hpp"

namespace fuzzygait::simd::test {

inline constexpr std::size_t kLanes = 8;

// Where a[k] < b[k], index[k] is in [0, kTableSize); elsewhere it lies far past the table, which a
// masked gather must not read. small[k] is in [0, 2^32) (multiply_small's lanes).
struct LaneInputs {
  double a[kLanes];
  double b[kLanes];
  std::int64_t i[kLanes];
  std::int64_t j[kLanes];
  std::int64_t small[kLanes];
  std::int64_t index[kLanes];
};

inline constexpr std::size_t kTableSize = 16;
inline constexpr double kTable[kTableSize] = {0.5,    -1.0,  2.0,  -0.0, 1e300,   -3.25,
                                              1e-310, 7.0,   -9.5, 11.0, 0.03125, -1e-5,
                                              42.0,   -0.75, 6e23, 1.0};

enum DoubleResult {
  kAdd,
  kSubtract,
  kMultiply,
  kDivide,
  kNegate,
  kAbs,
  kAddDouble,       // a + 2.5
  kDoubleMultiply,  // 0.1 * a
  kCompound,        // ((a += b) -= 0.25) *= b, then /= a
  kBroadcast,       // D(a[0])
  kSelect,          // a < b ? a : b
  kAsDouble,        // the bits of i
  kGather,          // table[index] where a < b
  kDoubleResults
};
enum IntResult {
  kIntAdd,
  kIntSubtract,
  kIntAnd,
  kIntOr,
  kIntXor,
  kIntAddConstant,  // i + 3
  kShiftLeft1,
  kShiftLeft62,
  kMultiplySmall8,
  kMultiplySmall3,
  kAsInt,      // the bits of a
  kMaskAsInt,  // a < b: -1, else 0
  kIntSelect,  // i == j, or a < b ? i : j
  kIntResults
};
enum MaskResult {
  kEqual,
  kNotEqual,
  kLess,
  kLessEqual,
  kGreater,
  kGreaterEqual,
  kNot,  // !(a < b)
  kAnd,  // a < b & b > 0
  kOr,   // a < b | a == b
  kIntEqual,
  kMaskResults
};

struct LaneResults {
  double doubles[kDoubleResults][kLanes];
  std::int64_t ints[kIntResults][kLanes];
  unsigned mask_bits[kMaskResults];  // lane k in bit k
  bool any[kMaskResults];
  bool has_ints;
};

template <class D>
void apply_lane_ops(const LaneInputs& in, std::size_t first, LaneResults& out) {
  using Mask = typename D::Mask;
  const D a = D::load(in.a + first);
  const D b = D::load(in.b + first);
  store(out.doubles[kAdd] + first, a + b);
  store(out.doubles[kSubtract] + first, a - b);
  store(out.doubles[kMultiply] + first, a * b);
  store(out.doubles[kDivide] + first, a / b);
  store(out.doubles[kNegate] + first, -a);
  store(out.doubles[kAbs] + first, abs(a));
  store(out.doubles[kAddDouble] + first, a + 2.5);
  store(out.doubles[kDoubleMultiply] + first, 0.1 * a);
  D compound = a;
  compound += b;
  compound -= 0.25;
  compound *= b;
  compound /= a;
  store(out.doubles[kCompound] + first, compound);
  store(out.doubles[kBroadcast] + first, D(in.a[0]));
  const Mask less = a < b;
  store(out.doubles[kSelect] + first, select(less, a, b));
  auto record = [&](MaskResult r, Mask m) {
    out.mask_bits[r] |= bits(m) << first;
    out.any[r] = out.any[r] || any(m);
  };
  record(kEqual, a == b);
  record(kNotEqual, a != b);
  record(kLess, less);
  record(kLessEqual, a <= b);
  record(kGreater, a > b);
  record(kGreaterEqual, a >= b);
  record(kNot, !less);
  record(kAnd, less & (b > 0.0));
  record(kOr, less | (a == b));
  if constexpr (requires { typename D::Int; }) {
    using Int = typename D::Int;
    const Int i = Int::load(in.i + first);
    const Int j = Int::load(in.j + first);
    store(out.ints[kIntAdd] + first, i + j);
    store(out.ints[kIntSubtract] + first, i - j);
    store(out.ints[kIntAnd] + first, i & j);
    store(out.ints[kIntOr] + first, i | j);
    store(out.ints[kIntXor] + first, i ^ j);
    store(out.ints[kIntAddConstant] + first, i + 3);
    store(out.ints[kShiftLeft1] + first, shift_left<1>(i));
    store(out.ints[kShiftLeft62] + first, shift_left<62>(i));
    const Int small = Int::load(in.small + first);
    store(out.ints[kMultiplySmall8] + first, multiply_small<8>(small));
    store(out.ints[kMultiplySmall3] + first, multiply_small<3>(small));
    store(out.ints[kAsInt] + first, as_int(a));
    store(out.ints[kMaskAsInt] + first, as_int(less));
    const Mask equal = i == j;
    store(out.ints[kIntSelect] + first, select(equal | less, i, j));
    record(kIntEqual, equal);
    store(out.doubles[kAsDouble] + first, as_double(i));
    store(out.doubles[kGather] + first, gather(kTable, Int::load(in.index + first), less));
    out.has_ints = true;
  }
}

// The eight lanes through body D (four calls for a pair).
template <class D>
void apply_lane_ops(const LaneInputs& in, LaneResults& out) {
  out = LaneResults{};
  for (std::size_t first = 0; first < kLanes; first += D::kLanes)
    apply_lane_ops<D>(in, first, out);
}

// apply_lane_ops with simd::avx2::Double4 (lanes_avx2.cpp, compiled for AVX2): only where
// simd::has_avx2(); with simd::avx512::Double8 (lanes_avx512.cpp) only where simd::has_avx512().
void apply_avx2_lane_ops(const LaneInputs& in, LaneResults& out);
void apply_avx512_lane_ops(const LaneInputs& in, LaneResults& out);

}  // namespace fuzzygait::simd::test

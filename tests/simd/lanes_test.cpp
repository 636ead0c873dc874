// The lane types (src/runtime/simd/lanes.hpp): the scalar body is C++'s own arithmetic lane by
// lane, and every other body this build and machine have (SSE2 pairs, AVX2 and AVX-512 from
// lanes_avx2.cpp and lanes_avx512.cpp) gives the scalar body's bits for every operation, with NaN,
// infinities, signed zeros, denormals and the extremes of the integers among the inputs. (A NaN
// equals any NaN: payloads carry no meaning here.)
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/simd/cpu.hpp"
#include "simd/lane_ops.hpp"
#include "support/bits.hpp"

namespace fuzzygait::simd::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

const double kSpecial[] = {0.0,
                           -0.0,
                           1.0,
                           -1.0,
                           0.5,
                           -2.25,
                           3.0,
                           kInf,
                           -kInf,
                           kNaN,
                           -kNaN,
                           std::numeric_limits<double>::denorm_min(),
                           -std::numeric_limits<double>::denorm_min(),
                           1e-310,
                           std::numeric_limits<double>::min(),
                           std::numeric_limits<double>::max(),
                           -std::numeric_limits<double>::max(),
                           1e-6,
                           6755399441055744.0};
const std::int64_t kSpecialInts[] = {0,
                                     1,
                                     -1,
                                     2,
                                     3,
                                     std::numeric_limits<std::int64_t>::min(),
                                     std::numeric_limits<std::int64_t>::max(),
                                     0x4000000000000000,
                                     0x00000000FFFFFFFF};

// Every ordered pair of special values, then random values and random bit patterns, four lanes
// at a time.
std::vector<LaneInputs> lane_inputs() {
  std::vector<double> a;
  std::vector<double> b;
  for (double x : kSpecial) {
    for (double y : kSpecial) {
      a.push_back(x);
      b.push_back(y);
    }
  }
  std::mt19937_64 random(12);
  std::uniform_real_distribution<double> value(-10.0, 10.0);
  for (int k = 0; k < 2000; ++k) {
    const bool bits = k % 2 == 1;
    a.push_back(bits ? std::bit_cast<double>(random()) : value(random));
    b.push_back(bits ? std::bit_cast<double>(random()) : value(random));
  }
  std::uniform_int_distribution<std::size_t> table_index(0, kTableSize - 1);
  std::vector<LaneInputs> inputs;
  for (std::size_t at = 0; at + kLanes <= a.size(); at += kLanes) {
    LaneInputs in{};
    for (std::size_t k = 0; k < kLanes; ++k) {
      const std::size_t n = at + k;
      in.a[k] = a[n];
      in.b[k] = b[n];
      const std::size_t special_count = std::size(kSpecialInts);
      in.i[k] = n % 3 == 0 ? kSpecialInts[n % special_count] : static_cast<std::int64_t>(random());
      in.j[k] = n % 5 == 0 ? in.i[k]
                           : (n % 3 == 1 ? kSpecialInts[(n / 3) % special_count]
                                         : static_cast<std::int64_t>(random()));
      in.small[k] = static_cast<std::int64_t>(random() >> 32);
      in.index[k] = a[n] < b[n] ? static_cast<std::int64_t>(table_index(random))
                                : std::int64_t{1} << 40;  // far past the table, never read
    }
    inputs.push_back(in);
  }
  return inputs;
}

std::string lanes_text(const LaneInputs& in) {
  std::ostringstream text;
  for (std::size_t k = 0; k < kLanes; ++k)
    text << " (" << in.a[k] << ", " << in.b[k] << ", " << in.i[k] << ", " << in.j[k] << ")";
  return text.str();
}

// Every result of `body` equals the scalar body's; the first few differences are reported.
void expect_same_results(const char* body, const LaneInputs& in, const LaneResults& got,
                         const LaneResults& reference, int& reported) {
  auto fail = [&](const char* kind, int result, std::size_t lane) {
    if (++reported <= 5) {
      ADD_FAILURE() << body << ": " << kind << " result " << result << " lane " << lane
                    << " differs from the scalar body's for" << lanes_text(in);
    }
  };
  for (int r = 0; r < kDoubleResults; ++r) {
    if (!got.has_ints && (r == kAsDouble || r == kGather)) continue;
    for (std::size_t k = 0; k < kLanes; ++k) {
      if (!fuzzygait::test::same_bits(got.doubles[r][k], reference.doubles[r][k])) {
        fail("double", r, k);
      }
    }
  }
  for (int r = 0; r < kMaskResults; ++r) {
    if (!got.has_ints && r == kIntEqual) continue;
    if (got.mask_bits[r] != reference.mask_bits[r] || got.any[r] != reference.any[r]) {
      fail("mask", r, 0);
    }
  }
  for (int r = 0; got.has_ints && r < kIntResults; ++r) {
    for (std::size_t k = 0; k < kLanes; ++k) {
      if (got.ints[r][k] != reference.ints[r][k]) fail("integer", r, k);
    }
  }
}

// The reference itself: each scalar lane is the C++ expression on that lane.
TEST(Lanes, ScalarBodyIsCppArithmeticLaneByLane) {
  using fuzzygait::test::same_bits;
  int differ = 0;
  for (const LaneInputs& in : lane_inputs()) {
    LaneResults r;
    apply_lane_ops<scalar::Double4>(in, r);
    ASSERT_TRUE(r.has_ints);
    unsigned less_bits = 0;
    for (std::size_t k = 0; k < kLanes; ++k) {
      const double a = in.a[k];
      const double b = in.b[k];
      const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
      const auto s = [](std::uint64_t v) { return static_cast<std::int64_t>(v); };
      const bool less = a < b;
      less_bits |= static_cast<unsigned>(less) << k;
      double compound = a;
      compound += b;
      compound -= 0.25;
      compound *= b;
      compound /= a;
      const double expected_doubles[kDoubleResults] = {a + b,
                                                       a - b,
                                                       a * b,
                                                       a / b,
                                                       -a,
                                                       std::abs(a),
                                                       a + 2.5,
                                                       0.1 * a,
                                                       compound,
                                                       in.a[0],
                                                       less ? a : b,
                                                       std::bit_cast<double>(in.i[k]),
                                                       less ? kTable[in.index[k]] : 0.0};
      for (int i = 0; i < kDoubleResults; ++i) {
        if (!same_bits(r.doubles[i][k], expected_doubles[i]) && ++differ <= 5) {
          ADD_FAILURE() << "double result " << i << " lane " << k << lanes_text(in);
        }
      }
      const std::int64_t i = in.i[k];
      const std::int64_t j = in.j[k];
      const std::int64_t expected_ints[kIntResults] = {s(u(i) + u(j)),
                                                       s(u(i) - u(j)),
                                                       i & j,
                                                       i | j,
                                                       i ^ j,
                                                       s(u(i) + 3u),
                                                       s(u(i) << 1),
                                                       s(u(i) << 62),
                                                       in.small[k] * 8,
                                                       in.small[k] * 3,
                                                       std::bit_cast<std::int64_t>(a),
                                                       less ? -1 : 0,
                                                       (i == j || less) ? i : j};
      for (int n = 0; n < kIntResults; ++n) {
        if (r.ints[n][k] != expected_ints[n] && ++differ <= 5) {
          ADD_FAILURE() << "integer result " << n << " lane " << k << lanes_text(in);
        }
      }
      const bool expected_masks[kMaskResults] = {a == b,         a != b, less,  a <= b,
                                                 a > b,          a >= b, !less, less && b > 0.0,
                                                 less || a == b, i == j};
      for (int m = 0; m < kMaskResults; ++m) {
        if (((r.mask_bits[m] >> k) & 1u) != static_cast<unsigned>(expected_masks[m]) &&
            ++differ <= 5) {
          ADD_FAILURE() << "mask result " << m << " lane " << k << lanes_text(in);
        }
      }
    }
    EXPECT_EQ(r.any[kLess], less_bits != 0);
  }
  EXPECT_EQ(differ, 0);
}

TEST(Lanes, ScalarPairsGiveTheScalarBodysBits) {
  int reported = 0;
  for (const LaneInputs& in : lane_inputs()) {
    LaneResults reference;
    apply_lane_ops<scalar::Double4>(in, reference);
    LaneResults pairs;
    apply_lane_ops<scalar::Double2>(in, pairs);
    expect_same_results("scalar::Double2", in, pairs, reference, reported);
  }
  EXPECT_EQ(reported, 0);
}

#if defined(FUZZYGAIT_SIMD_HAVE_SSE2)
TEST(Lanes, Sse2PairsGiveTheScalarBodysBits) {
  static_assert(std::is_same_v<Double2, sse2::Double2>);
  int reported = 0;
  for (const LaneInputs& in : lane_inputs()) {
    LaneResults reference;
    apply_lane_ops<scalar::Double4>(in, reference);
    LaneResults pairs;
    apply_lane_ops<sse2::Double2>(in, pairs);
    EXPECT_FALSE(pairs.has_ints);
    expect_same_results("sse2::Double2", in, pairs, reference, reported);
  }
  EXPECT_EQ(reported, 0);
}
#else
TEST(Lanes, WithoutSse2ThePairIsTheScalarOne) {
  static_assert(std::is_same_v<Double2, scalar::Double2>);
}
#endif

TEST(Lanes, ScalarOctetsGiveTheScalarBodysBits) {
  int reported = 0;
  for (const LaneInputs& in : lane_inputs()) {
    LaneResults reference;
    apply_lane_ops<scalar::Double4>(in, reference);
    LaneResults octets;
    apply_lane_ops<scalar::Double8>(in, octets);
    expect_same_results("scalar::Double8", in, octets, reference, reported);
  }
  EXPECT_EQ(reported, 0);
}

TEST(Lanes, Avx2GivesTheScalarBodysBits) {
#if defined(FUZZYGAIT_SIMD_AVX2)
  if (!has_avx2()) GTEST_SKIP() << "this machine has no AVX2";
  int reported = 0;
  for (const LaneInputs& in : lane_inputs()) {
    LaneResults reference;
    apply_lane_ops<scalar::Double4>(in, reference);
    LaneResults avx2;
    apply_avx2_lane_ops(in, avx2);
    EXPECT_TRUE(avx2.has_ints);
    expect_same_results("avx2::Double4", in, avx2, reference, reported);
  }
  EXPECT_EQ(reported, 0);
#else
  GTEST_SKIP() << "this build has no AVX2 bodies";
#endif
}

TEST(Lanes, Avx512GivesTheScalarBodysBits) {
#if defined(FUZZYGAIT_SIMD_AVX512)
  if (!has_avx512()) GTEST_SKIP() << "this machine has no AVX-512F";
  int reported = 0;
  for (const LaneInputs& in : lane_inputs()) {
    LaneResults reference;
    apply_lane_ops<scalar::Double4>(in, reference);
    LaneResults avx512;
    apply_avx512_lane_ops(in, avx512);
    EXPECT_TRUE(avx512.has_ints);
    expect_same_results("avx512::Double8", in, avx512, reference, reported);
  }
  EXPECT_EQ(reported, 0);
#else
  GTEST_SKIP() << "this build has no AVX-512 bodies";
#endif
}

// has_avx2() and has_avx512() against the processor's flags as Linux reports them (elsewhere
// skipped).
TEST(Lanes, CpuChecksAgreeWithTheProcessorsFlags) {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  std::string flags;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("flags", 0) == 0) {
      flags = line + " ";
      break;
    }
  }
  if (flags.empty()) GTEST_SKIP() << "no x86 flags in /proc/cpuinfo";
  const bool avx2 = flags.find(" avx2 ") != std::string::npos;
  const bool avx512 = flags.find(" avx512f ") != std::string::npos;
  // A build without a body's translation units never runs them.
#if defined(FUZZYGAIT_SIMD_AVX2)
  constexpr bool avx2_built = true;
#else
  constexpr bool avx2_built = false;
#endif
#if defined(FUZZYGAIT_SIMD_AVX512)
  constexpr bool avx512_built = true;
#else
  constexpr bool avx512_built = false;
#endif
  EXPECT_EQ(has_avx2(), avx2_built && avx2);
  EXPECT_EQ(has_avx512(), avx512_built && avx512);
  RecordProperty("has_avx2", has_avx2() ? "yes" : "no");
  RecordProperty("has_avx512", has_avx512() ? "yes" : "no");
}

}  // namespace
}  // namespace fuzzygait::simd::test

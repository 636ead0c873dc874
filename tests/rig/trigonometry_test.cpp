// The walker's own sine, cosine and arc tangents (src/rig/trigonometry.hpp): within about an ulp
// of libm over the angles a rig takes and far beyond, libm's answers where they hand over to it,
// and the same bits on every machine (golden values).
#include "runtime/rig/trigonometry.hpp"

#include "runtime/simd/cpu.hpp"
#include "runtime/simd/lanes.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

namespace fuzzygait::rig::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Distance in units in the last place of the reference.
double ulps(double value, double reference) {
  if (value == reference) return 0.0;
  const double ulp = std::nextafter(std::abs(reference), kInf) - std::abs(reference);
  return std::abs(value - reference) / ulp;
}

TEST(Trigonometry, SineAndCosineWithinAnUlpOfLibm) {
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> angle(-20.0, 20.0);
  double worst = 0.0;
  double worst_small = 0.0;
  for (int i = 0; i < 1000000; ++i) {
    const double x = angle(random);
    const SinCos r = sin_cos(x);
    // Absolute: within half an ulp of 1 (results near zero carry the reduction's error).
    worst = std::max({worst, std::abs(r.sin - std::sin(x)), std::abs(r.cos - std::cos(x))});
    const double tiny = std::ldexp(x, -30);  // relative error where sin x is x
    worst_small = std::max(worst_small, ulps(sin_cos(tiny).sin, std::sin(tiny)));
  }
  EXPECT_LE(worst, 1.2e-16);
  EXPECT_LE(worst_small, 1.0);
  // Quadrant boundaries and signs.
  for (int k = -8; k <= 8; ++k) {
    const double x = k * std::numbers::pi / 4.0;
    const SinCos r = sin_cos(x);
    EXPECT_NEAR(r.sin, std::sin(x), 1.2e-16) << k;
    EXPECT_NEAR(r.cos, std::cos(x), 1.2e-16) << k;
  }
  EXPECT_TRUE(std::signbit(sin_cos(-0.0).sin));
  EXPECT_EQ(sin_cos(0.0).cos, 1.0);
}

TEST(Trigonometry, FourLanesGiveTheScalarsBits) {
  const double x[4] = {-2.5, 0.3, 1.9, 7.0};
  double s[4];
  double c[4];
  sin_cos(x, s, c);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(s[i]), std::bit_cast<std::uint64_t>(sin_cos(x[i]).sin));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(c[i]), std::bit_cast<std::uint64_t>(sin_cos(x[i]).cos));
  }
}

TEST(Trigonometry, HugeInfiniteAndNanArguments) {
  for (double x : {kSinCosExactBelow, -3.0e7, 1.0e300}) {
    EXPECT_EQ(sin_cos(x).sin, std::sin(x)) << x;  // libm's answer, bit for bit
    EXPECT_EQ(sin_cos(x).cos, std::cos(x)) << x;
  }
  EXPECT_TRUE(std::isnan(sin_cos(kInf).sin));
  EXPECT_TRUE(std::isnan(sin_cos(kNaN).sin));
  EXPECT_TRUE(std::isnan(sin_cos(kNaN).cos));
  // A lane out of range gets libm's answer; the others keep their own bits.
  const double x[2] = {0.5, 1.0e8};
  double s[2];
  double c[2];
  sin_cos(x, s, c);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(s[0]), std::bit_cast<std::uint64_t>(sin_cos(0.5).sin));
  EXPECT_EQ(c[1], std::cos(1.0e8));
}

// The batch (a crowd's legs, in the widest vectors the machine has) gives every lane the bits
// of the one-lane call, whatever its neighbours hold, for any count.
TEST(Trigonometry, BatchGivesEachLaneTheScalarsBits) {
  std::mt19937_64 random(8);
  std::uniform_real_distribution<double> angle(-7.0, 7.0);
  std::vector<double> x(203);
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = i % 17 == 3 ? 1.0e8 : (i % 19 == 4 ? kNaN : (i % 23 == 5 ? 1e-30 : angle(random)));
  }
  x[7] = -0.0;
  x[8] = kInf;
  x[9] = -kInf;
  x[10] = 4.9e-324;
  for (std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{7}, std::size_t{8},
                        std::size_t{13}, x.size()}) {
    std::vector<double> s(n + 1, 5.0);
    std::vector<double> c(n + 1, 5.0);
    sin_cos(x.data(), s.data(), c.data(), n);
    EXPECT_EQ(s[n], 5.0) << "wrote past " << n;
    for (std::size_t i = 0; i < n; ++i) {
      const SinCos one = sin_cos(x[i]);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(s[i]), std::bit_cast<std::uint64_t>(one.sin)) << x[i];
      EXPECT_EQ(std::bit_cast<std::uint64_t>(c[i]), std::bit_cast<std::uint64_t>(one.cos)) << x[i];
    }
  }
}

// The batch's lane kernel (in AVX-512 or AVX2 lanes in the batch above, where the machine has
// them) with the scalar reference body: each lane the one-lane call's bits, and the lanes libm
// must answer (|x| from kSinCosExactBelow on, infinities) reported rather than answered.
template <class D>
void expect_scalar_body_gives_scalar_bits() {
  std::mt19937_64 random(9);
  std::uniform_real_distribution<double> angle(-7.0, 7.0);
  const double special[] = {0.0,
                            -0.0,
                            kNaN,
                            kInf,
                            -kInf,
                            1e-30,
                            -1e-300,
                            4.9e-324,
                            1.0e6,
                            1.0e8,
                            0x1p-27,
                            -0x1p-27,
                            0x1p-28,
                            std::numbers::pi / 4,
                            -std::numbers::pi / 2,
                            999999.9};
  std::vector<double> x(std::begin(special), std::end(special));
  while (x.size() < 400)
    x.push_back(angle(random));
  for (std::size_t at = 0; at + D::kLanes <= x.size(); at += D::kLanes) {
    D s;
    D c;
    const typename D::Mask beyond = sin_cos_vector(D::load(&x[at]), s, c);
    for (std::size_t k = 0; k < D::kLanes; ++k) {
      const double v = x[at + k];
      const bool libm = std::abs(v) >= kSinCosExactBelow;
      EXPECT_EQ(beyond.lane[k], libm) << v;
      if (libm) continue;
      const SinCos one = sin_cos(v);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(s.lane[k]), std::bit_cast<std::uint64_t>(one.sin))
          << v;
      EXPECT_EQ(std::bit_cast<std::uint64_t>(c.lane[k]), std::bit_cast<std::uint64_t>(one.cos))
          << v;
    }
  }
}

TEST(Trigonometry, LaneKernelWithTheScalarBodyGivesEachLaneTheScalarsBits) {
  expect_scalar_body_gives_scalar_bits<simd::scalar::Double4>();
  expect_scalar_body_gives_scalar_bits<simd::scalar::Double8>();
}

// Each vector body this build has and this machine runs, called directly (the batch above takes
// the widest only): the same bits, and whether a lane needs libm's answer.
TEST(Trigonometry, EachVectorKernelGivesEachLaneTheScalarsBits) {
  std::mt19937_64 random(10);
  std::uniform_real_distribution<double> angle(-7.0, 7.0);
  std::vector<double> x(400);
  for (double& v : x)
    v = angle(random);
  x[5] = kNaN;
  x[6] = -0.0;
  x[7] = 1e-300;
  using Kernel = bool (*)(const double*, double*, double*, std::size_t);
  std::vector<std::pair<const char*, Kernel>> kernels;
#if defined(FUZZYGAIT_SIMD_AVX2)
  if (simd::has_avx2()) kernels.emplace_back("AVX2", sin_cos_avx2);
#endif
#if defined(FUZZYGAIT_SIMD_AVX512)
  if (simd::has_avx512()) kernels.emplace_back("AVX-512", sin_cos_avx512);
#endif
  if (kernels.empty()) GTEST_SKIP() << "no vector kernel on this build and machine";
  for (const auto& [name, kernel] : kernels) {
    for (const bool with_huge : {false, true}) {
      std::vector<double> in = x;
      if (with_huge) in[203] = -3.0e7;
      std::vector<double> s(in.size());
      std::vector<double> c(in.size());
      EXPECT_EQ(kernel(in.data(), s.data(), c.data(), in.size()), with_huge) << name;
      for (std::size_t i = 0; i < in.size(); ++i) {
        if (with_huge && i == 203) continue;  // the caller's to replace
        const SinCos one = sin_cos(in[i]);
        EXPECT_EQ(std::bit_cast<std::uint64_t>(s[i]), std::bit_cast<std::uint64_t>(one.sin))
            << name << " " << in[i];
        EXPECT_EQ(std::bit_cast<std::uint64_t>(c[i]), std::bit_cast<std::uint64_t>(one.cos))
            << name << " " << in[i];
      }
    }
  }
}

TEST(Trigonometry, ArcTangentWithinTwoUlpsInEveryQuadrant) {
  std::mt19937_64 random(6);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  double worst = 0.0;
  for (int i = 0; i < 1000000; ++i) {
    const double y = coordinate(random);
    const double x = coordinate(random);
    worst = std::max(worst, ulps(arctan2(y, x), std::atan2(y, x)));
  }
  EXPECT_LE(worst, 2.0);
  // Zeros, infinities and NaN are libm's.
  for (double y : {0.0, -0.0, 1.0, -1.0, kInf, -kInf}) {
    for (double x : {0.0, -0.0, 2.0, -2.0, kInf, -kInf}) {
      if (y == 0.0 || x == 0.0 || std::isinf(x) || std::isinf(y)) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(arctan2(y, x)),
                  std::bit_cast<std::uint64_t>(std::atan2(y, x)))
            << y << " " << x;
      }
    }
  }
  EXPECT_TRUE(std::isnan(arctan2(kNaN, 1.0)));
  EXPECT_TRUE(std::isnan(arctan2(1.0, kNaN)));
}

TEST(Trigonometry, ArcCosineAndArcSine) {
  double worst = 0.0;
  for (int i = -100000; i <= 100000; ++i) {
    const double c = i / 100000.0;
    worst = std::max({worst, ulps(arccos(c), std::acos(c)), ulps(arcsin(c), std::asin(c))});
  }
  EXPECT_LE(worst, 2.0);
  EXPECT_EQ(arccos(1.0), 0.0);
  EXPECT_EQ(arccos(-1.0), std::acos(-1.0));
  EXPECT_EQ(arcsin(1.0), std::asin(1.0));
  EXPECT_TRUE(std::isnan(arccos(1.5)));
  EXPECT_TRUE(std::isnan(arcsin(-1.0000001)));
}

// Only IEEE basic operations: these bits are the same on every machine and compiler that keeps
// them (no fused multiply-add, no fast-math). A change here changes every walk. Where libm rounds
// the other way (glibc 2.36 for sin(0.117)), the kernel's own last bit is pinned.
TEST(Trigonometry, GoldenBits) {
  auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  EXPECT_EQ(bits(sin_cos(1.0).sin), 0x3FEAED548F090CEEull);
  EXPECT_EQ(bits(sin_cos(1.0).cos), 0x3FE14A280FB5068Cull);
  EXPECT_EQ(bits(sin_cos(-2.75).sin), 0xBFD86D2239C183FBull);
  EXPECT_EQ(bits(sin_cos(0.117).sin), 0x3FBDE23AE6D763C7ull);  // libm: ...C6
  EXPECT_EQ(bits(arctan2(0.3, -0.7)), 0x4005E4C36CA0118Aull);
  EXPECT_EQ(bits(arctan2(0.052, -0.7)), 0x40088A1FA03497D4ull);
}

}  // namespace
}  // namespace fuzzygait::rig::detail

// The sine and cosine kernel of trigonometry.hpp (fdlibm's, see there), its constants and its form
// over a lane type (simd/lanes.hpp) for a crowd's batch. Includes only lanes.hpp and the standard
// library, so that a translation unit compiled for AVX2 may instantiate it.
#pragma once

#include <cstddef>
#include <cstdint>

#include "fuzzygait/compiler.hpp"
#include "runtime/simd/lanes.hpp"

namespace fuzzygait::rig::detail {

// Exact below this |x|: the reduction multiplies pi/2's first 33 bits by the quadrant count.
inline constexpr double kSinCosExactBelow = 1.0e6;
// Below this |x|, sin x is x to the last bit.
inline constexpr double kSineIsArgumentBelow = 0x1p-27;

namespace sin_cos_constants {
inline constexpr double kTwoOverPi = 6.36619772367581382433e-01;
inline constexpr double kPiOver2High = 1.57079632673412561417e+00;  // first 33 bits
inline constexpr double kPiOver2Low = 6.07710050650619224932e-11;   // pi/2 - kPiOver2High
inline constexpr double kRoundShift = 6755399441055744.0;           // 1.5 * 2^52
// Minimax polynomials on [-pi/4, pi/4]: sin r = r + r z (S1 + z (S2 + ...)), z = r^2, and
// cos r = 1 - z/2 + z^2 (C1 + z (C2 + ...)).
inline constexpr double kS1 = -1.66666666666666324348e-01;
inline constexpr double kS2 = 8.33333333332248946124e-03;
inline constexpr double kS3 = -1.98412698298579493134e-04;
inline constexpr double kS4 = 2.75573137070700676789e-06;
inline constexpr double kS5 = -2.50507602534068634195e-08;
inline constexpr double kS6 = 1.58969099521155010221e-10;
inline constexpr double kC1 = 4.16666666666666019037e-02;
inline constexpr double kC2 = -1.38888888888741095749e-03;
inline constexpr double kC3 = 2.48015872894767294178e-05;
inline constexpr double kC4 = -2.75573143513906633035e-07;
inline constexpr double kC5 = 2.08757232129817482790e-09;
inline constexpr double kC6 = -1.13596475577881948265e-11;
}  // namespace sin_cos_constants

// sin and cos of every lane of x, the bits of sin_cos_lanes (trigonometry.hpp) for each lane with
// |x| below kSinCosExactBelow (or NaN). Returns the lanes at or beyond it, whose results the
// caller replaces with libm's.
template <class D>
FUZZYGAIT_ALWAYS_INLINE typename D::Mask sin_cos_vector(D x, D& sin, D& cos) {
  using namespace sin_cos_constants;
  using Int = typename D::Int;
  // Nearest quadrant count k, by rounding in the shift; its low bits are the quadrant.
  const D shifted = x * kTwoOverPi + kRoundShift;
  const D k = shifted - kRoundShift;
  const Int quadrant = as_int(shifted);
  const D r = (x - k * kPiOver2High) - k * kPiOver2Low;  // in [-pi/4, pi/4]
  const D z = r * r;
  const D s = r + r * z * (kS1 + z * (kS2 + z * (kS3 + z * (kS4 + z * (kS5 + z * kS6)))));
  const D half_z = 0.5 * z;
  const D w = 1.0 - half_z;
  const D c = w + (((1.0 - w) - half_z) +
                   z * z * (kC1 + z * (kC2 + z * (kC3 + z * (kC4 + z * (kC5 + z * kC6))))));
  // Quadrant q: (sin, cos) = (s, c), (c, -s), (-s, -c), (-c, s), by selects and sign flips.
  const typename D::Mask odd = (quadrant & 1) == Int(1);
  const Int sin_sign = shift_left<62>(quadrant & 2);
  const Int cos_sign = shift_left<62>((quadrant + 1) & 2);
  const D magnitude = abs(x);
  // Taking x itself below kSineIsArgumentBelow also keeps the sign of -0.
  sin =
      select(magnitude < kSineIsArgumentBelow, x, as_double(as_int(select(odd, c, s)) ^ sin_sign));
  cos = as_double(as_int(select(odd, s, c)) ^ cos_sign);
  return magnitude >= kSinCosExactBelow;
}

// sin_cos_vector with simd::avx2::Double4 over x[i] for i < n (sin_cos_avx2.cpp, compiled for
// AVX2): only where simd::has_avx2(), and n a multiple of 4. Returns whether a lane was at or
// beyond kSinCosExactBelow (its results then need libm's).
bool sin_cos_avx2(const double* x, double* sin, double* cos, std::size_t n);
// The same with simd::avx512::Double8 (sin_cos_avx512.cpp): only where simd::has_avx512(), and n a
// multiple of 8.
bool sin_cos_avx512(const double* x, double* sin, double* cos, std::size_t n);

}  // namespace fuzzygait::rig::detail

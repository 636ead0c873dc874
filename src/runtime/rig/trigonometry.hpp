// Sine, cosine and arc tangents for the walker's inner loop, inline and made of IEEE basic
// operations only. Two reasons: libm's calls were half of a walker step, and the same operations
// give the same bits on every machine and libm version (libm promises neither), so walks stay
// bit-identical across them. Errors are within about 1 ulp of the true value (tested against
// libm). The polynomials are the minimax kernels of fdlibm (Sun Microsystems, 1993) on
// [-pi/4, pi/4] (sine, cosine) and [-7/16, 7/16] (arc tangent), with its argument reductions.
//
// Private to the library: compiled with the project's floating-point flags (no contraction into
// fused multiply-adds), which a public inline header could not guarantee in a user's build.
#pragma once

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "fuzzygait/compiler.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "runtime/rig/sin_cos_vector.hpp"

namespace fuzzygait::rig::detail {

struct SinCos {
  double sin = 0.0;
  double cos = 1.0;
};

// sin and cos of x[i] for i < N. Branch-free in the lanes, so a compiler can vectorise the
// loop; a lane with |x| beyond kSinCosExactBelow (or infinite) is then given libm's answer, so
// each lane's bits do not depend on its neighbours (a crowd's batch equals a lone walker's call).
// (Always inlined, so that each caller's copy is vectorised for its width at any -O level.)
template <std::size_t N>
FUZZYGAIT_ALWAYS_INLINE void sin_cos_lanes(const double* FUZZYGAIT_RESTRICT x,
                                           double* FUZZYGAIT_RESTRICT sin,
                                           double* FUZZYGAIT_RESTRICT cos) {
  using namespace sin_cos_constants;
  bool in_range = true;
  for (std::size_t i = 0; i < N; ++i)
    in_range = in_range && !(std::abs(x[i]) >= kSinCosExactBelow);  // NaN propagates below
  for (std::size_t i = 0; i < N; ++i) {
    // Nearest quadrant count k, by rounding in the shift; its low bits are the quadrant.
    const double shifted = x[i] * kTwoOverPi + kRoundShift;
    const double k = shifted - kRoundShift;
    const std::uint64_t quadrant = std::bit_cast<std::uint64_t>(shifted);
    const double r = (x[i] - k * kPiOver2High) - k * kPiOver2Low;  // in [-pi/4, pi/4]
    const double z = r * r;
    const double s = r + r * z * (kS1 + z * (kS2 + z * (kS3 + z * (kS4 + z * (kS5 + z * kS6)))));
    const double half_z = 0.5 * z;
    const double w = 1.0 - half_z;
    const double c = w + (((1.0 - w) - half_z) +
                          z * z * (kC1 + z * (kC2 + z * (kC3 + z * (kC4 + z * (kC5 + z * kC6))))));
    // Quadrant q: (sin, cos) = (s, c), (c, -s), (-s, -c), (-c, s), by bit selects and sign flips.
    const std::uint64_t odd = std::uint64_t{0} - (quadrant & 1u);
    const std::uint64_t s_bits = std::bit_cast<std::uint64_t>(s);
    const std::uint64_t c_bits = std::bit_cast<std::uint64_t>(c);
    const std::uint64_t sin_bits = ((s_bits & ~odd) | (c_bits & odd)) ^ ((quadrant & 2u) << 62);
    const std::uint64_t cos_bits =
        ((c_bits & ~odd) | (s_bits & odd)) ^ (((quadrant + 1u) & 2u) << 62);
    // Taking x itself below kSineIsArgumentBelow also keeps the sign of -0.
    sin[i] = std::abs(x[i]) < kSineIsArgumentBelow ? x[i] : std::bit_cast<double>(sin_bits);
    cos[i] = std::bit_cast<double>(cos_bits);
  }
  if (in_range) return;
  for (std::size_t i = 0; i < N; ++i) {
    if (std::abs(x[i]) >= kSinCosExactBelow) {
      sin[i] = std::sin(x[i]);
      cos[i] = std::cos(x[i]);
    }
  }
}

template <std::size_t N>
FUZZYGAIT_ALWAYS_INLINE void sin_cos(const double (&x)[N], double (&sin)[N], double (&cos)[N]) {
  sin_cos_lanes<N>(x, sin, cos);
}

// sin and cos of x[i] for i < n, lane for lane the bits of sin_cos above: a crowd's legs at once,
// in AVX2 vectors where simd::has_avx2(), else in the baseline's (SSE2 on x86-64).
void sin_cos(const double* x, double* sin, double* cos, std::size_t n);

inline SinCos sin_cos(double x) {
  SinCos r;
  sin_cos_lanes<1>(&x, &r.sin, &r.cos);
  return r;
}

// atan(t) for t in [0, 1].
inline double arctan_unit(double t) {
  // fdlibm's reduction: t' = (2t - 1) / (2 + t) around atan(1/2), (t - 1) / (t + 1) around
  // atan(1); the angle's high and low parts keep the sum exact to the last bit.
  double high = 0.0;
  double low = 0.0;
  bool reduced = true;
  if (t < 0.4375) {
    reduced = false;
  } else if (t < 0.6875) {
    high = 4.63647609000806093515e-01;  // atan(1/2)
    low = 2.26987774529616870924e-17;
    t = (2.0 * t - 1.0) / (2.0 + t);
  } else {
    high = 7.85398163397448278999e-01;  // atan(1)
    low = 3.06161699786838301793e-17;
    t = (t - 1.0) / (t + 1.0);
  }
  const double z = t * t;
  const double w = z * z;
  const double odd =
      z * (3.33333333333329318027e-01 +
           w * (1.42857142725034663711e-01 +
                w * (9.09088713343650656196e-02 +
                     w * (6.66107313738753120669e-02 +
                          w * (4.97687799461593236017e-02 + w * 1.62858201153657823623e-02)))));
  const double even =
      w * (-1.99999999998764832476e-01 +
           w * (-1.11111104054623557880e-01 +
                w * (-7.69187620504482999495e-02 +
                     w * (-5.83357013379057348645e-02 + w * -3.65315727442169155270e-02))));
  if (!reduced) return t - t * (odd + even);
  return high - ((t * (odd + even) - low) - t);
}

// std::atan2(y, x) within about 1 ulp; zeros, infinities and NaN go to libm.
inline double arctan2(double y, double x) {
  const double ax = std::abs(x);
  const double ay = std::abs(y);
  constexpr double infinity = std::numeric_limits<double>::infinity();
  if (!(ax < infinity && ay < infinity) || ax == 0.0 || ay == 0.0) {
    return std::atan2(y, x);
  }
  constexpr double pi_over_2_high = 1.57079632679489655800e+00;
  constexpr double pi_over_2_low = 6.12323399573676603587e-17;
  constexpr double pi_high = 3.14159265358979311600e+00;
  constexpr double pi_low = 1.22464679914735317720e-16;
  // The angle of (|x|, |y|), in [0, pi/2].
  double angle =
      ay <= ax ? arctan_unit(ay / ax) : pi_over_2_high - (arctan_unit(ax / ay) - pi_over_2_low);
  if (x < 0.0) angle = pi_high - (angle - pi_low);
  return y < 0.0 ? -angle : angle;
}

// acos(c) for c in [-1, 1] (NaN outside).
inline double arccos(double c) {
  return arctan2(std::sqrt((1.0 - c) * (1.0 + c)), c);
}

// asin(s) for s in [-1, 1] (NaN outside).
inline double arcsin(double s) {
  return arctan2(s, std::sqrt((1.0 - s) * (1.0 + s)));
}

// A leg's four orientations as four lanes (thigh, shank, foot, toes), and their lanes' sines and
// cosines back as a LegTrig: the layout of leg_trig below and of a crowd's batch of legs.
inline void to_lanes(const LegOrientation& o, double* lanes) {
  lanes[0] = o.thigh;
  lanes[1] = o.shank;
  lanes[2] = o.foot;
  lanes[3] = o.toes;
}
inline LegTrig from_lanes(const double* sin, const double* cos) {
  LegTrig t;
  t.thigh_sin = sin[0];
  t.thigh_cos = cos[0];
  t.shank_sin = sin[1];
  t.shank_cos = cos[1];
  t.foot_sin = sin[2];
  t.foot_cos = cos[2];
  t.toes_sin = sin[3];
  t.toes_cos = cos[3];
  return t;
}

// rig::trig, inline for the walker's inner loop: the four orientations in one call.
inline LegTrig leg_trig(const LegOrientation& o) {
  double angles[4];
  to_lanes(o, angles);
  double sin[4];
  double cos[4];
  sin_cos(angles, sin, cos);
  return from_lanes(sin, cos);
}

}  // namespace fuzzygait::rig::detail

// Lane types for fuzzygait's vector code: a vector of doubles (DoubleN), of 64-bit integers (IntN)
// and a mask (MaskN, one per DoubleN), each with a plain scalar body, the reference, and a body per
// instruction set. The vector code is written once against these operations, never against an
// instruction set, and every body gives the scalar body's bits: each operation is the same IEEE
// operation in each lane.
//
//   simd::scalar::{Double2, Double4, Double8, Int4, Int8}   always (loops over lanes)
//   simd::sse2::Double2                      on x86-64 (SSE2 is part of it)
//   simd::avx2::{Double4, Int4}              only in a translation unit compiled for AVX2
//   simd::avx512::{Double8, Int8}            only in a translation unit compiled for AVX-512F
//   simd::Double2                            sse2's where there is one, else scalar's
//
// Bodies live in their own namespaces so that no inline function is shared by translation units
// compiled for different instruction sets: a linker keeps one copy of an inline function that was
// not inlined, and an AVX2 copy chosen for baseline code would crash a machine without AVX2. A
// translation unit compiled for AVX2 (AVX-512F) defines FUZZYGAIT_SIMD_AVX2_TU
// (FUZZYGAIT_SIMD_AVX512_TU) before including this header; it then sees that body alone, and it
// calls no other inline function (standard library ones included) but the compiler's intrinsics.
// The build defines FUZZYGAIT_SIMD_SCALAR to keep the scalar bodies only (CMake:
// -DFUZZYGAIT_SIMD=scalar), and FUZZYGAIT_SIMD_AVX2 (FUZZYGAIT_SIMD_AVX512) where it compiles such
// translation units, which run only where simd::has_avx2() (has_avx512()).
//
// Operations, the same in every body (D a DoubleN, I an IntN, M a MaskN; a double or an integer
// converts to every lane):
//   D(x), D::load(p), store(p, d), I(n), I::load(p), store(p, i), D(lane0, ...) for 2 and 4 lanes
//   D + - * / D, -D (the sign flipped), abs(D) (the sign cleared), compound assignments
//   D == != < <= > >= D -> M with C++'s IEEE semantics (a NaN compares false, except with !=)
//   M & M, M | M, !M, any(M), bits(M) (lane k in bit k), select(M, yes, no) for D and I
//   I + - & | ^ I, I == I -> M, shift_left<n>(I), multiply_small<k>(I) (lanes in [0, 2^32))
//   as_int(D) and as_double(I) (bit casts), as_int(M) (-1 where set, else 0)
//   gather(base, I, M): base[index] where the mask is set, 0.0 elsewhere (no load there)
#pragma once

#include <cstddef>
#include <cstdint>

#include "fuzzygait/compiler.hpp"

// Which bodies this translation unit sees.
#if defined(FUZZYGAIT_SIMD_AVX2_TU) || defined(FUZZYGAIT_SIMD_AVX512_TU)
#define FUZZYGAIT_SIMD_ISA_TU 1
#endif
#if defined(FUZZYGAIT_SIMD_AVX2_TU) && !defined(__AVX2__)
#error "FUZZYGAIT_SIMD_AVX2_TU: compile this translation unit for AVX2 (see CMake)"
#endif
#if defined(FUZZYGAIT_SIMD_AVX512_TU) && !defined(__AVX512F__)
#error "FUZZYGAIT_SIMD_AVX512_TU: compile this translation unit for AVX-512F (see CMake)"
#endif
#if !defined(FUZZYGAIT_SIMD_ISA_TU) && !defined(FUZZYGAIT_SIMD_SCALAR) && \
    (defined(__SSE2__) || defined(_M_X64))
#define FUZZYGAIT_SIMD_HAVE_SSE2 1
#endif
#if defined(__AVX2__) && !defined(FUZZYGAIT_SIMD_AVX512_TU)
#define FUZZYGAIT_SIMD_HAVE_AVX2 1
#endif
#if defined(__AVX512F__) && !defined(FUZZYGAIT_SIMD_AVX2_TU)
#define FUZZYGAIT_SIMD_HAVE_AVX512 1
#endif

#if !defined(FUZZYGAIT_SIMD_ISA_TU)
#include <bit>
#include <cmath>
#endif
#if defined(FUZZYGAIT_SIMD_HAVE_SSE2)
#include <emmintrin.h>
#endif
#if defined(FUZZYGAIT_SIMD_HAVE_AVX2) || defined(FUZZYGAIT_SIMD_HAVE_AVX512)
#include <immintrin.h>
#endif

namespace fuzzygait::simd {

#if !defined(FUZZYGAIT_SIMD_ISA_TU)
namespace scalar {

template <std::size_t N>
struct Masks {
  static constexpr std::size_t kLanes = N;
  bool lane[N];

  friend Masks operator&(Masks a, Masks b) {
    for (std::size_t k = 0; k < N; ++k)
      a.lane[k] = a.lane[k] && b.lane[k];
    return a;
  }
  friend Masks operator|(Masks a, Masks b) {
    for (std::size_t k = 0; k < N; ++k)
      a.lane[k] = a.lane[k] || b.lane[k];
    return a;
  }
  friend Masks operator!(Masks a) {
    for (std::size_t k = 0; k < N; ++k)
      a.lane[k] = !a.lane[k];
    return a;
  }
  friend bool any(Masks a) {
    bool set = false;
    for (std::size_t k = 0; k < N; ++k)
      set = set || a.lane[k];
    return set;
  }
  friend unsigned bits(Masks a) {
    unsigned b = 0;
    for (std::size_t k = 0; k < N; ++k)
      b |= static_cast<unsigned>(a.lane[k]) << k;
    return b;
  }
};

template <std::size_t N>
struct Ints {
  static constexpr std::size_t kLanes = N;
  using Mask = Masks<N>;
  std::int64_t lane[N];

  Ints() = default;
  Ints(std::int64_t n) {  // every lane n
    for (std::size_t k = 0; k < N; ++k)
      lane[k] = n;
  }
  static Ints load(const std::int64_t* p) {
    Ints r;
    for (std::size_t k = 0; k < N; ++k)
      r.lane[k] = p[k];
    return r;
  }
  friend void store(std::int64_t* p, Ints a) {
    for (std::size_t k = 0; k < N; ++k)
      p[k] = a.lane[k];
  }

  // Modulo 2^64, as the vector bodies (and without signed overflow).
  template <class Op>
  static Ints each(Ints a, Ints b, Op op) {
    for (std::size_t k = 0; k < N; ++k) {
      a.lane[k] = static_cast<std::int64_t>(
          op(static_cast<std::uint64_t>(a.lane[k]), static_cast<std::uint64_t>(b.lane[k])));
    }
    return a;
  }
  friend Ints operator+(Ints a, Ints b) {
    return each(a, b, [](std::uint64_t x, std::uint64_t y) { return x + y; });
  }
  friend Ints operator-(Ints a, Ints b) {
    return each(a, b, [](std::uint64_t x, std::uint64_t y) { return x - y; });
  }
  friend Ints operator&(Ints a, Ints b) {
    return each(a, b, [](std::uint64_t x, std::uint64_t y) { return x & y; });
  }
  friend Ints operator|(Ints a, Ints b) {
    return each(a, b, [](std::uint64_t x, std::uint64_t y) { return x | y; });
  }
  friend Ints operator^(Ints a, Ints b) {
    return each(a, b, [](std::uint64_t x, std::uint64_t y) { return x ^ y; });
  }
  friend Mask operator==(Ints a, Ints b) {
    Mask m;
    for (std::size_t k = 0; k < N; ++k)
      m.lane[k] = a.lane[k] == b.lane[k];
    return m;
  }
  friend Ints select(Mask m, Ints yes, Ints no) {
    for (std::size_t k = 0; k < N; ++k)
      no.lane[k] = m.lane[k] ? yes.lane[k] : no.lane[k];
    return no;
  }
};

template <unsigned Shift, std::size_t N>
Ints<N> shift_left(Ints<N> a) {
  static_assert(Shift < 64);
  for (std::size_t k = 0; k < N; ++k)
    a.lane[k] = static_cast<std::int64_t>(static_cast<std::uint64_t>(a.lane[k]) << Shift);
  return a;
}
template <std::uint32_t Factor, std::size_t N>
Ints<N> multiply_small(Ints<N> a) {
  for (std::size_t k = 0; k < N; ++k)
    a.lane[k] = static_cast<std::int64_t>(static_cast<std::uint64_t>(a.lane[k]) * Factor);
  return a;
}
template <std::size_t N>
Ints<N> as_int(Masks<N> m) {
  Ints<N> r;
  for (std::size_t k = 0; k < N; ++k)
    r.lane[k] = m.lane[k] ? -1 : 0;
  return r;
}

template <std::size_t N>
struct Doubles {
  static constexpr std::size_t kLanes = N;
  using Mask = Masks<N>;
  using Int = Ints<N>;
  double lane[N];

  Doubles() = default;
  Doubles(double x) {  // every lane x
    for (std::size_t k = 0; k < N; ++k)
      lane[k] = x;
  }
  Doubles(double lane0, double lane1) requires(N == 2) : lane{lane0, lane1} {}
  Doubles(double lane0, double lane1, double lane2, double lane3) requires(N == 4)
      : lane{lane0, lane1, lane2, lane3} {}
  static Doubles load(const double* p) {
    Doubles r;
    for (std::size_t k = 0; k < N; ++k)
      r.lane[k] = p[k];
    return r;
  }
  friend void store(double* p, Doubles a) {
    for (std::size_t k = 0; k < N; ++k)
      p[k] = a.lane[k];
  }

  template <class Op>
  static Doubles each(Doubles a, Doubles b, Op op) {
    for (std::size_t k = 0; k < N; ++k)
      a.lane[k] = op(a.lane[k], b.lane[k]);
    return a;
  }
  template <class Op>
  static Mask compare(Doubles a, Doubles b, Op op) {
    Mask m;
    for (std::size_t k = 0; k < N; ++k)
      m.lane[k] = op(a.lane[k], b.lane[k]);
    return m;
  }
  friend Doubles operator+(Doubles a, Doubles b) {
    return each(a, b, [](double x, double y) { return x + y; });
  }
  friend Doubles operator-(Doubles a, Doubles b) {
    return each(a, b, [](double x, double y) { return x - y; });
  }
  friend Doubles operator*(Doubles a, Doubles b) {
    return each(a, b, [](double x, double y) { return x * y; });
  }
  friend Doubles operator/(Doubles a, Doubles b) {
    return each(a, b, [](double x, double y) { return x / y; });
  }
  friend Doubles& operator+=(Doubles& a, Doubles b) { return a = a + b; }
  friend Doubles& operator-=(Doubles& a, Doubles b) { return a = a - b; }
  friend Doubles& operator*=(Doubles& a, Doubles b) { return a = a * b; }
  friend Doubles& operator/=(Doubles& a, Doubles b) { return a = a / b; }
  friend Doubles operator-(Doubles a) {
    for (std::size_t k = 0; k < N; ++k)
      a.lane[k] = -a.lane[k];
    return a;
  }
  friend Doubles abs(Doubles a) {
    for (std::size_t k = 0; k < N; ++k)
      a.lane[k] = std::abs(a.lane[k]);
    return a;
  }
  friend Mask operator==(Doubles a, Doubles b) {
    return compare(a, b, [](double x, double y) { return x == y; });
  }
  friend Mask operator!=(Doubles a, Doubles b) {
    return compare(a, b, [](double x, double y) { return x != y; });
  }
  friend Mask operator<(Doubles a, Doubles b) {
    return compare(a, b, [](double x, double y) { return x < y; });
  }
  friend Mask operator<=(Doubles a, Doubles b) {
    return compare(a, b, [](double x, double y) { return x <= y; });
  }
  friend Mask operator>(Doubles a, Doubles b) {
    return compare(a, b, [](double x, double y) { return x > y; });
  }
  friend Mask operator>=(Doubles a, Doubles b) {
    return compare(a, b, [](double x, double y) { return x >= y; });
  }
  friend Doubles select(Mask m, Doubles yes, Doubles no) {
    for (std::size_t k = 0; k < N; ++k)
      no.lane[k] = m.lane[k] ? yes.lane[k] : no.lane[k];
    return no;
  }
  friend Int as_int(Doubles a) {
    Int r;
    for (std::size_t k = 0; k < N; ++k)
      r.lane[k] = std::bit_cast<std::int64_t>(a.lane[k]);
    return r;
  }
};

template <std::size_t N>
Doubles<N> gather(const double* base, Ints<N> index, Masks<N> m) {
  Doubles<N> r(0.0);
  for (std::size_t k = 0; k < N; ++k) {
    if (m.lane[k]) r.lane[k] = base[index.lane[k]];
  }
  return r;
}
template <std::size_t N>
Doubles<N> as_double(Ints<N> a) {
  Doubles<N> r;
  for (std::size_t k = 0; k < N; ++k)
    r.lane[k] = std::bit_cast<double>(a.lane[k]);
  return r;
}

using Mask2 = Masks<2>;
using Mask4 = Masks<4>;
using Int4 = Ints<4>;
using Double2 = Doubles<2>;
using Double4 = Doubles<4>;
using Mask8 = Masks<8>;
using Int8 = Ints<8>;
using Double8 = Doubles<8>;

}  // namespace scalar
#endif  // !FUZZYGAIT_SIMD_ISA_TU

#if defined(FUZZYGAIT_SIMD_HAVE_SSE2) || defined(FUZZYGAIT_SIMD_HAVE_AVX2)
// The comparisons of the x86 bodies. GCC and Clang compare as their generic vector operations,
// which their optimisers know yield masks and so fold into the selects and bit operations that use
// them (GCC's comparison intrinsics are opaque to it, and a blend on such a mask cost an extra
// instruction); MSVC takes the intrinsics. The same instructions either way. Bit operations go
// through the integer intrinsics, which GCC also treats as generic operations.
enum class Compare { Equal, NotEqual, Less, LessEqual, Greater, GreaterEqual };
#endif

#if defined(FUZZYGAIT_SIMD_HAVE_SSE2)
namespace sse2 {

template <Compare C>
FUZZYGAIT_ALWAYS_INLINE __m128i compare(__m128d a, __m128d b) {
#if defined(__GNUC__)
  if constexpr (C == Compare::Equal) {
    return reinterpret_cast<__m128i>(a == b);
  } else if constexpr (C == Compare::NotEqual) {
    return reinterpret_cast<__m128i>(a != b);
  } else if constexpr (C == Compare::Less) {
    return reinterpret_cast<__m128i>(a < b);
  } else if constexpr (C == Compare::LessEqual) {
    return reinterpret_cast<__m128i>(a <= b);
  } else if constexpr (C == Compare::Greater) {
    return reinterpret_cast<__m128i>(a > b);
  } else {
    static_assert(C == Compare::GreaterEqual);
    return reinterpret_cast<__m128i>(a >= b);
  }
#else
  if constexpr (C == Compare::Equal) {
    return _mm_castpd_si128(_mm_cmpeq_pd(a, b));
  } else if constexpr (C == Compare::NotEqual) {
    return _mm_castpd_si128(_mm_cmpneq_pd(a, b));
  } else if constexpr (C == Compare::Less) {
    return _mm_castpd_si128(_mm_cmplt_pd(a, b));
  } else if constexpr (C == Compare::LessEqual) {
    return _mm_castpd_si128(_mm_cmple_pd(a, b));
  } else if constexpr (C == Compare::Greater) {
    return _mm_castpd_si128(_mm_cmpgt_pd(a, b));
  } else {
    static_assert(C == Compare::GreaterEqual);
    return _mm_castpd_si128(_mm_cmpge_pd(a, b));
  }
#endif
}

// Lanes of all ones (set) or all zeros.
struct Mask2 {
  static constexpr std::size_t kLanes = 2;
  __m128i v;

  friend FUZZYGAIT_ALWAYS_INLINE Mask2 operator&(Mask2 a, Mask2 b) {
    return {_mm_and_si128(a.v, b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask2 operator|(Mask2 a, Mask2 b) {
    return {_mm_or_si128(a.v, b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask2 operator!(Mask2 a) {
    return {_mm_xor_si128(a.v, _mm_set1_epi32(-1))};
  }
  friend FUZZYGAIT_ALWAYS_INLINE unsigned bits(Mask2 a) {
    return static_cast<unsigned>(_mm_movemask_pd(_mm_castsi128_pd(a.v)));
  }
  friend FUZZYGAIT_ALWAYS_INLINE bool any(Mask2 a) { return bits(a) != 0; }
};

struct Double2 {
  static constexpr std::size_t kLanes = 2;
  using Mask = Mask2;
  __m128d v;

  Double2() = default;
  FUZZYGAIT_ALWAYS_INLINE Double2(double x) : v(_mm_set1_pd(x)) {}  // every lane x
  FUZZYGAIT_ALWAYS_INLINE Double2(double lane0, double lane1) : v(_mm_set_pd(lane1, lane0)) {}
  FUZZYGAIT_ALWAYS_INLINE explicit Double2(__m128d x) : v(x) {}
  static FUZZYGAIT_ALWAYS_INLINE Double2 load(const double* p) { return Double2(_mm_loadu_pd(p)); }
  friend FUZZYGAIT_ALWAYS_INLINE void store(double* p, Double2 a) { _mm_storeu_pd(p, a.v); }

  friend FUZZYGAIT_ALWAYS_INLINE Double2 operator+(Double2 a, Double2 b) {
    return Double2(_mm_add_pd(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double2 operator-(Double2 a, Double2 b) {
    return Double2(_mm_sub_pd(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double2 operator*(Double2 a, Double2 b) {
    return Double2(_mm_mul_pd(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double2 operator/(Double2 a, Double2 b) {
    return Double2(_mm_div_pd(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double2& operator+=(Double2& a, Double2 b) { return a = a + b; }
  friend FUZZYGAIT_ALWAYS_INLINE Double2& operator-=(Double2& a, Double2 b) { return a = a - b; }
  friend FUZZYGAIT_ALWAYS_INLINE Double2& operator*=(Double2& a, Double2 b) { return a = a * b; }
  friend FUZZYGAIT_ALWAYS_INLINE Double2& operator/=(Double2& a, Double2 b) { return a = a / b; }
  // Sign bits flipped or cleared as integers (which a compiler folds into constants).
  friend FUZZYGAIT_ALWAYS_INLINE Double2 operator-(Double2 a) {
    return Double2(_mm_castsi128_pd(
        _mm_xor_si128(_mm_castpd_si128(a.v), _mm_set1_epi64x(std::int64_t{-1} << 63))));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double2 abs(Double2 a) {
    return Double2(_mm_castsi128_pd(
        _mm_and_si128(_mm_castpd_si128(a.v), _mm_set1_epi64x(~(std::int64_t{-1} << 63)))));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator==(Double2 a, Double2 b) {
    return {compare<Compare::Equal>(a.v, b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator!=(Double2 a, Double2 b) {
    return {compare<Compare::NotEqual>(a.v, b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator<(Double2 a, Double2 b) {
    return {compare<Compare::Less>(a.v, b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator<=(Double2 a, Double2 b) {
    return {compare<Compare::LessEqual>(a.v, b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator>(Double2 a, Double2 b) {
    return {compare<Compare::Greater>(a.v, b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator>=(Double2 a, Double2 b) {
    return {compare<Compare::GreaterEqual>(a.v, b.v)};
  }
  // Bitwise, as SSE2 has no blend.
  friend FUZZYGAIT_ALWAYS_INLINE Double2 select(Mask m, Double2 yes, Double2 no) {
    const __m128i kept = _mm_and_si128(m.v, _mm_castpd_si128(yes.v));
    const __m128i other = _mm_and_si128((!m).v, _mm_castpd_si128(no.v));
    return Double2(_mm_castsi128_pd(_mm_or_si128(kept, other)));
  }
};

}  // namespace sse2
#endif  // FUZZYGAIT_SIMD_HAVE_SSE2

#if defined(FUZZYGAIT_SIMD_HAVE_AVX2)
namespace avx2 {

template <Compare C>
FUZZYGAIT_ALWAYS_INLINE __m256i compare(__m256d a, __m256d b) {
#if defined(__GNUC__)
  if constexpr (C == Compare::Equal) {
    return reinterpret_cast<__m256i>(a == b);
  } else if constexpr (C == Compare::NotEqual) {
    return reinterpret_cast<__m256i>(a != b);
  } else if constexpr (C == Compare::Less) {
    return reinterpret_cast<__m256i>(a < b);
  } else if constexpr (C == Compare::LessEqual) {
    return reinterpret_cast<__m256i>(a <= b);
  } else if constexpr (C == Compare::Greater) {
    return reinterpret_cast<__m256i>(a > b);
  } else {
    static_assert(C == Compare::GreaterEqual);
    return reinterpret_cast<__m256i>(a >= b);
  }
#else
  // C++'s comparisons: ordered (false with a NaN), except != (true with a NaN).
  if constexpr (C == Compare::Equal) {
    return _mm256_castpd_si256(_mm256_cmp_pd(a, b, _CMP_EQ_OQ));
  } else if constexpr (C == Compare::NotEqual) {
    return _mm256_castpd_si256(_mm256_cmp_pd(a, b, _CMP_NEQ_UQ));
  } else if constexpr (C == Compare::Less) {
    return _mm256_castpd_si256(_mm256_cmp_pd(a, b, _CMP_LT_OS));
  } else if constexpr (C == Compare::LessEqual) {
    return _mm256_castpd_si256(_mm256_cmp_pd(a, b, _CMP_LE_OS));
  } else if constexpr (C == Compare::Greater) {
    return _mm256_castpd_si256(_mm256_cmp_pd(a, b, _CMP_GT_OS));
  } else {
    static_assert(C == Compare::GreaterEqual);
    return _mm256_castpd_si256(_mm256_cmp_pd(a, b, _CMP_GE_OS));
  }
#endif
}

// Lanes of all ones (set) or all zeros.
struct Mask4 {
  static constexpr std::size_t kLanes = 4;
  __m256i v;

  friend FUZZYGAIT_ALWAYS_INLINE Mask4 operator&(Mask4 a, Mask4 b) {
    return {_mm256_and_si256(a.v, b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask4 operator|(Mask4 a, Mask4 b) {
    return {_mm256_or_si256(a.v, b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask4 operator!(Mask4 a) {
    return {_mm256_xor_si256(a.v, _mm256_set1_epi64x(-1))};
  }
  friend FUZZYGAIT_ALWAYS_INLINE unsigned bits(Mask4 a) {
    return static_cast<unsigned>(_mm256_movemask_pd(_mm256_castsi256_pd(a.v)));
  }
  friend FUZZYGAIT_ALWAYS_INLINE bool any(Mask4 a) { return bits(a) != 0; }
};

struct Int4 {
  static constexpr std::size_t kLanes = 4;
  using Mask = Mask4;
  __m256i v;

  Int4() = default;
  FUZZYGAIT_ALWAYS_INLINE Int4(std::int64_t n) : v(_mm256_set1_epi64x(n)) {}  // every lane n
  FUZZYGAIT_ALWAYS_INLINE explicit Int4(__m256i x) : v(x) {}
  static FUZZYGAIT_ALWAYS_INLINE Int4 load(const std::int64_t* p) {
    return Int4(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)));
  }
  friend FUZZYGAIT_ALWAYS_INLINE void store(std::int64_t* p, Int4 a) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), a.v);
  }

  friend FUZZYGAIT_ALWAYS_INLINE Int4 operator+(Int4 a, Int4 b) {
    return Int4(_mm256_add_epi64(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Int4 operator-(Int4 a, Int4 b) {
    return Int4(_mm256_sub_epi64(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Int4 operator&(Int4 a, Int4 b) {
    return Int4(_mm256_and_si256(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Int4 operator|(Int4 a, Int4 b) {
    return Int4(_mm256_or_si256(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Int4 operator^(Int4 a, Int4 b) {
    return Int4(_mm256_xor_si256(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator==(Int4 a, Int4 b) {
    return {_mm256_cmpeq_epi64(a.v, b.v)};
  }
  // A blend on each lane's top bit (a mask's lanes are all ones or all zeros).
  friend FUZZYGAIT_ALWAYS_INLINE Int4 select(Mask m, Int4 yes, Int4 no) {
    return Int4(_mm256_castpd_si256(_mm256_blendv_pd(
        _mm256_castsi256_pd(no.v), _mm256_castsi256_pd(yes.v), _mm256_castsi256_pd(m.v))));
  }
};

template <unsigned Shift>
FUZZYGAIT_ALWAYS_INLINE Int4 shift_left(Int4 a) {
  static_assert(Shift < 64);
  return Int4(_mm256_slli_epi64(a.v, Shift));
}
// A power of two is a shift; any other factor multiplies the lanes' low 32 bits.
template <std::uint32_t Factor>
FUZZYGAIT_ALWAYS_INLINE Int4 multiply_small(Int4 a) {
  if constexpr (Factor != 0 && (Factor & (Factor - 1)) == 0) {
    constexpr int shift = [] {
      int s = 0;
      while ((std::uint32_t{1} << s) != Factor)
        ++s;
      return s;
    }();
    return Int4(_mm256_slli_epi64(a.v, shift));
  } else {
    return Int4(_mm256_mul_epu32(a.v, _mm256_set1_epi64x(Factor)));
  }
}
FUZZYGAIT_ALWAYS_INLINE Int4 as_int(Mask4 m) {
  return Int4(m.v);
}

struct Double4 {
  static constexpr std::size_t kLanes = 4;
  using Mask = Mask4;
  using Int = Int4;
  __m256d v;

  Double4() = default;
  FUZZYGAIT_ALWAYS_INLINE Double4(double x) : v(_mm256_set1_pd(x)) {}  // every lane x
  FUZZYGAIT_ALWAYS_INLINE Double4(double lane0, double lane1, double lane2, double lane3)
      : v(_mm256_set_pd(lane3, lane2, lane1, lane0)) {}
  FUZZYGAIT_ALWAYS_INLINE explicit Double4(__m256d x) : v(x) {}
  static FUZZYGAIT_ALWAYS_INLINE Double4 load(const double* p) {
    return Double4(_mm256_loadu_pd(p));
  }
  friend FUZZYGAIT_ALWAYS_INLINE void store(double* p, Double4 a) { _mm256_storeu_pd(p, a.v); }

  friend FUZZYGAIT_ALWAYS_INLINE Double4 operator+(Double4 a, Double4 b) {
    return Double4(_mm256_add_pd(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double4 operator-(Double4 a, Double4 b) {
    return Double4(_mm256_sub_pd(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double4 operator*(Double4 a, Double4 b) {
    return Double4(_mm256_mul_pd(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double4 operator/(Double4 a, Double4 b) {
    return Double4(_mm256_div_pd(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double4& operator+=(Double4& a, Double4 b) { return a = a + b; }
  friend FUZZYGAIT_ALWAYS_INLINE Double4& operator-=(Double4& a, Double4 b) { return a = a - b; }
  friend FUZZYGAIT_ALWAYS_INLINE Double4& operator*=(Double4& a, Double4 b) { return a = a * b; }
  friend FUZZYGAIT_ALWAYS_INLINE Double4& operator/=(Double4& a, Double4 b) { return a = a / b; }
  // Sign bits flipped or cleared as integers (which a compiler folds into constants).
  friend FUZZYGAIT_ALWAYS_INLINE Double4 operator-(Double4 a) {
    return Double4(_mm256_castsi256_pd(
        _mm256_xor_si256(_mm256_castpd_si256(a.v), _mm256_set1_epi64x(std::int64_t{-1} << 63))));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double4 abs(Double4 a) {
    return Double4(_mm256_castsi256_pd(
        _mm256_and_si256(_mm256_castpd_si256(a.v), _mm256_set1_epi64x(~(std::int64_t{-1} << 63)))));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator==(Double4 a, Double4 b) {
    return {compare<Compare::Equal>(a.v, b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator!=(Double4 a, Double4 b) {
    return {compare<Compare::NotEqual>(a.v, b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator<(Double4 a, Double4 b) {
    return {compare<Compare::Less>(a.v, b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator<=(Double4 a, Double4 b) {
    return {compare<Compare::LessEqual>(a.v, b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator>(Double4 a, Double4 b) {
    return {compare<Compare::Greater>(a.v, b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator>=(Double4 a, Double4 b) {
    return {compare<Compare::GreaterEqual>(a.v, b.v)};
  }
  // A blend on each lane's top bit (a mask's lanes are all ones or all zeros).
  friend FUZZYGAIT_ALWAYS_INLINE Double4 select(Mask m, Double4 yes, Double4 no) {
    return Double4(_mm256_blendv_pd(no.v, yes.v, _mm256_castsi256_pd(m.v)));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Int as_int(Double4 a) { return Int4(_mm256_castpd_si256(a.v)); }
};

FUZZYGAIT_ALWAYS_INLINE Double4 gather(const double* base, Int4 index, Mask4 m) {
  return Double4(
      _mm256_mask_i64gather_pd(_mm256_setzero_pd(), base, index.v, _mm256_castsi256_pd(m.v), 8));
}
FUZZYGAIT_ALWAYS_INLINE Double4 as_double(Int4 a) {
  return Double4(_mm256_castsi256_pd(a.v));
}

}  // namespace avx2
#endif  // FUZZYGAIT_SIMD_HAVE_AVX2

#if defined(FUZZYGAIT_SIMD_HAVE_AVX512)
namespace avx512 {

// AVX-512F only: a mask is a mask register, one bit a lane.
struct Mask8 {
  static constexpr std::size_t kLanes = 8;
  __mmask8 v;

  friend FUZZYGAIT_ALWAYS_INLINE Mask8 operator&(Mask8 a, Mask8 b) {
    return {static_cast<__mmask8>(a.v & b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask8 operator|(Mask8 a, Mask8 b) {
    return {static_cast<__mmask8>(a.v | b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask8 operator!(Mask8 a) { return {static_cast<__mmask8>(~a.v)}; }
  friend FUZZYGAIT_ALWAYS_INLINE unsigned bits(Mask8 a) { return a.v; }
  friend FUZZYGAIT_ALWAYS_INLINE bool any(Mask8 a) { return a.v != 0; }
};

struct Int8 {
  static constexpr std::size_t kLanes = 8;
  using Mask = Mask8;
  __m512i v;

  Int8() = default;
  FUZZYGAIT_ALWAYS_INLINE Int8(std::int64_t n) : v(_mm512_set1_epi64(n)) {}  // every lane n
  FUZZYGAIT_ALWAYS_INLINE explicit Int8(__m512i x) : v(x) {}
  static FUZZYGAIT_ALWAYS_INLINE Int8 load(const std::int64_t* p) {
    return Int8(_mm512_loadu_si512(p));
  }
  friend FUZZYGAIT_ALWAYS_INLINE void store(std::int64_t* p, Int8 a) {
    _mm512_storeu_si512(p, a.v);
  }

  friend FUZZYGAIT_ALWAYS_INLINE Int8 operator+(Int8 a, Int8 b) {
    return Int8(_mm512_add_epi64(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Int8 operator-(Int8 a, Int8 b) {
    return Int8(_mm512_sub_epi64(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Int8 operator&(Int8 a, Int8 b) {
    return Int8(_mm512_and_si512(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Int8 operator|(Int8 a, Int8 b) {
    return Int8(_mm512_or_si512(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Int8 operator^(Int8 a, Int8 b) {
    return Int8(_mm512_xor_si512(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator==(Int8 a, Int8 b) {
    return {_mm512_cmpeq_epi64_mask(a.v, b.v)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Int8 select(Mask m, Int8 yes, Int8 no) {
    return Int8(_mm512_mask_blend_epi64(m.v, no.v, yes.v));
  }
};

template <unsigned Shift>
FUZZYGAIT_ALWAYS_INLINE Int8 shift_left(Int8 a) {
  static_assert(Shift < 64);
  // (The zero-masking forms, all lanes kept: GCC 12 warns that the plain ones' undefined
  // pass-through value may be used uninitialised.)
  return Int8(_mm512_maskz_slli_epi64(0xFF, a.v, Shift));
}
// A power of two is a shift; any other factor multiplies the lanes' low 32 bits.
template <std::uint32_t Factor>
FUZZYGAIT_ALWAYS_INLINE Int8 multiply_small(Int8 a) {
  if constexpr (Factor != 0 && (Factor & (Factor - 1)) == 0) {
    constexpr unsigned shift = [] {
      unsigned s = 0;
      while ((std::uint32_t{1} << s) != Factor)
        ++s;
      return s;
    }();
    return Int8(_mm512_maskz_slli_epi64(0xFF, a.v, shift));
  } else {
    return Int8(_mm512_maskz_mul_epu32(0xFF, a.v, _mm512_set1_epi64(Factor)));
  }
}
FUZZYGAIT_ALWAYS_INLINE Int8 as_int(Mask8 m) {
  return Int8(_mm512_maskz_mov_epi64(m.v, _mm512_set1_epi64(-1)));
}

struct Double8 {
  static constexpr std::size_t kLanes = 8;
  using Mask = Mask8;
  using Int = Int8;
  __m512d v;

  Double8() = default;
  FUZZYGAIT_ALWAYS_INLINE Double8(double x) : v(_mm512_set1_pd(x)) {}  // every lane x
  FUZZYGAIT_ALWAYS_INLINE explicit Double8(__m512d x) : v(x) {}
  static FUZZYGAIT_ALWAYS_INLINE Double8 load(const double* p) {
    return Double8(_mm512_loadu_pd(p));
  }
  friend FUZZYGAIT_ALWAYS_INLINE void store(double* p, Double8 a) { _mm512_storeu_pd(p, a.v); }

  friend FUZZYGAIT_ALWAYS_INLINE Double8 operator+(Double8 a, Double8 b) {
    return Double8(_mm512_add_pd(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double8 operator-(Double8 a, Double8 b) {
    return Double8(_mm512_sub_pd(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double8 operator*(Double8 a, Double8 b) {
    return Double8(_mm512_mul_pd(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double8 operator/(Double8 a, Double8 b) {
    return Double8(_mm512_div_pd(a.v, b.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double8& operator+=(Double8& a, Double8 b) { return a = a + b; }
  friend FUZZYGAIT_ALWAYS_INLINE Double8& operator-=(Double8& a, Double8 b) { return a = a - b; }
  friend FUZZYGAIT_ALWAYS_INLINE Double8& operator*=(Double8& a, Double8 b) { return a = a * b; }
  friend FUZZYGAIT_ALWAYS_INLINE Double8& operator/=(Double8& a, Double8 b) { return a = a / b; }
  // Sign bits flipped or cleared as integers.
  friend FUZZYGAIT_ALWAYS_INLINE Double8 operator-(Double8 a) {
    return Double8(_mm512_castsi512_pd(
        _mm512_xor_si512(_mm512_castpd_si512(a.v), _mm512_set1_epi64(std::int64_t{-1} << 63))));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double8 abs(Double8 a) {
    return Double8(_mm512_castsi512_pd(
        _mm512_and_si512(_mm512_castpd_si512(a.v), _mm512_set1_epi64(~(std::int64_t{-1} << 63)))));
  }
  // C++'s comparisons: ordered (false with a NaN), except != (true with a NaN).
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator==(Double8 a, Double8 b) {
    return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_EQ_OQ)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator!=(Double8 a, Double8 b) {
    return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_NEQ_UQ)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator<(Double8 a, Double8 b) {
    return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_LT_OS)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator<=(Double8 a, Double8 b) {
    return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_LE_OS)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator>(Double8 a, Double8 b) {
    return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_GT_OS)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Mask operator>=(Double8 a, Double8 b) {
    return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_GE_OS)};
  }
  friend FUZZYGAIT_ALWAYS_INLINE Double8 select(Mask m, Double8 yes, Double8 no) {
    return Double8(_mm512_mask_blend_pd(m.v, no.v, yes.v));
  }
  friend FUZZYGAIT_ALWAYS_INLINE Int as_int(Double8 a) { return Int8(_mm512_castpd_si512(a.v)); }
};

FUZZYGAIT_ALWAYS_INLINE Double8 gather(const double* base, Int8 index, Mask8 m) {
  return Double8(_mm512_mask_i64gather_pd(_mm512_setzero_pd(), m.v, index.v, base, 8));
}
FUZZYGAIT_ALWAYS_INLINE Double8 as_double(Int8 a) {
  return Double8(_mm512_castsi512_pd(a.v));
}

}  // namespace avx512
#endif  // FUZZYGAIT_SIMD_HAVE_AVX512

#if !defined(FUZZYGAIT_SIMD_ISA_TU)
#if defined(FUZZYGAIT_SIMD_HAVE_SSE2)
using Double2 = sse2::Double2;
#else
using Double2 = scalar::Double2;
#endif
#endif

}  // namespace fuzzygait::simd

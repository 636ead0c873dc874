// The compiler hints fuzzygait's inline code uses, spelled once for GCC, Clang and MSVC (and
// nothing for others): the inner loops are measured with them. No other file names a compiler but
// the vector lanes' (src/runtime/simd: intrinsics and the processor check).
#pragma once

#if defined(__GNUC__) || defined(__clang__)
#define FUZZYGAIT_ALWAYS_INLINE inline __attribute__((always_inline))
#define FUZZYGAIT_NOINLINE __attribute__((noinline))
#define FUZZYGAIT_PRAGMA(text) _Pragma(#text)
#if defined(__clang__)
#define FUZZYGAIT_UNROLL(n) FUZZYGAIT_PRAGMA(unroll n)
#else
#define FUZZYGAIT_UNROLL(n) FUZZYGAIT_PRAGMA(GCC unroll n)
#endif
#define FUZZYGAIT_RESTRICT __restrict__
#elif defined(_MSC_VER)
#define FUZZYGAIT_ALWAYS_INLINE __forceinline
#define FUZZYGAIT_NOINLINE __declspec(noinline)
#define FUZZYGAIT_UNROLL(n)
#define FUZZYGAIT_RESTRICT __restrict
#else
#define FUZZYGAIT_ALWAYS_INLINE inline
#define FUZZYGAIT_NOINLINE
#define FUZZYGAIT_UNROLL(n)
#define FUZZYGAIT_RESTRICT
#endif

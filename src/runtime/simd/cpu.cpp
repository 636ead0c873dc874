#include "runtime/simd/cpu.hpp"

#if defined(FUZZYGAIT_SIMD_AVX2) && defined(_MSC_VER) && !defined(__clang__)
#include <immintrin.h>
#include <intrin.h>
#endif

namespace fuzzygait::simd {
namespace {

bool detect_avx2() noexcept {
#if !defined(FUZZYGAIT_SIMD_AVX2)
  return false;
#elif defined(_MSC_VER) && !defined(__clang__)
  // CPUID leaf 1: the OS saves the AVX registers (OSXSAVE, then XCR0's SSE and AVX state bits)
  // and the processor has AVX; leaf 7: AVX2.
  int info[4] = {};
  __cpuid(info, 0);
  if (info[0] < 7) return false;
  __cpuid(info, 1);
  const bool osxsave = (info[2] & (1 << 27)) != 0;
  const bool avx = (info[2] & (1 << 28)) != 0;
  if (!osxsave || !avx || (_xgetbv(0) & 6) != 6) return false;
  __cpuidex(info, 7, 0);
  return (info[1] & (1 << 5)) != 0;
#else
  // GCC and Clang: their runtime checks the processor and the OS's saved state the same way.
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") != 0;
#endif
}

}  // namespace

bool has_avx2() noexcept {
  static const bool supported = detect_avx2();
  return supported;
}

}  // namespace fuzzygait::simd

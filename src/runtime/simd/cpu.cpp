#include "runtime/simd/cpu.hpp"

#if (defined(FUZZYGAIT_SIMD_AVX2) || defined(FUZZYGAIT_SIMD_AVX512)) && defined(_MSC_VER) && \
    !defined(__clang__)
#include <immintrin.h>
#include <intrin.h>
#define FUZZYGAIT_CPUID_MSVC 1
#endif

namespace fuzzygait::simd {
namespace {

#if defined(FUZZYGAIT_CPUID_MSVC)
// CPUID and XGETBV: the processor has the feature (leaf 7, EBX) and the operating system saves
// the registers it uses (OSXSAVE, then XCR0's state bits).
bool cpu_and_os_support(int leaf7_ebx_bit, unsigned long long xcr0_bits) noexcept {
  int info[4] = {};
  __cpuid(info, 0);
  if (info[0] < 7) return false;
  __cpuid(info, 1);
  const bool osxsave = (info[2] & (1 << 27)) != 0;
  const bool avx = (info[2] & (1 << 28)) != 0;
  if (!osxsave || !avx || (_xgetbv(0) & xcr0_bits) != xcr0_bits) return false;
  __cpuidex(info, 7, 0);
  return (info[1] & (1 << leaf7_ebx_bit)) != 0;
}
#endif

bool detect_avx2() noexcept {
#if !defined(FUZZYGAIT_SIMD_AVX2)
  return false;
#elif defined(FUZZYGAIT_CPUID_MSVC)
  return cpu_and_os_support(5, 0x6);    // AVX2; SSE and AVX state
#else
  // GCC and Clang: their runtime checks the processor and the saved state the same way.
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") != 0;
#endif
}

bool detect_avx512() noexcept {
#if !defined(FUZZYGAIT_SIMD_AVX512)
  return false;
#elif defined(FUZZYGAIT_CPUID_MSVC)
  return cpu_and_os_support(16, 0xE6);  // AVX-512F; SSE, AVX, opmask and ZMM state
#else
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx512f") != 0;
#endif
}

}  // namespace

bool has_avx2() noexcept {
  static const bool supported = detect_avx2();
  return supported;
}

bool has_avx512() noexcept {
  static const bool supported = detect_avx512();
  return supported;
}

}  // namespace fuzzygait::simd

#include "runtime/rig/trigonometry.hpp"

#include "runtime/simd/cpu.hpp"

namespace fuzzygait::rig::detail {

void sin_cos(const double* x, double* sin, double* cos, std::size_t n) {
  // The widest vectors the machine runs, over whole vectors; then libm's answers where the
  // kernel reports an argument beyond its range.
  std::size_t done = 0;
  bool beyond = false;
#if defined(FUZZYGAIT_SIMD_AVX512)
  if (simd::has_avx512()) {
    done = n - n % 8;
    beyond = sin_cos_avx512(x, sin, cos, done);
  }
#endif
#if defined(FUZZYGAIT_SIMD_AVX2)
  if (done + 4 <= n && simd::has_avx2()) {
    const std::size_t from = done;
    done = n - n % 4;
    beyond = sin_cos_avx2(x + from, sin + from, cos + from, done - from) || beyond;
  }
#endif
  for (std::size_t i = 0; beyond && i < done; ++i) {
    if (std::abs(x[i]) >= kSinCosExactBelow) {
      sin[i] = std::sin(x[i]);
      cos[i] = std::cos(x[i]);
    }
  }
  constexpr std::size_t kLanes = 8;  // four SSE2 vectors
  for (; done + kLanes <= n; done += kLanes)
    sin_cos_lanes<kLanes>(x + done, sin + done, cos + done);
  for (; done < n; ++done)
    sin_cos_lanes<1>(x + done, sin + done, cos + done);
}

}  // namespace fuzzygait::rig::detail

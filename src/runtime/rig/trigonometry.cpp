#include "runtime/rig/trigonometry.hpp"

#include "runtime/simd/cpu.hpp"

namespace fuzzygait::rig::detail {

void sin_cos(const double* x, double* sin, double* cos, std::size_t n) {
  std::size_t done = 0;
#if defined(FUZZYGAIT_SIMD_AVX2)
  if (simd::has_avx2()) {
    done = n - n % 4;
    if (sin_cos_avx2(x, sin, cos, done)) {
      for (std::size_t i = 0; i < done; ++i) {
        if (std::abs(x[i]) >= kSinCosExactBelow) {
          sin[i] = std::sin(x[i]);
          cos[i] = std::cos(x[i]);
        }
      }
    }
  }
#endif
  constexpr std::size_t kLanes = 8;  // four SSE2 vectors
  for (; done + kLanes <= n; done += kLanes)
    sin_cos_lanes<kLanes>(x + done, sin + done, cos + done);
  for (; done < n; ++done)
    sin_cos_lanes<1>(x + done, sin + done, cos + done);
}

}  // namespace fuzzygait::rig::detail

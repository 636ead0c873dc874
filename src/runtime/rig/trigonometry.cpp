#include "runtime/rig/trigonometry.hpp"

#include "runtime/simd_targets.hpp"

namespace fuzzygait::rig::detail {

FUZZYGAIT_VECTOR_TARGETS
void sin_cos(const double* x, double* sin, double* cos, std::size_t n) {
  constexpr std::size_t kLanes = 8;  // one AVX-512 vector, two AVX2, four SSE2
  std::size_t i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    sin_cos_lanes<kLanes>(x + i, sin + i, cos + i);
  }
  for (; i < n; ++i) {
    sin_cos_lanes<1>(x + i, sin + i, cos + i);
  }
}

}  // namespace fuzzygait::rig::detail

#include "trigonometry.hpp"

#include "../simd_targets.hpp"

namespace fuzzygait::rig::detail {

FUZZYGAIT_VECTOR_TARGETS
void sin_cos(const double* x, double* sin, double* cos, std::size_t n) {
  constexpr std::size_t kLanes = 8;  // one AVX-512 vector, two AVX2, four SSE2
  std::size_t i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    sin_cos(*reinterpret_cast<const double(*)[kLanes]>(x + i),
            *reinterpret_cast<double(*)[kLanes]>(sin + i),
            *reinterpret_cast<double(*)[kLanes]>(cos + i));
  }
  for (; i < n; ++i) {
    sin_cos(*reinterpret_cast<const double(*)[1]>(x + i), *reinterpret_cast<double(*)[1]>(sin + i),
            *reinterpret_cast<double(*)[1]>(cos + i));
  }
}

}  // namespace fuzzygait::rig::detail

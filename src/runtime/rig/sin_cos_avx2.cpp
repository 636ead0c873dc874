// A crowd's batch of sines and cosines for AVX2: compiled for AVX2 (see src/runtime/CMakeLists.txt)
// and run only where simd::has_avx2(). Includes nothing but sin_cos_vector.hpp (lanes.hpp and the
// standard library), so that no inline function compiled here is shared with baseline code.
#define FUZZYGAIT_SIMD_AVX2_TU 1
#include "runtime/rig/sin_cos_vector.hpp"

namespace fuzzygait::rig::detail {

bool sin_cos_avx2(const double* x, double* sin, double* cos, std::size_t n) {
  using simd::avx2::Double4;
  Double4::Mask beyond{};
  for (std::size_t i = 0; i < n; i += Double4::kLanes) {
    Double4 s;
    Double4 c;
    beyond = beyond | sin_cos_vector(Double4::load(x + i), s, c);
    store(sin + i, s);
    store(cos + i, c);
  }
  return any(beyond);
}

}  // namespace fuzzygait::rig::detail

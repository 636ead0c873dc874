// A crowd's batch of sines and cosines for AVX-512F: compiled for it (see
// src/runtime/CMakeLists.txt) and run only where simd::has_avx512(). Includes nothing but
// sin_cos_vector.hpp (lanes.hpp and the standard library), so that no inline function compiled
// here is shared with other code.
#define FUZZYGAIT_SIMD_AVX512_TU 1
#include "runtime/rig/sin_cos_vector.hpp"

namespace fuzzygait::rig::detail {

bool sin_cos_avx512(const double* x, double* sin, double* cos, std::size_t n) {
  using simd::avx512::Double8;
  Double8::Mask beyond{};
  for (std::size_t i = 0; i < n; i += Double8::kLanes) {
    Double8 s;
    Double8 c;
    beyond = beyond | sin_cos_vector(Double8::load(x + i), s, c);
    store(sin + i, s);
    store(cos + i, c);
  }
  return any(beyond);
}

}  // namespace fuzzygait::rig::detail

// The packed controllers' batch kernel for AVX2: compiled for AVX2 (see src/runtime/CMakeLists.txt)
// and run only where simd::has_avx2(). Includes nothing but packed_lanes.hpp (lanes.hpp and the
// standard library), so that no inline function compiled here is shared with baseline code.
#define FUZZYGAIT_SIMD_AVX2_TU 1
#include "runtime/fuzzy/packed_lanes.hpp"

namespace fuzzygait::fuzzy::detail {

void evaluate_packed_avx2(const PackedView& p, const double* x0, const double* x1, double* out,
                          std::size_t n) {
  evaluate_packed_lanes<simd::avx2::Double4>(p, x0, x1, out, n);
}

}  // namespace fuzzygait::fuzzy::detail

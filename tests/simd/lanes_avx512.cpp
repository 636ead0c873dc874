// The AVX-512 body's side of lanes_test.cpp, compiled for AVX-512F.
#define FUZZYGAIT_SIMD_AVX512_TU 1
#include "simd/lane_ops.hpp"

namespace fuzzygait::simd::test {

void apply_avx512_lane_ops(const LaneInputs& in, LaneResults& out) {
  apply_lane_ops<avx512::Double8>(in, out);
}

}  // namespace fuzzygait::simd::test

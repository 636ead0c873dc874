// The AVX2 body's side of lanes_test.cpp, compiled for AVX2.
#define FUZZYGAIT_SIMD_AVX2_TU 1
#include "simd/lane_ops.hpp"

namespace fuzzygait::simd::test {

void apply_avx2_lane_ops(const LaneInputs& in, LaneResults& out) {
  apply_lane_ops<avx2::Double4>(in, out);
}

}  // namespace fuzzygait::simd::test

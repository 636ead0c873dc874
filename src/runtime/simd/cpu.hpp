// Which vector bodies of simd/lanes.hpp this machine runs, decided once.
#pragma once

namespace fuzzygait::simd {

// True when the library was built with its AVX2 translation units (x86-64, FUZZYGAIT_SIMD=auto)
// and the processor and the operating system support AVX2; false on other architectures and in a
// scalar build. Decided on the first call.
bool has_avx2() noexcept;

// The same for the AVX-512F translation units and AVX-512F.
bool has_avx512() noexcept;

}  // namespace fuzzygait::simd

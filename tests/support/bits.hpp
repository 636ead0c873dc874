// Bit-for-bit comparison of doubles for the tests that hold fuzzygait to another implementation's
// exact results.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

namespace fuzzygait::test {

// The same bits, except that any NaN equals any NaN: payloads and signs of NaN carry no meaning
// here. +0 and -0 differ, as do infinities of opposite sign.
inline bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b) ||
         (std::isnan(a) && std::isnan(b));
}

}  // namespace fuzzygait::test

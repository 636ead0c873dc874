// Numbers as the BVH writers print them. Internal to the offline library.
#pragma once

#include <string>

namespace fuzzygait::io::detail {

// Appends `value` with `decimals` fixed decimals, independent of the C locale and never as
// "-0.000000", after a space when `line` is not empty. Throws std::invalid_argument for a value
// too large to print.
void append_fixed(std::string& line, double value, int decimals = 6);

}  // namespace fuzzygait::io::detail

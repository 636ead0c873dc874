// The one way numbers are written into messages (errors, warnings, reports): the shortest text
// that reads back to the same double ("0.7", "1e-07", "1e+300"), and "nan", "inf", "-inf" without
// a sign a platform might add. Internal to fuzzygait (not installed).
#pragma once

#include <string>

namespace fuzzygait::common {

std::string number_text(double value);
// Rounded to at most `decimals` decimals (0 to 17), without trailing zeros or a "-0": "0.427"
// for 0.42665 with 3, "12.5", "3".
std::string number_text(double value, int decimals);

}  // namespace fuzzygait::common

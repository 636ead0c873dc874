#include "runtime/common/format.hpp"

#include <charconv>
#include <cmath>

namespace fuzzygait::common {

std::string number_text(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value < 0.0 ? "-inf" : "inf";
  char text[32];  // the longest shortest form is 24 characters
  return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
}

}  // namespace fuzzygait::common

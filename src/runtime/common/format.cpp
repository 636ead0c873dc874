#include "runtime/common/format.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>

namespace fuzzygait::common {

std::string number_text(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value < 0.0 ? "-inf" : "inf";
  char text[32];  // the longest shortest form is 24 characters
  return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
}

std::string number_text(double value, int decimals) {
  if (!std::isfinite(value)) return number_text(value);
  std::array<char, 400> buffer{};  // room for any double in full
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                    std::chars_format::fixed, std::clamp(decimals, 0, 17));
  std::string text(buffer.data(), result.ptr);
  if (text.find('.') != std::string::npos) {
    while (text.back() == '0')
      text.pop_back();
    if (text.back() == '.') text.pop_back();
  }
  if (text == "-0") text = "0";
  return text;
}

}  // namespace fuzzygait::common

#include "offline/io/bvh_text.hpp"

#include <charconv>
#include <stdexcept>
#include <string_view>

namespace fuzzygait::io::detail {

void append_fixed(std::string& line, double value, int decimals) {
  char buffer[64];
  const auto [end, error] =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals);
  if (error != std::errc()) throw std::invalid_argument("BVH: value out of range");
  std::string_view text(buffer, static_cast<std::size_t>(end - buffer));
  if (text.starts_with('-') && text.find_first_not_of("-0.") == std::string_view::npos) {
    text.remove_prefix(1);
  }
  if (!line.empty()) line += ' ';
  line += text;
}

}  // namespace fuzzygait::io::detail

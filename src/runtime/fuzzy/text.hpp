// Text helpers the readers share (internal to the fuzzy library).
#pragma once

#include <string_view>
#include <vector>

namespace fuzzygait::fuzzy {

// The non-empty runs of text between any of the separator characters.
inline std::vector<std::string_view> split_words(std::string_view text,
                                                 std::string_view separators) {
  std::vector<std::string_view> words;
  std::size_t i = text.find_first_not_of(separators);
  while (i != std::string_view::npos) {
    std::size_t j = text.find_first_of(separators, i);
    if (j == std::string_view::npos) j = text.size();
    words.push_back(text.substr(i, j - i));
    i = text.find_first_not_of(separators, j);
  }
  return words;
}

}  // namespace fuzzygait::fuzzy

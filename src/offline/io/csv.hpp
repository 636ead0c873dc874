// The cells of one CSV line and the columns a reader needs, shared by the CSV readers of io/
// (normative curves, walk files).
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/fll.hpp"

namespace fuzzygait::io::detail {

// Splits at every comma (no quoting) and drops carriage returns, so CRLF files read as LF ones.
inline std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  for (char c : line) {
    if (c == ',') {
      cells.push_back(cell);
      cell.clear();
    } else if (c != '\r') {
      cell += c;
    }
  }
  cells.push_back(cell);
  return cells;
}

// Where each of `names` is in `header` (its first occurrence), in the order of `names`. Throws a
// ParseError on line 1 of `source` for the first name missing.
inline std::vector<std::size_t> required_columns(const std::vector<std::string>& header,
                                                 std::span<const std::string> names,
                                                 const std::string& source) {
  std::vector<std::size_t> columns;
  columns.reserve(names.size());
  for (const std::string& name : names) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) throw fuzzy::ParseError(source, 1, "missing column '" + name + "'");
    columns.push_back(static_cast<std::size_t>(it - header.begin()));
  }
  return columns;
}

}  // namespace fuzzygait::io::detail

// The cells of one CSV line, shared by the CSV readers of io/ (normative curves, walk files).
#pragma once

#include <string>
#include <vector>

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

}  // namespace fuzzygait::io::detail

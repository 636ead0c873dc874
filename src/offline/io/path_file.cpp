#include "fuzzygait/io/path_file.hpp"

#include <cmath>
#include <fstream>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/fuzzy/term.hpp"

namespace fuzzygait::io {

namespace {

std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  for (const char c : line) {
    if (c == ',') {
      cells.push_back(cell);
      cell.clear();
    } else if (c != '\r' && c != ' ' && c != '\t') {
      cell += c;
    }
  }
  cells.push_back(cell);
  return cells;
}

}  // namespace

path::Path read_path_csv(std::istream& in, std::string_view source, double corner_radius) {
  const std::string where(source);
  std::string line;
  if (!std::getline(in, line) || cells_of(line) != std::vector<std::string>{"x", "z"}) {
    throw fuzzy::ParseError(where, 1, "expected the header 'x,z'");
  }
  std::vector<path::GroundPoint> points;
  std::vector<int> lines;
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line == "\r" || line[0] == '#') continue;
    const std::vector<std::string> cells = cells_of(line);
    if (cells.size() != 2) throw fuzzy::ParseError(where, number, "expected two values 'x,z'");
    double xz[2] = {0.0, 0.0};
    for (std::size_t c = 0; c < 2; ++c) {
      const std::string column = std::string("column '") + (c == 0 ? "x" : "z") + "': ";
      const std::optional<double> value = fuzzy::parse_scalar(cells[c]);
      if (!value || !std::isfinite(*value)) {
        throw fuzzy::ParseError(where, number,
                                column + "'" + cells[c] + "' is not a finite number");
      }
      xz[c] = *value;
    }
    points.push_back({xz[0], xz[1]});
    lines.push_back(number);
  }
  try {
    return path::Path::polyline(points, corner_radius);
  } catch (const std::invalid_argument& e) {
    // The path names its points from 1: the line that point was read from.
    std::smatch match;
    const std::string message = e.what();
    if (std::regex_search(message, match, std::regex("path point ([0-9]+)"))) {
      const auto point = static_cast<std::size_t>(std::stoul(match[1].str()));
      if (point >= 1 && point <= lines.size()) {
        throw fuzzy::ParseError(where, lines[point - 1], message);
      }
    }
    throw fuzzy::ParseError(where, number, message);
  }
}

path::Path read_path_file(const std::filesystem::path& file, double corner_radius) {
  if (std::filesystem::is_directory(file)) {
    throw std::invalid_argument(file.string() + ": is a directory, not a path file");
  }
  std::ifstream in(file);
  if (!in) throw std::invalid_argument(file.string() + ": cannot open the file");
  return read_path_csv(in, file.string(), corner_radius);
}

}  // namespace fuzzygait::io

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

std::string_view trimmed(std::string_view text) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (!text.empty() && blank(text.front()))
    text.remove_prefix(1);
  while (!text.empty() && blank(text.back()))
    text.remove_suffix(1);
  return text;
}

// The comma-separated cells of a line, each trimmed of blanks at its ends.
std::vector<std::string> cells_of(std::string_view line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    cells.emplace_back(trimmed(line.substr(start, comma - start)));
    if (comma == std::string_view::npos) return cells;
    start = comma + 1;
  }
}

}  // namespace

path::Path read_path_csv(std::istream& in, std::string_view source, double corner_radius) {
  const std::string where(source);
  if (!std::isfinite(corner_radius) || corner_radius < path::Path::kSmallestRadius) {
    throw std::invalid_argument("the corner radius must be at least " +
                                std::to_string(path::Path::kSmallestRadius) + " m");
  }
  std::string line;
  if (std::getline(in, line) && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // a BOM
  if (!in || cells_of(line) != std::vector<std::string>{"x", "z"}) {
    throw fuzzy::ParseError(where, 1, "expected the header 'x,z'");
  }
  std::vector<path::GroundPoint> points;
  std::vector<int> lines;
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    const std::string_view content = trimmed(line);
    if (content.empty() || content.front() == '#') continue;
    const std::vector<std::string> cells = cells_of(content);
    if (cells.size() != 2) throw fuzzy::ParseError(where, number, "expected two values 'x,z'");
    double xz[2] = {0.0, 0.0};
    for (std::size_t c = 0; c < 2; ++c) {
      const std::string column = std::string("column '") + (c == 0 ? "x" : "z") + "': ";
      const std::optional<double> value = fuzzy::parse_scalar(cells[c]);
      if (!value || !std::isfinite(*value) || cells[c].find_first_of(" \t") != std::string::npos) {
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
    throw std::invalid_argument(where + ": " + message);  // no point of it: the whole path
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

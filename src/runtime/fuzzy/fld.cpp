#include "fuzzygait/fuzzy/fld.hpp"

#include <cmath>
#include <cstdio>
#include <istream>
#include <ostream>
#include <sstream>

#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/fuzzy/term.hpp"
#include "text.hpp"

namespace fuzzygait::fuzzy {
int Table::column(std::string_view name) const {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == name) return static_cast<int>(i);
  }
  return -1;
}

Table read_fld(std::string_view text, std::string_view source) {
  Table table;
  bool header_seen = false;
  int number = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(start, end - start);
    start = end + 1;
    ++number;
    const std::vector<std::string_view> cells = split_words(line, " \t\r,");
    if (cells.empty() || cells.front().front() == '#') continue;
    if (!header_seen) {
      header_seen = true;
      bool numeric = true;
      for (std::string_view c : cells)
        numeric = numeric && parse_scalar(c).has_value();
      if (!numeric) {
        for (std::string_view c : cells)
          table.columns.emplace_back(c);
        continue;
      }
      table.columns.assign(cells.size(), std::string());  // no header: columns by position
    }
    if (cells.size() != table.columns.size()) {
      throw ParseError(std::string(source), number,
                       "expected " + std::to_string(table.columns.size()) + " values, found " +
                           std::to_string(cells.size()));
    }
    std::vector<double> row;
    row.reserve(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const std::optional<double> v = parse_scalar(cells[c]);
      if (!v) {
        const std::string column =
            table.columns[c].empty() ? "column " + std::to_string(c + 1) : table.columns[c];
        throw ParseError(std::string(source), number,
                         column + ": '" + std::string(cells[c]) + "' is not a number");
      }
      row.push_back(*v);
    }
    table.rows.push_back(std::move(row));
  }
  if (!header_seen) throw ParseError(std::string(source), 0, "the table is empty");
  return table;
}

Table read_fld_stream(std::istream& in, std::string_view source) {
  std::ostringstream content;
  content << in.rdbuf();
  return read_fld(content.str(), source);
}

std::string format_fixed(double value, int decimals) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value < 0 ? "-inf" : "inf";
  // Like fuzzylite: a value that rounds to zero prints without a sign.
  if (std::fabs(value) < std::pow(10.0, -decimals)) value = 0.0;
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

void write_fld(std::ostream& out, const Table& table, int decimals) {
  for (std::size_t c = 0; c < table.columns.size(); ++c) {
    out << (c ? " " : "") << table.columns[c];
  }
  out << "\n";
  std::string line;
  for (const std::vector<double>& row : table.rows) {
    line.clear();
    for (std::size_t c = 0; c < row.size(); ++c) {
      if (c) line += ' ';
      line += format_fixed(row[c], decimals);
    }
    line += '\n';
    out << line;
  }
}

}  // namespace fuzzygait::fuzzy

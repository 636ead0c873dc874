// FLD tables: columns of numbers separated by spaces, tabs or commas, under a header of variable
// names, as fuzzylite writes its datasets.
#pragma once

#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

namespace fuzzygait::fuzzy {

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;  // every row has columns.size() values

  // Index of a column by name, or -1.
  int column(std::string_view name) const;
};

// Parses an FLD table. Lines starting with '#' and blank lines are skipped; the first
// remaining line is the header. A row with the wrong number of values or a value that is not a
// number is a ParseError naming the source, line and column.
Table read_fld(std::string_view text, std::string_view source = "<fld>");
Table read_fld_stream(std::istream& in, std::string_view source);

// Writes the header and the rows with `decimals` decimals, "nan", "inf", "-inf".
void write_fld(std::ostream& out, const Table& table, int decimals = 9);
std::string format_fixed(double value, int decimals);

}  // namespace fuzzygait::fuzzy

// libFuzzer target for the FLD table reader, fuzzygait::fuzzy::read_fld.
//
// Contract: any bytes either parse or are refused with a ParseError naming the source. A table
// that parses has rows as wide as its header, and writing it and reading it back gives the same
// columns and rows, each value within the written precision.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <sstream>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "fuzzygait/fuzzy/fld.hpp"
#include "fuzzygait/fuzzy/fll.hpp"

namespace {

using namespace fuzzygait::fuzzy;
using fuzzygait::fuzz::check_names_source;
using fuzzygait::fuzz::fail;

constexpr std::string_view kSource = "fuzz.fld";
constexpr int kDecimals = 9;

// Written with kDecimals decimals: half a unit in the last place, a whole one for values that
// write_fld rounds to zero (as fuzzylite does), plus the double's own error.
bool close_enough(double written, double read) {
  if (std::isnan(written) || std::isnan(read)) return std::isnan(written) && std::isnan(read);
  if (std::isinf(written) || std::isinf(read)) return written == read;
  return std::fabs(written - read) <= 1e-9 + 1e-15 * std::fabs(written);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  Table table;
  try {
    table = read_fld(text, kSource);
  } catch (const ParseError& e) {
    check_names_source(e, kSource);
    return 0;
  } catch (const std::exception& e) {
    fail("read_fld threw something other than a ParseError", e.what());
  }
  if (table.columns.empty()) fail("a table without columns parsed");
  for (const auto& row : table.rows) {
    if (row.size() != table.columns.size()) fail("a row is not as wide as the header");
  }
  std::ostringstream out;
  write_fld(out, table, kDecimals);
  Table again;
  try {
    again = read_fld(out.str(), "round-trip.fld");
  } catch (const std::exception& e) {
    fail("read_fld refused what write_fld wrote", std::string(e.what()) + "\n" + out.str());
  }
  if (again.columns != table.columns || again.rows.size() != table.rows.size()) {
    fail("the table read back has other columns or rows", out.str());
  }
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    for (std::size_t c = 0; c < table.columns.size(); ++c) {
      if (!close_enough(table.rows[r][c], again.rows[r][c])) {
        fail("a value read back differs",
             format_scalar(table.rows[r][c]) + " became " + format_scalar(again.rows[r][c]));
      }
    }
  }
  return 0;
}

// Reading and writing fuzzylite's FLL language.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "fuzzygait/fuzzy/engine.hpp"

namespace fuzzygait::fuzzy {

// A problem in a text file, located by file and line ("file:line: message").
class ParseError : public std::runtime_error {
 public:
  ParseError(std::string source, int line, const std::string& message);
  const std::string& source() const { return source_; }
  int line() const { return line_; }

 private:
  std::string source_;
  int line_;
};

struct FllOptions {
  // Refuse nan and infinities wherever the text gives a number (ranges, term parameters and
  // heights, the default, rule weights, thresholds). fuzzylite reads them, and so does read_fll
  // by default; a joint controller cannot use them (a NaN speed, a term that covers nothing).
  bool finite_numbers = false;
  // Refuse a Triangle, Trapezoid, PiShape or Rectangle whose points are out of order
  // (points_out_of_order), naming the line and the term. fuzzylite reads them, and so does
  // read_fll by default; `fuzzygait fuzzy check` does not.
  bool ordered_points = false;
};

// Parses FLL text. `source` names the text in error messages (usually the file path).
// Stricter than fuzzylite where fuzzylite would guess: unknown keys, missing or extra term
// parameters, unparsable rules and unsorted Discrete points are errors, never defaults.
// Also refused, so that every engine read writes back losslessly and evaluates in bounded
// time: a '\r' inside a line (only "\r\n" line endings), a Discrete x that is nan, a
// variable named 'and' or 'or', and a defuzzifier resolution above
// Defuzzifier::kMaxResolution (10^6).
Engine read_fll(std::string_view text, std::string_view source = "<fll>",
                const FllOptions& options = {});
Engine read_fll_file(const std::filesystem::path& path, const FllOptions& options = {});
// The whole text of the file at `path`; throws ParseError naming it when it is a directory or
// cannot be opened. The FLL and controller-set readers share it.
std::string read_text_file(const std::filesystem::path& path);

// Writes FLL that fuzzylite reads, with every number in its shortest exact form, so that
// reading it back gives the same engine (a lossless round trip).
std::string write_fll(const Engine& engine);

}  // namespace fuzzygait::fuzzy

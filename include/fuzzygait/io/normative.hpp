// Normative gait curves: the reference data the walk is compared with (data/normative, see
// data/SOURCES.md). The Schwartz et al. (2008) speed groups are built in.
#pragma once

#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "fuzzygait/eval/evaluation.hpp"

namespace fuzzygait::io {

// Reads a CSV with columns percent,hip_mean,hip_sd,knee_mean,knee_sd,ankle_mean,ankle_sd,
// pelvis_tilt_mean,pelvis_tilt_sd (percent 0..100). Throws fuzzy::ParseError naming the line.
eval::Normative read_normative_csv(std::istream& in, std::string_view source);

// Built-in references: "schwartz2008_veryslow", "_slow", "_free", "_fast", "_veryfast".
std::vector<std::string> builtin_normative_names();
// A built-in name, or a path to a CSV file.
eval::Normative load_normative(std::string_view name_or_path);

}  // namespace fuzzygait::io

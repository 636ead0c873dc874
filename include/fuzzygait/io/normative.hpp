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

// Spatio-temporal parameters of people at one walking task (data/parameters, see
// data/SOURCES.md), each as mean and one standard deviation.
struct MeanSd {
  double mean = 0.0;
  double sd = 0.0;
};
struct GaitParameters {
  std::string task;          // the source's name for it ("xs", "natural", "l", "ascending", ...)
  std::string curves;        // the built-in reference of its curves ("bovi2011_adult_xs")
  MeanSd speed_per_height;   // body heights a second
  MeanSd cadence;            // steps a minute
  MeanSd step_length;        // m
  MeanSd stride_per_height;  // body heights
  MeanSd stance;             // % of the cycle
  MeanSd double_support;     // % of the cycle, the first double support
};
// The built-in parameters of a source: "bovi2011_adult" (Bovi et al. 2011, adults: five level
// speeds, stairs up and down). Throws std::invalid_argument naming the known ones otherwise.
std::vector<GaitParameters> load_gait_parameters(std::string_view source);
// Bovi et al. 2011's five level walking speeds, slowest first (tasks xs, s, natural, m, l).
std::vector<GaitParameters> level_speeds();

}  // namespace fuzzygait::io

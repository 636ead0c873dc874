#include "fuzzygait/io/normative.hpp"

#include <array>
#include <cmath>
#include <fstream>
#include <istream>
#include <optional>
#include <sstream>

#include "csv.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/fuzzy/term.hpp"
#include "offline/io/builtin_data.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::io {
eval::Normative read_normative_csv(std::istream& in, std::string_view source) {
  const std::string where(source);
  std::string line;
  int number = 0;
  // Comment lines (#) before the header; one that says "ankle offset unknown" marks a source
  // whose ankle zero is its own (eval::Normative::ankle_offset_unknown).
  bool ankle_offset_unknown = false;
  do {
    if (!std::getline(in, line)) throw fuzzy::ParseError(where, number + 1, "the file is empty");
    ++number;
    if (line.starts_with("#") && line.find("ankle offset unknown") != std::string::npos) {
      ankle_offset_unknown = true;
    }
  } while (line.starts_with("#"));
  const std::vector<std::string> header = detail::split_csv_line(line);
  const std::string wanted[] = {"percent",   "hip_mean",         "hip_sd",
                                "knee_mean", "knee_sd",          "ankle_mean",
                                "ankle_sd",  "pelvis_tilt_mean", "pelvis_tilt_sd"};
  const std::vector<std::size_t> column = detail::required_columns(header, wanted, where);
  std::vector<std::array<double, 9>> rows;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> cells = detail::split_csv_line(line);
    std::array<double, 9> row{};
    for (std::size_t k = 0; k < column.size(); ++k) {
      const std::optional<double> v =
          column[k] < cells.size() ? fuzzy::parse_scalar(cells[column[k]]) : std::nullopt;
      if (!v || !std::isfinite(*v)) {
        throw fuzzy::ParseError(where, number, "column '" + wanted[k] + "' is not a finite number");
      }
      // Angles in degrees: a mean beyond a half turn or a negative spread is a wrong unit or a
      // wrong column, and would draw a band upside down or off the plot.
      const bool is_sd = wanted[k].ends_with("_sd");
      const double low = is_sd ? 0.0 : -180.0;
      if (k > 0 && (*v < low || *v > 180.0)) {
        throw fuzzy::ParseError(where, number,
                                "column '" + wanted[k] + "' is " + common::number_text(*v) +
                                    (is_sd ? "; a standard deviation in degrees is 0 to 180"
                                           : "; a mean angle in degrees is -180 to 180"));
      }
      row[k] = *v;
    }
    if (!rows.empty() && !(row[0] > rows.back()[0])) {
      throw fuzzy::ParseError(where, number, "percent must increase");
    }
    rows.push_back(row);
  }
  if (rows.size() < 2 || rows.front()[0] > 0.0 || rows.back()[0] < 100.0) {
    throw fuzzy::ParseError(where, number, "the curves must cover 0 to 100 percent");
  }
  // Resample onto 0, 2, ..., 100 percent.
  auto at = [&rows](std::size_t k, double percent) {
    std::size_t i = 0;
    while (i + 2 < rows.size() && rows[i + 1][0] < percent)
      ++i;
    const double t = (percent - rows[i][0]) / (rows[i + 1][0] - rows[i][0]);
    return rows[i][k] + std::clamp(t, 0.0, 1.0) * (rows[i + 1][k] - rows[i][k]);
  };
  eval::Normative n;
  n.name = where;
  n.ankle_offset_unknown = ankle_offset_unknown;
  for (int s = 0; s < eval::kCycleSamples; ++s) {
    const double percent = 2.0 * s;
    const auto i = static_cast<std::size_t>(s);
    n.hip.mean[i] = at(1, percent);
    n.hip.sd[i] = at(2, percent);
    n.knee.mean[i] = at(3, percent);
    n.knee.sd[i] = at(4, percent);
    n.ankle.mean[i] = at(5, percent);
    n.ankle.sd[i] = at(6, percent);
    n.pelvis_tilt.mean[i] = at(7, percent);
    n.pelvis_tilt.sd[i] = at(8, percent);
    n.thigh.mean[i] = n.hip.mean[i] - n.pelvis_tilt.mean[i];
    n.thigh.sd[i] = n.hip.sd[i];  // the thigh varies as the hip does across subjects
  }
  return n;
}

namespace {
// "normative/schwartz2008_sagittal_free.csv" -> "schwartz2008_free"; empty for other files.
std::string builtin_name(std::string_view path) {
  if (!path.starts_with("normative/") || !path.ends_with(".csv")) return {};
  std::string name(path.substr(10, path.size() - 14));
  const std::size_t at = name.find("_sagittal");
  if (at != std::string::npos) name.erase(at, 9);
  return name;
}
}  // namespace

std::vector<std::string> builtin_normative_names() {
  std::vector<std::string> names;
  for (const detail::EmbeddedFile& f : detail::embedded_files()) {
    const std::string name = builtin_name(f.path);
    if (!name.empty()) names.push_back(name);
  }
  return names;
}

eval::Normative load_normative(std::string_view name_or_path) {
  for (const detail::EmbeddedFile& f : detail::embedded_files()) {
    if (builtin_name(f.path) == name_or_path) {
      std::istringstream in{std::string(f.text)};
      eval::Normative n = read_normative_csv(in, "data/" + std::string(f.path));
      n.name = std::string(name_or_path);
      return n;
    }
  }
  std::ifstream in{std::string(name_or_path)};
  if (!in) {
    std::string known;
    for (const std::string& n : builtin_normative_names())
      known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("'" + std::string(name_or_path) +
                                "' is neither a built-in reference (" + known +
                                ") nor a readable file");
  }
  return read_normative_csv(in, name_or_path);
}

std::vector<GaitParameters> load_gait_parameters(std::string_view source) {
  const std::string path = "parameters/" + std::string(source) + "_parameters.csv";
  for (const detail::EmbeddedFile& f : detail::embedded_files()) {
    if (f.path != path) continue;
    const std::string where = "data/" + path;
    std::istringstream in{std::string(f.text)};
    std::string line;
    int number = 0;
    do {
      std::getline(in, line);
      ++number;
    } while (line.starts_with("#"));
    const std::vector<std::string> header = detail::split_csv_line(line);
    const std::string wanted[] = {
        "task",        "speed_bh_mean",       "speed_bh_sd",      "cadence_mean", "cadence_sd",
        "step_m_mean", "step_m_sd",           "stride_bh_mean",   "stride_bh_sd", "stance_mean",
        "stance_sd",   "double_support_mean", "double_support_sd"};
    const std::vector<std::size_t> column = detail::required_columns(header, wanted, where);
    std::vector<GaitParameters> out;
    while (std::getline(in, line)) {
      ++number;
      if (line.empty()) continue;
      const std::vector<std::string> cells = detail::split_csv_line(line);
      std::array<double, 12> v{};
      for (std::size_t k = 1; k < column.size(); ++k) {
        const std::optional<double> x =
            column[k] < cells.size() ? fuzzy::parse_scalar(cells[column[k]]) : std::nullopt;
        if (!x || !std::isfinite(*x)) {
          throw fuzzy::ParseError(where, number, "column '" + wanted[k] + "' is not a number");
        }
        v[k - 1] = *x;
      }
      GaitParameters p;
      p.task = cells.at(column[0]);
      p.curves = std::string(source) + "_" + p.task;
      p.speed_per_height = {v[0] / 100.0, v[1] / 100.0};
      p.cadence = {v[2], v[3]};
      p.step_length = {v[4], v[5]};
      p.stride_per_height = {v[6] / 100.0, v[7] / 100.0};
      p.stance = {v[8], v[9]};
      p.double_support = {v[10], v[11]};
      out.push_back(p);
    }
    return out;
  }
  throw std::invalid_argument("no built-in gait parameters '" + std::string(source) +
                              "' (built in: bovi2011_adult)");
}

std::vector<GaitParameters> level_speeds() {
  std::vector<GaitParameters> all = load_gait_parameters("bovi2011_adult");
  std::vector<GaitParameters> level;
  for (const char* task : {"xs", "s", "natural", "m", "l"}) {
    for (const GaitParameters& p : all) {
      if (p.task == task) level.push_back(p);
    }
  }
  return level;
}

}  // namespace fuzzygait::io

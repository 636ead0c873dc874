#include "fuzzygait/gait/controllers.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <stdexcept>

#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "runtime/common/format.hpp"
#include "runtime/common/json.hpp"
#include "runtime/gait/builtin_controllers.hpp"

namespace fuzzygait::gait {
namespace {

constexpr std::array<std::string_view, kSlotCount> kSlotNames = {
    "swing_hip",  "swing_knee",  "swing_ankle",  "swing_toe",
    "stance_hip", "stance_knee", "stance_ankle", "stance_toe"};
constexpr std::array<std::string_view, kMetricCount> kMetricNames = {
    "delta", "other_delta", "hip", "knee", "ankle", "toe", "sole", "incline"};

using fuzzygait::common::number_text;
using fuzzygait::common::json::Value;

// "SOURCE:LINE: " for a manifest value.
std::string where(const std::string& source, const Value& v) {
  return source + ":" + std::to_string(v.line) + ": ";
}

double number(const Value& manifest, const char* key, double fallback, double low, double high,
              const std::string& source) {
  const Value* v = manifest.find(key);
  if (!v) return fallback;
  if (v->kind != Value::Kind::Number || !(v->number >= low && v->number <= high)) {
    throw std::invalid_argument(where(source, *v) + "'" + key + "' must be a number between " +
                                number_text(low) + " and " + number_text(high));
  }
  return v->number;
}

std::string text(const Value& manifest, const char* key, const std::string& source) {
  const Value* v = manifest.find(key);
  if (!v) return {};
  if (v->kind != Value::Kind::String) {
    throw std::invalid_argument(where(source, *v) + "'" + key + "' must be a string, found " +
                                fuzzygait::common::json::kind_name(v->kind));
  }
  return v->string;
}

std::size_t slot_index(std::string_view name) {
  for (std::size_t s = 0; s < kSlotNames.size(); ++s) {
    if (kSlotNames[s] == name) return s;
  }
  return kSlotNames.size();
}

// The manifest's "terrain": {"incline_deg": {WORD: PEAK, ...}, "controllers": {SLOT: {WORD:
// FILE}}}.
void read_terrain(const Value& terrain, const std::map<std::string, std::string>& files,
                  const std::string& source, const std::string& manifest_source,
                  ControllerSet& set) {
  if (terrain.kind != Value::Kind::Object) {
    throw std::invalid_argument(where(manifest_source, terrain) + "'terrain' must be an object");
  }
  const Value* words = terrain.find("incline_deg");
  if (!words || words->kind != Value::Kind::Object || words->object.size() < 2) {
    throw std::invalid_argument(where(manifest_source, words ? *words : terrain) +
                                "'terrain' needs 'incline_deg': two or more words and the "
                                "incline (degrees) where each holds fully");
  }
  std::vector<std::pair<double, std::string>> peaks;
  for (const auto& [word, peak] : words->object) {
    if (peak.kind != Value::Kind::Number || !(std::abs(peak.number) <= 90.0)) {
      throw std::invalid_argument(where(manifest_source, peak) + "incline word '" + word +
                                  "' must peak at a number of degrees between -90 and 90");
    }
    peaks.emplace_back(peak.number, word);
  }
  std::sort(peaks.begin(), peaks.end());
  for (std::size_t i = 1; i < peaks.size(); ++i) {
    if (peaks[i].first == peaks[i - 1].first) {
      throw std::invalid_argument(where(manifest_source, *words) + "incline words '" +
                                  peaks[i - 1].second + "' and '" + peaks[i].second +
                                  "' peak at the same incline");
    }
  }
  ControllerSet::Terrain& t = set.terrain;
  for (const auto& [peak, word] : peaks) {
    t.words.push_back(word);
    t.peaks.push_back(peak);
  }
  for (std::vector<int>& of : t.of_slot)
    of.assign(t.words.size(), -1);
  t.ascent.assign(t.words.size(), false);
  if (const Value* ascent = terrain.find("ascent")) {
    if (ascent->kind != Value::Kind::Array) {
      throw std::invalid_argument(where(manifest_source, *ascent) +
                                  "'terrain.ascent' must list incline words");
    }
    for (const Value& word : ascent->array) {
      const auto w = word.kind == Value::Kind::String
                         ? std::find(t.words.begin(), t.words.end(), word.string)
                         : t.words.end();
      if (w == t.words.end()) {
        throw std::invalid_argument(where(manifest_source, word) +
                                    "'terrain.ascent' names a word not in 'incline_deg'");
      }
      t.ascent[static_cast<std::size_t>(w - t.words.begin())] = true;
    }
  }
  const Value* slots = terrain.find("controllers");
  if (!slots) return;
  if (slots->kind != Value::Kind::Object) {
    throw std::invalid_argument(where(manifest_source, *slots) +
                                "'terrain.controllers' must map slots to their words' FLL files");
  }
  for (const auto& [slot, by_word] : slots->object) {
    const std::size_t s = slot_index(slot);
    if (s == kSlotNames.size()) {
      throw std::invalid_argument(where(manifest_source, by_word) + "unknown controller slot '" +
                                  slot + "'");
    }
    if (by_word.kind != Value::Kind::Object) {
      throw std::invalid_argument(where(manifest_source, by_word) + "terrain controllers of '" +
                                  slot + "' must map incline words to FLL files");
    }
    for (const auto& [word, file] : by_word.object) {
      const auto w = std::find(t.words.begin(), t.words.end(), word);
      if (w == t.words.end()) {
        throw std::invalid_argument(where(manifest_source, file) + "'" + word +
                                    "' is not an incline word of 'incline_deg'");
      }
      if (file.kind != Value::Kind::String) {
        throw std::invalid_argument(where(manifest_source, file) + "terrain controller '" + slot +
                                    "' for '" + word + "' must name an FLL file (a string)");
      }
      const auto text = files.find(file.string);
      if (text == files.end()) {
        throw std::invalid_argument(where(manifest_source, file) + "terrain controller '" + slot +
                                    "' for '" + word + "' names '" + file.string +
                                    "', which is not in the set");
      }
      const std::string path = source + "/" + file.string;
      t.of_slot[s][static_cast<std::size_t>(w - t.words.begin())] =
          static_cast<int>(t.controllers.size());
      t.controllers.emplace_back(
          fuzzy::read_fll(text->second, path, fuzzy::FllOptions{.finite_numbers = true}), path);
    }
  }
}

}  // namespace

const Controller& ControllerSet::controller(int slot, std::size_t word) const {
  const auto s = static_cast<std::size_t>(slot);
  const int v = terrain.empty() ? -1 : terrain.of_slot[s][word];
  return v < 0 ? controllers[s] : terrain.controllers[static_cast<std::size_t>(v)];
}

double ControllerSet::evaluate(int slot, const MetricValues& metrics,
                               std::vector<fuzzy::Workspace>& workspaces) const {
  const auto s = static_cast<std::size_t>(slot);
  if (terrain.empty()) return controllers[s].evaluate(metrics, workspaces[s]);
  const double incline = metrics[static_cast<std::size_t>(Metric::Incline)];
  if (std::isnan(incline)) return controllers[s].evaluate(metrics, workspaces[s]);
  // The incline words as the rules of a one-input partition controller whose consequents are
  // their controllers' commands (fuzzy::evaluate_partition's order and tolerance).
  const fuzzy::PartitionDegrees<double> d =
      fuzzy::partition_degrees(terrain.peaks.data(), terrain.peaks.size(), incline);
  double sum = 0.0;
  double weights = 0.0;
  auto fire = [&](double degree, std::size_t word) {
    if (!(degree >= fuzzy::kTolerance)) return;
    const int v = terrain.of_slot[s][word];
    const double command =
        v < 0 ? controllers[s].evaluate(metrics, workspaces[s])
              : terrain.controllers[static_cast<std::size_t>(v)].evaluate(
                    metrics, workspaces[controllers.size() + static_cast<std::size_t>(v)]);
    sum += degree * command;
    weights += degree;
  };
  fire(d.lower_degree, d.lower);
  if (d.lower + 1 < terrain.peaks.size()) fire(d.upper_degree, d.lower + 1);
  return sum / weights;
}

bool ControllerSet::own_controllers_at(LegPhase phase, double incline) const {
  if (terrain.empty() || std::isnan(incline)) return true;
  const fuzzy::PartitionDegrees<double> d =
      fuzzy::partition_degrees(terrain.peaks.data(), terrain.peaks.size(), incline);
  auto own = [&](double degree, std::size_t word) {
    if (!(degree >= fuzzy::kTolerance) || word >= terrain.words.size()) return true;
    for (int j = 0; j < 4; ++j) {
      if (terrain.of_slot[static_cast<std::size_t>(slot(phase, static_cast<Joint>(j)))][word] >= 0)
        return false;
    }
    return true;
  };
  return own(d.lower_degree, d.lower) && own(d.upper_degree, d.lower + 1);
}

double ControllerSet::ascent_weight(double incline) const {
  if (terrain.empty() || std::isnan(incline)) return 0.0;
  const fuzzy::PartitionDegrees<double> d =
      fuzzy::partition_degrees(terrain.peaks.data(), terrain.peaks.size(), incline);
  double weight = terrain.ascent[d.lower] ? d.lower_degree : 0.0;
  if (d.lower + 1 < terrain.ascent.size() && terrain.ascent[d.lower + 1]) {
    weight += d.upper_degree;
  }
  return weight;
}

std::string_view slot_name(int slot) {
  return kSlotNames.at(static_cast<std::size_t>(slot));
}

std::string_view metric_name(Metric metric) {
  return kMetricNames.at(static_cast<std::size_t>(metric));
}

std::optional<Metric> metric_from_name(std::string_view name) {
  for (std::size_t i = 0; i < kMetricNames.size(); ++i) {
    if (kMetricNames[i] == name) return static_cast<Metric>(i);
  }
  return std::nullopt;
}

Controller::Controller(fuzzy::Engine engine, std::string source)
    : engine_(std::move(engine)), source_(std::move(source)) {
  if (engine_.inputs.empty() || engine_.inputs.size() > 2) {
    throw std::invalid_argument(source_ + ": a joint controller reads one or two metrics, found " +
                                std::to_string(engine_.inputs.size()) + " inputs");
  }
  for (std::size_t i = 0; i < engine_.inputs.size(); ++i) {
    const std::optional<Metric> m = metric_from_name(engine_.inputs[i].name);
    if (!m) {
      std::string known;
      for (std::string_view n : kMetricNames)
        known += (known.empty() ? "" : ", ") + std::string(n);
      throw std::invalid_argument(source_ + ": input '" + engine_.inputs[i].name +
                                  "' is not a metric (" + known + ")");
    }
    inputs_[i] = *m;
  }
  input_count_ = engine_.inputs.size();
  if (engine_.outputs.size() != 1) {
    throw std::invalid_argument(source_ + ": a joint controller has one output, found " +
                                std::to_string(engine_.outputs.size()));
  }
  // A NaN speed would stop the joint without a word, and a term over nothing never fires.
  if (const std::vector<std::string> bad = engine_.non_finite_numbers(); !bad.empty()) {
    throw std::invalid_argument(source_ + ": " + bad.front() +
                                "; a joint controller's numbers must be finite");
  }
  partition_ = fuzzy::as_partition(engine_);
  if (partition_) packed_ = fuzzy::PackedPartition::pack(*partition_);
  try {
    evaluator_.emplace(engine_);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(source_ + ": " + e.what());
  }
}

fuzzy::Workspace Controller::make_workspace() const {
  return partition_ ? fuzzy::Workspace() : evaluator_->make_workspace();
}

double Controller::evaluate_unpacked(const MetricValues& metrics,
                                     fuzzy::Workspace& workspace) const {
  if (partition_) {
    const double a = metrics[static_cast<std::size_t>(inputs_[0])];
    return input_count_ == 1
               ? partition_->evaluate(a)
               : partition_->evaluate(a, metrics[static_cast<std::size_t>(inputs_[1])]);
  }
  std::array<double, 2> in{};
  for (std::size_t i = 0; i < input_count_; ++i) {
    in[i] = metrics[static_cast<std::size_t>(inputs_[i])];
  }
  double out = 0.0;
  evaluator_->evaluate(std::span<const double>(in.data(), input_count_), std::span<double>(&out, 1),
                       workspace);
  return out;
}

ControllerSet ControllerSet::parse(std::string_view manifest_text,
                                   const std::map<std::string, std::string>& files,
                                   const std::string& source) {
  const std::string manifest_source = source + "/manifest.json";
  const Value manifest = fuzzygait::common::json::parse(manifest_text, manifest_source);
  if (manifest.kind != Value::Kind::Object) {
    throw std::invalid_argument(where(manifest_source, manifest) + "not a JSON object");
  }
  ControllerSet set;
  set.name = text(manifest, "name", manifest_source);
  set.description = text(manifest, "description", manifest_source);
  set.inertia = number(manifest, "inertia_s", 0.03, 0.001, 1.0, manifest_source);
  set.pelvis_tilt =
      rig::radians(number(manifest, "pelvis_tilt_deg", 11.0, -45.0, 45.0, manifest_source));
  set.swing_knee_reference_sweep = rig::radians(
      number(manifest, "swing_knee_reference_sweep_deg", 0.0, 0.0, 180.0, manifest_source));
  set.shortest_step =
      number(manifest, "shortest_step_leg_lengths", 0.46, 0.1, 1.2, manifest_source);
  const Value* names = manifest.find("controllers");
  if (!names || names->kind != Value::Kind::Object) {
    throw std::invalid_argument(where(manifest_source, names ? *names : manifest) +
                                "'controllers' must map slots to FLL files");
  }
  for (const auto& [key, file] : names->object) {
    bool known = false;
    for (std::string_view s : kSlotNames)
      known = known || s == key;
    if (!known) {
      throw std::invalid_argument(where(manifest_source, file) + "unknown controller slot '" + key +
                                  "'");
    }
  }
  for (int s = 0; s < kSlotCount; ++s) {
    const std::string key(slot_name(s));
    const Value* file = names->find(key);
    if (!file) {
      throw std::invalid_argument(where(manifest_source, *names) + "controller '" + key +
                                  "' is missing");
    }
    if (file->kind != Value::Kind::String) {
      throw std::invalid_argument(where(manifest_source, *file) + "controller '" + key +
                                  "' must name an FLL file (a string)");
    }
    const auto text = files.find(file->string);
    if (text == files.end()) {
      throw std::invalid_argument(where(manifest_source, *file) + "controller '" + key +
                                  "' names '" + file->string + "', which is not in the set");
    }
    const std::string path = source + "/" + file->string;
    set.controllers.emplace_back(
        fuzzy::read_fll(text->second, path, fuzzy::FllOptions{.finite_numbers = true}), path);
  }
  if (const Value* terrain = manifest.find("terrain")) {
    read_terrain(*terrain, files, source, manifest_source, set);
  }
  return set;
}

ControllerSet ControllerSet::load(const std::filesystem::path& directory) {
  const std::string manifest = fuzzy::read_text_file(directory / "manifest.json");
  std::map<std::string, std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    if (entry.path().extension() == ".fll") {
      files[entry.path().filename().string()] = fuzzy::read_text_file(entry.path());
    }
  }
  return parse(manifest, files, directory.string());
}

namespace {
std::pair<std::string_view, std::string_view> split_path(std::string_view path) {
  const std::size_t slash = path.find('/');
  return {path.substr(0, slash), path.substr(slash + 1)};
}
}  // namespace

std::vector<std::string> ControllerSet::builtin_names() {
  // A set is a folder with a manifest; other compiled-in files (the paper's example) are not.
  std::set<std::string> names;
  for (const detail::EmbeddedFile& f : detail::embedded_files()) {
    const auto [folder, file] = split_path(f.path);
    if (file == "manifest.json") names.emplace(folder);
  }
  return {names.begin(), names.end()};
}

ControllerSet ControllerSet::builtin(std::string_view name) {
  std::map<std::string, std::string> files;
  std::string manifest;
  for (const detail::EmbeddedFile& f : detail::embedded_files()) {
    const auto [set, file] = split_path(f.path);
    if (set != name) continue;
    if (file == "manifest.json") {
      manifest = std::string(f.text);
    } else {
      files[std::string(file)] = std::string(f.text);
    }
  }
  if (manifest.empty()) {
    std::string known;
    for (const std::string& n : builtin_names())
      known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("no built-in controller set '" + std::string(name) +
                                "' (built in: " + known + ")");
  }
  return parse(manifest, files, "controllers/" + std::string(name));
}

}  // namespace fuzzygait::gait

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
    "delta", "other_delta", "hip", "knee", "ankle", "toe", "sole", "incline", "stairs", "pace"};

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

// The manifest's "body": {"thigh_m": ..., "shank_m": ..., "ankle_height_m": ..., "heel_m": ...,
// "ball_m": ..., "toe_m": ..., "step_length_m": ..., "speed_m_s": ...}, every field required but
// the speed.
void read_body(const Value& body, const std::string& source, ControllerSet& set) {
  if (body.kind != Value::Kind::Object) {
    throw std::invalid_argument(where(source, body) + "'body' must be an object of lengths");
  }
  for (const auto& [key, value] : body.object) {
    const bool known = key == "thigh_m" || key == "shank_m" || key == "ankle_height_m" ||
                       key == "heel_m" || key == "ball_m" || key == "toe_m" ||
                       key == "step_length_m" || key == "speed_m_s";
    if (!known) {
      throw std::invalid_argument(where(source, value) + "'body' has no field '" + key +
                                  "' (thigh_m, shank_m, ankle_height_m, heel_m, ball_m, toe_m, "
                                  "step_length_m, speed_m_s)");
    }
  }
  auto length = [&](const char* key) {
    if (!body.find(key)) {
      throw std::invalid_argument(where(source, body) + "'body' needs '" + key + "'");
    }
    return number(body, key, 0.0, 0.001, 10.0, source);
  };
  rig::Segments s;
  s.thigh = length("thigh_m");
  s.shank = length("shank_m");
  s.ankle_height = length("ankle_height_m");
  s.heel = length("heel_m");
  s.ball = length("ball_m");
  s.toe = length("toe_m");
  set.body_step_length = length("step_length_m");
  if (body.find("speed_m_s")) set.body_speed = number(body, "speed_m_s", 0.0, 0.01, 20.0, source);
  try {
    rig::validate(s);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where(source, body) + "'body': " + e.what());
  }
  set.body = s;
}

// One kind of ground of the manifest's "terrain": {"incline_deg": {WORD: PEAK, ...}, "ascent":
// [WORD...], "landing_knee_deg": {WORD: DEG}, "controllers": {SLOT: {WORD: FILE}}}.
void read_ground(const Value& ground, const std::string& name,
                 const std::map<std::string, std::string>& files, const std::string& source,
                 const std::string& manifest_source, ControllerSet::GroundWords& g,
                 std::vector<Controller>& controllers) {
  const std::string at = "'terrain." + name;
  if (ground.kind != Value::Kind::Object) {
    throw std::invalid_argument(where(manifest_source, ground) + at + "' must be an object");
  }
  const Value* words = ground.find("incline_deg");
  if (!words || words->kind != Value::Kind::Object || words->object.size() < 2) {
    throw std::invalid_argument(where(manifest_source, words ? *words : ground) + at +
                                "' needs 'incline_deg': two or more words and the incline "
                                "(degrees) where each holds fully");
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
  for (const auto& [peak, word] : peaks) {
    g.words.push_back(word);
    g.peaks.push_back(peak);
  }
  for (std::vector<int>& of : g.of_slot)
    of.assign(g.words.size(), -1);
  auto word_index = [&](const Value& v, const std::string& word, const char* what) {
    const auto w = std::find(g.words.begin(), g.words.end(), word);
    if (w == g.words.end()) {
      throw std::invalid_argument(where(manifest_source, v) + at + "." + what + "' names '" + word +
                                  "', not a word of its 'incline_deg'");
    }
    return static_cast<std::size_t>(w - g.words.begin());
  };
  g.ascent.assign(g.words.size(), false);
  if (const Value* ascent = ground.find("ascent")) {
    if (ascent->kind != Value::Kind::Array) {
      throw std::invalid_argument(where(manifest_source, *ascent) + at +
                                  ".ascent' must list incline words");
    }
    for (const Value& word : ascent->array) {
      if (word.kind != Value::Kind::String) {
        throw std::invalid_argument(where(manifest_source, word) + at +
                                    ".ascent' must list incline words (strings)");
      }
      g.ascent[word_index(word, word.string, "ascent")] = true;
    }
  }
  g.landing_knee.assign(g.words.size(), 0.0);
  if (const Value* knees = ground.find("landing_knee_deg")) {
    if (knees->kind != Value::Kind::Object) {
      throw std::invalid_argument(where(manifest_source, *knees) + at +
                                  ".landing_knee_deg' must map incline words to degrees");
    }
    for (const auto& [word, knee] : knees->object) {
      const std::size_t w = word_index(knee, word, "landing_knee_deg");
      if (knee.kind != Value::Kind::Number || !(knee.number >= 0.0 && knee.number <= 90.0)) {
        throw std::invalid_argument(where(manifest_source, knee) + "the landing knee of '" + word +
                                    "' must be between 0 and 90 degrees");
      }
      g.landing_knee[w] = rig::radians(knee.number);
    }
  }
  const Value* slots = ground.find("controllers");
  if (!slots) return;
  if (slots->kind != Value::Kind::Object) {
    throw std::invalid_argument(where(manifest_source, *slots) + at +
                                ".controllers' must map slots to their words' FLL files");
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
      const std::size_t w = word_index(file, word, "controllers");
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
      g.of_slot[s][w] = static_cast<int>(controllers.size());
      controllers.emplace_back(
          fuzzy::read_fll(text->second, path, fuzzy::FllOptions{.finite_numbers = true}), path);
    }
  }
}

// The manifest's "upper_body": an object naming an FLL file for any of the parts, each reading
// metrics the follower supplies and answering one angle.
void read_upper_body(const Value& upper_body, const std::map<std::string, std::string>& files,
                     const std::string& source, const std::string& manifest_source,
                     ControllerSet& set) {
  if (upper_body.kind != Value::Kind::Object) {
    throw std::invalid_argument(where(manifest_source, upper_body) +
                                "'upper_body' must be an object of part: FLL file");
  }
  for (const auto& [key, file] : upper_body.object) {
    int part = -1;
    for (int p = 0; p < kUpperBodyCount; ++p) {
      if (upper_body_name(static_cast<UpperBody>(p)) == key) part = p;
    }
    if (part < 0) {
      throw std::invalid_argument(
          where(manifest_source, file) + "unknown upper body part '" + key +
          "' (shoulder, elbow, pelvis_rotation, thorax_rotation, pelvis_obliquity, "
          "pelvis_sway or trunk_lean)");
    }
    if (file.kind != Value::Kind::String) {
      throw std::invalid_argument(where(manifest_source, file) + "upper body part '" + key +
                                  "' must name an FLL file (a string)");
    }
    const auto text = files.find(file.string);
    if (text == files.end()) {
      throw std::invalid_argument(where(manifest_source, file) + "upper body part '" + key +
                                  "' names '" + file.string + "', which is not in the set");
    }
    const std::string path = source + "/" + file.string;
    Controller c(fuzzy::read_fll(text->second, path, fuzzy::FllOptions{.finite_numbers = true}),
                 path);
    for (std::size_t i = 0; i < c.input_count(); ++i) {
      const Metric m = c.input(i);
      if (m == Metric::Sole) {
        throw std::invalid_argument(path +
                                    ": the upper body reads delta, other_delta, hip, knee, "
                                    "ankle, toe, incline, stairs or pace, not '" +
                                    std::string(metric_name(m)) + "'");
      }
    }
    set.upper_body[static_cast<std::size_t>(part)].emplace(std::move(c));
  }
}

// The manifest's "stride": the FLL file of the stride relation, one input "pace" and one output
// (the step, leg lengths) that rises with the pace over the input's range.
void read_stride(const Value& stride, const std::map<std::string, std::string>& files,
                 const std::string& source, const std::string& manifest_source,
                 ControllerSet& set) {
  if (stride.kind != Value::Kind::String) {
    throw std::invalid_argument(where(manifest_source, stride) +
                                "'stride' must name an FLL file (a string)");
  }
  const auto text = files.find(stride.string);
  if (text == files.end()) {
    throw std::invalid_argument(where(manifest_source, stride) + "'stride' names '" +
                                stride.string + "', which is not in the set");
  }
  const std::string path = source + "/" + stride.string;
  Controller c(fuzzy::read_fll(text->second, path, fuzzy::FllOptions{.finite_numbers = true}),
               path);
  if (c.input_count() != 1 || c.input(0) != Metric::Pace) {
    throw std::invalid_argument(path + ": the stride reads one input, 'pace'");
  }
  const fuzzy::InputVariable& pace = c.engine().inputs.front();
  if (!(pace.minimum > 0.0 && pace.maximum > pace.minimum && pace.maximum <= 2.0)) {
    throw std::invalid_argument(path + ": the stride's 'pace' range must lie within 0 to 2, got " +
                                number_text(pace.minimum) + " " + number_text(pace.maximum));
  }
  set.stride.emplace(std::move(c));
  if (const std::string problem = set.stride_problem(); !problem.empty()) {
    throw std::invalid_argument(path + ": " + problem);
  }
}

void read_terrain(const Value& terrain, const std::map<std::string, std::string>& files,
                  const std::string& source, const std::string& manifest_source,
                  ControllerSet& set) {
  if (terrain.kind != Value::Kind::Object) {
    throw std::invalid_argument(where(manifest_source, terrain) + "'terrain' must be an object");
  }
  for (const auto& [name, ground] : terrain.object) {
    const Ground kind =
        name == "slopes" ? Ground::Slopes
        : name == "stairs"
            ? Ground::Stairs
            : throw std::invalid_argument(where(manifest_source, ground) +
                                          "'terrain' has words for 'slopes' (level ground "
                                          "and ramps) and 'stairs', not '" +
                                          name + "'");
    read_ground(ground, name, files, source, manifest_source,
                set.ground[static_cast<std::size_t>(kind)], set.terrain_controllers);
  }
}

// The words of the ground the metrics say and their degrees at its incline, the blend of a
// one-input partition controller over the incline (fuzzy::evaluate_partition's order and
// tolerance): `fire(word, degree)` for each word that fires. False (nothing fired) without words.
template <class Fire>
bool fire_words(const ControllerSet& set, const MetricValues& metrics, Fire fire) {
  const double stairs = metrics[static_cast<std::size_t>(Metric::Stairs)];
  const double incline = metrics[static_cast<std::size_t>(Metric::Incline)];
  const ControllerSet::GroundWords& g =
      set.ground[static_cast<std::size_t>(stairs > 0.5 ? Ground::Stairs : Ground::Slopes)];
  if (g.empty() || std::isnan(incline)) return false;
  const fuzzy::PartitionDegrees<double> d =
      fuzzy::partition_degrees(g.peaks.data(), g.peaks.size(), incline);
  if (d.lower_degree >= fuzzy::kTolerance) fire(g, d.lower, d.lower_degree);
  if (d.lower + 1 < g.peaks.size() && d.upper_degree >= fuzzy::kTolerance) {
    fire(g, d.lower + 1, d.upper_degree);
  }
  return true;
}

}  // namespace

const Controller& ControllerSet::controller(int slot, Ground kind, std::size_t word) const {
  const auto s = static_cast<std::size_t>(slot);
  const GroundWords& g = ground[static_cast<std::size_t>(kind)];
  const int v = g.empty() ? -1 : g.of_slot[s][word];
  return v < 0 ? controllers[s] : terrain_controllers[static_cast<std::size_t>(v)];
}

ControllerSet::GroundBlend ControllerSet::blend(const MetricValues& metrics) const {
  GroundBlend b;
  bool words = false;
  words = fire_words(*this, metrics, [&](const GroundWords& g, std::size_t word, double degree) {
    b.words = &g;
    b.word[b.fired] = word;
    b.degree[b.fired] = degree;
    ++b.fired;
  });
  if (!words) return b;
  for (std::size_t i = 0; i < b.fired; ++i) {
    const GroundWords& g = *b.words;
    const std::size_t word = b.word[i];
    const double degree = b.degree[i];
    if (g.ascent[word]) b.ascent += degree;
    b.landing_knee += degree * g.landing_knee[word];
    for (std::size_t s = 0; s < static_cast<std::size_t>(kSlotCount); ++s) {
      b.own_at[s / 4] = b.own_at[s / 4] && g.of_slot[s][word] < 0;
    }
  }
  return b;
}

double ControllerSet::evaluate(int slot, const MetricValues& metrics, const GroundBlend& blend,
                               std::vector<fuzzy::Workspace>& workspaces) const {
  const auto s = static_cast<std::size_t>(slot);
  double sum = 0.0;
  double weights = 0.0;
  for (std::size_t i = 0; i < blend.fired; ++i) {
    const int v = blend.words->of_slot[s][blend.word[i]];
    const double command =
        v < 0 ? controllers[s].evaluate(metrics, detail::workspace_at(workspaces, s))
              : terrain_controllers[static_cast<std::size_t>(v)].evaluate(
                    metrics, detail::workspace_at(
                                 workspaces, controllers.size() + static_cast<std::size_t>(v)));
    sum += blend.degree[i] * command;
    weights += blend.degree[i];
  }
  if (!(weights > 0.0))
    return controllers[s].evaluate(metrics, detail::workspace_at(workspaces, s));
  return sum / weights;
}

std::vector<fuzzy::Workspace> ControllerSet::make_workspaces() const {
  std::vector<fuzzy::Workspace> workspaces;
  const auto fast = [](const Controller& c) { return c.fast_path(); };
  if (std::all_of(controllers.begin(), controllers.end(), fast) &&
      std::all_of(terrain_controllers.begin(), terrain_controllers.end(), fast)) {
    return workspaces;
  }
  workspaces.reserve(controller_count());
  for (const Controller& c : controllers)
    workspaces.push_back(c.make_workspace());
  for (const Controller& c : terrain_controllers)
    workspaces.push_back(c.make_workspace());
  return workspaces;
}

double ControllerSet::evaluate(int slot, const MetricValues& metrics,
                               std::vector<fuzzy::Workspace>& workspaces) const {
  return evaluate(slot, metrics, blend(metrics), workspaces);
}

double ControllerSet::evaluate(int slot, const MetricValues& metrics,
                               const std::function<double(std::size_t)>& controller) const {
  const auto s = static_cast<std::size_t>(slot);
  double sum = 0.0;
  double weights = 0.0;
  const bool words =
      fire_words(*this, metrics, [&](const GroundWords& g, std::size_t word, double degree) {
        const int v = g.of_slot[s][word];
        sum += degree * controller(v < 0 ? s : controllers.size() + static_cast<std::size_t>(v));
        weights += degree;
      });
  if (!words || !(weights > 0.0)) return controller(s);
  return sum / weights;
}

bool ControllerSet::own_controllers_at(LegPhase phase, const MetricValues& metrics) const {
  return blend(metrics).own_at[static_cast<std::size_t>(phase)];
}

double ControllerSet::own_degree(int slot, const MetricValues& metrics) const {
  return blend(metrics).own_degree(slot);
}

double ControllerSet::ascent_weight(const MetricValues& metrics) const {
  return blend(metrics).ascent;
}

double ControllerSet::landing_knee(const MetricValues& metrics) const {
  return blend(metrics).landing_knee;
}

std::string_view slot_name(int slot) {
  return kSlotNames.at(static_cast<std::size_t>(slot));
}

std::string ControllerSet::stride_problem() const {
  if (!stride) return {};
  // People's steps lengthen with their pace: a stride that does not would make a speed ask for two
  // steps, or none.
  const fuzzy::InputVariable& pace = stride->engine().inputs.front();
  constexpr int kSamples = 200;
  double before = step_at_pace(pace.minimum);
  for (int i = 0; i <= kSamples; ++i) {
    const double p = pace.minimum + (pace.maximum - pace.minimum) * i / kSamples;
    const double step = step_at_pace(p);
    if ((i > 0 && !(step > before)) || !(step >= 0.1 && step <= 2.0)) {
      return "the step must rise with the pace and lie between 0.1 and 2 leg lengths; at pace " +
             number_text(p, 3) + " it is " + number_text(step, 4) +
             (i > 0 ? " after " + number_text(before, 4) : std::string());
    }
    before = step;
  }
  return {};
}

std::string_view upper_body_name(UpperBody part) {
  static constexpr std::array<std::string_view, kUpperBodyCount> kNames = {
      "shoulder",         "elbow",       "pelvis_rotation", "thorax_rotation",
      "pelvis_obliquity", "pelvis_sway", "trunk_lean"};
  return kNames.at(static_cast<std::size_t>(part));
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
  for (const ManifestNumber& n : manifest_numbers())
    n.set(set, number(manifest, n.key, n.fallback, n.low, n.high, manifest_source));
  if (const Value* body = manifest.find("body")) read_body(*body, manifest_source, set);
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
  if (const Value* stride = manifest.find("stride")) {
    read_stride(*stride, files, source, manifest_source, set);
  }
  if (const Value* upper_body = manifest.find("upper_body")) {
    read_upper_body(*upper_body, files, source, manifest_source, set);
  }
  if (const Value* terrain = manifest.find("terrain")) {
    read_terrain(*terrain, files, source, manifest_source, set);
  }
  return set;
}

std::span<const ControllerSet::ManifestNumber> ControllerSet::manifest_numbers() {
  using S = ControllerSet;
  static const std::array<ManifestNumber, 12> kNumbers = {{
      {"inertia_s", 0.001, 1.0, 0.03, [](const S& s) { return s.inertia; },
       [](S& s, double v) { s.inertia = v; }},
      {"pelvis_tilt_deg", -45.0, 45.0, 11.0, [](const S& s) { return rig::degrees(s.pelvis_tilt); },
       [](S& s, double v) { s.pelvis_tilt = rig::radians(v); }},
      {"swing_knee_reference_sweep_deg", 0.0, 180.0, 0.0,
       [](const S& s) { return rig::degrees(s.swing_knee_reference_sweep); },
       [](S& s, double v) { s.swing_knee_reference_sweep = rig::radians(v); }},
      {"shortest_step_leg_lengths", 0.1, 1.2, 0.46, [](const S& s) { return s.shortest_step; },
       [](S& s, double v) { s.shortest_step = v; }},
      {"cadence_steps_per_min", 30.0, 240.0, 110.0, [](const S& s) { return s.cadence; },
       [](S& s, double v) { s.cadence = v; }},
      {"acceleration_m_s2", 0.05, 10.0, 0.6, [](const S& s) { return s.acceleration; },
       [](S& s, double v) { s.acceleration = v; }},
      {"first_step_share", 0.3, 1.0, 0.8, [](const S& s) { return s.first_step; },
       [](S& s, double v) { s.first_step = v; }},
      {"first_step_s", 0.2, 2.0, 0.5, [](const S& s) { return s.first_step_duration; },
       [](S& s, double v) { s.first_step_duration = v; }},
      {"start_tempo_share", 0.1, 1.0, 0.4, [](const S& s) { return s.start_tempo; },
       [](S& s, double v) { s.start_tempo = v; }},
      {"start_easing_s", 0.05, 5.0, 1.0, [](const S& s) { return s.start_easing; },
       [](S& s, double v) { s.start_easing = v; }},
      {"placed_step_lift_leg_lengths", 0.02, 0.3, 0.12,
       [](const S& s) { return s.placed_step_lift; },
       [](S& s, double v) { s.placed_step_lift = v; }},
      {"settle_rate_per_s", 1.0, 50.0, 7.0, [](const S& s) { return s.settle_rate; },
       [](S& s, double v) { s.settle_rate = v; }},
  }};
  return kNumbers;
}

double ControllerSet::step_at_pace(double pace) const {
  MetricValues m{};
  m[static_cast<std::size_t>(Metric::Pace)] = pace;
  fuzzy::Workspace none;
  return stride->evaluate(m, none);
}

double ControllerSet::slowest_pace() const {
  return stride->engine().inputs.front().minimum;
}

double ControllerSet::fastest_pace() const {
  return stride->engine().inputs.front().maximum;
}

double ControllerSet::pace_at_step(double step) const {
  double low = slowest_pace();
  double high = fastest_pace();
  if (!(step > step_at_pace(low))) return low;
  if (!(step < step_at_pace(high))) return high;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (low + high);
    (step_at_pace(mid) < step ? low : high) = mid;
  }
  return 0.5 * (low + high);
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

#include "fuzzygait/studio/studio.hpp"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

#include "fired.hpp"
#include "fuzzygait/eval/evaluation.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/io/bvh.hpp"
#include "fuzzygait/io/controller_files.hpp"
#include "fuzzygait/io/gltf.hpp"
#include "fuzzygait/io/normative.hpp"
#include "fuzzygait/io/terrain_spec.hpp"
#include "fuzzygait/io/walk_csv.hpp"
#include "fuzzygait/path/path.hpp"
#include "request.hpp"
#include "runtime/common/format.hpp"
#include "set_folder.hpp"
#include "set_view.hpp"
#include "walk_view.hpp"

namespace fuzzygait::studio {

using common::number_text;
using nlohmann::json;

RequestError::RequestError(int status, std::string field, const std::string& message)
    : std::invalid_argument(message), status_(status), field_(std::move(field)) {}

json RequestError::to_json() const {
  return {{"error", what()}, {"field", field_}, {"status", status_}};
}

namespace {

// The grounds offered by name: level, ramps and stairs both ways, a kerb, a hill.
const std::vector<std::pair<std::string, std::string>>& builtin_terrains() {
  static const std::vector<std::pair<std::string, std::string>> terrains = {
      {"flat", "level ground"},
      {"slope:8", "ramp up 8 deg"},
      {"slope:-8", "ramp down 8 deg"},
      {"stairs:0.17:0.28:6", "6 stairs up, 0.17 x 0.28 m"},
      {"stairs:-0.17:0.28:6", "6 stairs down, 0.17 x 0.28 m"},
      {"stairs:0.15:0.30:1+flat:2+stairs:-0.15:0.30:1", "a kerb up and down, 0.15 m"},
      {"slope:5:3+flat:2+slope:-5:3", "a hill, 5 deg up and down"},
  };
  return terrains;
}

// A request may name any spec but profile files: reading files is for whoever starts the studio
// (StudioOptions::terrains).
terrain::Terrain parse_terrain(const std::string& spec, const std::vector<std::string>& offered) {
  const bool offered_spec = std::find(offered.begin(), offered.end(), spec) != offered.end();
  if (!offered_spec && spec.find("profile") != std::string::npos) {
    throw RequestError(422, "terrain",
                       "terrain: profile files are opened only from the command line "
                       "(fuzzygait studio --terrain SPEC)");
  }
  try {
    return io::terrain_from_spec(spec, "terrain");
  } catch (const std::invalid_argument& e) {
    throw RequestError(422, "terrain", e.what());
  }
}

// The steps (metres) these legs and this set walk.
std::pair<double, double> step_range(const gait::ControllerSet& set, double stature) {
  const rig::Segments segments = rig::segments_from_stature(stature);
  return {gait::Walker::min_step_length(set, segments), gait::Walker::max_step_length(segments)};
}

// The speeds (m/s) these legs walk this set at by speed; none for a set without a stride relation.
std::optional<std::pair<double, double>> speed_range(const gait::ControllerSet& set,
                                                     double stature) {
  if (!set.stride) return std::nullopt;
  gait::WalkerOptions options;
  options.segments = rig::segments_from_stature(stature);
  options.step_length = gait::Walker::min_step_length(set, options.segments);
  const terrain::Terrain flat = terrain::Terrain::flat();
  const gait::Walker walker(set, options, flat);
  return std::pair{walker.min_speed(), walker.max_speed()};
}

json term_shape_names() {
  json names = json::array();
  for (const fuzzy::TermKind kind : detail::input_term_shapes())
    names.push_back(fuzzy::shape_info(kind).name);
  return names;
}

}  // namespace

struct Studio::Session {
  // The set last opened, as it was opened (the compare choice "opened").
  struct Opened {
    std::string id;
    std::string label;
    std::shared_ptr<const gait::ControllerSet> set;
  };
  struct Step {
    gait::ControllerSet set;  // the set before the step
    std::string label;        // what the step did
    Opened opened;            // the set opened before the step
    std::uint64_t version;    // the set's version (Session::version)
  };
  struct Compared {
    std::string id;
    std::string label;
    gait::ControllerSet set;
    std::shared_ptr<const gait::ControllerSet> set_source;  // for "opened", the set opened
    std::optional<detail::Walked> walked;
    std::optional<json> view;
  };

  StudioOptions options;
  gait::ControllerSet current;
  Opened opened;
  std::vector<Step> undo;
  std::vector<Step> redo;
  std::string gesture;          // of the last edit, while the next edit may join it
  std::string gesture_subject;  // what that gesture changes, and its value before it began
  double gesture_from = 0.0;
  detail::WalkSettings settings;
  terrain::Terrain ground = terrain::Terrain::flat();
  eval::Normative reference;
  std::optional<detail::Walked> walked;
  std::optional<json> walk_view;
  std::optional<Compared> compared;
  // Each set the session holds has a version, new with every change; the version last opened
  // or saved is the one without unsaved edits (history's "unsaved").
  std::uint64_t version = 0;
  std::uint64_t versions = 0;
  std::uint64_t saved_version = 0;
  std::string saved_name;  // where the set was opened from or last saved since ("" for none)

  std::vector<std::string> offered_terrains() const {
    std::vector<std::string> specs;
    for (const auto& [spec, label] : builtin_terrains())
      specs.push_back(spec);
    specs.insert(specs.end(), options.terrains.begin(), options.terrains.end());
    return specs;
  }

  // The set an id names, with a label for people; throws RequestError naming `field`.
  std::pair<gait::ControllerSet, std::string> load(const std::string& id,
                                                   const std::string& field) const {
    const auto colon = id.find(':');
    const std::string kind = id.substr(0, colon);
    const std::string name = colon == std::string::npos ? "" : id.substr(colon + 1);
    try {
      if (kind == "style") {
        const std::vector<std::string> styles = gait::ControllerSet::builtin_names();
        if (std::find(styles.begin(), styles.end(), name) != styles.end()) {
          return {gait::ControllerSet::builtin(name), name + " (shipped style)"};
        }
      } else if (kind == "folder") {
        for (std::size_t i = 0; i < options.folders.size(); ++i) {
          if (name != std::to_string(i)) continue;
          gait::ControllerSet set = gait::ControllerSet::load(options.folders[i]);
          std::string label = set.name + " (" + options.folders[i].string() + ")";
          return {std::move(set), std::move(label)};
        }
      } else if (kind == "saved" && detail::is_plain_name(name) &&
                 std::filesystem::is_regular_file(options.workspace / name / "manifest.json")) {
        return {gait::ControllerSet::load(options.workspace / name), name + " (saved)"};
      }
    } catch (const std::exception& e) {  // a folder changed on disk since it was listed
      throw RequestError(422, field, "'" + id + "' does not load: " + e.what());
    }
    throw RequestError(422, field,
                       "no set '" + id + "' (style:NAME, folder:N or saved:NAME; see 'sets')");
  }

  json sets() const {
    json list = json::array();
    for (const std::string& name : gait::ControllerSet::builtin_names()) {
      list.push_back(
          {{"id", "style:" + name}, {"label", name + " (shipped style)"}, {"kind", "style"}});
    }
    for (std::size_t i = 0; i < options.folders.size(); ++i) {
      list.push_back({{"id", "folder:" + std::to_string(i)},
                      {"label", options.folders[i].string()},
                      {"kind", "folder"}});
    }
    std::error_code error;
    std::vector<std::string> saved;
    for (const auto& entry : std::filesystem::directory_iterator(options.workspace, error)) {
      const std::string name = entry.path().filename().string();
      if (detail::is_plain_name(name) &&
          std::filesystem::is_regular_file(entry.path() / "manifest.json", error)) {
        saved.push_back(name);
      }
    }
    std::sort(saved.begin(), saved.end());
    for (const std::string& name : saved) {
      list.push_back({{"id", "saved:" + name}, {"label", name + " (saved)"}, {"kind", "saved"}});
    }
    return list;
  }

  json history() const {
    return {{"undo", undo.size()},
            {"redo", redo.size()},
            {"undo_label", undo.empty() ? "" : undo.back().label},
            {"redo_label", redo.empty() ? "" : redo.back().label},
            {"unsaved", version != saved_version},
            {"steps", steps_json()}};
  }

  // Every step of the history, oldest first: those done (undo's), then those undone (redo's,
  // the next first). The set stands after the first `undo` of them.
  json steps_json() const {
    json steps = json::array();
    for (const Step& step : undo)
      steps.push_back(step.label);
    for (auto it = redo.rbegin(); it != redo.rend(); ++it)
      steps.push_back(it->label);
    return steps;
  }

  json settings_json() const {
    const auto [low, high] = step_range(current, settings.stature);
    const std::optional<std::pair<double, double>> speeds = speed_range(current, settings.stature);
    return {{"step", settings.step},
            {"speed", settings.speed},
            {"stature", settings.stature},
            {"cycles", settings.cycles},
            {"terrain", settings.terrain},
            {"reference", settings.reference},
            {"path", path_points_json()},
            {"corner_radius", settings.corner_radius},
            {"limits",
             {{"step", {low, high}},
              {"speed", speeds ? json{speeds->first, speeds->second} : json(nullptr)},
              {"stature", {Limits::kMinStature, Limits::kMaxStature}},
              {"cycles", {Limits::kMinCycles, Limits::kMaxCycles}},
              {"corner_radius", {path::Path::kSmallestRadius, Limits::kLargestCornerRadius}},
              {"path_points", Limits::kMostPathPoints},
              {"path_length", Limits::kLongestPath}}}};
  }

  json path_points_json() const {
    if (settings.path.empty()) return nullptr;
    json points = json::array();
    for (const path::GroundPoint& p : settings.path)
      points.push_back({p.x, p.z});
    return points;
  }

  void forget_walks() {
    trace.reset();
    strengths.clear();
    walked.reset();
    walk_view.reset();
    if (compared) {
      compared->walked.reset();
      compared->view.reset();
    }
  }

  // The inputs the controllers read at the current walk's frames, and the rule strengths of the
  // slots' and the upper body's controllers, made when the page first asks which rules fire.
  std::optional<std::vector<detail::FrameInputs>> trace;
  std::vector<detail::RuleStrengths> strengths;

  const json& current_walk() {
    if (!walk_view) {
      walked = detail::walk(current, settings, ground, reference);
      walk_view = detail::walk_json(*walked, ground, settings);
    }
    return *walk_view;
  }

  json compared_walk() {
    if (!compared) return nullptr;
    if (!compared->view) {
      compared->walked = detail::walk(compared->set, settings, ground, reference);
      compared->view = detail::walk_json(*compared->walked, ground, settings);
    }
    return {{"id", compared->id}, {"label", compared->label}, {"walk", *compared->view}};
  }

  // Puts `set` in place of the current one as one step of the history.
  void replace(gait::ControllerSet set, std::string label) {
    undo.push_back({std::move(current), std::move(label), opened, version});
    if (undo.size() > Limits::kHistory) undo.erase(undo.begin());
    redo.clear();
    gesture.clear();
    current = std::move(set);
    version = ++versions;
    forget_walks();
  }

  // Undo (from undo to redo) or redo (the other way): the set of the step on top of `from`
  // becomes the current one, which goes onto `to` with the step's label.
  json step_through(std::vector<Step>& from, std::vector<Step>& to) {
    move_step(from, to);
    return whole();
  }

  // One step from `from` to `to`, without walking.
  void move_step(std::vector<Step>& from, std::vector<Step>& to) {
    Step step = std::move(from.back());
    from.pop_back();
    to.push_back({std::move(current), step.label, opened, version});
    current = std::move(step.set);
    version = step.version;
    set_opened(std::move(step.opened));
    gesture.clear();
    fit_step();
    forget_walks();
  }

  // Everything an undo, a redo or a jump through the history changes.
  json whole() {
    return {{"set", detail::set_json(current)},
            {"opened", opened_json()},
            {"history", history()},
            {"settings", settings_json()},
            {"walk", current_walk()},
            {"compare", compared_walk()}};
  }

  // A new set opened; a comparison with the set as opened follows it.
  void set_opened(Opened next) {
    opened = std::move(next);
    if (compared && compared->id == "opened" && compared->set_source != opened.set) {
      compared->set = *opened.set;
      compared->set_source = opened.set;
      compared->label = opened.label + " as opened";
      compared->walked.reset();
      compared->view.reset();
    }
  }

  json opened_json() const { return {{"id", opened.id}, {"label", opened.label}}; }

  // Refuses (422 naming `field`) a set that would not walk with the current settings.
  void check_walks(const gait::ControllerSet& set, const char* field) const {
    try {
      detail::check_walkable(set, settings, ground);
    } catch (const std::invalid_argument& e) {
      throw RequestError(422, field, std::string("the set would not walk: ") + e.what());
    }
  }

  // What an edit of one controller answers: the history, the walk and the controller `id` as it
  // is now (none for an empty id).
  json edited_answer(const std::string& id) {
    json answer = {{"history", history()}, {"walk", current_walk()}};
    for (const detail::ControllerPlace& place : detail::controller_places(current)) {
      if (place.id == id) answer["controller"] = detail::controller_json(current, place);
    }
    return answer;
  }

  // A step the set walks: the setting, or the nearest the set takes (a set whose shortest step
  // is longer than the current one); a speed, the nearest it walks, or by step length for a set
  // without a stride relation.
  void fit_step() {
    const auto [low, high] = step_range(current, settings.stature);
    settings.step = std::clamp(settings.step, low, high);
    if (settings.speed > 0.0) {
      const std::optional<std::pair<double, double>> speeds =
          speed_range(current, settings.stature);
      settings.speed = speeds ? std::clamp(settings.speed, speeds->first, speeds->second) : 0.0;
    }
  }
};

Studio::Studio(StudioOptions options) : session_(std::make_unique<Session>()) {
  Session& s = *session_;
  s.options = std::move(options);
  const StudioOptions& o = s.options;
  if (!(o.stature >= Limits::kMinStature && o.stature <= Limits::kMaxStature)) {
    throw std::invalid_argument("stature must be between " + number_text(Limits::kMinStature) +
                                " and " + number_text(Limits::kMaxStature) + " m, got " +
                                number_text(o.stature));
  }
  if (o.cycles < Limits::kMinCycles || o.cycles > Limits::kMaxCycles) {
    throw std::invalid_argument("cycles must be between " + std::to_string(Limits::kMinCycles) +
                                " and " + std::to_string(Limits::kMaxCycles));
  }
  for (const std::string& spec : o.terrains)
    io::terrain_from_spec(spec, "--terrain");
  s.settings.step = o.step;
  s.settings.stature = o.stature;
  s.settings.cycles = o.cycles;
  s.reference = io::load_normative(s.settings.reference);
  if (!o.folders.empty()) {
    s.current = gait::ControllerSet::load(o.folders.front());
    s.opened.id = "folder:0";
    s.opened.label = s.current.name + " (" + o.folders.front().string() + ")";
    for (const std::filesystem::path& folder : o.folders)
      gait::ControllerSet::load(folder);  // each must load now, not when first opened
  } else {
    s.current = gait::ControllerSet::builtin(o.style);
    s.opened.id = "style:" + o.style;
    s.opened.label = o.style + " (shipped style)";
  }
  s.opened.set = std::make_shared<const gait::ControllerSet>(s.current);
  const auto [low, high] = step_range(s.current, o.stature);
  if (!(o.step >= low && o.step <= high)) {
    throw std::invalid_argument("step must be between " + number_text(low, 3) + " and " +
                                number_text(high, 3) + " m for this set and stature, got " +
                                number_text(o.step));
  }
}

Studio::~Studio() = default;

json Studio::state() const {
  const Session& s = *session_;
  json terrains = json::array();
  for (const auto& [spec, label] : builtin_terrains())
    terrains.push_back({{"spec", spec}, {"label", label}});
  for (const std::string& spec : s.options.terrains)
    terrains.push_back({{"spec", spec}, {"label", spec}});
  return {{"set", detail::set_json(s.current)},
          {"opened", s.opened_json()},
          {"history", s.history()},
          {"settings", s.settings_json()},
          {"sets", s.sets()},
          {"terrains", terrains},
          {"references", io::builtin_normative_names()},
          {"reference", detail::reference_json(s.reference)},
          {"compare", s.compared ? json(s.compared->id) : json(nullptr)},
          {"term_shapes", term_shape_names()},
          {"rule_limits",
           {{"rules", Limits::kMostRules},
            {"rule_bytes", Limits::kLongestRule},
            {"body_bytes", Limits::kLargestRulesBody}}}};
}

json Studio::walk() {
  Session& s = *session_;
  return {{"walk", s.current_walk()}, {"compare", s.compared_walk()}};
}

json Studio::edit(const json& request) {
  Session& s = *session_;
  detail::Edited edited = detail::apply_edit(s.current, request);
  s.check_walks(edited.set, "value");
  const std::string gesture = detail::optional_string(request, "gesture").value_or("");
  if (!gesture.empty() && gesture == s.gesture && !s.undo.empty() &&
      edited.subject == s.gesture_subject) {
    // The same drag: one step of the history from where the drag began.
    s.undo.back().label = edited.label(s.gesture_from);
    s.current = std::move(edited.set);
    s.version = ++s.versions;
    s.redo.clear();
    s.forget_walks();
  } else {
    s.replace(std::move(edited.set), edited.label());
    s.gesture_from = edited.before;
    s.gesture_subject = edited.subject;
  }
  s.gesture = gesture;
  json answer = s.edited_answer(edited.controller);
  if (edited.controller.empty()) answer["parameters"] = detail::parameters_json(s.current);
  return answer;
}

json Studio::edit_rules(const json& request) {
  Session& s = *session_;
  detail::Edited edited = detail::apply_rules(s.current, request);
  if (!edited.controller.empty()) {
    s.check_walks(edited.set, "rules");
    s.replace(std::move(edited.set), edited.label());
  }
  return s.edited_answer(detail::string_field(request, "controller"));
}

json Studio::edit_term(const json& request) {
  Session& s = *session_;
  detail::Edited edited = detail::apply_term(s.current, request);
  s.check_walks(edited.set, "term");
  s.replace(std::move(edited.set), edited.label());
  return s.edited_answer(edited.controller);
}

json Studio::fired(const json& request) {
  Session& s = *session_;
  detail::check_fields(request, {"time"});
  const double time = detail::number_field(request, "time", 0.0, Limits::kLargestValue);
  s.current_walk();
  if (!s.trace) {
    s.trace = detail::trace_inputs(s.current, s.settings, s.ground, s.walked->motion.frames.size());
    s.strengths = detail::rule_strengths(s.current);
  }
  if (s.trace->empty()) throw RequestError(422, "time", "the walk has no frames");
  const auto index =
      std::min(static_cast<std::size_t>(std::lround(time * detail::kPageFps)), s.trace->size() - 1);
  return detail::fired_json(s.current, (*s.trace)[index], index, s.strengths);
}

json Studio::change_settings(const json& request) {
  Session& s = *session_;
  detail::check_fields(request, {"step", "speed", "stature", "terrain", "cycles", "reference",
                                 "path", "corner_radius"});
  detail::WalkSettings next = s.settings;
  next.stature =
      detail::optional_number(request, "stature", Limits::kMinStature, Limits::kMaxStature)
          .value_or(next.stature);
  if (request.contains("cycles")) {
    next.cycles = detail::integer_field(request, "cycles", Limits::kMinCycles, Limits::kMaxCycles);
  }
  const auto [low, high] = step_range(s.current, next.stature);
  if (const std::optional<double> step = detail::optional_number(request, "step")) {
    if (!(*step >= low && *step <= high)) {
      throw RequestError(422, "step",
                         "step must be between " + number_text(low, 3) + " and " +
                             number_text(high, 3) +
                             " m: this set's shortest step and the legs' reach at stature " +
                             number_text(next.stature) + " m; got " + number_text(*step));
    }
    next.step = *step;
    next.speed = 0.0;  // a step asked for: the walk is by step length
  } else {
    next.step = std::clamp(next.step, low, high);
  }
  // A speed above 0 walks by speed (the step the set's stride gives), 0 by step length.
  const std::optional<double> speed = detail::optional_number(request, "speed", 0.0, 100.0);
  if (speed && *speed > 0.0 && request.contains("step")) {
    throw RequestError(422, "speed",
                       "give a step or a speed, not both: a walk by speed takes the step its "
                       "set's stride relation gives");
  }
  const std::optional<std::pair<double, double>> speeds = speed_range(s.current, next.stature);
  if (speed) next.speed = *speed;
  if (next.speed > 0.0) {
    if (!speeds) {
      throw RequestError(422, "speed",
                         "this set has no stride relation (its manifest's 'stride'): walk it by "
                         "step length");
    }
    if (speed && !(*speed >= speeds->first && *speed <= speeds->second)) {
      throw RequestError(422, "speed",
                         "speed must be between " + number_text(speeds->first, 3) + " and " +
                             number_text(speeds->second, 3) + " m/s for this set at stature " +
                             number_text(next.stature) + " m; got " + number_text(*speed));
    }
    next.speed = std::clamp(next.speed, speeds->first, speeds->second);
  }
  std::optional<terrain::Terrain> ground;
  if (const std::optional<std::string> spec = detail::optional_string(request, "terrain")) {
    ground = parse_terrain(*spec, s.offered_terrains());
    next.terrain = *spec;
  }
  std::optional<eval::Normative> reference;
  if (const std::optional<std::string> name = detail::optional_string(request, "reference")) {
    const std::vector<std::string> names = io::builtin_normative_names();
    if (std::find(names.begin(), names.end(), *name) == names.end()) {
      std::string known;
      for (const std::string& n : names)
        known += (known.empty() ? "" : ", ") + n;
      throw RequestError(422, "reference", "no reference '" + *name + "' (" + known + ")");
    }
    reference = io::load_normative(*name);
    next.reference = *name;
  }
  // A path drawn (null: straight ahead), its corners rounded to the radius.
  next.corner_radius =
      detail::optional_number(request, "corner_radius", path::Path::kSmallestRadius,
                              Limits::kLargestCornerRadius)
          .value_or(next.corner_radius);
  if (const auto path = request.find("path"); path != request.end()) {
    next.path = path->is_null() ? std::vector<path::GroundPoint>{}
                                : detail::points_field(request, "path", 2, Limits::kMostPathPoints);
  }
  if (request.contains("path") || request.contains("corner_radius")) {
    next.route = detail::drawn_path(next.path, next.corner_radius);
  }
  s.settings = next;
  if (ground) s.ground = std::move(*ground);
  if (reference) s.reference = std::move(*reference);
  s.forget_walks();
  json answer = {{"settings", s.settings_json()}, {"walk", s.current_walk()}};
  if (s.compared) {
    try {
      detail::check_walkable(s.compared->set, s.settings, s.ground);
    } catch (const std::invalid_argument& e) {
      answer["compare_dropped"] = s.compared->label + " does not walk these settings: " + e.what();
      s.compared.reset();
    }
  }
  answer["compare"] = s.compared_walk();
  if (reference) answer["reference"] = detail::reference_json(s.reference);
  return answer;
}

json Studio::undo() {
  Session& s = *session_;
  if (s.undo.empty()) throw RequestError(409, "undo", "nothing to undo");
  return s.step_through(s.undo, s.redo);
}

json Studio::redo() {
  Session& s = *session_;
  if (s.redo.empty()) throw RequestError(409, "redo", "nothing to redo");
  return s.step_through(s.redo, s.undo);
}

json Studio::go_to(const json& request) {
  Session& s = *session_;
  detail::check_fields(request, {"to"});
  const int total = static_cast<int>(s.undo.size() + s.redo.size());
  const int to = detail::integer_field(request, "to", 0, total);
  while (static_cast<int>(s.undo.size()) > to)
    s.move_step(s.undo, s.redo);
  while (static_cast<int>(s.undo.size()) < to)
    s.move_step(s.redo, s.undo);
  return s.whole();
}

json Studio::open(const json& request) {
  Session& s = *session_;
  detail::check_fields(request, {"set"});
  const std::string id = detail::string_field(request, "set");
  auto [set, label] = s.load(id, "set");
  auto opened = std::make_shared<const gait::ControllerSet>(set);
  s.replace(std::move(set), "open " + label);
  s.saved_version = s.version;  // a set as opened has no unsaved edits
  // The set saves back where it was opened from without asking; elsewhere only when new.
  s.saved_name = id.rfind("saved:", 0) == 0 ? id.substr(6) : "";
  s.set_opened({id, label, std::move(opened)});
  s.fit_step();
  s.forget_walks();
  return {{"set", detail::set_json(s.current)},
          {"opened", s.opened_json()},
          {"history", s.history()},
          {"settings", s.settings_json()},
          {"walk", s.current_walk()},
          {"compare", s.compared_walk()}};
}

namespace {

// Refuses a save whose folder is a symbolic link, holds one, or is not a folder of the workspace:
// a save writes only into WORKSPACE/NAME itself.
void check_save_folder(const std::filesystem::path& workspace,
                       const std::filesystem::path& folder) {
  namespace fs = std::filesystem;
  auto refuse = [](const fs::path& path, const std::string& why) {
    throw RequestError(422, "name", "cannot save to " + path.string() + ": " + why);
  };
  std::error_code error;
  const fs::file_status status = fs::symlink_status(folder, error);
  if (!fs::exists(status)) return;
  if (fs::is_symlink(status))
    refuse(folder, "it is a symbolic link (a save writes only into the workspace)");
  if (!fs::is_directory(status)) refuse(folder, "it is not a folder");
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
    if (entry.is_symlink(error))
      refuse(entry.path(), "it is a symbolic link (a save writes only into the workspace)");
  }
  const fs::path real_workspace = fs::weakly_canonical(workspace, error);
  const fs::path real_folder = fs::weakly_canonical(folder, error);
  if (error || real_folder.parent_path() != real_workspace)
    refuse(folder, "it is not inside the workspace " + real_workspace.string());
}

}  // namespace

json Studio::save(const json& request) {
  Session& s = *session_;
  detail::check_fields(request, {"name", "overwrite"});
  const std::string name = detail::string_field(request, "name");
  const bool overwrite = detail::optional_flag(request, "overwrite");
  if (!detail::is_plain_name(name)) {
    throw RequestError(422, "name",
                       "a set's name is 1 to 64 letters, digits, '-' or '_' (it names a folder "
                       "in the workspace), got '" +
                           name + "'");
  }
  const std::filesystem::path folder = s.options.workspace / name;
  check_save_folder(s.options.workspace, folder);
  // Another set saved under the name is replaced only when asked: not the set opened from there
  // or saved there since it was opened.
  std::error_code exists_error;
  if (!overwrite && std::filesystem::exists(folder / "manifest.json", exists_error) &&
      name != s.saved_name) {
    throw RequestError(409, "name",
                       "a set is saved as '" + name + "' already (" + folder.string() +
                           "): save with \"overwrite\": true to replace it");
  }
  gait::ControllerSet copy = s.current;
  copy.name = name;
  // The check above tells why a save is refused; writing relative to the folder opened without
  // following links keeps a link swapped in since from being followed.
  detail::write_set_folder(s.options.workspace, name, io::controller_set_files(copy));
  s.saved_version = s.version;
  s.saved_name = name;
  return {{"saved", "saved:" + name},
          {"folder", folder.string()},
          {"sets", s.sets()},
          {"history", s.history()}};
}

json Studio::compare(const json& request) {
  Session& s = *session_;
  detail::check_fields(request, {"with"});
  const auto with = request.find("with");
  if (with == request.end()) throw RequestError(400, "with", "'with' is missing");
  if (with->is_null()) {
    s.compared.reset();
    return {{"compare", nullptr}};
  }
  const std::string id = detail::string_field(request, "with");
  Session::Compared next;
  next.id = id;
  if (id == "opened") {
    next.set = *s.opened.set;
    next.set_source = s.opened.set;
    next.label = s.opened.label + " as opened";
  } else {
    std::tie(next.set, next.label) = s.load(id, "with");
  }
  try {
    detail::check_walkable(next.set, s.settings, s.ground);
  } catch (const std::invalid_argument& e) {
    throw RequestError(422, "with", next.label + " does not walk these settings: " + e.what());
  }
  s.compared = std::move(next);
  json answer = {{"compare", s.compared_walk()}};
  // The compared set itself, once: the page draws its knots and words beside the current ones.
  answer["compare"]["set"] = detail::set_json(s.compared->set);
  return answer;
}

Download Studio::download(std::string_view filename) {
  Session& s = *session_;
  s.current_walk();
  const eval::Motion& motion = s.walked->motion;
  std::ostringstream out;
  Download d{std::string(filename), "text/csv; charset=utf-8", {}};
  if (filename == "walk.csv") {
    io::write_walk_csv(out, motion);
  } else if (filename == "walk.bvh") {
    d.content_type = "application/octet-stream";
    io::write_bvh(out, motion);
  } else if (filename == "walk.glb") {
    d.content_type = "model/gltf-binary";
    io::write_gltf(out, motion, s.ground);
  } else if (filename == "walk.terrain.csv") {
    double low = motion.frames.front().pose.pelvis.x;
    double high = low;
    for (const eval::Frame& f : motion.frames) {
      low = std::min(low, f.pose.pelvis.x);
      high = std::max(high, f.pose.pelvis.x);
    }
    io::write_terrain_csv(out, s.ground, low - 2.0, high + 2.0);
  } else {
    throw RequestError(404, "file",
                       "no download '" + std::string(filename) +
                           "' (walk.csv, walk.bvh, walk.glb, walk.terrain.csv)");
  }
  d.bytes = std::move(out).str();
  return d;
}

}  // namespace fuzzygait::studio

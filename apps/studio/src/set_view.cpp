#include "set_view.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <optional>
#include <span>
#include <stdexcept>
#include <utility>

#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/partition.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "request.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::studio::detail {
namespace {

using common::number_text;
using nlohmann::json;

constexpr std::array<const char*, gait::kGroundCount> kGroundNames = {"slopes", "stairs"};
// Points along a one-input controller's output curve and a membership function drawn from
// samples; rows and columns of a two-input controller's output grid.
constexpr int kCurveSamples = 101;
constexpr int kGridSamples = 31;

// JSON has no infinities: an unbounded end of a range is null.
json finite_or_null(double x) {
  return std::isfinite(x) ? json(x) : json(nullptr);
}

// The span of x the page draws for an input: its range, or where its terms lie when the range is
// unbounded.
std::pair<double, double> input_domain(const fuzzy::InputVariable& v) {
  double low = v.minimum;
  double high = v.maximum;
  if (std::isfinite(low) && std::isfinite(high) && low < high) return {low, high};
  double term_low = INFINITY;
  double term_high = -INFINITY;
  for (const fuzzy::Term& t : v.terms) {
    for (double p : t.parameters) {
      if (!std::isfinite(p)) continue;
      term_low = std::min(term_low, p);
      term_high = std::max(term_high, p);
    }
  }
  if (!std::isfinite(low)) low = std::isfinite(term_low) ? term_low : -1.0;
  if (!std::isfinite(high)) high = std::isfinite(term_high) ? term_high : 1.0;
  if (!(low < high)) high = low + 1.0;
  return {low, high};
}

double lerp(double low, double high, int i, int count) {
  return low + (high - low) * static_cast<double>(i) / static_cast<double>(count - 1);
}

json term_json(const fuzzy::Term& t) {
  json term = {{"name", t.name},
               {"shape", fuzzy::shape_info(t.kind).name},
               {"parameters", t.parameters},
               {"height", t.height}};
  if (t.kind == fuzzy::TermKind::Function) term["formula"] = t.formula;
  return term;
}

// The controller's output with its inputs at x0 (and x1), the other metrics 0, to a thousandth
// (it is drawn, and an edit's answer carries a two-input controller's 961 of them).
double respond(const gait::Controller& c, fuzzy::Workspace& workspace, double x0, double x1) {
  gait::MetricValues metrics{};
  metrics[static_cast<std::size_t>(c.input(0))] = x0;
  if (c.input_count() == 2) metrics[static_cast<std::size_t>(c.input(1))] = x1;
  const double y = c.evaluate(metrics, workspace);
  return std::isfinite(y) ? std::round(y * 1e3) / 1e3 : 0.0;
}

json response_json(const gait::Controller& c) {
  fuzzy::Workspace workspace = c.make_workspace();
  const auto [x0, x1] = input_domain(c.engine().inputs[0]);
  if (c.input_count() == 1) {
    std::vector<double> xs;
    std::vector<double> ys;
    for (int i = 0; i < kCurveSamples; ++i) {
      xs.push_back(lerp(x0, x1, i, kCurveSamples));
      ys.push_back(respond(c, workspace, xs.back(), 0.0));
    }
    return {{"x", xs}, {"y", ys}};
  }
  const auto [y0, y1] = input_domain(c.engine().inputs[1]);
  std::vector<double> xs;
  std::vector<double> ys;
  for (int i = 0; i < kGridSamples; ++i) {
    xs.push_back(lerp(x0, x1, i, kGridSamples));
    ys.push_back(lerp(y0, y1, i, kGridSamples));
  }
  json rows = json::array();  // rows[j][i]: output at xs[i], ys[j]
  for (double y : ys) {
    std::vector<double> row;
    for (double x : xs)
      row.push_back(respond(c, workspace, x, y));
    rows.push_back(row);
  }
  return {{"x", xs}, {"y", ys}, {"z", rows}};
}

json inputs_json(const gait::Controller& c,
                 const std::optional<fuzzy::PartitionController<double>>& partition) {
  const fuzzy::Engine& engine = c.engine();
  std::optional<fuzzy::Evaluator> evaluator;
  std::optional<fuzzy::Workspace> workspace;
  json inputs = json::array();
  for (std::size_t i = 0; i < engine.inputs.size(); ++i) {
    const fuzzy::InputVariable& v = engine.inputs[i];
    const auto [low, high] = input_domain(v);
    json input = {{"name", v.name},
                  {"description", v.description},
                  {"range", {finite_or_null(v.minimum), finite_or_null(v.maximum)}},
                  {"domain", {low, high}},
                  {"partition", partition.has_value()}};
    if (partition) input["knots"] = partition->knots[i];
    json terms = json::array();
    for (std::size_t t = 0; t < v.terms.size(); ++t) {
      json term = term_json(v.terms[t]);
      if (v.terms[t].kind != fuzzy::TermKind::Triangle) {
        // Shapes other than triangles are drawn from samples of the engine's own membership.
        if (!evaluator) {
          evaluator.emplace(engine);
          workspace.emplace(evaluator->make_workspace());
        }
        std::vector<double> ys;
        for (int k = 0; k < kCurveSamples; ++k) {
          ys.push_back(
              evaluator->input_membership(i, t, lerp(low, high, k, kCurveSamples), *workspace));
        }
        term["samples"] = ys;
      }
      terms.push_back(term);
    }
    input["terms"] = terms;
    inputs.push_back(input);
  }
  return inputs;
}

json output_json(const fuzzy::OutputVariable& out) {
  json words = json::array();
  json others = json::array();
  for (const fuzzy::Term& t : out.terms) {
    if (t.kind == fuzzy::TermKind::Constant) {
      words.push_back({{"name", t.name}, {"value", t.parameters.at(0)}});
    } else {
      others.push_back(term_json(t));
    }
  }
  return {{"name", out.name},
          {"description", out.description},
          {"range", {finite_or_null(out.minimum), finite_or_null(out.maximum)}},
          {"words", words},
          {"terms", others}};
}

// The rules as text, and for a partition the word each combination of terms answers with.
json rules_json(const fuzzy::Engine& engine, bool partition) {
  json rules = json::array();
  for (const fuzzy::RuleBlock& block : engine.rule_blocks) {
    for (const fuzzy::Rule& rule : block.rules)
      rules.push_back(rule.text());
  }
  json result = {{"text", rules}};
  if (partition) {
    // as_partition holds the rules in row order: the first input's terms down, the second's
    // across.
    const std::size_t columns = engine.inputs.size() == 2 ? engine.inputs[1].terms.size() : 1;
    json grid = json::array();
    const std::vector<fuzzy::Rule>& block = engine.rule_blocks.at(0).rules;
    for (std::size_t r = 0; r < block.size(); ++r) {
      if (r % columns == 0) grid.push_back(json::array());
      grid.back().push_back(block[r].conclusions.at(0).term);
    }
    result["grid"] = grid;
  }
  return result;
}

std::string title(const ControllerPlace& place) {
  std::string text(place.part >= 0 ? gait::upper_body_name(static_cast<gait::UpperBody>(place.part))
                                   : gait::slot_name(place.slot));
  std::replace(text.begin(), text.end(), '_', ' ');
  if (place.part >= 0) return "upper body: " + text;
  if (place.ground >= 0) {
    text +=
        std::string(", ") + kGroundNames[static_cast<std::size_t>(place.ground)] + " " + place.word;
  }
  return text;
}

fuzzy::InputVariable& find_input(fuzzy::Engine& engine, const std::string& name,
                                 const std::string& controller) {
  for (fuzzy::InputVariable& v : engine.inputs) {
    if (v.name == name) return v;
  }
  std::string known;
  for (const fuzzy::InputVariable& v : engine.inputs)
    known += (known.empty() ? "" : ", ") + v.name;
  throw RequestError(
      422, "variable",
      "'" + controller + "' has no input '" + name + "' (its inputs: " + known + ")");
}

// The variable (input or output) and term a request names.
fuzzy::Term& find_term(fuzzy::Engine& engine, const std::string& variable, const std::string& term,
                       const std::string& controller) {
  std::vector<fuzzy::Term>* terms = nullptr;
  for (fuzzy::InputVariable& v : engine.inputs) {
    if (v.name == variable) terms = &v.terms;
  }
  for (fuzzy::OutputVariable& v : engine.outputs) {
    if (v.name == variable) terms = &v.terms;
  }
  if (!terms) {
    throw RequestError(422, "variable", "'" + controller + "' has no variable '" + variable + "'");
  }
  for (fuzzy::Term& t : *terms) {
    if (t.name == term) return t;
  }
  std::string known;
  for (const fuzzy::Term& t : *terms)
    known += (known.empty() ? "" : ", ") + t.name;
  throw RequestError(422, "term",
                     "'" + variable + "' of '" + controller + "' has no term '" + term +
                         "' (its terms: " + known + ")");
}

// Moves knot `index` of a strong triangular partition to `value`, keeping the partition: the
// term peaking there and its neighbours' feet move with it; the end knots carry the input's
// range (and their outer feet keep their distance).
// Sets edited's subject, before and after.
void move_knot(fuzzy::Engine& engine, const std::string& controller, const std::string& variable,
               const json& request, Edited& edited) {
  fuzzy::InputVariable& v = find_input(engine, variable, controller);
  std::string why;
  if (!fuzzy::as_partition(engine, &why)) {
    throw RequestError(422, "knot",
                       "'" + controller + "' is not a strong triangular partition (" + why +
                           "): change its terms' parameters instead");
  }
  const std::size_t n = v.terms.size();
  const auto index =
      static_cast<std::size_t>(integer_field(request, "knot", 0, static_cast<int>(n) - 1));
  const double value = number_field(request, "value");
  const double low = index > 0 ? v.terms[index - 1].parameters[1] : -Limits::kLargestValue;
  const double high = index + 1 < n ? v.terms[index + 1].parameters[1] : Limits::kLargestValue;
  if (!(value > low && value < high)) {
    throw RequestError(422, "value",
                       "knot " + std::to_string(index) + " ('" + v.terms[index].name + "') of '" +
                           variable + "' must lie between its neighbours' knots " +
                           number_text(low) + " and " + number_text(high) + ", got " +
                           number_text(value));
  }
  std::vector<double>& p = v.terms[index].parameters;
  const double old = p[1];
  const double shift = value - old;
  p[1] = value;
  if (index > 0) {
    v.terms[index - 1].parameters[2] = value;
  } else {
    p[0] += shift;
    v.minimum = value;
  }
  if (index + 1 < n) {
    v.terms[index + 1].parameters[0] = value;
  } else {
    p[2] += shift;
    v.maximum = value;
  }
  edited.subject = variable + " knot " + std::to_string(index) + " (" + v.terms[index].name + ")";
  edited.before = old;
  edited.after = value;
}

// The set's own numbers as the manifest spells them, with the manifest reader's ranges.
using SetParameter = gait::ControllerSet::ManifestNumber;
std::span<const SetParameter> set_parameters() {
  return gait::ControllerSet::manifest_numbers();
}

ControllerPlace find_place(const gait::ControllerSet& set, const std::string& id) {
  const std::vector<ControllerPlace> places = controller_places(set);
  for (const ControllerPlace& p : places) {
    if (p.id == id) return p;
  }
  throw RequestError(422, "controller",
                     "the set has no controller '" + id +
                         "' (a slot such as 'swing_knee', a terrain word's such as "
                         "'stairs_swing_knee_up', or an upper body part's such as "
                         "'upper_body_shoulder')");
}

std::string names_of(const std::vector<fuzzy::Term>& terms) {
  std::string known;
  for (const fuzzy::Term& t : terms)
    known += (known.empty() ? "" : ", ") + t.name;
  return known;
}

// The parser's sentence for rule `number` (from 1), with what the word at fault could have been:
// the terms of the variable it was read against, or the engine's variables.
std::string rule_problem(const fuzzy::Engine& engine, std::size_t number, const std::string& text,
                         std::string message) {
  const std::string quoted = "rule '" + text + "'";
  if (message.starts_with(quoted)) message.erase(0, quoted.size());
  if (!message.starts_with(":") && !message.starts_with(" ")) message.insert(0, " ");
  message = "rule " + std::to_string(number) + message;
  const std::string term_of = "nor a term of '";
  if (const std::size_t at = message.find(term_of); at != std::string::npos) {
    const std::size_t begin = at + term_of.size();
    const std::string variable = message.substr(begin, message.find('\'', begin) - begin);
    if (const fuzzy::InputVariable* v = engine.find_input(variable)) {
      message += " (its terms: " + names_of(v->terms) + ")";
    } else if (const fuzzy::OutputVariable* o = engine.find_output(variable)) {
      message += " (its terms: " + names_of(o->terms) + ")";
    }
  } else if (message.find("variable") != std::string::npos) {
    std::string inputs;
    for (const fuzzy::InputVariable& v : engine.inputs)
      inputs += (inputs.empty() ? "" : ", ") + v.name;
    std::string outputs;
    for (const fuzzy::OutputVariable& v : engine.outputs)
      outputs += (outputs.empty() ? "" : ", ") + v.name;
    message += " (inputs: " + inputs + "; outputs: " + outputs + ")";
  }
  return message;
}

// What an edit of the rules did, from the rules' normalised texts before and after.
std::string rules_change(const std::vector<std::string>& before,
                         const std::vector<std::string>& after) {
  // One rule added or deleted: the rest as they were, in order.
  auto one_more = [](const std::vector<std::string>& shorter,
                     const std::vector<std::string>& longer) -> std::optional<std::size_t> {
    if (longer.size() != shorter.size() + 1) return std::nullopt;
    std::size_t i = 0;
    while (i < shorter.size() && shorter[i] == longer[i])
      ++i;
    if (!std::equal(shorter.begin() + static_cast<std::ptrdiff_t>(i), shorter.end(),
                    longer.begin() + static_cast<std::ptrdiff_t>(i) + 1)) {
      return std::nullopt;
    }
    return i;
  };
  if (const std::optional<std::size_t> i = one_more(before, after)) {
    return "rule " + std::to_string(*i + 1) + " added";
  }
  if (const std::optional<std::size_t> i = one_more(after, before)) {
    return "rule " + std::to_string(*i + 1) + " deleted";
  }
  if (before.size() == after.size()) {
    std::vector<std::size_t> changed;
    for (std::size_t i = 0; i < before.size(); ++i) {
      if (before[i] != after[i]) changed.push_back(i + 1);
    }
    if (changed.size() == 1) return "rule " + std::to_string(changed[0]) + " edited";
    return std::to_string(changed.size()) + " rules edited";
  }
  return "rules edited (" + std::to_string(before.size()) + " -> " + std::to_string(after.size()) +
         " rules)";
}

// The engine as the controller at `place` of `set`; RequestError naming `field` when the
// controller refuses it.
void put_controller(gait::ControllerSet& set, const ControllerPlace& place, fuzzy::Engine engine,
                    const std::string& source, const char* field) {
  std::optional<gait::Controller> changed;
  try {
    changed.emplace(std::move(engine), source);
  } catch (const std::invalid_argument& e) {
    throw RequestError(422, field, std::string("the controller would not work: ") + e.what());
  }
  // An edit changes no controller's inputs, so an upper body controller still reads only what
  // body::PathFollower supplies (the set loader's check).
  if (place.part >= 0) {
    set.upper_body.at(static_cast<std::size_t>(place.part)) = std::move(changed);
  } else if (place.ground < 0) {
    set.controllers.at(static_cast<std::size_t>(place.slot)) = std::move(*changed);
  } else {
    set.terrain_controllers.at(place.terrain_index) = std::move(*changed);
  }
}

}  // namespace

std::string Edited::label(double from) const {
  if (!text_label.empty()) return text_label;
  return subject + " " + number_text(from, 4) + " -> " + number_text(after, 4);
}

std::vector<ControllerPlace> controller_places(const gait::ControllerSet& set) {
  std::vector<ControllerPlace> places;
  for (int s = 0; s < gait::kSlotCount; ++s) {
    places.push_back({std::string(gait::slot_name(s)), s, -1, {}, 0, -1});
  }
  for (std::size_t g = 0; g < set.ground.size(); ++g) {
    const gait::ControllerSet::GroundWords& words = set.ground[g];
    if (words.empty()) continue;
    for (int s = 0; s < gait::kSlotCount; ++s) {
      for (std::size_t w = 0; w < words.words.size(); ++w) {
        const int c = words.of_slot[static_cast<std::size_t>(s)][w];
        if (c < 0) continue;
        places.push_back({std::string(kGroundNames[g]) + "_" + std::string(gait::slot_name(s)) +
                              "_" + words.words[w],
                          s, static_cast<int>(g), words.words[w], static_cast<std::size_t>(c), -1});
      }
    }
  }
  for (int part = 0; part < gait::kUpperBodyCount; ++part) {
    if (!set.upper_body[static_cast<std::size_t>(part)]) continue;
    places.push_back(
        {"upper_body_" + std::string(gait::upper_body_name(static_cast<gait::UpperBody>(part))),
         0,
         -1,
         {},
         0,
         part});
  }
  return places;
}

const gait::Controller& controller_at(const gait::ControllerSet& set, const ControllerPlace& p) {
  if (p.part >= 0) return set.upper_body.at(static_cast<std::size_t>(p.part)).value();
  return p.ground < 0 ? set.controllers.at(static_cast<std::size_t>(p.slot))
                      : set.terrain_controllers.at(p.terrain_index);
}

json controller_json(const gait::ControllerSet& set, const ControllerPlace& place) {
  const gait::Controller& c = controller_at(set, place);
  const fuzzy::Engine& engine = c.engine();
  const std::optional<fuzzy::PartitionController<double>> partition = fuzzy::as_partition(engine);
  json controller = {{"id", place.id},
                     {"slot", place.part >= 0 ? json(nullptr) : json(gait::slot_name(place.slot))},
                     {"title", title(place)},
                     {"description", engine.description},
                     {"inputs", inputs_json(c, partition)},
                     {"outputs", json::array()},
                     {"rules", rules_json(engine, partition.has_value())},
                     {"response", response_json(c)},
                     {"fast_path", c.fast_path()}};
  if (place.ground >= 0) {
    controller["ground"] = kGroundNames[static_cast<std::size_t>(place.ground)];
    controller["word"] = place.word;
  }
  if (place.part >= 0) {
    controller["group"] = "upper body";
    controller["part"] = gait::upper_body_name(static_cast<gait::UpperBody>(place.part));
  }
  for (const fuzzy::OutputVariable& out : engine.outputs)
    controller["outputs"].push_back(output_json(out));
  return controller;
}

json parameters_json(const gait::ControllerSet& set) {
  json parameters = json::array();
  for (const SetParameter& p : set_parameters()) {
    parameters.push_back({{"name", p.key}, {"value", p.get(set)}, {"range", {p.low, p.high}}});
  }
  return parameters;
}

json set_json(const gait::ControllerSet& set) {
  json terrain = json::array();
  for (std::size_t g = 0; g < set.ground.size(); ++g) {
    const gait::ControllerSet::GroundWords& words = set.ground[g];
    if (words.empty()) continue;
    json list = json::array();
    for (std::size_t w = 0; w < words.words.size(); ++w) {
      list.push_back({{"word", words.words[w]},
                      {"incline_deg", words.peaks[w]},
                      {"ascent", static_cast<bool>(words.ascent[w])},
                      {"landing_knee_deg", rig::degrees(words.landing_knee[w])}});
    }
    terrain.push_back({{"ground", kGroundNames[g]}, {"words", list}});
  }
  json controllers = json::array();
  for (const ControllerPlace& place : controller_places(set))
    controllers.push_back(controller_json(set, place));
  return {{"name", set.name},
          {"description", set.description},
          {"parameters", parameters_json(set)},
          {"terrain", terrain},
          {"controllers", controllers}};
}

Edited apply_edit(const gait::ControllerSet& set, const json& request) {
  check_fields(request,
               {"controller", "variable", "knot", "term", "parameter", "value", "set", "gesture"});
  Edited edited{set, {}, {}, 0.0, 0.0, {}};
  if (const std::optional<std::string> name = optional_string(request, "set")) {
    check_fields(request, {"set", "value", "gesture"});
    for (const SetParameter& p : set_parameters()) {
      if (*name != p.key) continue;
      edited.before = p.get(set);
      edited.after = number_field(request, "value", p.low, p.high);
      p.set(edited.set, edited.after);
      edited.subject = p.key;
      return edited;
    }
    std::string known;
    for (const SetParameter& p : set_parameters())
      known += (known.empty() ? "" : ", ") + std::string(p.key);
    throw RequestError(422, "set", "the set has no parameter '" + *name + "' (" + known + ")");
  }
  const ControllerPlace place = find_place(set, string_field(request, "controller"));
  const gait::Controller& before = controller_at(set, place);
  fuzzy::Engine engine = before.engine();
  const std::string variable = string_field(request, "variable");
  if (request.contains("knot")) {
    check_fields(request, {"controller", "variable", "knot", "value", "gesture"});
    move_knot(engine, place.id, variable, request, edited);
  } else {
    fuzzy::Term& term = find_term(engine, variable, string_field(request, "term"), place.id);
    if (request.contains("parameter")) {
      const int count = static_cast<int>(term.parameters.size());
      if (count == 0) {
        throw RequestError(422, "parameter",
                           "term '" + term.name + "' has no numeric parameters (a formula)");
      }
      const auto i = static_cast<std::size_t>(integer_field(request, "parameter", 0, count - 1));
      edited.before = term.parameters[i];
      edited.after = term.parameters[i] = number_field(request, "value");
      edited.subject = variable + " " + term.name + " " + fuzzy::parameter_label(term, i);
      if (const std::string disorder = fuzzy::points_out_of_order(term); !disorder.empty()) {
        throw RequestError(422, "value", place.id + ", '" + variable + "': " + disorder);
      }
    } else {
      if (term.kind != fuzzy::TermKind::Constant) {
        throw RequestError(422, "term",
                           "'" + term.name + "' is a " +
                               std::string(fuzzy::shape_info(term.kind).name) +
                               " term, not a word with one value: name its 'parameter'");
      }
      edited.before = term.parameters.at(0);
      edited.after = term.parameters[0] = number_field(request, "value");
      edited.subject = variable + " " + term.name;
    }
  }
  put_controller(edited.set, place, std::move(engine), before.source(), "value");
  edited.controller = place.id;
  edited.subject = place.id + ": " + edited.subject;
  return edited;
}

}  // namespace fuzzygait::studio::detail

namespace fuzzygait::studio::detail {

Edited apply_rules(const gait::ControllerSet& set, const json& request) {
  check_fields(request, {"controller", "rules"});
  const ControllerPlace place = find_place(set, string_field(request, "controller"));
  const gait::Controller& before = controller_at(set, place);
  fuzzy::Engine engine = before.engine();
  if (!request.contains("rules")) throw RequestError(400, "rules", "'rules' is missing");
  const json& texts = request.at("rules");
  if (!texts.is_array()) {
    throw RequestError(400, "rules", "'rules' must be a list of rules, one text each");
  }
  if (texts.empty() || texts.size() > Limits::kMostRules) {
    throw RequestError(422, "rules",
                       "a controller needs 1 to " + std::to_string(Limits::kMostRules) +
                           " rules, got " + std::to_string(texts.size()));
  }
  if (engine.rule_blocks.size() != 1) {
    throw RequestError(422, "rules",
                       "'" + place.id + "' has " + std::to_string(engine.rule_blocks.size()) +
                           " rule blocks: edit its FLL file");
  }
  std::vector<fuzzy::Rule> rules;
  std::vector<std::string> after;
  for (std::size_t i = 0; i < texts.size(); ++i) {
    const std::string number = "rule " + std::to_string(i + 1);
    if (!texts[i].is_string()) throw RequestError(400, "rules", number + " is not a text");
    const std::string& text = texts[i].get_ref<const std::string&>();
    if (text.size() > Limits::kLongestRule) {
      throw RequestError(
          422, "rules",
          number + " is longer than " + std::to_string(Limits::kLongestRule) + " characters");
    }
    for (char c : text) {
      if (static_cast<unsigned char>(c) < 0x20 || c == '#') {
        throw RequestError(422, "rules",
                           number +
                               " holds a line break, a control character or a '#' "
                               "(one rule a line, no comments)");
      }
    }
    try {
      rules.push_back(fuzzy::parse_rule(text, engine));
    } catch (const std::invalid_argument& e) {
      throw RequestError(422, "rules", rule_problem(engine, i + 1, text, e.what()));
    }
    after.push_back(rules.back().text());
  }
  std::vector<std::string> was;
  for (const fuzzy::Rule& r : engine.rule_blocks[0].rules)
    was.push_back(r.text());
  Edited edited{set, {}, {}, 0.0, 0.0, {}};
  if (was == after) return edited;  // nothing changed
  engine.rule_blocks[0].rules = std::move(rules);
  if (const std::vector<std::string> problems = engine.problems(); !problems.empty()) {
    throw RequestError(422, "rules", "the rules cannot be evaluated: " + problems.front());
  }
  put_controller(edited.set, place, std::move(engine), before.source(), "rules");
  edited.controller = place.id;
  edited.subject = place.id + ": rules";
  edited.text_label = place.id + ": " + rules_change(was, after);
  return edited;
}

}  // namespace fuzzygait::studio::detail

namespace fuzzygait::studio::detail {
namespace {

using fuzzy::TermKind;

std::string shape_names() {
  std::string names;
  for (const TermKind kind : input_term_shapes())
    names += (names.empty() ? "" : ", ") + std::string(fuzzy::shape_info(kind).name);
  return names;
}

TermKind shape_field(const json& request) {
  const std::string name = string_field(request, "shape");
  const std::optional<TermKind> kind = fuzzy::term_kind_from_name(name);
  const std::vector<TermKind>& offered = input_term_shapes();
  if (kind && std::find(offered.begin(), offered.end(), *kind) != offered.end()) return *kind;
  const bool output_only = kind && (*kind == TermKind::Constant || *kind == TermKind::Linear ||
                                    *kind == TermKind::Function);
  throw RequestError(
      422, "shape",
      "an input's term cannot be a '" + name + "'" +
          (output_only ? " (an output's term: it has no membership over the input)" : "") +
          "; the studio offers " + shape_names());
}

// Where a term lies along its input: its left foot, its peak and its right foot.
struct Extent {
  double low;
  double peak;
  double high;
};

Extent extent_of(const fuzzy::Term& t) {
  const std::vector<double>& p = t.parameters;
  switch (t.kind) {
    case TermKind::Triangle:
      return {p[0], p[1], p[2]};
    case TermKind::Trapezoid:
      return {p[0], (p[1] + p[2]) / 2, p[3]};
    case TermKind::Gaussian:
      return {p[0] - 2 * p[1], p[0], p[0] + 2 * p[1]};
    case TermKind::Ramp: {
      // Full at its end: the foot mirrored past it.
      const double run = p[1] - p[0];
      return run > 0 ? Extent{p[0], p[1], p[1] + run} : Extent{p[1] + run, p[1], p[0]};
    }
    default:
      throw RequestError(422, "parameters",
                         "term '" + t.name + "' is a " +
                             std::string(fuzzy::shape_info(t.kind).name) +
                             ": give the new shape's 'parameters'");
  }
}

// The parameters of `kind` over `e`; a Ramp falls toward the peak when the peak lies in the lower
// half of the input's span (a left shoulder), and rises to it otherwise.
std::vector<double> parameters_over(TermKind kind, const Extent& e, double middle) {
  switch (kind) {
    case TermKind::Triangle:
      return {e.low, e.peak, e.high};
    case TermKind::Trapezoid:
      return {e.low, (e.low + e.peak) / 2, (e.peak + e.high) / 2, e.high};
    case TermKind::Gaussian:
      return {e.peak, (e.high - e.low) / 4};
    case TermKind::Ramp:
      return e.peak <= middle ? std::vector<double>{e.high, e.peak}
                              : std::vector<double>{e.low, e.peak};
    default:
      return {};
  }
}

// Why `t` is no shape an input can hold, or "".
std::string shape_problem(const fuzzy::Term& t) {
  const fuzzy::TermShapeInfo& info = fuzzy::shape_info(t.kind);
  const std::string shape(info.name);
  if (static_cast<int>(t.parameters.size()) != info.parameter_count) {
    std::string names;
    for (const std::string_view n : info.parameter_names)
      names += (names.empty() ? "" : " ") + std::string(n);
    return "a " + shape + " takes " + std::to_string(info.parameter_count) + " parameters (" +
           names + "), got " + std::to_string(t.parameters.size());
  }
  for (const double p : t.parameters) {
    if (!std::isfinite(p) || std::abs(p) > Limits::kLargestValue)
      return "parameters must be finite and within " + number_text(Limits::kLargestValue);
  }
  if (std::string disorder = fuzzy::points_out_of_order(t); !disorder.empty()) return disorder;
  const std::vector<double>& p = t.parameters;
  if ((t.kind == TermKind::Triangle || t.kind == TermKind::Trapezoid) && !(p.front() < p.back()))
    return "a " + shape + "'s feet must be apart (it would be no wider than a point)";
  if (t.kind == TermKind::Ramp && !(p[0] != p[1]))
    return "a Ramp's start and end must differ (it would be a step)";
  if (t.kind == TermKind::Gaussian && !(p[1] > 0))
    return "a Gaussian's standardDeviation must be above 0, got " + number_text(p[1]);
  return {};
}

std::vector<double> parameters_field(const json& request) {
  const json& list = request.at("parameters");
  if (!list.is_array()) throw RequestError(400, "parameters", "'parameters' must be a list");
  std::vector<double> values;
  for (const json& v : list) {
    if (!v.is_number()) throw RequestError(400, "parameters", "'parameters' must be numbers");
    values.push_back(v.get<double>());
  }
  return values;
}

// The rules (numbers from 1, as rules_json lists them) whose conditions read `term` of `input`.
std::vector<std::size_t> rules_reading(const fuzzy::Engine& engine, const std::string& input,
                                       const std::string& term) {
  std::vector<std::size_t> numbers;
  std::size_t number = 0;
  for (const fuzzy::RuleBlock& block : engine.rule_blocks) {
    for (const fuzzy::Rule& rule : block.rules) {
      ++number;
      const bool reads = std::any_of(rule.propositions.begin(), rule.propositions.end(),
                                     [&](const fuzzy::Proposition& p) {
                                       return !p.output && p.variable == input && p.term == term;
                                     });
      if (reads) numbers.push_back(number);
    }
  }
  return numbers;
}

std::vector<fuzzy::Term>::iterator term_named(fuzzy::InputVariable& v, const std::string& name,
                                              const std::string& controller) {
  const auto found = std::find_if(v.terms.begin(), v.terms.end(),
                                  [&](const fuzzy::Term& t) { return t.name == name; });
  if (found == v.terms.end()) {
    throw RequestError(422, "term",
                       "'" + v.name + "' of '" + controller + "' has no term '" + name +
                           "' (its terms: " + names_of(v.terms) + ")");
  }
  return found;
}

// A new term's name: letters, digits and '_', not taken by another term of the input.
void check_new_name(const fuzzy::InputVariable& v, const std::string& name) {
  const bool plain = !name.empty() && name.size() <= 64 &&
                     std::isalpha(static_cast<unsigned char>(name.front())) &&
                     std::all_of(name.begin(), name.end(), [](char c) {
                       return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                     });
  if (!plain) {
    throw RequestError(
        422, "term",
        "a term's name is a letter then up to 63 letters, digits or '_', got '" + name + "'");
  }
  if (std::any_of(v.terms.begin(), v.terms.end(),
                  [&](const fuzzy::Term& t) { return t.name == name; })) {
    throw RequestError(422, "term", "'" + v.name + "' has a term '" + name + "' already");
  }
}

// A rule can read the term ("if INPUT is TERM then ..."): its name is no word of the rules' own.
void check_readable_in_rules(const fuzzy::Engine& engine, const std::string& input,
                             const std::string& term) {
  if (engine.outputs.empty() || engine.outputs[0].terms.empty()) return;
  const fuzzy::OutputVariable& out = engine.outputs[0];
  try {
    fuzzy::parse_rule(
        "if " + input + " is " + term + " then " + out.name + " is " + out.terms[0].name, engine);
  } catch (const std::invalid_argument& e) {
    throw RequestError(422, "term", "'" + term + "' cannot be read in a rule: " + e.what());
  }
}

}  // namespace

const std::vector<fuzzy::TermKind>& input_term_shapes() {
  static const std::vector<fuzzy::TermKind> shapes = {TermKind::Triangle, TermKind::Trapezoid,
                                                      TermKind::Ramp, TermKind::Gaussian};
  return shapes;
}

Edited apply_term(const gait::ControllerSet& set, const json& request) {
  check_fields(request, {"controller", "variable", "term", "action", "shape", "parameters"});
  const ControllerPlace place = find_place(set, string_field(request, "controller"));
  const gait::Controller& before = controller_at(set, place);
  fuzzy::Engine engine = before.engine();
  const std::string variable = string_field(request, "variable");
  fuzzy::InputVariable& input = find_input(engine, variable, place.id);
  const std::string name = string_field(request, "term");
  const std::string action = string_field(request, "action");
  const auto [low, high] = input_domain(input);
  std::string change;
  if (action == "add") {
    fuzzy::Term term;
    term.name = name;
    term.kind = shape_field(request);
    check_new_name(input, name);
    term.parameters =
        request.contains("parameters")
            ? parameters_field(request)
            : parameters_over(term.kind,
                              {low + (high - low) / 4, (low + high) / 2, high - (high - low) / 4},
                              (low + high) / 2);
    if (const std::string problem = shape_problem(term); !problem.empty())
      throw RequestError(422, "parameters", "term '" + name + "': " + problem);
    change = "added (" + std::string(fuzzy::shape_info(term.kind).name) + " " +
             term.parameter_text() + ")";
    input.terms.push_back(std::move(term));
    check_readable_in_rules(engine, variable, name);
  } else if (action == "remove") {
    check_fields(request, {"controller", "variable", "term", "action"});
    const auto term = term_named(input, name, place.id);
    if (input.terms.size() == 1) {
      throw RequestError(
          422, "term", "'" + name + "' is the only term of '" + variable + "': an input keeps one");
    }
    if (const std::vector<std::size_t> rules = rules_reading(engine, variable, name);
        !rules.empty()) {
      std::string numbers;
      for (const std::size_t r : rules)
        numbers += (numbers.empty() ? "" : ", ") + std::to_string(r);
      throw RequestError(422, "term",
                         "'" + name + "' of '" + variable + "' is read by rule" +
                             (rules.size() > 1 ? "s " : " ") + numbers +
                             ": change or delete them first");
    }
    input.terms.erase(term);
    change = "removed";
  } else if (action == "shape") {
    const auto term = term_named(input, name, place.id);
    const TermKind kind = shape_field(request);
    const std::string was = term->parameter_text();
    const std::string from(fuzzy::shape_info(term->kind).name);
    std::vector<double> parameters =
        request.contains("parameters") ? parameters_field(request)
                                       : parameters_over(kind, extent_of(*term), (low + high) / 2);
    term->kind = kind;
    term->parameters = std::move(parameters);
    if (const std::string problem = shape_problem(*term); !problem.empty())
      throw RequestError(422, "parameters", "term '" + name + "': " + problem);
    const std::string to(fuzzy::shape_info(kind).name);
    change = from == to ? to + " " + was + " -> " + term->parameter_text()
                        : from + " -> " + to + " " + term->parameter_text();
  } else {
    throw RequestError(422, "action",
                       "'action' is \"add\", \"remove\" or \"shape\", got '" + action + "'");
  }
  if (const std::vector<std::string> problems = engine.problems(); !problems.empty())
    throw RequestError(422, "term", "the controller could not be evaluated: " + problems.front());
  Edited edited{set, {}, {}, 0.0, 0.0, {}};
  put_controller(edited.set, place, std::move(engine), before.source(), "term");
  const bool fast_after = controller_at(edited.set, place).fast_path();
  edited.controller = place.id;
  edited.subject = place.id + ": " + variable + " term '" + name + "'";
  edited.text_label = edited.subject + " " + change +
                      (before.fast_path() && !fast_after   ? ", off the walker's fast path"
                       : !before.fast_path() && fast_after ? ", on the walker's fast path"
                                                           : "");
  return edited;
}

}  // namespace fuzzygait::studio::detail

// A controller set as the page shows it, and the edits the page makes to it.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/term.hpp"
#include "fuzzygait/gait/controllers.hpp"

namespace fuzzygait::studio::detail {

// Where a controller sits in a set. Its id is a slot's name ("swing_knee"), for a terrain word's
// own controller GROUND_SLOT_WORD ("stairs_swing_knee_up"), and for an upper body controller
// upper_body_PART ("upper_body_shoulder"): the file name io::save_controller_set gives it.
struct ControllerPlace {
  std::string id;
  int slot = 0;     // the slot, when neither ground nor part is set
  int ground = -1;  // gait::Ground, or -1 for the slot's own controller
  std::string word;
  std::size_t terrain_index = 0;  // into ControllerSet::terrain_controllers when ground >= 0
  int part = -1;                  // gait::UpperBody of an upper body controller, or -1
};

// Every controller of the set: the slots' in slot order, the terrain words', then the upper
// body's the set has, in gait::UpperBody order.
std::vector<ControllerPlace> controller_places(const gait::ControllerSet& set);
const gait::Controller& controller_at(const gait::ControllerSet& set, const ControllerPlace& p);

// The page's view of one controller: its inputs' terms (knots for strong triangular partitions,
// samples of other shapes), its output words, its rules in plain text (and as a grid for a
// partition), and its output over its inputs (a curve for one input, a grid for two).
nlohmann::json controller_json(const gait::ControllerSet& set, const ControllerPlace& place);
// The set's own numbers (the manifest's), in the manifest's units.
nlohmann::json parameters_json(const gait::ControllerSet& set);
// The whole set: name, description, parameters, terrain words and every controller.
nlohmann::json set_json(const gait::ControllerSet& set);

// An edit (Studio::edit's request) applied to a copy of `set`. Throws RequestError naming the
// field when the request is malformed, names nothing in the set, or gives a value the set cannot
// take (a knot past its neighbour, a value out of range, an engine that does not compile).
struct Edited {
  gait::ControllerSet set;
  std::string controller;  // the id of the controller changed; empty for the set's parameters
  std::string subject;     // the number changed: "swing_knee: delta knot 1 (center)"
  double before;           // its value before and after the edit
  double after;
  // For the history: "swing_knee: delta knot 1 (center) 0.513 -> 0.6", from `from` (a drag's
  // first value).
  std::string label(double from) const;
  std::string label() const { return label(before); }
  // A change that is not one number (the rules): the history's label as it is.
  std::string text_label;
};
Edited apply_edit(const gait::ControllerSet& set, const nlohmann::json& request);

// {"controller": ID, "rules": [TEXT, ...]}: the controller's rules replaced by these, each read
// by the library's FLL rule parser (fuzzy::parse_rule) against the controller's variables and
// terms, and the engine checked as `fuzzy check` does (fuzzy::Engine::problems, then
// gait::Controller). Throws RequestError naming "rules" with the rule's number (from 1) and the
// word at fault, and for an unknown term the terms its variable has. text_label says what
// changed ("swing_knee: rule 3 edited", "rule 5 added", "rule 2 deleted"); an edit that leaves
// the rules as they were has an empty controller.
Edited apply_rules(const gait::ControllerSet& set, const nlohmann::json& request);

// The shapes an input's term may take in the studio. Each runs on the library's evaluator; only
// a strong triangular partition (triangles, one rule a combination) runs on the walker's fast
// path.
const std::vector<fuzzy::TermKind>& input_term_shapes();

// {"controller": ID, "variable": INPUT, "term": NAME, "action": A, ...}: one term of an input
// changed, each a step of the history with a label ("swing_knee: delta term 'far' added"):
//   "add"     a new term NAME of "shape" (input_term_shapes), its "parameters" given or placed
//             in the middle of the input's span; no rule reads it until one is written
//   "remove"  the term NAME; refused (422, "term") while rules read it, naming them
//   "shape"   the term NAME as "shape": its "parameters" given, or made from its present shape
//             (its foot, peak and foot kept: a Gaussian's mean at the peak, 4 deviations across)
// A shape the input cannot hold (an output's Constant, Linear or Function, a shape not offered),
// parameters of the wrong count, out of order, a zero width or deviation, a name a rule could
// not read or one taken are refused with 422 naming the field and why.
Edited apply_term(const gait::ControllerSet& set, const nlohmann::json& request);

}  // namespace fuzzygait::studio::detail

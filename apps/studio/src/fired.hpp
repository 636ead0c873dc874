// Which rules fire at a frame of the walk: the inputs each controller read there and each of its
// rules' firing strength, evaluated by the library.
#pragma once

#include <array>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/terrain/terrain.hpp"
#include "walk_view.hpp"

namespace fuzzygait::studio::detail {

// The metrics both legs' controllers read at one of the page's frames.
struct FrameInputs {
  double time = 0.0;
  std::array<gait::MetricValues, 2> metrics{};  // [left, right]
  std::array<bool, 2> swing{};
  // What the upper body's controllers read of each leg there (body::PathFollower::leg_metrics).
  std::array<gait::MetricValues, 2> body_metrics{};
};

// The metrics the walker's controllers read at each of the page's frames (every kRecordFps /
// kPageFps-th recorded frame, as walk_json sends them): the set walked again with the settings of
// walk(), frame by frame as eval::record_cycles steps it, `recorded_frames` frames; at each
// page frame a copy of the walker measures its metrics as its next time step will (the walker's
// own measuring stage), so these are the inputs the controllers read from that frame on.
std::vector<FrameInputs> trace_inputs(const gait::ControllerSet& set, const WalkSettings& settings,
                                      const terrain::Terrain& ground, std::size_t recorded_frames);

// Each rule's firing strength (its activation degree: weight times the antecedent's degree under
// the block's conjunction, disjunction and hedges) computed by the library's Evaluator: for each
// rule an engine of that rule alone, concluding a constant 1 summed by WeightedSum, whose output
// is that degree.
class RuleStrengths {
 public:
  explicit RuleStrengths(const fuzzy::Engine& engine);
  std::vector<double> at(std::span<const double> inputs);

 private:
  std::vector<fuzzy::Evaluator> evaluators_;
  std::vector<fuzzy::Workspace> workspaces_;
};

// One RuleStrengths for each controller fired_json shows: the eight slots', then the set's upper
// body controllers in gait::UpperBody order.
std::vector<RuleStrengths> rule_strengths(const gait::ControllerSet& set);

// {"time", "frame", "controllers": {ID: {"leg", "inputs": [x...], "rules": [strength...],
// "output"}}} at `frame` for the eight slots' controllers, each read by the leg it drives there
// (the left leg when both are in the slot's phase, as the page's curves are the left leg's), and
// for the upper body's, each as the left side reads it ("side": "left"): from the left leg, or
// the right for the pelvis's and the thorax's turn. `strengths` as rule_strengths made it.
nlohmann::json fired_json(const gait::ControllerSet& set, const FrameInputs& frame,
                          std::size_t index, std::vector<RuleStrengths>& strengths);

}  // namespace fuzzygait::studio::detail

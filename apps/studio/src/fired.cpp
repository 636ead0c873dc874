#include "fired.hpp"

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "fuzzygait/body/follower.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "runtime/gait/walker_stages.hpp"

namespace fuzzygait::studio::detail {
namespace {

using nlohmann::json;

// A ten-thousandth: what a marker on a plot or a bar needs.
double rounded(double x) {
  return std::isfinite(x) ? std::round(x * 1e4) / 1e4 : 0.0;
}

bool swing_slot(int slot) {
  return gait::slot_name(slot).starts_with("swing");
}

// The controller's entry: the inputs as sent, and everything else evaluated at them, so that what
// the page shows is the library's evaluation at the numbers it shows.
json reading_json(const gait::Controller& c, const gait::MetricValues& read,
                  RuleStrengths& strengths) {
  std::vector<double> inputs;
  gait::MetricValues metrics{};
  for (std::size_t i = 0; i < c.input_count(); ++i) {
    const auto m = static_cast<std::size_t>(c.input(i));
    inputs.push_back(rounded(read[m]));
    metrics[m] = inputs.back();
  }
  std::vector<double> rules = strengths.at(inputs);
  for (double& x : rules)
    x = rounded(x);
  fuzzy::Workspace workspace = c.make_workspace();
  return {
      {"inputs", inputs}, {"rules", rules}, {"output", rounded(c.evaluate(metrics, workspace))}};
}

// Whether the left side's `part` reads the right leg: each side turns with the other leg.
bool reads_other_leg(gait::UpperBody part) {
  return part == gait::UpperBody::PelvisRotation || part == gait::UpperBody::ThoraxRotation;
}

}  // namespace

std::vector<FrameInputs> trace_inputs(const gait::ControllerSet& set, const WalkSettings& settings,
                                      const terrain::Terrain& ground, std::size_t recorded_frames) {
  gait::Walker walker = make_walker(set, settings, ground);
  const auto stride = static_cast<std::size_t>(std::lround(kRecordFps / kPageFps));
  std::vector<FrameInputs> frames;
  for (std::size_t i = 0; i < recorded_frames; ++i) {
    if (i > 0) walker.advance(1.0 / kRecordFps);
    if (i % stride != 0) continue;
    // Measuring writes the legs' last progress (which the next step writes again, the same): a
    // copy keeps the walk as it is.
    gait::Walker copy = walker;
    gait::detail::StepData step{};
    gait::detail::WalkerStages::measure(copy, step);
    FrameInputs frame;
    frame.time = static_cast<double>(i) / kRecordFps;
    frame.metrics = step.metrics;
    frame.swing = {walker.phase(rig::Side::Left) == gait::Phase::Swing,
                   walker.phase(rig::Side::Right) == gait::Phase::Swing};
    frame.body_metrics = {body::PathFollower::leg_metrics(walker, 0),
                          body::PathFollower::leg_metrics(walker, 1)};
    frames.push_back(frame);
  }
  return frames;
}

RuleStrengths::RuleStrengths(const fuzzy::Engine& engine) {
  if (engine.rule_blocks.size() != 1 || engine.outputs.empty()) return;
  fuzzy::Engine one = engine;
  fuzzy::OutputVariable& out = one.outputs.at(0);
  one.outputs.resize(1);
  out.minimum = -fuzzy::kInfinity;
  out.maximum = fuzzy::kInfinity;
  out.lock_range = false;
  out.lock_previous = false;
  out.aggregation = fuzzy::SNorm::None;
  out.default_value = 0.0;
  out.defuzzifier = fuzzy::Defuzzifier{fuzzy::Defuzzifier::Kind::WeightedSum, 100,
                                       fuzzy::Defuzzifier::WeightedType::TakagiSugeno};
  fuzzy::Term unit;
  unit.name = "one";
  unit.kind = fuzzy::TermKind::Constant;
  unit.parameters = {1.0};
  out.terms = {unit};
  fuzzy::RuleBlock& block = one.rule_blocks[0];
  block.implication = fuzzy::TNorm::None;
  const std::vector<fuzzy::Rule> rules = block.rules;
  try {
    for (const fuzzy::Rule& rule : rules) {
      fuzzy::Rule alone = rule;
      alone.conclusions = {fuzzy::Proposition{out.name, true, {}, "one"}};
      block.rules = {alone};
      evaluators_.emplace_back(one);
      workspaces_.push_back(evaluators_.back().make_workspace());
    }
  } catch (const std::exception&) {
    // A rule that reads the output (a chained engine) alone: no strengths, the page shows none.
    evaluators_.clear();
    workspaces_.clear();
  }
}

std::vector<double> RuleStrengths::at(std::span<const double> inputs) {
  std::vector<double> strengths;
  double out = 0.0;
  for (std::size_t r = 0; r < evaluators_.size(); ++r) {
    evaluators_[r].evaluate(inputs, std::span<double>(&out, 1), workspaces_[r]);
    strengths.push_back(out);
  }
  return strengths;
}

std::vector<RuleStrengths> rule_strengths(const gait::ControllerSet& set) {
  std::vector<RuleStrengths> strengths;
  for (int slot = 0; slot < gait::kSlotCount; ++slot)
    strengths.emplace_back(set.controllers.at(static_cast<std::size_t>(slot)).engine());
  for (const std::optional<gait::Controller>& c : set.upper_body) {
    if (c) strengths.emplace_back(c->engine());
  }
  return strengths;
}

json fired_json(const gait::ControllerSet& set, const FrameInputs& frame, std::size_t index,
                std::vector<RuleStrengths>& strengths) {
  json controllers = json::object();
  for (int s = 0; s < gait::kSlotCount; ++s) {
    const gait::Controller& c = set.controllers.at(static_cast<std::size_t>(s));
    const bool swing = swing_slot(s);
    const std::string name(gait::slot_name(s));
    if (frame.swing[0] != swing && frame.swing[1] != swing) {
      // No leg in this slot's phase (the swing slots in double support): it drives nothing now.
      controllers[name] = {{"leg", nullptr}};
      continue;
    }
    const std::size_t leg = frame.swing[0] == swing ? 0 : 1;
    json reading = reading_json(c, frame.metrics[leg], strengths.at(static_cast<std::size_t>(s)));
    reading["leg"] = leg == 0 ? "left" : "right";
    controllers[name] = std::move(reading);
  }
  std::size_t next = gait::kSlotCount;
  for (int p = 0; p < gait::kUpperBodyCount; ++p) {
    const std::optional<gait::Controller>& c = set.upper_body[static_cast<std::size_t>(p)];
    if (!c) continue;
    const auto part = static_cast<gait::UpperBody>(p);
    const std::size_t leg = reads_other_leg(part) ? 1 : 0;
    json reading = reading_json(*c, frame.body_metrics[leg], strengths.at(next++));
    reading["leg"] = leg == 0 ? "left" : "right";
    reading["side"] = "left";
    controllers["upper_body_" + std::string(gait::upper_body_name(part))] = std::move(reading);
  }
  return {{"time", frame.time}, {"frame", index}, {"controllers", controllers}};
}

}  // namespace fuzzygait::studio::detail

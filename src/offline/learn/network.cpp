#include "fuzzygait/learn/network.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "offline/learn/set_edit.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::learn {

SetNetwork::SetNetwork(const gait::ControllerSet& base) : base_(base) {
  if (base.controllers.size() != static_cast<std::size_t>(gait::kSlotCount)) {
    throw std::invalid_argument("the controller set is incomplete");
  }
  for (int s = 0; s < gait::kSlotCount; ++s) {
    const gait::Controller& c = base.controllers[static_cast<std::size_t>(s)];
    std::string why;
    const std::optional<fuzzy::PartitionController<double>> p =
        fuzzy::as_partition(c.engine(), &why);
    if (!p) {
      throw std::invalid_argument(c.source() + ": cannot learn " + std::string(gait::slot_name(s)) +
                                  ": not a partition controller (" + why + ")");
    }
    const fuzzy::Engine& e = c.engine();
    Slot& slot = slots_[static_cast<std::size_t>(s)];
    slot.inputs = c.input_count();
    slot.conjunction = p->conjunction;
    slot.default_value = p->default_value;
    const std::string prefix(gait::slot_name(s));
    for (std::size_t i = 0; i < slot.inputs; ++i) {
      slot.metric[i] = c.input(i);
      const std::vector<double>& knots = p->knots[i];
      if (knots.size() > kMaxKnots) {
        throw std::invalid_argument(c.source() + ": cannot learn " + prefix + ": input '" +
                                    e.inputs[i].name + "' has more than " +
                                    std::to_string(kMaxKnots) + " terms");
      }
      slot.knot_count[i] = knots.size();
      for (std::size_t k = 0; k < knots.size(); ++k) {
        slot.fixed_knot[i][k] = knots[k];
        slot.knot_weight[i][k] = -1;
        // The range's ends stay where they are: the words' interior peaks move.
        if (k == 0 || k + 1 == knots.size()) continue;
        slot.knot_weight[i][k] = static_cast<int>(weights_.size());
        slot.weights.push_back(weights_.size());
        weights_.push_back(
            {.kind = WeightKind::Knot,
             .slot = s,
             .input = i,
             .index = k,
             .name = prefix + "." + e.inputs[i].name + "." + e.inputs[i].terms[k].name});
        values_.push_back(knots[k]);
      }
    }
    const fuzzy::OutputVariable& out = e.outputs.at(0);
    std::vector<int> term_weight(out.terms.size(), -1);
    for (std::size_t t = 0; t < out.terms.size(); ++t) {
      term_weight[t] = static_cast<int>(weights_.size());
      slot.weights.push_back(weights_.size());
      weights_.push_back({.kind = WeightKind::Output,
                          .slot = s,
                          .input = 0,
                          .index = t,
                          .name = prefix + "." + out.name + "." + out.terms[t].name});
      values_.push_back(out.terms[t].parameters.at(0));
    }
    // Rules in row-major order (as_partition checked it): each names its output term.
    const std::vector<fuzzy::Rule>& rules = e.rule_blocks.at(0).rules;
    slot.cells = rules.size();
    for (std::size_t r = 0; r < rules.size(); ++r) {
      for (std::size_t t = 0; t < out.terms.size(); ++t) {
        if (out.terms[t].name == rules[r].conclusions.at(0).term) {
          slot.cell_weight[r] = term_weight[t];
        }
      }
    }
  }
  weights_.push_back({.kind = WeightKind::Inertia, .slot = -1, .name = "inertia"});
  values_.push_back(base.inertia);
}

const std::vector<std::size_t>& SetNetwork::slot_weights(int slot) const {
  return slot_at(slot).weights;
}

std::size_t SetNetwork::find(const std::string& name) const {
  for (std::size_t i = 0; i < weights_.size(); ++i) {
    if (weights_[i].name == name) return i;
  }
  return weights_.size();
}

double SetNetwork::knot_below(std::size_t knot, std::span<const double> w) const {
  const NetworkWeight& k = weights_.at(knot);
  const Slot& s = slot_at(k.slot);
  const int below = s.knot_weight[k.input][k.index - 1];
  return below < 0 ? s.fixed_knot[k.input][k.index - 1] : w[static_cast<std::size_t>(below)];
}

double SetNetwork::knot_above(std::size_t knot, std::span<const double> w) const {
  const NetworkWeight& k = weights_.at(knot);
  const Slot& s = slot_at(k.slot);
  const int above = s.knot_weight[k.input][k.index + 1];
  return above < 0 ? s.fixed_knot[k.input][k.index + 1] : w[static_cast<std::size_t>(above)];
}

std::size_t SetNetwork::next_knot(std::size_t knot) const {
  const NetworkWeight& k = weights_.at(knot);
  const int above = slot_at(k.slot).knot_weight[k.input][k.index + 1];
  return above < 0 ? weights_.size() : static_cast<std::size_t>(above);
}

double SetNetwork::input_start(std::size_t knot) const {
  const NetworkWeight& k = weights_.at(knot);
  return slot_at(k.slot).fixed_knot[k.input][0];
}

double SetNetwork::input_end(std::size_t knot) const {
  const NetworkWeight& k = weights_.at(knot);
  const Slot& s = slot_at(k.slot);
  return s.fixed_knot[k.input][s.knot_count[k.input] - 1];
}

double SetNetwork::range(std::size_t i) const {
  const NetworkWeight& k = weights_.at(i);
  if (k.kind == WeightKind::Inertia) return 0.1;
  const fuzzy::Engine& e = base_.controllers[static_cast<std::size_t>(k.slot)].engine();
  if (k.kind == WeightKind::Knot) {
    const fuzzy::InputVariable& v = e.inputs[k.input];
    return v.maximum - v.minimum;
  }
  const fuzzy::OutputVariable& v = e.outputs[0];
  return v.maximum - v.minimum;
}

gait::ControllerSet SetNetwork::apply(std::span<const double> w) const {
  if (w.size() != weights_.size()) {
    throw std::invalid_argument("the network has " + std::to_string(weights_.size()) +
                                " weights, " + std::to_string(w.size()) + " were given");
  }
  std::vector<fuzzy::Engine> engines;
  for (const gait::Controller& c : base_.controllers)
    engines.push_back(c.engine());
  for (std::size_t i = 0; i < weights_.size(); ++i) {
    const NetworkWeight& k = weights_[i];
    if (!std::isfinite(w[i])) {
      throw std::invalid_argument("weight " + k.name + " is not finite");
    }
    if (k.kind == WeightKind::Knot) {
      if (!(knot_below(i, w) < w[i] && w[i] < knot_above(i, w))) {
        throw std::invalid_argument("knot " + k.name + " at " + common::number_text(w[i]) +
                                    " is not between its neighbours");
      }
      detail::move_knot(engines[static_cast<std::size_t>(k.slot)].inputs[k.input], k.index, w[i]);
    } else if (k.kind == WeightKind::Output) {
      engines[static_cast<std::size_t>(k.slot)].outputs[0].terms[k.index].parameters[0] = w[i];
    }
  }
  const double inertia = w[inertia_index()];
  if (!(inertia >= 0.001 && inertia <= 1.0)) {
    throw std::invalid_argument("the inertia must be between 0.001 and 1 s, got " +
                                common::number_text(inertia));
  }
  return detail::with_engines(base_, engines, inertia);
}

}  // namespace fuzzygait::learn

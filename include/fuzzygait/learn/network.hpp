// A controller set viewed as a fuzzy neural network (the paper's GARIC-style FNN): its weights are
// the partition controllers' interior knots (where along its input a word holds fully), their
// Constant output values (how fast a word turns the joint) and the set's inertia. Evaluation runs
// through the runtime's own partition code (fuzzy::evaluate_partition) templated on the scalar:
// with double it answers the walker's controllers bit for bit, with dual numbers (Ceres Jets) it
// differentiates them. The walker itself is untouched; this is a second instantiation of the same
// code for the learning tools.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/partition.hpp"
#include "fuzzygait/gait/controllers.hpp"

namespace fuzzygait::learn {

// A metric vector of any scalar (gait::MetricValues for double).
template <class T>
using Metrics = std::array<T, gait::kMetricCount>;

enum class WeightKind : std::uint8_t { Knot, Output, Inertia };

struct NetworkWeight {
  WeightKind kind = WeightKind::Output;
  int slot = -1;          // the controller's slot; -1 for the inertia
  std::size_t input = 0;  // Knot: which input of the controller
  std::size_t index = 0;  // Knot: the term whose peak it is (interior: 1 to terms - 2);
                          // Output: the output term
  // "swing_knee.delta.center", "swing_knee.velocity.flex_fast", "inertia"
  std::string name;
};

class SetNetwork {
 public:
  static constexpr std::size_t kMaxKnots = fuzzy::PackedPartition::kMaxKnots;

  // Every slot's controller must be of the partition shape (fuzzy::as_partition) with at most
  // kMaxKnots terms per input; throws std::invalid_argument naming the slot's file and why
  // otherwise. Terrain controllers are not weights: apply() keeps them as they are.
  explicit SetNetwork(const gait::ControllerSet& base);

  const gait::ControllerSet& base() const { return base_; }
  std::size_t size() const { return weights_.size(); }
  const NetworkWeight& weight(std::size_t i) const { return weights_.at(i); }
  // The base set's weights: knots in their input's unit, outputs in the output's, inertia in s.
  const std::vector<double>& values() const { return values_; }
  // Indices of the weights of one slot's controller (knots first), and of the inertia.
  const std::vector<std::size_t>& slot_weights(int slot) const;
  std::size_t inertia_index() const { return weights_.size() - 1; }
  // The weight named so (NetworkWeight::name), or size() when there is none.
  std::size_t find(const std::string& name) const;
  // A knot's neighbours: the knots before and after it on its input (weights or fixed ends), as
  // values in `w`.
  double knot_below(std::size_t knot, std::span<const double> w) const;
  double knot_above(std::size_t knot, std::span<const double> w) const;
  // The weight of the next interior knot on a knot's input, or size() where its range ends; whether
  // a knot is its input's first interior one; and its input's range.
  std::size_t next_knot(std::size_t knot) const;
  bool first_knot(std::size_t knot) const { return weights_.at(knot).index == 1; }
  double input_start(std::size_t knot) const;
  double input_end(std::size_t knot) const;
  // The span of the input a knot lies on, or of the output an output value belongs to.
  double range(std::size_t i) const;

  // The metrics slot `slot` reads, in input order.
  std::size_t input_count(int slot) const { return slot_at(slot).inputs; }
  gait::Metric input(int slot, std::size_t i) const { return slot_at(slot).metric.at(i); }

  // The controller of `slot` with weights `w` (size() of them) for inputs x0 (and x1): with
  // w = values() and T = double, the bits gait::Controller::evaluate gives. Knots out of order give
  // an answer of no meaning (the fits keep them ordered).
  template <class T>
  T evaluate(int slot, const T* w, const T& x0, const T& x1) const {
    const Slot& s = slot_at(slot);
    std::array<T, kMaxKnots> knots[2];
    for (std::size_t i = 0; i < s.inputs; ++i) {
      for (std::size_t k = 0; k < s.knot_count[i]; ++k) {
        const int index = s.knot_weight[i][k];
        knots[i][k] = index < 0 ? T(s.fixed_knot[i][k]) : w[index];
      }
    }
    std::array<T, kMaxKnots * kMaxKnots> consequents;
    for (std::size_t r = 0; r < s.cells; ++r)
      consequents[r] = w[s.cell_weight[r]];
    const bool two = s.inputs == 2;
    return fuzzy::evaluate_partition(two, knots[0].data(), s.knot_count[0], knots[1].data(),
                                     s.knot_count[1], consequents.data(), two ? s.knot_count[1] : 1,
                                     s.conjunction, T(s.default_value), x0, two ? x1 : T(0.0));
  }
  // The same reading the slot's inputs from a metric vector.
  template <class T>
  T evaluate(int slot, const T* w, const Metrics<T>& metrics) const {
    const Slot& s = slot_at(slot);
    return evaluate(slot, w, metrics[static_cast<std::size_t>(s.metric[0])],
                    s.inputs == 2 ? metrics[static_cast<std::size_t>(s.metric[1])] : T(0.0));
  }

  // The base set with weights `w` written into its controllers (knots as the peaks of their terms
  // and the feet of their neighbours, outputs as their Constant terms) and its inertia. Throws
  // std::invalid_argument when w has the wrong size, a value is not finite, knots of an input do
  // not increase, or the inertia is outside 0.001-1 s.
  gait::ControllerSet apply(std::span<const double> w) const;

 private:
  struct Slot {
    std::size_t inputs = 1;
    std::array<gait::Metric, 2> metric{};
    std::array<std::size_t, 2> knot_count{};
    std::array<std::array<double, kMaxKnots>, 2> fixed_knot{};
    std::array<std::array<int, kMaxKnots>, 2> knot_weight{};  // weight index, -1 for a fixed end
    std::size_t cells = 0;                                    // rules, row-major
    std::array<int, kMaxKnots * kMaxKnots> cell_weight{};     // each rule's output weight
    fuzzy::Conjunction conjunction = fuzzy::Conjunction::Product;
    double default_value = 0.0;
    std::vector<std::size_t> weights;
  };
  const Slot& slot_at(int slot) const { return slots_.at(static_cast<std::size_t>(slot)); }

  gait::ControllerSet base_;
  std::array<Slot, gait::kSlotCount> slots_;
  std::vector<NetworkWeight> weights_;
  std::vector<double> values_;
};

}  // namespace fuzzygait::learn

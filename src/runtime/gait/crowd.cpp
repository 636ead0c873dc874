#include "fuzzygait/gait/crowd.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "runtime/fuzzy/packed_batch.hpp"
#include "runtime/gait/walker_stages.hpp"
#include "runtime/rig/trigonometry.hpp"

namespace fuzzygait::gait {
namespace {
constexpr std::size_t kLanesPerSlot = 2 * Crowd::kBlock;
}
using detail::StepData;
using detail::WalkerStages;

Crowd::Crowd(const ControllerSet& controllers, const terrain::Terrain& terrain,
             std::span<const WalkerOptions> characters)
    : Crowd(controllers, terrain, characters, {}) {}

Crowd::~Crowd() = default;
Crowd::Crowd(Crowd&&) noexcept = default;
Crowd& Crowd::operator=(Crowd&&) noexcept = default;

Crowd::Crowd(const ControllerSet& controllers, const terrain::Terrain& terrain,
             std::span<const WalkerOptions> characters,
             std::span<const detail::ControllerBackend* const> backends)
    : controllers_(&controllers) {
  walkers_.reserve(characters.size());
  for (std::size_t i = 0; i < characters.size(); ++i) {
    if (i > 0 && !(characters[i].time_step == characters[0].time_step)) {
      throw std::invalid_argument("character " + std::to_string(i) +
                                  ": a crowd's characters step together, so their time steps "
                                  "must be equal");
    }
    try {
      walkers_.push_back(WalkerStages::make_walker(controllers, characters[i], terrain,
                                                   i < backends.size() ? backends[i] : nullptr));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("character " + std::to_string(i) + ": " + e.what());
    }
  }
  time_step_ = characters.empty() ? WalkerOptions{}.time_step : characters[0].time_step;
  steps_.resize(kBlock);
  batched_ = controllers.controllers.size() == static_cast<std::size_t>(kSlotCount);
  for (const Controller& c : controllers.controllers)
    batched_ = batched_ && c.packed() != nullptr;
  for (const Walker& w : walkers_)
    batched_ = batched_ && w.backend_ == nullptr;
  if (batched_) {
    metrics_.resize(2 * kMetricCount * kLanesPerSlot);
    output_.resize(kLanesPerSlot * static_cast<std::size_t>(kSlotCount));
    output_of_.resize(2 * kBlock);
    for (std::size_t s = 0; s < static_cast<std::size_t>(kSlotCount); ++s) {
      const Controller& c = controllers.controllers[s];
      packed_[s] = c.packed();
      input_of_slot_[s][0] = static_cast<std::size_t>(c.input(0));
      // A one-input controller does not read its second input.
      input_of_slot_[s][1] = static_cast<std::size_t>(c.input(c.input_count() - 1));
    }
    // The metrics some controller reads: the only ones copied into lanes each step.
    std::array<bool, kMetricCount> read{};
    for (const std::array<std::size_t, 2>& inputs : input_of_slot_) {
      read[inputs[0]] = true;
      read[inputs[1]] = true;
    }
    for (std::size_t m = 0; m < read.size(); ++m) {
      if (read[m]) read_metrics_[read_metric_count_++] = m;
    }
  }
  angles_.resize(8 * kBlock);
  sines_.resize(angles_.size());
  cosines_.resize(angles_.size());
}

bool Crowd::advance(double dt) noexcept {
  if (!(dt >= 0.0 && dt <= Walker::kLongestAdvance)) return false;
  const detail::SubSteps s = detail::sub_steps(dt, time_step_);
  for (std::size_t first = 0; first < walkers_.size(); first += kBlock) {
    const std::size_t count = std::min(kBlock, walkers_.size() - first);
    for (int i = 0; i < s.count; ++i)
      step(first, count, s.length);
  }
  return true;
}

double Crowd::set_step_length(std::size_t i, double metres) noexcept {
  if (i >= walkers_.size()) return std::numeric_limits<double>::quiet_NaN();
  return walkers_[i].set_step_length(metres);
}

double Crowd::set_speed(std::size_t i, double metres_per_second) noexcept {
  if (i >= walkers_.size()) return std::numeric_limits<double>::quiet_NaN();
  return walkers_[i].set_speed(metres_per_second);
}

void Crowd::clear_events() noexcept {
  for (Walker& w : walkers_)
    w.clear_events();
}

void Crowd::step(std::size_t first, std::size_t count, double h) {
  for (std::size_t i = 0; i < count; ++i)
    WalkerStages::measure(walkers_[first + i], steps_[i]);
  command(first, count);
  for (std::size_t i = 0; i < count; ++i)
    WalkerStages::integrate(walkers_[first + i], h, steps_[i]);
  place_legs(first, count);
  for (std::size_t i = 0; i < count; ++i)
    WalkerStages::finish_step(walkers_[first + i], h, steps_[i]);
}

// Each controller for every leg of the block it drives this step at once: each leg's metrics laid
// out once in its phase's lanes, metric by metric, each slot evaluated in vectors over its phase's
// lanes, and each leg's four outputs put back as its commands.
void Crowd::command(std::size_t first, std::size_t count) {
  if (!batched_) {
    for (std::size_t i = 0; i < count; ++i)
      WalkerStages::command(walkers_[first + i], steps_[i]);
    return;
  }
  // A leg's four controllers are those of its phase, so it takes the same lane in each.
  std::size_t legs_in[2] = {};  // [swing, stance]
  constexpr std::size_t kMetrics = kMetricCount;
  for (std::size_t i = 0; i < count; ++i) {
    StepData& d = steps_[i];
    const WalkerState& state = walkers_[first + i].state_;
    for (std::size_t leg = 0; leg < 2; ++leg) {
      const std::size_t phase = state.legs[leg].phase == Phase::Swing ? 0 : 1;
      const std::size_t k = legs_in[phase]++;
      double* metrics = &metrics_[phase * kMetrics * kLanesPerSlot + k];
      for (std::size_t r = 0; r < read_metric_count_; ++r) {
        const std::size_t m = read_metrics_[r];
        metrics[m * kLanesPerSlot] = d.metrics[leg][m];
      }
      output_of_[2 * i + leg] = 4 * phase * kLanesPerSlot + k;
    }
  }
  // Each phase's lanes padded to whole vectors (the padding holds what earlier steps left there;
  // its outputs are unread). A phase has room for every lane padding can add.
  static_assert(kLanesPerSlot % fuzzy::detail::kMaxBatchVectorLanes == 0);
  const std::size_t lanes_in[2] = {fuzzy::detail::padded_lanes(legs_in[0]),
                                   fuzzy::detail::padded_lanes(legs_in[1])};
  for (std::size_t s = 0; s < static_cast<std::size_t>(kSlotCount); ++s) {
    const std::size_t phase = s / 4;
    const std::size_t lane = s * kLanesPerSlot;
    const double* metrics = &metrics_[phase * kMetrics * kLanesPerSlot];
    fuzzy::detail::evaluate_batch(*packed_[s], metrics + input_of_slot_[s][0] * kLanesPerSlot,
                                  metrics + input_of_slot_[s][1] * kLanesPerSlot, &output_[lane],
                                  lanes_in[phase]);
  }
  // Each leg's four outputs, a slot's lanes apart, to its commands; a leg on terrain whose words
  // the set has controllers for blends them, as a Walker does.
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t leg = 0; leg < 2; ++leg) {
      const double* out = &output_[output_of_[2 * i + leg]];
      for (std::size_t joint = 0; joint < 4; ++joint)
        steps_[i].commands[leg][joint] = out[joint * kLanesPerSlot];
    }
    if (controllers_->has_terrain_words())
      WalkerStages::command_on_terrain(walkers_[first + i], steps_[i]);
  }
}

// Every leg's segment sines and cosines in one batch, for the orientations the legs are placed
// with next (finish_step() finds them in its cache).
void Crowd::place_legs(std::size_t first, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t leg = 0; leg < 2; ++leg) {
      Walker& w = walkers_[first + i];
      w.trig_orientation_[leg] = rig::orientation(w.state_.pelvis_tilt, w.state_.legs[leg].angles);
      rig::detail::to_lanes(w.trig_orientation_[leg], &angles_[8 * i + 4 * leg]);
    }
  }
  rig::detail::sin_cos(angles_.data(), sines_.data(), cosines_.data(), 8 * count);
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t leg = 0; leg < 2; ++leg) {
      walkers_[first + i].trig_[leg] =
          rig::detail::from_lanes(&sines_[8 * i + 4 * leg], &cosines_[8 * i + 4 * leg]);
    }
  }
}

}  // namespace fuzzygait::gait

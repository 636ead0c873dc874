#include "fuzzygait/gait/crowd.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include "runtime/fuzzy/packed_batch.hpp"
#include "runtime/gait/walker_stages.hpp"
#include "runtime/rig/trigonometry.hpp"

namespace fuzzygait::gait {
namespace {
constexpr std::size_t kLanesPerSlot = 2 * Crowd::kBlock;
constexpr std::size_t kBlocksPerRange = 4;  // the fewest blocks a worker takes at once
}  // namespace
using detail::StepData;
using detail::WalkerStages;

Crowd::Crowd(const ControllerSet& controllers, const terrain::Terrain& terrain,
             std::span<const WalkerOptions> characters, const CrowdOptions& options)
    : Crowd(controllers, terrain, characters, {}, options) {}

Crowd::~Crowd() = default;
Crowd::Crowd(Crowd&&) noexcept = default;
Crowd& Crowd::operator=(Crowd&&) noexcept = default;

Crowd::Crowd(const ControllerSet& controllers, const terrain::Terrain& terrain,
             std::span<const WalkerOptions> characters,
             std::span<const detail::ControllerBackend* const> backends,
             const CrowdOptions& options)
    : controllers_(&controllers) {
  if (options.tasks) {
    if (!options.tasks->enqueue || !options.tasks->finish || options.tasks->worker_count == 0) {
      throw std::invalid_argument(
          "a crowd's task system needs enqueue, finish and at least one worker");
    }
    tasks_ = *options.tasks;
  } else {
    const std::size_t threads = options.threads > 0
                                    ? options.threads
                                    : std::max<std::size_t>(std::thread::hardware_concurrency(), 1);
    // No more threads than runs of blocks: a thread without one would only wait.
    const std::size_t blocks =
        (characters.size() + kBlock * kBlocksPerRange - 1) / (kBlock * kBlocksPerRange);
    pool_ = std::make_unique<WorkerPool>(
        std::clamp<std::size_t>(threads, 1, std::max<std::size_t>(blocks, 1)));
    tasks_ = pool_->tasks();
  }
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
  batched_ = controllers.controllers.size() == static_cast<std::size_t>(kSlotCount);
  for (const Controller& c : controllers.controllers)
    batched_ = batched_ && c.packed() != nullptr;
  for (const Walker& w : walkers_)
    batched_ = batched_ && w.backend_ == nullptr;
  if (batched_) {
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
  scratch_.resize(tasks_.worker_count);
  for (Scratch& s : scratch_) {
    s.steps.resize(kBlock);
    if (batched_) {
      s.metrics.resize(2 * kMetricCount * kLanesPerSlot);
      s.output.resize(kLanesPerSlot * static_cast<std::size_t>(kSlotCount));
      s.output_of.resize(2 * kBlock);
    }
    s.angles.resize(8 * kBlock);
    s.sines.resize(s.angles.size());
    s.cosines.resize(s.angles.size());
  }
}

bool Crowd::advance(double dt) noexcept {
  if (!(dt >= 0.0 && dt <= Walker::kLongestAdvance)) return false;
  sub_steps_ = detail::sub_steps(dt, time_step_);
  const std::size_t blocks = (walkers_.size() + kBlock - 1) / kBlock;
  if (blocks == 0 || sub_steps_.count == 0) return true;
  // Runs of neighbouring blocks to a worker, never single blocks: two cores stepping blocks side
  // by side in memory stepped 4096 characters 1.25 times as fast as one, runs of four blocks or
  // more 1.8-1.9 times (the walkers a range steps are one stretch of memory). Eight runs a worker
  // keep the load even.
  const std::size_t range = std::max(kBlocksPerRange, blocks / (8 * tasks_.worker_count));
  if (pool_) {
    pool_->run(&Crowd::step_blocks, blocks, range, this);
  } else {
    void* task = tasks_.enqueue(&Crowd::step_blocks, blocks, range, this, tasks_.user_context);
    tasks_.finish(task, tasks_.user_context);
  }
  return true;
}

// A worker's share of advance(): each of its blocks through every sub-step, with its scratch.
void Crowd::step_blocks(std::size_t begin, std::size_t end, std::size_t worker, void* crowd) {
  Crowd& c = *static_cast<Crowd*>(crowd);
  Scratch& scratch = c.scratch_[worker];
  for (std::size_t block = begin; block < end; ++block) {
    const std::size_t first = block * kBlock;
    const std::size_t count = std::min(kBlock, c.walkers_.size() - first);
    for (int i = 0; i < c.sub_steps_.count; ++i)
      c.step(first, count, c.sub_steps_.length, scratch);
  }
}

double Crowd::set_step_length(std::size_t i, double metres) noexcept {
  if (i >= walkers_.size()) return std::numeric_limits<double>::quiet_NaN();
  return walkers_[i].set_step_length(metres);
}

double Crowd::set_speed(std::size_t i, double metres_per_second) noexcept {
  if (i >= walkers_.size()) return std::numeric_limits<double>::quiet_NaN();
  return walkers_[i].set_speed(metres_per_second);
}

bool Crowd::stop(std::size_t i) noexcept {
  if (i >= walkers_.size()) return false;
  walkers_[i].stop();
  return true;
}

bool Crowd::go(std::size_t i) noexcept {
  if (i >= walkers_.size()) return false;
  walkers_[i].go();
  return true;
}

void Crowd::clear_events() noexcept {
  for (Walker& w : walkers_)
    w.clear_events();
}

void Crowd::step(std::size_t first, std::size_t count, double h, Scratch& scratch) {
  std::vector<StepData>& steps = scratch.steps;
  for (std::size_t i = 0; i < count; ++i)
    WalkerStages::measure(walkers_[first + i], steps[i]);
  command(first, count, scratch);
  for (std::size_t i = 0; i < count; ++i)
    WalkerStages::integrate(walkers_[first + i], h, steps[i]);
  place_legs(first, count, scratch);
  for (std::size_t i = 0; i < count; ++i)
    WalkerStages::finish_step(walkers_[first + i], h, steps[i]);
}

// Each controller for every leg of the block it drives this step at once: each leg's metrics laid
// out once in its phase's lanes, metric by metric, each slot evaluated in vectors over its phase's
// lanes, and each leg's four outputs put back as its commands.
void Crowd::command(std::size_t first, std::size_t count, Scratch& scratch) {
  std::vector<StepData>& steps = scratch.steps;
  if (!batched_) {
    for (std::size_t i = 0; i < count; ++i)
      WalkerStages::command(walkers_[first + i], steps[i]);
    return;
  }
  // A leg's four controllers are those of its phase, so it takes the same lane in each.
  std::size_t legs_in[2] = {};  // [swing, stance]
  constexpr std::size_t kMetrics = kMetricCount;
  for (std::size_t i = 0; i < count; ++i) {
    StepData& d = steps[i];
    const WalkerState& state = walkers_[first + i].state_;
    for (std::size_t leg = 0; leg < 2; ++leg) {
      const std::size_t phase = state.legs[leg].phase == Phase::Swing ? 0 : 1;
      const std::size_t k = legs_in[phase]++;
      double* metrics = &scratch.metrics[phase * kMetrics * kLanesPerSlot + k];
      for (std::size_t r = 0; r < read_metric_count_; ++r) {
        const std::size_t m = read_metrics_[r];
        metrics[m * kLanesPerSlot] = d.metrics[leg][m];
      }
      scratch.output_of[2 * i + leg] = 4 * phase * kLanesPerSlot + k;
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
    const double* metrics = &scratch.metrics[phase * kMetrics * kLanesPerSlot];
    fuzzy::detail::evaluate_batch(*packed_[s], metrics + input_of_slot_[s][0] * kLanesPerSlot,
                                  metrics + input_of_slot_[s][1] * kLanesPerSlot,
                                  &scratch.output[lane], lanes_in[phase]);
  }
  // Each leg's four outputs, a slot's lanes apart, to its commands; a leg on terrain whose words
  // the set has controllers for blends them, as a Walker does.
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t leg = 0; leg < 2; ++leg) {
      const double* out = &scratch.output[scratch.output_of[2 * i + leg]];
      for (std::size_t joint = 0; joint < 4; ++joint)
        steps[i].commands[leg][joint] = out[joint * kLanesPerSlot];
    }
    if (controllers_->has_terrain_words())
      WalkerStages::command_on_terrain(walkers_[first + i], steps[i]);
  }
}

// Every leg's segment sines and cosines in one batch, for the orientations the legs are placed
// with next (finish_step() finds them in its cache).
void Crowd::place_legs(std::size_t first, std::size_t count, Scratch& scratch) {
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t leg = 0; leg < 2; ++leg) {
      Walker& w = walkers_[first + i];
      w.trig_orientation_[leg] = rig::orientation(w.state_.pelvis_tilt, w.state_.legs[leg].angles);
      rig::detail::to_lanes(w.trig_orientation_[leg], &scratch.angles[8 * i + 4 * leg]);
    }
  }
  rig::detail::sin_cos(scratch.angles.data(), scratch.sines.data(), scratch.cosines.data(),
                       8 * count);
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t leg = 0; leg < 2; ++leg) {
      walkers_[first + i].trig_[leg] = rig::detail::from_lanes(&scratch.sines[8 * i + 4 * leg],
                                                               &scratch.cosines[8 * i + 4 * leg]);
    }
  }
}

}  // namespace fuzzygait::gait

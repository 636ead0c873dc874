// Many characters walking with one controller set on one terrain, stepped together: each stage of
// a time step runs for a block of characters before the next, so each controller is evaluated for
// all of the block's legs it drives at once (AVX2 lanes where the machine has them), and the legs'
// segment sines and cosines in one batch (the widest vectors the machine has). Every character
// walks bit for bit as a lone Walker with its options would: the crowd does the same arithmetic,
// only in a different order of characters.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "fuzzygait/gait/walker.hpp"

namespace fuzzygait::gait::detail {
struct StepData;  // what a time step hands from stage to stage (internal)
}  // namespace fuzzygait::gait::detail

namespace fuzzygait::gait {

class Crowd {
 public:
  // One character per element of `characters` (body, step length, start pose, ...). The
  // controller set and terrain must outlive the crowd. Throws std::invalid_argument as Walker's
  // constructor does, naming the character, or when the characters' time steps differ (they
  // step together).
  Crowd(const ControllerSet& controllers, const terrain::Terrain& terrain,
        std::span<const WalkerOptions> characters);
  ~Crowd();
  Crowd(Crowd&&) noexcept;
  Crowd& operator=(Crowd&&) noexcept;

  std::size_t size() const noexcept { return walkers_.size(); }

  // Per frame: none of these throws or allocates.

  // Advances every character by dt, in the sub-steps Walker::advance() takes. Returns false and
  // changes nothing when dt is NaN, negative or longer than Walker::kLongestAdvance.
  bool advance(double dt) noexcept;
  // A character (i < size()): its pose, points, state and events, read as a Walker's.
  const Walker& operator[](std::size_t i) const noexcept { return walkers_[i]; }
  // Every character, in order, contiguous in memory for the crowd's life: so a binding can view
  // their states (Walker::state()) in place, a character's a fixed stride from the one before.
  std::span<const Walker> walkers() const noexcept { return walkers_; }
  // Walker::set_step_length() of character i: the step length now commanded, or NaN (nothing
  // changed) when i is not a character of the crowd.
  double set_step_length(std::size_t i, double metres) noexcept;
  // Walker::set_speed() of character i: the speed now commanded, or NaN (nothing changed) when i
  // is not a character of the crowd.
  double set_speed(std::size_t i, double metres_per_second) noexcept;
  // Every character's Walker::clear_events().
  void clear_events() noexcept;

  // Whether the controllers are evaluated across characters (every controller of the set on the
  // fast path); otherwise each character evaluates its own, as a Walker does.
  bool batched_controllers() const noexcept { return batched_; }

  // Characters stepped together: their data stays in the core's caches through a frame's stages.
  static constexpr std::size_t kBlock = 32;

 private:
  friend struct detail::WalkerStages;
  Crowd(const ControllerSet& controllers, const terrain::Terrain& terrain,
        std::span<const WalkerOptions> characters,
        std::span<const detail::ControllerBackend* const> backends);
  void step(std::size_t first, std::size_t count, double h);
  void command(std::size_t first, std::size_t count);
  void place_legs(std::size_t first, std::size_t count);

  const ControllerSet* controllers_;
  std::vector<Walker> walkers_;
  std::vector<detail::StepData> steps_;  // a block's
  bool batched_ = false;
  double time_step_ = 0.0;
  // Each slot's controller and the metrics it reads. A block's legs take lanes by phase (swing,
  // stance): each metric of each phase's legs, [phase][metric][lane], and each slot's outputs,
  // [slot][lane]; room for both legs of a block in either phase.
  std::array<const fuzzy::PackedPartition*, kSlotCount> packed_{};
  std::array<std::array<std::size_t, 2>, kSlotCount> input_of_slot_{};
  std::array<std::size_t, kMetricCount> read_metrics_{};  // the metrics any slot reads
  std::size_t read_metric_count_ = 0;
  std::vector<double> metrics_;
  std::vector<double> output_;
  std::vector<std::size_t> output_of_;  // [character][leg]: where its hip's output lies
  // A block's leg orientations (four a leg) and their sines and cosines.
  std::vector<double> angles_;
  std::vector<double> sines_;
  std::vector<double> cosines_;
};

}  // namespace fuzzygait::gait

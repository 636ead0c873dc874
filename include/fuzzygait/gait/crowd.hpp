// Many characters walking with one controller set on one terrain, stepped together: each stage of
// a time step runs for a block of characters before the next, so each controller is evaluated for
// all of the block's legs it drives at once (AVX2 lanes where the machine has them), and the legs'
// segment sines and cosines in one batch (the widest vectors the machine has). Every character
// walks bit for bit as a lone Walker with its options would: the crowd does the same arithmetic,
// only in a different order of characters.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "fuzzygait/gait/tasks.hpp"
#include "fuzzygait/gait/walker.hpp"

namespace fuzzygait::gait::detail {
struct StepData;  // what a time step hands from stage to stage (internal)
// advance(dt)'s equal sub-steps, none longer than the time step (none for a refused dt).
struct SubSteps {
  int count = 0;
  double length = 0.0;
};
}  // namespace fuzzygait::gait::detail

namespace fuzzygait::gait {

// How a crowd uses the machine's cores. The characters are stepped in blocks of Crowd::kBlock,
// each block by one worker; which worker steps which block changes no bit of any walk.
struct CrowdOptions {
  // The game's task system (see TaskSystem); `threads` is then ignored.
  std::optional<TaskSystem> tasks;
  // Without one: threads of the crowd's own pool (WorkerPool), the calling thread among them;
  // 1 steps everything on the calling thread; 0 one per hardware thread.
  std::size_t threads = 1;
};

class Crowd {
 public:
  // One character per element of `characters` (body, step length, start pose, ...). The
  // controller set and terrain (and a task system's user context) must outlive the crowd. Throws
  // std::invalid_argument as Walker's constructor does, naming the character, when the
  // characters' time steps differ (they step together), or when a task system has no enqueue or
  // finish or no worker.
  Crowd(const ControllerSet& controllers, const terrain::Terrain& terrain,
        std::span<const WalkerOptions> characters, const CrowdOptions& options = {});
  ~Crowd();
  Crowd(Crowd&&) noexcept;
  Crowd& operator=(Crowd&&) noexcept;

  std::size_t size() const noexcept { return walkers_.size(); }

  // Per frame: none of these throws or allocates.

  // Advances every character by dt, in the sub-steps Walker::advance() takes, on the crowd's
  // workers. Returns false and changes nothing when dt is NaN, negative or longer than
  // Walker::kLongestAdvance.
  bool advance(double dt) noexcept;
  // How many workers step the characters (the task system's, or the pool's threads).
  std::size_t worker_count() const noexcept { return tasks_.worker_count; }
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
  // Walker::stop() and Walker::go() of character i; false (nothing changed) when i is not a
  // character.
  bool stop(std::size_t i) noexcept;
  bool go(std::size_t i) noexcept;
  // Every character's Walker::clear_events().
  void clear_events() noexcept;

  // Whether the controllers are evaluated across characters (every controller of the set on the
  // fast path); otherwise each character evaluates its own, as a Walker does.
  bool batched_controllers() const noexcept { return batched_; }

  // Characters stepped together: their data stays in the core's caches through a frame's stages.
  static constexpr std::size_t kBlock = 32;

 private:
  friend struct detail::WalkerStages;
  // What a worker needs to step a block: each slot's controller reads, for the block's legs in
  // lanes by phase (swing, stance), each metric of each phase's legs, [phase][metric][lane], and
  // each slot's outputs, [slot][lane]; room for both legs of a block in either phase.
  struct Scratch {
    std::vector<detail::StepData> steps;  // a block's
    std::vector<double> metrics;
    std::vector<double> output;
    std::vector<std::size_t> output_of;  // [character][leg]: where its hip's output lies
    // A block's leg orientations (four a leg) and their sines and cosines.
    std::vector<double> angles;
    std::vector<double> sines;
    std::vector<double> cosines;
  };

  Crowd(const ControllerSet& controllers, const terrain::Terrain& terrain,
        std::span<const WalkerOptions> characters,
        std::span<const detail::ControllerBackend* const> backends, const CrowdOptions& options);
  static void step_blocks(std::size_t begin, std::size_t end, std::size_t worker, void* crowd);
  void step(std::size_t first, std::size_t count, double h, Scratch& scratch);
  void command(std::size_t first, std::size_t count, Scratch& scratch);
  void place_legs(std::size_t first, std::size_t count, Scratch& scratch);

  const ControllerSet* controllers_;
  std::vector<Walker> walkers_;
  bool batched_ = false;
  double time_step_ = 0.0;
  // Each slot's controller and the metrics it reads.
  std::array<const fuzzy::PackedPartition*, kSlotCount> packed_{};
  std::array<std::array<std::size_t, 2>, kSlotCount> input_of_slot_{};
  std::array<std::size_t, kMetricCount> read_metrics_{};  // the metrics any slot reads
  std::size_t read_metric_count_ = 0;
  // The workers: the pool (when the crowd runs its own), the task system, a scratch each, and
  // the sub-steps of the advance() under way.
  std::unique_ptr<WorkerPool> pool_;
  TaskSystem tasks_;
  std::vector<Scratch> scratch_;
  detail::SubSteps sub_steps_;
};

}  // namespace fuzzygait::gait

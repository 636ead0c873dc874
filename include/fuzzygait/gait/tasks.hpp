// Threads belong to the game: a crowd steps its characters on the game's own task system, as
// Box2D v3's world does, or on a small pool of its own when the game gives none.
#pragma once

#include <cstddef>
#include <memory>

namespace fuzzygait::gait {

// A game's task system. The crowd calls enqueue() with a task over `item_count` items and then
// finish() with what enqueue() returned, from the thread that called Crowd::advance(), once a
// time it advances. Contract:
// - enqueue() runs `task` over [0, item_count) split into ranges of at least `min_range` items
//   (the last may be shorter), each range once, on any threads, before finish() returns; it may
//   run them all before it returns (and return null).
// - Each call of `task` gets a worker index below worker_count, and no two calls running at the
//   same time get the same index (the crowd keeps one scratch a worker).
// - Neither may throw. Which thread runs which range changes nothing: every character walks bit
//   for bit as it would alone.
struct TaskSystem {
  using Task = void(std::size_t begin, std::size_t end, std::size_t worker, void* task_context);
  std::size_t worker_count = 1;
  void* (*enqueue)(Task* task, std::size_t item_count, std::size_t min_range, void* task_context,
                   void* user_context) = nullptr;
  void (*finish)(void* user_task, void* user_context) = nullptr;
  void* user_context = nullptr;
};

// A small pool of threads serving as a TaskSystem: the calling thread is worker 0 and joins the
// work, `threads - 1` more wait for it. Ranges are handed out one at a time, in order, to
// whichever worker is free. Not copyable or movable (tasks() points at it); threads stop when
// it is destroyed.
class WorkerPool {
 public:
  // threads: 1 or more (1: everything on the calling thread, no thread started). Throws
  // std::system_error when a thread cannot be started.
  explicit WorkerPool(std::size_t threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  std::size_t threads() const noexcept { return threads_; }
  TaskSystem tasks() noexcept;
  // Runs task over [0, item_count) in ranges of min_range items and returns when all have run.
  void run(TaskSystem::Task* task, std::size_t item_count, std::size_t min_range,
           void* task_context) noexcept;

 private:
  struct Shared;
  std::size_t threads_;
  std::unique_ptr<Shared> shared_;
};

}  // namespace fuzzygait::gait

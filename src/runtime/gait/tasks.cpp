#include "fuzzygait/gait/tasks.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace fuzzygait::gait {

// One run at a time: the caller publishes it under the mutex with a new generation, the workers
// wake, take ranges from `next` until none is left, and the last to finish wakes the caller.
struct WorkerPool::Shared {
  std::mutex mutex;
  std::condition_variable wake;  // workers wait for a new generation (or stop)
  std::condition_variable done;  // the caller waits for every worker to finish the run
  std::uint64_t generation = 0;
  bool stop = false;
  std::size_t busy = 0;  // workers still in the current run
  // The run (written under the mutex before the generation changes).
  TaskSystem::Task* task = nullptr;
  void* context = nullptr;
  std::size_t item_count = 0;
  std::size_t range = 1;
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> threads;

  void stop_and_join() {
    {
      std::lock_guard lock(mutex);
      stop = true;
    }
    wake.notify_all();
    for (std::thread& t : threads)
      t.join();
    threads.clear();
  }

  void work(std::size_t worker) {
    for (;;) {
      const std::size_t begin = next.fetch_add(range, std::memory_order_relaxed);
      if (begin >= item_count) return;
      task(begin, std::min(item_count, begin + range), worker, context);
    }
  }

  void serve(std::size_t worker) {
    std::uint64_t seen = 0;
    for (;;) {
      {
        std::unique_lock lock(mutex);
        wake.wait(lock, [&] { return stop || generation != seen; });
        if (stop) return;
        seen = generation;
      }
      work(worker);
      std::lock_guard lock(mutex);
      if (--busy == 0) done.notify_one();
    }
  }
};

WorkerPool::WorkerPool(std::size_t threads)
    : threads_(std::max<std::size_t>(threads, 1)), shared_(std::make_unique<Shared>()) {
  shared_->threads.reserve(threads_ - 1);
  try {
    for (std::size_t worker = 1; worker < threads_; ++worker)
      shared_->threads.emplace_back([shared = shared_.get(), worker] { shared->serve(worker); });
  } catch (...) {
    shared_->stop_and_join();
    throw;
  }
}

WorkerPool::~WorkerPool() {
  shared_->stop_and_join();
}

void WorkerPool::run(TaskSystem::Task* task, std::size_t item_count, std::size_t min_range,
                     void* task_context) noexcept {
  Shared& s = *shared_;
  const std::size_t range = std::max<std::size_t>(min_range, 1);
  if (s.threads.empty() || item_count <= range) {
    for (std::size_t begin = 0; begin < item_count; begin += range)
      task(begin, std::min(item_count, begin + range), 0, task_context);
    return;
  }
  {
    std::lock_guard lock(s.mutex);
    s.task = task;
    s.context = task_context;
    s.item_count = item_count;
    s.range = range;
    s.next.store(0, std::memory_order_relaxed);
    s.busy = s.threads.size();
    ++s.generation;
  }
  s.wake.notify_all();
  s.work(0);
  std::unique_lock lock(s.mutex);
  s.done.wait(lock, [&] { return s.busy == 0; });
}

TaskSystem WorkerPool::tasks() noexcept {
  TaskSystem t;
  t.worker_count = threads_;
  t.enqueue = [](TaskSystem::Task* task, std::size_t item_count, std::size_t min_range,
                 void* task_context, void* user_context) -> void* {
    static_cast<WorkerPool*>(user_context)->run(task, item_count, min_range, task_context);
    return nullptr;
  };
  t.finish = [](void*, void*) {};
  t.user_context = this;
  return t;
}

}  // namespace fuzzygait::gait

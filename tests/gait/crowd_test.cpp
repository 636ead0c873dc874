// A crowd steps its characters together (controllers across characters, the legs' trigonometry
// in one batch); each character must walk to the bit as it would alone, through every kind of
// step: double support, awkward starts, slopes and a kerb, a step length changed mid-walk.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "fuzzygait/gait/crowd.hpp"
#include "runtime/gait/walker_stages.hpp"
#include "support/allocation_counter.hpp"
#include "support/walks.hpp"

using namespace fuzzygait;

namespace {

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Everything a game reads of a character: state, pose points and events, to the bit.
void expect_same_walk(const gait::Walker& crowd, const gait::Walker& alone,
                      const std::string& who) {
  ASSERT_EQ(fuzzygait::test::state_difference(crowd.state(), alone.state()), "")
      << who << " at " << alone.time() << " s";
  const rig::LegPoints p = crowd.points(rig::Side::Right);
  const rig::LegPoints q = alone.points(rig::Side::Right);
  ASSERT_TRUE(same_bits(p.tip.x, q.tip.x) && same_bits(p.tip.y, q.tip.y)) << who;
  ASSERT_EQ(crowd.events().size(), alone.events().size()) << who;
  for (std::size_t e = 0; e < crowd.events().size(); ++e) {
    const gait::EventRecord& a = crowd.events()[e];
    const gait::EventRecord& b = alone.events()[e];
    ASSERT_TRUE(a.event == b.event && a.side == b.side && same_bits(a.time, b.time) &&
                same_bits(a.where.x, b.where.x) && same_bits(a.where.y, b.where.y))
        << who << " event " << e;
  }
}

// Forty characters (more than a block, so two blocks, the second partly filled): statures from
// 1.50 to 2.00 m, steps across each one's range, phases spread by their warm-ups, every fifth
// from a random awkward pose.
gait::CrowdOptions on_threads(std::size_t threads) {
  gait::CrowdOptions options;
  options.threads = threads;
  return options;
}

std::vector<gait::WalkerOptions> mixed_characters(const gait::ControllerSet& set,
                                                  std::size_t count = 40) {
  std::vector<gait::WalkerOptions> characters(count);
  for (std::size_t i = 0; i < characters.size(); ++i) {
    gait::WalkerOptions& o = characters[i];
    const double a = std::fmod(0.6180339887 * static_cast<double>(i), 1.0);
    const double b = std::fmod(0.7548776662 * static_cast<double>(i), 1.0);
    o.segments = rig::segments_from_stature(1.5 + 0.5 * a);
    const double shortest = gait::Walker::min_step_length(set, o.segments);
    const double longest = gait::Walker::max_step_length(o.segments);
    o.step_length = shortest + (longest - shortest) * (0.1 + 0.8 * b);
    o.start.warm_up = 3.0 + 1.1 * b;
    if (i % 5 == 2) {
      o.start.random = true;
      o.start.seed = i;
    }
  }
  return characters;
}

// `backends`: a controller back end per character (none, or null, for the set's own engines).
void walk_crowd_and_alone(
    const gait::ControllerSet& set, const terrain::Terrain& ground,
    const std::vector<gait::WalkerOptions>& characters, bool batched,
    const std::vector<const gait::detail::ControllerBackend*>& backends = {}) {
  gait::Crowd crowd = gait::detail::WalkerStages::make_crowd(set, ground, characters, backends);
  ASSERT_EQ(crowd.size(), characters.size());
  EXPECT_EQ(crowd.batched_controllers(), batched);
  std::vector<gait::Walker> alone;
  for (std::size_t i = 0; i < characters.size(); ++i) {
    alone.push_back(gait::detail::WalkerStages::make_walker(
        set, characters[i], ground, i < backends.size() ? backends[i] : nullptr));
  }
  for (int frame = 0; frame < 480; ++frame) {
    // Frames of 1/60 s, and now and then a longer one (more sub-steps) and a zero one.
    const double dt = frame % 97 == 5 ? 0.05 : (frame % 131 == 7 ? 0.0 : 1.0 / 60.0);
    if (frame == 200) {
      for (std::size_t i = 0; i < characters.size(); i += 3) {
        const double step = 0.5 * (crowd[i].step_length() +
                                   gait::Walker::min_step_length(set, crowd[i].segments()));
        crowd.set_step_length(i, step);
        alone[i].set_step_length(step);
      }
    }
    crowd.advance(dt);
    for (std::size_t i = 0; i < alone.size(); ++i) {
      alone[i].advance(dt);
      expect_same_walk(crowd[i], alone[i], set.name + " character " + std::to_string(i));
      if (::testing::Test::HasFatalFailure()) return;
      alone[i].clear_events();
    }
    crowd.clear_events();
  }
}

TEST(Crowd, EveryCharacterWalksAsItWouldAlone) {
  const terrain::Terrain ground = terrain::Terrain::polyline(
      {{-10.0, 0.0}, {2.0, 0.0}, {4.0, 0.2}, {6.0, 0.2}, {6.001, 0.1}, {30.0, 0.1}});
  for (const std::string& name : gait::ControllerSet::builtin_names()) {
    const gait::ControllerSet set = gait::ControllerSet::builtin(name);
    walk_crowd_and_alone(set, ground, mixed_characters(set), true);
    if (HasFatalFailure()) return;
  }
}

// With a controller back end (here the general fuzzy path through the set's own controllers)
// each character evaluates its own controllers, and still walks as alone.
TEST(Crowd, CharactersWithAControllerBackEndWalkAsAlone) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  std::vector<gait::WalkerOptions> characters = mixed_characters(set);
  characters.resize(12);
  const gait::detail::ControllerBackend backend{
      [&set](int slot, const gait::MetricValues& metrics) {
        fuzzy::Workspace none;
        return set.controllers[static_cast<std::size_t>(slot)].evaluate(metrics, none);
      }};
  std::vector<const gait::detail::ControllerBackend*> backends(characters.size(), nullptr);
  backends[4] = &backend;
  walk_crowd_and_alone(set, ground, characters, false, backends);
}

TEST(Crowd, AdvancingAllocatesNothing) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  for (std::size_t threads : {1, 2}) {
    // Eight blocks: two runs of blocks, one a worker.
    gait::Crowd crowd(set, ground, mixed_characters(set, 8 * gait::Crowd::kBlock),
                      on_threads(threads));
    EXPECT_EQ(crowd.worker_count(), threads);
    crowd.advance(1.0);
    const long before = fuzzygait::testing::allocation_count();
    for (int i = 0; i < 120; ++i) {
      crowd.advance(1.0 / 60.0);
      crowd.clear_events();
    }
    EXPECT_EQ(fuzzygait::testing::allocation_count(), before) << threads << " threads";
  }
}

// A game's task system as a test can make one: each enqueue() starts a thread per worker, worker
// w running ranges w, w + workers, ... from the last to the first; finish() joins them. It checks
// the contract from its side: every item once, ranges of at least min_range.
struct GameTasks {
  explicit GameTasks(std::size_t worker_count) : workers(worker_count) {}
  std::size_t workers;
  std::vector<std::thread> running;
  std::mutex mutex;
  std::vector<int> runs;  // how often each item ran

  static void* enqueue(gait::TaskSystem::Task* task, std::size_t items, std::size_t min_range,
                       void* task_context, void* user_context) {
    GameTasks& g = *static_cast<GameTasks*>(user_context);
    g.runs.assign(items, 0);
    const std::size_t ranges = (items + min_range - 1) / min_range;
    for (std::size_t w = 0; w < g.workers; ++w) {
      g.running.emplace_back([&g, task, items, min_range, task_context, ranges, w] {
        for (std::size_t r = ranges; r-- > 0;) {
          if (r % g.workers != w) continue;
          const std::size_t begin = r * min_range;
          const std::size_t end = std::min(items, begin + min_range);
          task(begin, end, w, task_context);
          std::lock_guard lock(g.mutex);
          for (std::size_t i = begin; i < end; ++i)
            ++g.runs[i];
        }
      });
    }
    return &g;
  }
  static void finish(void* user_task, void*) {
    GameTasks& g = *static_cast<GameTasks*>(user_task);
    for (std::thread& t : g.running)
      t.join();
    g.running.clear();
  }
  gait::TaskSystem tasks() {
    gait::TaskSystem t;
    t.worker_count = workers;
    t.enqueue = &enqueue;
    t.finish = &finish;
    t.user_context = this;
    return t;
  }
};

// Nine blocks (the last partly filled, three runs of blocks) on one thread, two, eight (as many
// as there are runs: three), one per hardware thread and a game's own task system of three
// workers: every character's state, points and events to the bit, frame by frame, and as it
// would walk alone.
TEST(Crowd, EveryCharacterWalksTheSameBitsOnAnyNumberOfWorkers) {
  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  const terrain::Terrain ground = terrain::Terrain::polyline(
      {{-10.0, 0.0}, {2.0, 0.0}, {4.0, 0.2}, {6.0, 0.2}, {6.001, 0.1}, {30.0, 0.1}});
  const std::vector<gait::WalkerOptions> characters =
      mixed_characters(set, 8 * gait::Crowd::kBlock + 7);
  std::vector<gait::Walker> alone;
  for (const gait::WalkerOptions& o : characters)
    alone.emplace_back(set, o, ground);
  GameTasks game(3);
  std::vector<gait::Crowd> crowds;
  for (std::size_t threads : {1, 2, 8, 0})
    crowds.emplace_back(set, ground, characters, on_threads(threads));
  gait::CrowdOptions with_game_tasks;
  with_game_tasks.tasks = game.tasks();
  crowds.emplace_back(set, ground, characters, with_game_tasks);
  EXPECT_EQ(crowds[2].worker_count(), 3u);
  EXPECT_EQ(crowds[4].worker_count(), 3u);
  for (int frame = 0; frame < 240; ++frame) {
    const double dt = frame % 97 == 5 ? 0.05 : 1.0 / 60.0;
    for (std::size_t i = 0; i < alone.size(); ++i)
      alone[i].advance(dt);
    for (gait::Crowd& crowd : crowds) {
      ASSERT_TRUE(crowd.advance(dt));
      for (std::size_t i = 0; i < alone.size(); ++i) {
        expect_same_walk(
            crowd[i], alone[i],
            std::to_string(crowd.worker_count()) + " workers, character " + std::to_string(i));
        if (::testing::Test::HasFatalFailure()) return;
      }
      crowd.clear_events();
    }
    for (gait::Walker& w : alone)
      w.clear_events();
    ASSERT_EQ(std::count(game.runs.begin(), game.runs.end(), 1), 9) << "frame " << frame;
  }
}

// The pool hands out each range once, to one worker at a time, and runs short jobs on the
// calling thread.
TEST(WorkerPool, RunsEveryRangeOnceOnDistinctWorkers) {
  gait::WorkerPool pool(4);
  EXPECT_EQ(pool.threads(), 4u);
  struct Record {
    std::vector<std::atomic<int>> runs = std::vector<std::atomic<int>>(1000);
    std::array<std::atomic<int>, 4> inside{};
    std::atomic<bool> overlap{false};
    std::atomic<bool> bad_range{false};
    std::set<std::thread::id> threads;
    std::mutex mutex;
  } record;
  auto task = [](std::size_t begin, std::size_t end, std::size_t worker, void* context) {
    Record& r = *static_cast<Record*>(context);
    if (worker >= 4 || end - begin > 7 || (end - begin < 7 && end != 1000)) r.bad_range = true;
    if (worker < 4 && r.inside[worker]++ != 0) r.overlap = true;
    for (std::size_t i = begin; i < end; ++i)
      ++r.runs[i];
    {
      std::lock_guard lock(r.mutex);
      r.threads.insert(std::this_thread::get_id());
    }
    std::this_thread::sleep_for(std::chrono::microseconds(50));
    if (worker < 4) --r.inside[worker];
  };
  const gait::TaskSystem tasks = pool.tasks();
  for (int round = 0; round < 3; ++round) {
    tasks.finish(tasks.enqueue(task, 1000, 7, &record, tasks.user_context), tasks.user_context);
  }
  for (const std::atomic<int>& n : record.runs)
    ASSERT_EQ(n.load(), 3);
  EXPECT_FALSE(record.overlap.load());
  EXPECT_FALSE(record.bad_range.load());
  EXPECT_GT(record.threads.size(), 1u);
  EXPECT_LE(record.threads.size(), 4u);
}

TEST(Crowd, BadInputGetsClearErrors) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  std::vector<gait::WalkerOptions> characters(3);
  auto build = [&] { gait::Crowd crowd(set, ground, characters); };
  using ::testing::HasSubstr;
  using ::testing::ThrowsMessage;
  characters[2].step_length = 5.0;
  EXPECT_THAT(build, ThrowsMessage<std::invalid_argument>(
                         HasSubstr("character 2: step length must be between")));
  characters[2] = gait::WalkerOptions{};
  characters[1].time_step = 1.0 / 120.0;
  EXPECT_THAT(build, ThrowsMessage<std::invalid_argument>(
                         HasSubstr("character 1: a crowd's characters step together")));
  characters[1] = gait::WalkerOptions{};
  // Per frame nothing throws: a dt no frame has is refused, a step is clamped as a walker's, a
  // character past the crowd answers NaN.
  gait::Crowd crowd(set, ground, characters);
  const gait::WalkerState before = crowd[1].state();
  EXPECT_FALSE(crowd.advance(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_FALSE(crowd.advance(-1.0));
  EXPECT_FALSE(crowd.advance(1e9));
  EXPECT_EQ(fuzzygait::test::state_difference(crowd[1].state(), before), "");
  EXPECT_EQ(crowd.set_step_length(0, 0.1), crowd[0].min_step_length());
  EXPECT_TRUE(std::isnan(crowd.set_step_length(3, 0.7)));
  static_assert(noexcept(crowd.advance(0.0))&& noexcept(crowd.set_step_length(0, 0.7))&& noexcept(
      crowd[0])&& noexcept(crowd.clear_events()));
  gait::CrowdOptions no_finish;
  no_finish.tasks = gait::TaskSystem{};
  no_finish.tasks->enqueue = [](gait::TaskSystem::Task*, std::size_t, std::size_t, void*,
                                void*) -> void* { return nullptr; };
  EXPECT_THAT([&] { gait::Crowd c(set, ground, characters, no_finish); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("needs enqueue, finish")));
  gait::Crowd empty(set, ground, {});
  EXPECT_EQ(empty.size(), 0u);
  EXPECT_TRUE(empty.advance(1.0));
}

}  // namespace

// The C face (fuzzygait/fuzzygait.h): walkers and crowds walk bit for bit as the C++ ones with the
// same options, and every failure comes back as a message, never an exception or a crash.
#include "fuzzygait/fuzzygait.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "fuzzygait/gait/crowd.hpp"
#include "support/walks.hpp"

using namespace fuzzygait;
using ::testing::HasSubstr;

namespace {

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

void expect_pose(const fg_pose& c, const rig::Pose& p) {
  EXPECT_TRUE(same_bits(c.pelvis_x, p.pelvis.x));
  EXPECT_TRUE(same_bits(c.pelvis_y, p.pelvis.y));
  EXPECT_TRUE(same_bits(c.pelvis_tilt, p.pelvis_tilt));
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_TRUE(same_bits(c.legs[k].hip, p.legs[k].hip)) << k;
    EXPECT_TRUE(same_bits(c.legs[k].knee, p.legs[k].knee)) << k;
    EXPECT_TRUE(same_bits(c.legs[k].ankle, p.legs[k].ankle)) << k;
    EXPECT_TRUE(same_bits(c.legs[k].toe, p.legs[k].toe)) << k;
  }
}

TEST(CApi, AWalkerWalksAsTheCppWalker) {
  fg_error error;
  fg_set* set = fg_set_builtin("default", &error);
  ASSERT_NE(set, nullptr) << error.message;
  fg_walker_def def = fg_walker_def_default();
  ASSERT_EQ(fg_segments_from_stature(1.8, &def), 1);
  def.speed = 1.3;
  def.random_start = 1;
  def.start_seed = 11;
  fg_walker* walker = fg_walker_new(set, &def, nullptr, &error);
  ASSERT_NE(walker, nullptr) << error.message;
  EXPECT_EQ(error.failed, 0);

  const terrain::Terrain flat = terrain::Terrain::flat();
  gait::WalkerOptions o;
  o.segments = rig::segments_from_stature(1.8);
  o.speed = 1.3;
  o.start.random = true;
  o.start.seed = 11;
  gait::Walker alone(test::default_set(), o, flat);
  for (int frame = 0; frame < 480; ++frame) {
    if (frame == 240) {
      EXPECT_EQ(fg_walker_set_speed(walker, 1.7), alone.set_speed(1.7));
    }
    ASSERT_EQ(fg_walker_advance(walker, 1.0 / 60.0), 1);
    alone.advance(1.0 / 60.0);
  }
  fg_pose pose;
  fg_walker_pose(walker, &pose);
  expect_pose(pose, alone.pose());
  fg_leg_points points;
  fg_walker_points(walker, FG_LEFT, &points);
  EXPECT_TRUE(same_bits(points.tip.x, alone.points(rig::Side::Left).tip.x));
  EXPECT_EQ(fg_walker_in_contact(walker, FG_RIGHT), alone.in_contact(rig::Side::Right) ? 1 : 0);
  EXPECT_EQ(fg_walker_time(walker), alone.time());
  EXPECT_EQ(fg_walker_step_length(walker), alone.step_length());
  EXPECT_EQ(fg_walker_advance(walker, std::nan("")), 0);
  EXPECT_EQ(fg_walker_advance(walker, -1.0), 0);
  EXPECT_DOUBLE_EQ(fg_walker_set_step_length(walker, 0.7), 0.7);
  fg_walker_free(walker);
  fg_set_free(set);
}

TEST(CApi, ACrowdWalksAsTheCppCrowdOnAGroundOfItsOwn) {
  fg_error error;
  fg_set* set = fg_set_builtin("heavy", &error);
  ASSERT_NE(set, nullptr) << error.message;
  const double xy[] = {-10.0, 0.0, 1.0, 0.0, 6.0, 0.5, 20.0, 0.5};
  fg_ground* ground = fg_ground_polyline(xy, 4, &error);
  ASSERT_NE(ground, nullptr) << error.message;
  EXPECT_DOUBLE_EQ(fg_ground_height(ground, 3.5), 0.25);
  std::vector<fg_walker_def> defs(3, fg_walker_def_default());
  fg_segments_from_stature(1.6, &defs[1]);
  defs[2].speed = 1.2;
  fg_crowd* crowd = fg_crowd_new(set, defs.data(), defs.size(), ground, &error);
  ASSERT_NE(crowd, nullptr) << error.message;
  EXPECT_EQ(fg_crowd_size(crowd), 3u);
  EXPECT_EQ(fg_crowd_workers(crowd), 1u);

  const gait::ControllerSet heavy = gait::ControllerSet::builtin("heavy");
  const terrain::Terrain ramp = terrain::Terrain::polyline({{-10, 0}, {1, 0}, {6, 0.5}, {20, 0.5}});
  std::vector<gait::WalkerOptions> options(3);
  options[1].segments = rig::segments_from_stature(1.6);
  options[2].speed = 1.2;
  gait::Crowd cpp(heavy, ramp, options);
  EXPECT_DOUBLE_EQ(fg_crowd_set_speed(crowd, 2, 1.4), cpp.set_speed(2, 1.4));
  EXPECT_TRUE(std::isnan(fg_crowd_set_speed(crowd, 3, 1.4)));
  for (int frame = 0; frame < 300; ++frame) {
    ASSERT_EQ(fg_crowd_advance(crowd, 1.0 / 60.0), 1);
    cpp.advance(1.0 / 60.0);
  }
  for (std::size_t i = 0; i < 3; ++i) {
    fg_pose pose;
    fg_crowd_pose(crowd, i, &pose);
    expect_pose(pose, cpp[i].pose());
  }
  fg_pose untouched{};
  untouched.pelvis_x = 42.0;
  fg_crowd_pose(crowd, 7, &untouched);
  EXPECT_EQ(untouched.pelvis_x, 42.0);
  fg_crowd_free(crowd);
  fg_ground_free(ground);
  fg_set_free(set);
}

// On the crowd's own threads and on a game's task system (here one that runs every range on the
// calling thread, counting them), 300 characters (ten blocks, in three runs) walk as the C++
// crowd on one thread.
TEST(CApi, ACrowdOnThreadsOrTheGamesTasksWalksAsOnOne) {
  fg_error error;
  fg_set* set = fg_set_builtin("default", &error);
  ASSERT_NE(set, nullptr) << error.message;
  std::vector<fg_walker_def> defs(300, fg_walker_def_default());
  std::vector<gait::WalkerOptions> options(300);
  for (std::size_t i = 0; i < defs.size(); ++i) {
    defs[i].step_length = options[i].step_length = 0.5 + 0.001 * static_cast<double>(i);
  }
  struct Counted {
    std::size_t ranges = 0;
  } counted;
  fg_crowd_def on_game = fg_crowd_def_default();
  on_game.tasks.worker_count = 1;
  on_game.tasks.user_context = &counted;
  on_game.tasks.enqueue = [](fg_task* task, size_t items, size_t min_range, void* task_context,
                             void* user_context) -> void* {
    for (size_t begin = 0; begin < items; begin += min_range) {
      task(begin, std::min(items, begin + min_range), 0, task_context);
      ++static_cast<Counted*>(user_context)->ranges;
    }
    return nullptr;
  };
  on_game.tasks.finish = [](void*, void*) {};
  fg_crowd_def on_two = fg_crowd_def_default();
  on_two.threads = 2;
  fg_crowd* crowds[] = {
      fg_crowd_new_with(set, defs.data(), defs.size(), nullptr, &on_two, &error),
      fg_crowd_new_with(set, defs.data(), defs.size(), nullptr, &on_game, &error)};
  ASSERT_NE(crowds[0], nullptr) << error.message;
  ASSERT_NE(crowds[1], nullptr) << error.message;
  EXPECT_EQ(fg_crowd_workers(crowds[0]), 2u);
  const gait::ControllerSet cpp_set = gait::ControllerSet::builtin("default");
  const terrain::Terrain flat = terrain::Terrain::flat();
  gait::Crowd cpp(cpp_set, flat, options);
  for (int frame = 0; frame < 120; ++frame) {
    cpp.advance(1.0 / 60.0);
    for (fg_crowd* crowd : crowds)
      ASSERT_EQ(fg_crowd_advance(crowd, 1.0 / 60.0), 1);
  }
  EXPECT_EQ(counted.ranges, 120u * 3u);  // three runs of blocks a frame
  for (fg_crowd* crowd : crowds) {
    for (std::size_t i = 0; i < defs.size(); ++i) {
      fg_pose pose;
      fg_crowd_pose(crowd, i, &pose);
      expect_pose(pose, cpp[i].pose());
    }
    fg_crowd_free(crowd);
  }
  fg_crowd_def broken = fg_crowd_def_default();
  broken.tasks.enqueue = on_game.tasks.enqueue;  // no finish
  EXPECT_EQ(fg_crowd_new_with(set, defs.data(), defs.size(), nullptr, &broken, &error), nullptr);
  EXPECT_THAT(error.message, HasSubstr("task system needs enqueue, finish"));
  fg_set_free(set);
}

TEST(CApi, AWalkerStopsAndGoesAsTheCppWalker) {
  fg_error error{};
  fg_set* set = fg_set_builtin("default", &error);
  fg_ground* ground = fg_ground_flat(&error);
  ASSERT_TRUE(set && ground) << error.message;
  fg_walker_def def = fg_walker_def_default();
  def.standing_start = 1;
  fg_walker* c = fg_walker_new(set, &def, ground, &error);
  ASSERT_TRUE(c) << error.message;
  gait::WalkerOptions o;
  o.start.standing = true;
  const terrain::Terrain flat = terrain::Terrain::flat();
  gait::Walker cpp(test::default_set(), o, flat);
  EXPECT_EQ(fg_walker_standing(c), 1);
  for (int frame = 0; frame < 60 * 8; ++frame) {
    if (frame == 30) {
      fg_walker_go(c);
      cpp.go();
    }
    if (frame == 240) {
      fg_walker_stop(c);
      cpp.stop();
    }
    fg_walker_advance(c, 1.0 / 60.0);
    cpp.advance(1.0 / 60.0);
    fg_pose pose;
    fg_walker_pose(c, &pose);
    ASSERT_EQ(pose.pelvis_x, cpp.pose().pelvis.x) << "frame " << frame;
    ASSERT_EQ(fg_walker_standing(c), cpp.standing() ? 1 : 0) << "frame " << frame;
  }
  EXPECT_EQ(fg_walker_standing(c), 1);
  fg_walker_stop(nullptr);
  fg_walker_go(nullptr);
  EXPECT_EQ(fg_walker_standing(nullptr), 0);
  EXPECT_EQ(fg_crowd_stop(nullptr, 0), 0);
  EXPECT_EQ(fg_crowd_go(nullptr, 0), 0);
  fg_walker_free(c);
  fg_ground_free(ground);
  fg_set_free(set);
}

TEST(CApi, FailuresComeBackAsMessages) {
  fg_error error;
  EXPECT_EQ(fg_set_builtin("sprightly", &error), nullptr);
  EXPECT_EQ(error.failed, 1);
  EXPECT_THAT(error.message, HasSubstr("sprightly"));
  EXPECT_EQ(fg_set_load("/no/such/folder", &error), nullptr);
  EXPECT_THAT(error.message, HasSubstr("manifest.json"));
  EXPECT_EQ(fg_set_builtin(nullptr, nullptr), nullptr);  // no error to write: still no crash

  fg_set* set = fg_set_builtin("default", &error);
  ASSERT_NE(set, nullptr);
  fg_walker_def def = fg_walker_def_default();
  def.thigh = -0.1;
  EXPECT_EQ(fg_walker_new(set, &def, nullptr, &error), nullptr);
  EXPECT_THAT(error.message, HasSubstr("segment 'thigh'"));
  def = fg_walker_def_default();
  def.speed = 9.0;
  EXPECT_EQ(fg_walker_new(set, &def, nullptr, &error), nullptr);
  EXPECT_THAT(error.message, HasSubstr("speed must be between"));
  def = fg_walker_def_default();
  def.time_step = 1.0;
  std::vector<fg_walker_def> defs = {fg_walker_def_default(), def};
  EXPECT_EQ(fg_crowd_new(set, defs.data(), defs.size(), nullptr, &error), nullptr);
  EXPECT_THAT(error.message, HasSubstr("character 1"));
  EXPECT_EQ(fg_walker_new(nullptr, &def, nullptr, &error), nullptr);
  EXPECT_THAT(error.message, HasSubstr("no set"));
  const double backwards[] = {1.0, 0.0, 0.0, 0.0};
  EXPECT_EQ(fg_ground_polyline(backwards, 2, &error), nullptr);
  EXPECT_EQ(error.failed, 1);
  EXPECT_GT(std::string(error.message).size(), 0u);
  EXPECT_EQ(fg_segments_from_stature(9.0, &def), 0);
  // A message longer than the buffer is cut, NUL-terminated.
  const std::string long_name(3000, 'x');
  EXPECT_EQ(fg_set_builtin(long_name.c_str(), &error), nullptr);
  EXPECT_EQ(std::string(error.message).size(), sizeof error.message - 1);
  // Calls on no handle do nothing.
  EXPECT_EQ(fg_walker_advance(nullptr, 0.1), 0);
  EXPECT_TRUE(std::isnan(fg_walker_speed(nullptr)));
  fg_walker_free(nullptr);
  fg_set_free(set);
}

}  // namespace

// The walker's contracts: determinism, planted feet that never slide, nothing below the
// ground, the step length it is told, clear errors for bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "runtime/gait/walker_stages.hpp"
#include "support/allocation_counter.hpp"
#include "support/walks.hpp"

using namespace fuzzygait;

namespace {

using fuzzygait::test::default_set;
using fuzzygait::test::make_walker;

TEST(Walker, SameInputsGiveBitIdenticalOutputs) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::Walker a = make_walker(ground);
  gait::Walker b = make_walker(ground);
  for (int i = 0; i < 600; ++i) {
    a.advance(1.0 / 60.0);
    b.advance(1.0 / 60.0);
  }
  // Field by field, bit for bit (memcmp of the whole struct would read padding).
  EXPECT_EQ(fuzzygait::test::state_difference(a.state(), b.state()), "");
  const gait::WalkerState& s = a.state();
  EXPECT_GE(s.heel_strikes, 10u);
}

// The cap on a joint's remembered speed (20 rad/s for hip, knee and ankle) is for awkward
// starts: the default set's walks over the step/stature grid stay below it, so it never shapes
// them. A retuned set that reached it would walk differently from its controllers' word.
TEST(Walker, DefaultWalksStayBelowTheJointSpeedCap) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  double fastest = 0.0;
  for (double step : {0.50, 0.60, 0.70, 0.85}) {
    for (double stature : {1.50, 1.75, 2.00}) {
      gait::Walker w = make_walker(ground, step, stature);
      for (int i = 0; i < 240 * 6; ++i) {
        w.advance(1.0 / 240.0);
        for (const gait::LegState& l : w.state().legs) {
          fastest = std::max({fastest, std::abs(l.velocity.hip), std::abs(l.velocity.knee),
                              std::abs(l.velocity.ankle)});
        }
      }
    }
  }
  EXPECT_GT(fastest, 10.0);  // the swing knee does move fast
  EXPECT_LT(fastest, 19.0) << "rad/s";
}

TEST(Walker, PlantedFeetNeverSlideAndNothingGoesBelowTheGround) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::Walker w = make_walker(ground);
  std::array<rig::Point, 2> anchor{};
  std::array<gait::Phase, 2> phase{gait::Phase::Swing, gait::Phase::Swing};
  for (int i = 0; i < 240 * 8; ++i) {
    w.advance(1.0 / 240.0);
    for (rig::Side side : rig::kSides) {
      const int s = rig::index(side);
      const gait::LegState& l = w.state().legs[static_cast<std::size_t>(s)];
      const rig::LegPoints p = w.points(side);
      for (const rig::Point& q : {p.heel, p.ball, p.tip}) {
        ASSERT_GE(q.y, ground.height(q.x) - 1e-9) << "frame " << i;
      }
      if (l.phase == gait::Phase::Swing) {
        phase[static_cast<std::size_t>(s)] = l.phase;
        continue;
      }
      // The contact point sits on its anchor, and the anchor stays put while the phase lasts.
      const rig::Point c = l.phase == gait::Phase::Ball ? p.ball : p.heel;
      EXPECT_NEAR(c.x, l.anchor.x, 1e-9);
      EXPECT_NEAR(c.y, l.anchor.y, 1e-9);
      if (phase[static_cast<std::size_t>(s)] == l.phase) {
        EXPECT_EQ(anchor[static_cast<std::size_t>(s)].x, l.anchor.x);
        EXPECT_EQ(anchor[static_cast<std::size_t>(s)].y, l.anchor.y);
      }
      anchor[static_cast<std::size_t>(s)] = l.anchor;
      phase[static_cast<std::size_t>(s)] = l.phase;
    }
  }
  EXPECT_GE(w.state().heel_strikes, 12u);
}

TEST(Walker, ChangingTheStepLengthTakesEffect) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::Walker w = make_walker(ground, 0.70);
  w.advance(4.0);
  w.set_step_length(0.55);
  w.clear_events();
  w.advance(6.0);
  std::vector<double> strikes;
  for (const gait::EventRecord& e : w.events()) {
    if (e.event == gait::Event::HeelStrike) strikes.push_back(e.where.x);
  }
  ASSERT_GE(strikes.size(), 6u);
  for (std::size_t i = strikes.size() - 4; i < strikes.size(); ++i) {
    EXPECT_NEAR(strikes[i] - strikes[i - 1], 0.55, 0.55 * 0.03);
  }
}

TEST(Walker, BadInputGetsClearErrors) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::WalkerOptions o;
  o.step_length = 3.0;  // longer than these legs reach
  try {
    gait::Walker w(default_set(), o, ground);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("step length must be between"), std::string::npos);
  }
  o.step_length = std::nan("");
  EXPECT_THROW(gait::Walker(default_set(), o, ground), std::invalid_argument);
  o.step_length = 0.7;
  o.segments.shank = 0.0;  // a leg of length zero
  try {
    gait::Walker w(default_set(), o, ground);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'shank'"), std::string::npos);
  }
  // The per-frame calls refuse a dt no frame has (NaN, negative, a broken timer's) without
  // throwing, leaving the walker as it was: no days of sub-steps or an overflowing count of them.
  gait::Walker w = make_walker(ground);
  const gait::WalkerState before = w.state();
  for (double dt : {std::nan(""), -1.0, -0.0 - 1e-300, 3600.5, 1e12, 1e300,
                    std::numeric_limits<double>::infinity()}) {
    EXPECT_FALSE(w.advance(dt)) << dt;
  }
  EXPECT_EQ(test::state_difference(w.state(), before), "");
  EXPECT_TRUE(w.advance(0.0));
  EXPECT_EQ(test::state_difference(w.state(), before), "");
  static_assert(
      noexcept(w.advance(0.0))&& noexcept(w.set_step_length(0.7))&& noexcept(w.pose())&& noexcept(
          w.points(
              rig::Side::Left))&& noexcept(w
                                               .in_contact(
                                                   rig::Side::Left))&& noexcept(w.clear_events()));
  o.segments = rig::segments_from_stature(1.75);
  // Joint limits that cannot clamp anything (clamping to them was undefined).
  for (double knee : {std::nan(""), std::numeric_limits<double>::infinity(), 3.0}) {
    gait::WalkerOptions bad = o;
    bad.limits.minimum.knee = knee;  // 3 rad lies above the knee's maximum
    try {
      gait::Walker walker(default_set(), bad, ground);
      ADD_FAILURE() << knee;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("joint limits of the knee"), std::string::npos);
    }
  }
  for (double h : {0.0, 1e-12, 0.06, std::nan("")}) {
    o.time_step = h;
    EXPECT_THROW(gait::Walker(default_set(), o, ground), std::invalid_argument) << h;
  }
  // Step lengths are clamped to what the set walks and the legs reach (0.46 to 1.2 leg lengths
  // for the default); NaN changes nothing. The limits themselves are taken.
  const double shortest = gait::Walker::min_step_length(default_set(), w.segments());
  const double longest = gait::Walker::max_step_length(w.segments());
  EXPECT_NEAR(shortest, 0.46 * w.segments().leg_length(), 1e-12);
  EXPECT_EQ(w.min_step_length(), shortest);
  EXPECT_EQ(w.max_step_length(), longest);
  EXPECT_EQ(w.set_step_length(-0.1), shortest);
  EXPECT_EQ(w.set_step_length(0.99 * shortest), shortest);
  EXPECT_EQ(w.set_step_length(std::nan("")), shortest);
  EXPECT_EQ(w.set_step_length(1e300), longest);
  EXPECT_EQ(w.set_step_length(0.65), 0.65);
  EXPECT_EQ(w.step_length(), 0.65);
  EXPECT_EQ(w.set_step_length(std::nan("")), 0.65);
  // At construction a step out of range is an error that names both ends.
  o.time_step = 1.0 / 240.0;
  o.step_length = 0.99 * shortest;
  try {
    gait::Walker walker(default_set(), o, ground);
    ADD_FAILURE() << "a step of 0.45 leg lengths was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("(0.46 leg lengths, the shortest 'default' walks)"),
              std::string::npos)
        << e.what();
  }
}

// A walker keeps its last event_capacity events, the same as the default keeps, and none at 0.
TEST(Walker, KeepsItsLastEventsUpToItsCapacity) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::WalkerOptions o;
  gait::Walker all(default_set(), o, ground);
  o.event_capacity = 5;
  gait::Walker five(default_set(), o, ground);
  o.event_capacity = 0;
  gait::Walker none(default_set(), o, ground);
  for (gait::Walker* w : {&all, &five, &none})
    w->advance(3.0);  // about 24 events
  ASSERT_GT(all.events().size(), 5u);
  ASSERT_EQ(five.events().size(), 5u);
  EXPECT_TRUE(none.events().empty());
  const std::size_t skip = all.events().size() - 5;
  for (std::size_t i = 0; i < 5; ++i) {
    const gait::EventRecord& a = all.events()[skip + i];
    const gait::EventRecord& b = five.events()[i];
    EXPECT_EQ(a.time, b.time);
    EXPECT_EQ(a.event, b.event);
    EXPECT_EQ(a.side, b.side);
    EXPECT_EQ(a.where.x, b.where.x);
  }
  // The walks themselves are the same bits.
  EXPECT_EQ(all.state().pelvis.x, none.state().pelvis.x);
  EXPECT_EQ(all.state().legs[0].angles.knee, five.state().legs[0].angles.knee);
  o.event_capacity = gait::Walker::kMostEvents + 1;
  try {
    gait::Walker w(default_set(), o, ground);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("event capacity must be at most 4096"), std::string::npos)
        << e.what();
  }
}

TEST(Walker, AdvancingAllocatesNothing) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::Walker w = make_walker(ground);
  w.advance(1.0);  // past the start
  const long before = fuzzygait::testing::allocation_count();
  for (int i = 0; i < 600; ++i) {
    w.advance(1.0 / 60.0);
    w.clear_events();
    (void)w.pose();
    (void)w.points(rig::Side::Left);
  }
  EXPECT_EQ(fuzzygait::testing::allocation_count(), before);
}

// Walking by speed and changing it, or going back to a step length, allocates nothing either.
TEST(Walker, ChangingSpeedAllocatesNothing) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::WalkerOptions o;
  o.speed = 1.2;
  gait::Walker w(fuzzygait::test::default_set(), o, ground);
  w.advance(1.0);
  const long before = fuzzygait::testing::allocation_count();
  for (int i = 0; i < 600; ++i) {
    if (i % 100 == 0) w.set_speed(1.6);
    if (i % 100 == 50) w.set_speed(0.9);
    if (i == 333) w.set_step_length(0.7);
    if (i == 400) w.set_speed(1.2);
    (void)w.min_speed();
    w.advance(1.0 / 60.0);
    w.clear_events();
  }
  EXPECT_EQ(fuzzygait::testing::allocation_count(), before);
}

// Every shipped controller, the slots', the terrain words' and the upper body's (a rule out of
// row-major order would put one on the general engine unnoticed: the sway's was, until
// 2026-12-07).
TEST(Walker, ControllersRunOnTheFastPath) {
  for (const std::string& name : gait::ControllerSet::builtin_names()) {
    const gait::ControllerSet set = gait::ControllerSet::builtin(name);
    std::vector<const gait::Controller*> all;
    for (const gait::Controller& c : set.controllers)
      all.push_back(&c);
    for (const gait::Controller& c : set.terrain_controllers)
      all.push_back(&c);
    for (const std::optional<gait::Controller>& c : set.upper_body) {
      EXPECT_TRUE(c.has_value()) << name << ": every shipped set has its whole upper body";
      if (c) all.push_back(&*c);
    }
    for (const gait::Controller* c : all) {
      EXPECT_TRUE(c->fast_path()) << c->source();
      EXPECT_NE(c->packed(), nullptr) << c->source();
    }
  }
}

// A controller that answers NaN or an infinity commands nothing: the joint's velocity eases to
// zero, exactly as if the controller had answered 0 (the same walk to the bit), and the walk stays
// finite.
TEST(Walker, NonFiniteCommandsAreNoCommand) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  const gait::ControllerSet& set = test::default_set();
  std::vector<fuzzy::Workspace> workspaces;
  for (const gait::Controller& c : set.controllers)
    workspaces.push_back(c.make_workspace());
  // Per slot (swing hip, knee, ankle, toe, then stance): what replaces the controller's answer
  // every third call (eight calls a time step, so every leg's every joint in turn); the others
  // pass it through.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::array<double, gait::kSlotCount> odd = {nan, inf, -inf, nan, -inf, nan, inf, -inf};
  auto backend = [&](bool zero) {
    return
        [&set, &workspaces, odd, zero, calls = 0L](int slot, const gait::MetricValues& m) mutable {
          const auto s = static_cast<std::size_t>(slot);
          const double answer = set.controllers[s].evaluate(m, workspaces[s]);
          return ++calls % 3 == 0 ? (zero ? 0.0 : odd[s]) : answer;
        };
  };
  for (const gait::StartPose start : {gait::StartPose{}, gait::StartPose{true, 3, 0.0}}) {
    gait::WalkerOptions options;
    options.start = start;
    const gait::detail::ControllerBackend with_odd{backend(false)};
    const gait::detail::ControllerBackend with_zero{backend(true)};
    gait::Walker a = gait::detail::WalkerStages::make_walker(set, options, ground, &with_odd);
    gait::Walker b = gait::detail::WalkerStages::make_walker(set, options, ground, &with_zero);
    EXPECT_EQ(test::walk_side_by_side(a, b, 300), "");
    EXPECT_GE(a.state().heel_strikes, 5u);
    EXPECT_TRUE(std::isfinite(a.state().pelvis.x) && std::isfinite(a.state().pelvis.y));
  }
}

// The walker's controllers run on the packed fast path; the same set run through the general
// fuzzy evaluator (as a controller back end) must give the same walk to the bit, so the fast path
// reads the right metrics and keeps the engines' arithmetic.
TEST(Walker, FastPathWalksAsTheGeneralEvaluator) {
  const terrain::Terrain ground = terrain::Terrain::polyline(
      {{-10.0, 0.0}, {2.0, 0.0}, {4.0, 0.2}, {6.0, 0.2}, {6.001, 0.1}, {20.0, 0.1}});
  for (const std::string& name : gait::ControllerSet::builtin_names()) {
    const gait::ControllerSet set = gait::ControllerSet::builtin(name);
    // Every controller, the slots' and the terrain words' (the ramp and the kerb fire them).
    std::vector<const gait::Controller*> controllers;
    for (const gait::Controller& c : set.controllers)
      controllers.push_back(&c);
    for (const gait::Controller& c : set.terrain_controllers)
      controllers.push_back(&c);
    std::vector<fuzzy::Evaluator> evaluators;
    std::vector<fuzzy::Workspace> workspaces;
    for (const gait::Controller* c : controllers) {
      evaluators.emplace_back(c->engine());
      workspaces.push_back(evaluators.back().make_workspace());
    }
    long calls = 0;
    gait::detail::ControllerBackend general;
    general.evaluate = [&](int slot, const gait::MetricValues& metrics) {
      const auto s = static_cast<std::size_t>(slot);
      const gait::Controller& c = *controllers[s];
      double in[2] = {};
      for (std::size_t i = 0; i < c.input_count(); ++i)
        in[i] = metrics[static_cast<std::size_t>(c.input(i))];
      double out = 0.0;
      evaluators[s].evaluate(std::span<const double>(in, c.input_count()),
                             std::span<double>(&out, 1), workspaces[s]);
      ++calls;
      return out;
    };
    for (const gait::StartPose start : {gait::StartPose{}, gait::StartPose{true, 7, 0.0}}) {
      gait::WalkerOptions options;
      options.start = start;
      gait::Walker a(set, options, ground);
      gait::Walker b = gait::detail::WalkerStages::make_walker(set, options, ground, &general);
      EXPECT_EQ(test::walk_side_by_side(a, b, 600), "")
          << name << ", start " << (start.random ? "random" : "default");
      EXPECT_GE(a.state().heel_strikes, 10u) << name;
    }
    EXPECT_GT(calls, 8 * 4 * 600) << name;
  }
}

}  // namespace

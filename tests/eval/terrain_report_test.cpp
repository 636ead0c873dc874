// The terrain measures of eval::evaluate_terrain, checked on walks built by hand whose answers are
// known: feet placed on chosen footholds at chosen pitches, swings passing edges at a chosen
// height, a pelvis rising by a chosen height per stride, joint angles with known peaks.
#include "fuzzygait/eval/terrain_report.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::eval {
namespace {

using rig::Point;
using terrain::Terrain;
using ::testing::HasSubstr;

constexpr double kPi = std::numbers::pi;
constexpr int kCycle = 100;  // frames a gait cycle (1 s at 100 fps)
constexpr int kStance = 60;  // frames of stance: 60 %
constexpr int kSwing = kCycle - kStance;
constexpr int kFirstStrike = 10;  // foothold 0's strike; foothold n strikes 50 n frames later

double radians(double degrees) {
  return degrees * kPi / 180.0;
}

// A walk planned foothold by foothold: foothold n (n >= -2) is struck at frame 10 + 50 n by the
// left foot for even n, the right for odd n, which stands on it for 60 frames, then swings 40
// frames to foothold n + 2: 8 frames lifting straight up to `top` above the higher of the ground
// under the swing, 24 frames across at that height (sole level), 8 frames down onto the next
// foothold (8/9 of the way; the strike frame puts it there).
struct Plan {
  const Terrain* ground = nullptr;
  std::function<double(int)> heel_x;  // where foothold n puts the heel
  double clearance = 0.04;            // m, the sole above the highest ground under the swing
  // Radians: the foot's pitch at the strike frame of foothold n, about the ball when toe-down
  // of the surface, about the heel when toe-up; NaN lands the foot flat on the surface.
  std::function<double(int)> landing_pitch = [](int) {
    return std::numeric_limits<double>::quiet_NaN();
  };
  double stance_tilt = 0.0;  // radians added to the surface's angle in stance (after the strike)
  std::function<double(double)> pelvis_height = [](double t) { return 0.9 + 0.0 * t; };
  int frames = 0;
};

struct FootPlace {
  Point heel;
  double pitch = 0.0;
  double toes = std::numeric_limits<double>::quiet_NaN();  // the toes' pitch; NaN: the foot's
};

rig::LegPoints place_foot(const rig::Segments& s, FootPlace f) {
  const double c = std::cos(f.pitch);
  const double d = std::sin(f.pitch);
  const double toes = std::isnan(f.toes) ? f.pitch : f.toes;
  rig::LegPoints p;
  p.heel = f.heel;
  p.ball = {f.heel.x + (s.heel + s.ball) * c, f.heel.y + (s.heel + s.ball) * d};
  p.tip = {p.ball.x + s.toe * std::cos(toes), p.ball.y + s.toe * std::sin(toes)};
  p.ankle = {f.heel.x + s.heel * c - s.ankle_height * d,
             f.heel.y + s.heel * d + s.ankle_height * c};
  p.knee = {p.ankle.x, p.ankle.y + s.shank};
  p.hip = {p.knee.x, p.knee.y + s.thigh};
  return p;
}

int strike_frame(int n) {
  return kFirstStrike + 50 * n;
}

// The foot standing on foothold n: on the surface, pitched by it (plus `tilt`).
FootPlace stance_place(const Plan& plan, int n, double tilt) {
  const double x = plan.heel_x(n);
  const double angle = plan.ground->slope(x + 0.05) + tilt;
  return {{x, plan.ground->height(x)}, angle};
}

Motion planned_walk(const Plan& plan) {
  Motion m;
  m.fps = 100.0;
  m.segments = rig::segments_from_stature(1.75);
  const rig::Segments& s = m.segments;
  const double sole = s.heel + s.ball + s.toe;
  for (int i = 0; i < plan.frames; ++i) {
    Frame f;
    f.time = i / m.fps;
    for (int side = 0; side < 2; ++side) {
      // The latest foothold of this side struck at or before frame i.
      int n = side - 2;
      while (strike_frame(n + 2) <= i)
        n += 2;
      const int since = i - strike_frame(n);
      FootPlace place;
      rig::LegAngles angles;
      bool contact = since < kStance;
      if (contact) {
        place = stance_place(plan, n, plan.stance_tilt);
        const double landing = plan.landing_pitch(n);
        if (since == 0 && !std::isnan(landing)) {
          const FootPlace flat = stance_place(plan, n, 0.0);
          const rig::LegPoints on = place_foot(s, flat);
          if (landing < flat.pitch) {  // toe-down: about the ball, the toes on the ground
            place = {{on.ball.x - (s.heel + s.ball) * std::cos(landing),
                      on.ball.y - (s.heel + s.ball) * std::sin(landing)},
                     landing,
                     flat.pitch};
          } else {
            place = {flat.heel, landing};
          }
        }
        // Hip falls from 60 to 30 deg over stance; the knee bends 10 deg at 25 % of the cycle.
        angles.hip = radians(60.0 - 0.5 * since);
        angles.knee = radians(20.0 + 10.0 * std::sin(kPi * since / kStance));
        angles.ankle = radians(10.0);
      } else {
        const int k = since - kStance;  // 0..39
        const FootPlace from = stance_place(plan, n, 0.0);
        const FootPlace to = stance_place(plan, n + 2, 0.0);
        double highest = std::max(from.heel.y, to.heel.y);
        for (const Point& p : plan.ground->profile(from.heel.x, to.heel.x + sole))
          highest = std::max(highest, p.y);
        const double top = highest + plan.clearance;
        if (k < 8) {
          place = {{from.heel.x, from.heel.y + (k + 1) / 8.0 * (top - from.heel.y)}, 0.0};
        } else if (k < 32) {
          const double share = (k - 7) / 24.0;
          place = {{from.heel.x + share * (to.heel.x - from.heel.x), top}, 0.0};
        } else {
          const double share = (k - 31) / 9.0;
          place = {{to.heel.x, top + share * (to.heel.y - top)}, share * to.pitch};
        }
        angles.hip = radians(30.0 + 40.0 * std::sin(kPi * k / kSwing));
        angles.knee = radians(20.0 + 75.0 * std::sin(kPi * k / kSwing));
        angles.ankle = radians(0.0);
      }
      f.points[static_cast<std::size_t>(side)] = place_foot(s, place);
      f.pose.legs[static_cast<std::size_t>(side)] = angles;
      f.contact[static_cast<std::size_t>(side)] = contact;
    }
    f.pose.pelvis = {0.5 * (f.points[0].heel.x + f.points[1].heel.x) + 0.1,
                     plan.pelvis_height(f.time)};
    for (rig::LegPoints& p : f.points)
      p.hip = f.pose.pelvis;
    m.frames.push_back(f);
  }
  return m;
}

// Stairs of 0.17 x 0.40 m, 8 steps from x = 1 (up or down): foothold n on tread n, the heel
// 0.07 m past the riser behind it, the toe tip 0.063 m before the next (footholds 0 and below on
// the ground before, 9 and 10 on the landing).
Plan stair_plan(const Terrain& stairs) {
  Plan plan;
  plan.ground = &stairs;
  plan.heel_x = [](int n) { return 1.0 + 0.4 * (n - 1) + 0.001 + 0.07; };
  plan.frames = strike_frame(10) + 1;
  return plan;
}

const TerrainGroup* group(const TerrainReport& r, Footing footing, int degrees = 0) {
  for (const TerrainGroup& g : r.groups) {
    if (g.footing == footing && g.degrees == degrees) return &g;
  }
  return nullptr;
}

TEST(TerrainReport, StairStepsAreFoundWithTheirTreadsAndTheLanding) {
  const Terrain stairs = Terrain::stairs(0.17, 0.40, 8);
  const Motion walk = planned_walk(stair_plan(stairs));
  const TerrainReport r = evaluate_terrain(walk, stairs);
  ASSERT_EQ(r.steps.size(), 11u);
  for (int n = 0; n <= 10; ++n) {
    const TerrainStep& step = r.steps[static_cast<std::size_t>(n)];
    EXPECT_EQ(step.side, n % 2 == 0 ? rig::Side::Left : rig::Side::Right) << n;
    EXPECT_EQ(step.frame, static_cast<std::size_t>(strike_frame(n))) << n;
    EXPECT_NEAR(step.x, 1.0 + 0.4 * (n - 1) + 0.071, 1e-12) << n;
    EXPECT_EQ(step.run, static_cast<std::size_t>(std::clamp(n, 0, 8))) << n;
    const Footing expected = n == 0 || n >= 9 ? Footing::Level : Footing::StairUp;
    EXPECT_EQ(step.footing, expected) << n;
    EXPECT_NEAR(step.height, 0.17 * std::clamp(n, 0, 8), 1e-9) << n;
    if (n > 0) {
      EXPECT_NEAR(step.rise, n <= 8 ? 0.17 : 0.0, 1e-9) << n;
      EXPECT_NEAR(step.step_length, 0.4, 1e-12) << n;
    }
  }
  EXPECT_EQ(r.runs, 9u);
  EXPECT_EQ(r.last_run, 8u);
  ASSERT_TRUE(r.reached_end.has_value());
  EXPECT_TRUE(*r.reached_end);
  ASSERT_NE(group(r, Footing::StairUp), nullptr);
  EXPECT_EQ(group(r, Footing::StairUp)->steps, 8);
  EXPECT_EQ(group(r, Footing::Level)->steps, 3);
  // Cut before the landing, the walk does not reach the end.
  Motion short_walk = walk;
  short_walk.frames.resize(static_cast<std::size_t>(strike_frame(7) + 5));
  const TerrainReport cut = evaluate_terrain(short_walk, stairs);
  EXPECT_EQ(cut.last_run, 7u);
  ASSERT_TRUE(cut.reached_end.has_value());
  EXPECT_FALSE(*cut.reached_end);
  // Ground of one run has no end to reach.
  EXPECT_FALSE(evaluate_terrain(walk, Terrain::flat()).reached_end.has_value());
}

TEST(TerrainReport, AnglesAtContactAndOverTheCycleAreTheWalksOwn) {
  const Terrain stairs = Terrain::stairs(0.17, 0.40, 8);
  const TerrainReport r = evaluate_terrain(planned_walk(stair_plan(stairs)), stairs);
  for (std::size_t n = 0; n + 2 < r.steps.size(); ++n) {
    const TerrainStep& s = r.steps[n];
    EXPECT_NEAR(s.hip, 60.0, 1e-9) << n;
    EXPECT_NEAR(s.knee, 20.0, 1e-9) << n;
    EXPECT_NEAR(s.ankle, 10.0, 1e-9) << n;
    EXPECT_NEAR(s.early_stance_knee, 30.0, 1e-9) << n;  // the bump at 30 frames
    EXPECT_NEAR(s.knee_at_toe_off, 20.0, 1e-9) << n;
    EXPECT_NEAR(s.mid_stance_ankle, 10.0, 1e-9) << n;
    EXPECT_NEAR(s.peak_swing_knee, 95.0, 1e-9) << n;
    EXPECT_NEAR(s.peak_swing_hip, 70.0, 1e-9) << n;
    EXPECT_NEAR(s.hip_range, 40.0, 1e-9) << n;  // 30 at toe off to 70 in swing
    EXPECT_NEAR(s.stance_percent, 60.0, 1e-9) << n;
    EXPECT_NEAR(s.cycle_time, 1.0, 1e-12) << n;
    EXPECT_NEAR(s.cadence, 120.0, 1e-9) << n;
  }
  // The last two steps' cycles end after the walk: NaN, not counted.
  EXPECT_TRUE(std::isnan(r.steps.back().peak_swing_knee));
  EXPECT_TRUE(std::isnan(r.steps.back().stance_percent));
  EXPECT_NEAR(r.cadence, 120.0, 1e-9);
  const TerrainGroup* up = group(r, Footing::StairUp);
  ASSERT_NE(up, nullptr);
  EXPECT_EQ(up->peak_swing_knee.count, 8);
  EXPECT_NEAR(up->peak_swing_knee.mean, 95.0, 1e-9);
  EXPECT_NEAR(up->stance_percent.min, 60.0, 1e-9);
  EXPECT_NEAR(up->stance_percent.max, 60.0, 1e-9);
}

TEST(TerrainReport, AFootPitchedAtContactIsMeasuredAgainstLevelSteps) {
  // Stair steps land on the ball pitched 20 deg toe-down; level steps flat.
  const Terrain stairs = Terrain::stairs(0.17, 0.40, 8);
  Plan plan = stair_plan(stairs);
  plan.landing_pitch = [](int n) {
    return n >= 1 && n <= 8 ? radians(-20.0) : std::numeric_limits<double>::quiet_NaN();
  };
  const Motion walk = planned_walk(plan);
  const TerrainReport r = evaluate_terrain(walk, stairs);
  ASSERT_EQ(r.steps.size(), 11u);
  for (int n = 0; n <= 10; ++n) {
    const TerrainStep& s = r.steps[static_cast<std::size_t>(n)];
    const bool stair = n >= 1 && n <= 8;
    EXPECT_EQ(s.footing, stair ? Footing::StairUp : Footing::Level) << n;
    EXPECT_NEAR(s.foot_pitch, stair ? -20.0 : 0.0, 1e-9) << n;
    EXPECT_EQ(s.forefoot, stair) << n;
    // The foothold is the ball on a forefoot landing, the heel otherwise.
    const double ball = walk.segments.heel + walk.segments.ball;
    EXPECT_NEAR(s.x, plan.heel_x(n) + (stair ? ball : 0.0), 1e-9) << n;
  }
  for (const PointContact& c : r.points) {  // (rounding puts a toe 1e-17 m down)
    EXPECT_NEAR(c.max_slip, 0.0, 1e-12);
    EXPECT_NEAR(c.max_penetration, 0.0, 1e-12);
  }
  const TerrainGroup* up = group(r, Footing::StairUp);
  ASSERT_NE(up, nullptr);
  EXPECT_NEAR(up->foot_pitch.mean, -20.0, 1e-9);
  EXPECT_NEAR(up->toe_down_vs_level, 20.0, 1e-9);
  EXPECT_DOUBLE_EQ(up->forefoot_percent, 100.0);
  EXPECT_DOUBLE_EQ(group(r, Footing::Level)->forefoot_percent, 0.0);
}

TEST(TerrainReport, SwingsClearEachNosingByTheirPlannedHeight) {
  // Every swing passes its highest ground 40 mm up, sole level: over the nosing of the tread it
  // lands on going up, over the nosing of the tread it leaves going down.
  for (const double rise : {0.17, -0.17}) {
    const Terrain stairs = Terrain::stairs(rise, 0.40, 8);
    Plan plan = stair_plan(stairs);
    plan.clearance = 0.04;
    const TerrainReport r = evaluate_terrain(planned_walk(plan), stairs);
    const std::string where = rise > 0.0 ? "up" : "down";
    ASSERT_EQ(r.steps.size(), 11u) << where;
    for (int n = 0; n <= 8; ++n) {
      const TerrainStep& s = r.steps[static_cast<std::size_t>(n)];
      // The nosings between foothold n and n + 2: the treads n + 1 and n + 2 (up), or the front
      // edges of treads n and n + 1 (down); the landing has none.
      const int expected = n <= 6 ? 2 : (n == 7 ? 1 : 0);
      ASSERT_EQ(s.edges.size(), static_cast<std::size_t>(expected)) << where << " " << n;
      if (expected == 0) {
        EXPECT_TRUE(std::isnan(s.edge_tip)) << n;
        continue;
      }
      for (const EdgeClearance& e : s.edges)
        EXPECT_TRUE(e.nosing) << where << " " << n;
      EXPECT_NEAR(s.edge_tip, 0.04, 1e-9) << where << " " << n;
      EXPECT_NEAR(s.edge_heel, 0.04, 1e-9) << where << " " << n;
      EXPECT_NEAR(s.edge_foot, 0.04, 1e-9) << where << " " << n;
      if (expected == 2) {
        // The other nosing is a riser further from the sole: 40 + 170 mm.
        const EdgeClearance& far = rise > 0.0 ? s.edges[0] : s.edges[1];
        EXPECT_NEAR(far.tip, 0.21, 1e-9) << where << " " << n;
      }
    }
    EXPECT_NEAR(r.min_edge_tip, 0.04, 1e-9) << where;
    EXPECT_NEAR(r.min_swing_clearance, 0.04, 1e-9) << where;
    EXPECT_TRUE(missed_contact_bounds(r).empty()) << where;
    // 5 mm clears the ground by less than the 10 mm bound.
    plan.clearance = 0.005;
    const TerrainReport low = evaluate_terrain(planned_walk(plan), stairs);
    EXPECT_NEAR(low.min_swing_clearance, 0.005, 1e-9) << where;
    EXPECT_THAT(missed_contact_bounds(low),
                ::testing::ElementsAre("swing clearance 5.00 mm (bound 10 mm)"))
        << where;
  }
}

TEST(TerrainReport, AToeBelowANosingButBeforeItsRiserIsNotOverIt) {
  // The heel 0.101 m past a riser puts the toe tip 32 mm before the next: lifting, it rises
  // within 5 cm of the nosing above, but in front of the riser, over the lower tread.
  const Terrain stairs = Terrain::stairs(0.17, 0.40, 8);
  Plan plan = stair_plan(stairs);
  plan.heel_x = [](int n) { return 1.0 + 0.4 * (n - 1) + 0.001 + 0.101; };
  const TerrainReport r = evaluate_terrain(planned_walk(plan), stairs);
  for (int n = 0; n <= 6; ++n) {
    const TerrainStep& s = r.steps[static_cast<std::size_t>(n)];
    EXPECT_NEAR(s.edge_tip, 0.04, 1e-9) << n;
    EXPECT_NEAR(s.edge_heel, 0.04, 1e-9) << n;
    // The sole outline passes that nosing 32 mm away in x, nearer than 40 mm as sampled.
    EXPECT_GT(s.edge_foot, 0.032) << n;
    EXPECT_LT(s.edge_foot, 0.039) << n;
  }
}

TEST(TerrainReport, StairsDownAreFoundAsDescent) {
  const Terrain stairs = Terrain::stairs(-0.17, 0.40, 8);
  const TerrainReport r = evaluate_terrain(planned_walk(stair_plan(stairs)), stairs);
  for (int n = 1; n <= 8; ++n) {
    const TerrainStep& s = r.steps[static_cast<std::size_t>(n)];
    EXPECT_EQ(s.footing, Footing::StairDown) << n;
    EXPECT_NEAR(s.rise, -0.17, 1e-9) << n;
    EXPECT_EQ(s.run, static_cast<std::size_t>(n)) << n;
  }
  EXPECT_EQ(group(r, Footing::StairDown)->steps, 8);
  EXPECT_TRUE(*r.reached_end);
}

TEST(TerrainReport, ThePelvisRiseIsSetAgainstTheGroundsPerStride) {
  const Terrain stairs = Terrain::stairs(0.17, 0.40, 8);
  Plan plan = stair_plan(stairs);
  plan.pelvis_height = [](double t) { return 0.9 + 0.34 * t; };  // 0.34 m a 1 s cycle
  const TerrainReport r = evaluate_terrain(planned_walk(plan), stairs);
  for (int n = 0; n <= 8; ++n) {
    const TerrainStep& s = r.steps[static_cast<std::size_t>(n)];
    EXPECT_NEAR(s.pelvis_rise, 0.34, 1e-9) << n;
    // Two treads a stride, then onto the landing (one tread), then along it.
    EXPECT_NEAR(s.ground_rise, n <= 6 ? 0.34 : (n == 7 ? 0.17 : 0.0), 1e-9) << n;
  }
  const TerrainGroup* up = group(r, Footing::StairUp);
  EXPECT_NEAR(up->pelvis_rise.mean, 0.34, 1e-9);
}

TEST(TerrainReport, OnARampTheSoleIsMeasuredAgainstTheSurface) {
  for (const double degrees : {10.0, -10.0}) {
    const Terrain ramp = Terrain::ramp(degrees);
    Plan plan;
    plan.ground = &ramp;
    plan.heel_x = [](int n) { return 1.5 + 0.35 * n; };
    plan.stance_tilt = radians(3.0);  // the foot lies 3 deg toes-up of the surface
    plan.frames = strike_frame(10) + 1;
    const TerrainReport r = evaluate_terrain(planned_walk(plan), ramp);
    const Footing footing = degrees > 0.0 ? Footing::RampUp : Footing::RampDown;
    ASSERT_EQ(r.groups.size(), 1u) << degrees;
    EXPECT_EQ(r.groups[0].footing, footing);
    EXPECT_EQ(r.groups[0].degrees, static_cast<int>(degrees));
    EXPECT_EQ(r.groups[0].steps, 11);
    for (const TerrainStep& s : r.steps) {
      EXPECT_NEAR(s.surface, degrees, 1e-9);
      EXPECT_NEAR(s.foot_pitch, degrees + 3.0, 1e-9);
      EXPECT_EQ(s.run, 0u);
    }
    EXPECT_NEAR(r.groups[0].mid_stance_sole.mean, 3.0, 1e-9) << degrees;
    EXPECT_NEAR(r.groups[0].mid_stance_sole.max, 3.0, 1e-9) << degrees;
    EXPECT_TRUE(std::isnan(r.groups[0].toe_down_vs_level));  // no level steps
    EXPECT_FALSE(r.reached_end.has_value());
  }
}

TEST(TerrainReport, EveryLegPointSlipsAndPenetratesAsPlaced) {
  const Terrain stairs = Terrain::stairs(0.17, 0.40, 8);
  Motion walk = planned_walk(stair_plan(stairs));
  // The right foot on tread 3 slides forward 2 mm a frame for 10 frames, then holds.
  const int start = strike_frame(3) + 10;
  for (int i = start; i < strike_frame(3) + kStance; ++i) {
    const double shift = 0.002 * std::min(i - start, 10);
    rig::LegPoints& p = walk.frames[static_cast<std::size_t>(i)].points[1];
    for (Point* q : {&p.heel, &p.ball, &p.tip, &p.ankle, &p.knee})
      q->x += shift;
  }
  // One frame puts the left knee 10.6 mm behind the face of riser 5, 70 mm above its foot (and
  // 100 mm below the tread): the depth is the distance to the face.
  const double riser = 1.0 + 0.4 * 4;
  walk.frames[300].points[0].knee = {riser + 0.011, 0.17 * 4 + 0.07};
  const TerrainReport r = evaluate_terrain(walk, stairs);
  for (std::size_t p = 2; p < 5; ++p) {  // heel, ball, tip
    EXPECT_NEAR(r.points[p].max_slip, 0.002, 1e-9) << kContactPoints[p];
    EXPECT_DOUBLE_EQ(r.points[p].max_penetration, 0.0) << kContactPoints[p];
  }
  EXPECT_DOUBLE_EQ(r.points[0].max_slip, 0.0);  // the knee is never on the ground
  EXPECT_DOUBLE_EQ(r.points[1].max_slip, 0.0);
  EXPECT_NEAR(r.points[0].max_penetration, 0.010588, 1e-5);
  EXPECT_DOUBLE_EQ(r.points[0].penetration_time, 3.0);
  EXPECT_DOUBLE_EQ(r.points[1].max_penetration, 0.0);
  EXPECT_THAT(missed_contact_bounds(r),
              ::testing::ElementsAre("knee penetration 10.59 mm (bound 1 mm)",
                                     "heel slip 2.00 mm a frame (bound 1 mm)",
                                     "ball slip 2.00 mm a frame (bound 1 mm)",
                                     "tip slip 2.00 mm a frame (bound 1 mm)"));
}

// A knee snapped 30 deg in one frame (the stair walks of trained sets snap 24-64 deg) is the
// fastest joint, and misses the continuity bound; the planned walk's joints turn slower.
TEST(TerrainReport, AJointSnappingInOneFrameMissesTheContinuityBound) {
  const Terrain stairs = Terrain::stairs(0.17, 0.40, 8);
  Motion walk = planned_walk(stair_plan(stairs));
  // The planned walk's angles are set frame by frame; here every joint swings 30 deg either way
  // once a second, at most 188 deg/s.
  for (Frame& f : walk.frames) {
    for (rig::LegAngles& leg : f.pose.legs)
      leg.hip = leg.knee = leg.ankle = leg.toe = radians(30.0) * std::sin(2.0 * kPi * f.time);
  }
  const TerrainReport smooth = evaluate_terrain(walk, stairs);
  EXPECT_LT(smooth.fastest_joint.speed, kFastestJointSpeed);
  EXPECT_EQ(missed_continuity_bound(smooth, walk.fps), "");
  for (std::size_t i = 250; i < walk.frames.size(); ++i)
    walk.frames[i].pose.legs[1].knee += radians(30.0);
  const TerrainReport snapped = evaluate_terrain(walk, stairs);
  EXPECT_NEAR(snapped.fastest_joint.degrees, 30.0, 3.0);
  EXPECT_NEAR(snapped.fastest_joint.speed, snapped.fastest_joint.degrees * walk.fps, 1e-6);
  EXPECT_STREQ(snapped.fastest_joint.joint, "knee");
  EXPECT_EQ(snapped.fastest_joint.side, rig::Side::Right);
  EXPECT_DOUBLE_EQ(snapped.fastest_joint.time, walk.frames[250].time);
  EXPECT_THAT(missed_continuity_bound(snapped, walk.fps),
              ::testing::MatchesRegex("right knee turned [0-9.]+ deg in one frame at 2\\.500 s "
                                      "\\([0-9]+ deg/s; people's fastest 455 deg/s, 4\\.[56] deg "
                                      "a frame\\)"));
  EXPECT_THAT(to_text(snapped), HasSubstr("fastest joint between two frames"));
  EXPECT_EQ(nlohmann::json::parse(to_json(snapped)).at("fastest_joint").at("joint"), "knee");
}

// The continuity bound is the fastest slope of people's mean curves (Bovi et al. 2011's adults,
// each task at its cadence): read again from the data, it is the constant's 455 deg/s.
TEST(TerrainReport, PeoplesFastestJointSpeedIsTheNormativeDatasFastest) {
  const std::filesystem::path data = std::filesystem::path(FUZZYGAIT_SOURCE_DIR) / "data";
  auto rows = [](const std::filesystem::path& file) {
    std::ifstream in(file);
    std::vector<std::vector<std::string>> table;
    for (std::string line; std::getline(in, line);) {
      if (line.empty() || line[0] == '#') continue;
      std::vector<std::string> cells;
      std::stringstream cells_in(line);
      for (std::string cell; std::getline(cells_in, cell, ',');)
        cells.push_back(cell);
      table.push_back(cells);
    }
    return table;
  };
  const auto parameters = rows(data / "parameters" / "bovi2011_adult_parameters.csv");
  ASSERT_GT(parameters.size(), 1u);
  const auto cadence_column =
      std::find(parameters[0].begin(), parameters[0].end(), "cadence_mean") - parameters[0].begin();
  double fastest = 0.0;
  for (std::size_t t = 1; t < parameters.size(); ++t) {
    const double cycle = 120.0 / std::stod(parameters[t][cadence_column]);
    const auto curves = rows(data / "normative" / ("bovi2011_adult_" + parameters[t][0] + ".csv"));
    ASSERT_GT(curves.size(), 2u) << parameters[t][0];
    for (const char* joint : {"hip_mean", "knee_mean", "ankle_mean"}) {
      const auto column = std::find(curves[0].begin(), curves[0].end(), joint) - curves[0].begin();
      for (std::size_t i = 2; i < curves.size(); ++i) {
        const double percent = std::stod(curves[i][0]) - std::stod(curves[i - 1][0]);
        const double change = std::stod(curves[i][column]) - std::stod(curves[i - 1][column]);
        fastest = std::max(fastest, std::abs(change) / (percent / 100.0 * cycle));
      }
    }
  }
  EXPECT_NEAR(fastest, kFastestJointSpeed, 0.5);
}

TEST(TerrainReport, GroundDistanceIsToTheNearestSurfaceHoweverSteep) {
  const Terrain stairs = Terrain::stairs(0.17, 0.28, 3);
  // Above a tread, straight down.
  EXPECT_NEAR(ground_distance(stairs, {1.1, 0.2}), 0.03, 1e-12);
  // Before a riser, to its face rather than to the tread below.
  // (The riser leans 1 mm over its height: at 0.1 m up its face is at x = 1.000588.)
  EXPECT_NEAR(ground_distance(stairs, {0.99, 0.1}), 0.010588, 1e-6);
  // Inside a step: negative, the distance out through the nearer face (the riser's, 5.06 mm;
  // the tread is 10 mm up).
  EXPECT_NEAR(ground_distance(stairs, {1.006, 0.16}), -0.005059, 1e-6);
  EXPECT_NEAR(ground_distance(stairs, {1.05, 0.16}), -0.01, 1e-12);
  // Beyond a polyline's ends the ground is level.
  const Terrain short_ground = Terrain::polyline({{0.0, 0.0}, {1.0, 0.5}});
  EXPECT_NEAR(ground_distance(short_ground, {-3.0, 0.25}), 0.25, 1e-12);
  EXPECT_NEAR(ground_distance(short_ground, {5.0, 0.4}), -0.1, 1e-12);
  EXPECT_TRUE(std::isnan(ground_distance(stairs, {std::nan(""), 0.0})));
}

TEST(TerrainReport, NanFramesAreCountedAndTheRestMeasured) {
  const Terrain stairs = Terrain::stairs(0.17, 0.40, 8);
  Motion walk = planned_walk(stair_plan(stairs));
  walk.frames[123].points[1].ankle.x = std::numeric_limits<double>::quiet_NaN();
  walk.frames[400].pose.legs[0].knee = std::numeric_limits<double>::infinity();
  const TerrainReport r = evaluate_terrain(walk, stairs);
  EXPECT_EQ(r.nan_frames, 2);
  EXPECT_EQ(r.steps.size(), 11u);
  EXPECT_NEAR(r.min_swing_clearance, 0.04, 1e-9);
  for (const PointContact& c : r.points)
    EXPECT_FALSE(std::isnan(c.max_penetration));
  EXPECT_THAT(missed_contact_bounds(r), ::testing::Contains("2 frames with NaN"));
  EXPECT_THROW(evaluate_terrain(Motion{}, stairs), std::invalid_argument);
}

TEST(TerrainReport, TablesAndJsonCarryEveryMeasureTheSameEveryTime) {
  const Terrain stairs = Terrain::stairs(0.17, 0.40, 8);
  Plan plan = stair_plan(stairs);
  plan.landing_pitch = [](int n) {
    return n >= 1 && n <= 8 ? radians(-20.0) : std::numeric_limits<double>::quiet_NaN();
  };
  const Motion walk = planned_walk(plan);
  const TerrainReport r = evaluate_terrain(walk, stairs);
  const std::string text = to_text(r);
  for (const char* row :
       {"stairs up", "level", "hip flexion at contact", "toe-down vs level",
        "peak swing knee flexion", "sole to surface, mid-stance", "toe tip over edges",
        "pelvis rise per stride", "knee", "tip", "min swing clearance", "reached the end"}) {
    EXPECT_THAT(text, HasSubstr(row));
  }
  const nlohmann::json j = nlohmann::json::parse(to_json(r));
  EXPECT_EQ(j.at("runs").get<int>(), 9);
  EXPECT_TRUE(j.at("reached_end").get<bool>());
  EXPECT_EQ(j.at("steps").size(), 11u);
  EXPECT_EQ(j.at("steps")[1].at("ground"), "stairs up");
  EXPECT_EQ(j.at("steps")[1].at("landing"), "forefoot");
  EXPECT_EQ(j.at("steps")[1].at("edges").size(), 2u);
  EXPECT_TRUE(j.at("steps").back().at("peak_swing_knee_deg").is_null());
  const nlohmann::json& up = j.at("groups")[1];
  EXPECT_EQ(up.at("ground"), "stairs up");
  EXPECT_NEAR(up.at("toe_down_vs_level_deg").get<double>(), 20.0, 1e-9);
  EXPECT_NEAR(up.at("stance_percent").at("mean").get<double>(), 60.0, 1e-9);
  EXPECT_NEAR(j.at("points").at("tip").at("max_slip_m_per_frame").get<double>(), 0.0, 1e-12);
  EXPECT_EQ(to_json(evaluate_terrain(walk, stairs)), to_json(r));
  EXPECT_EQ(to_text(evaluate_terrain(walk, stairs)), text);
}

}  // namespace
}  // namespace fuzzygait::eval

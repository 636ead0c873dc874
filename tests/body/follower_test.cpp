#include "fuzzygait/body/follower.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "fuzzygait/gait/walker.hpp"

namespace fuzzygait::body {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kFrame = 1.0 / 60.0;

const gait::ControllerSet& default_set() {
  static const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  return set;
}

// A foot point this close to the ground bears on it (as eval's slip: docs/measuring.md).
constexpr double kOnGround = 0.002;

struct Frame {
  BodyPose pose;
  std::array<bool, 2> planted{};
  std::array<std::array<bool, 3>, 2> on_ground{};  // heel, ball, toe tip of each foot
  double drop = 0.0;
  double pelvis_x = 0.0;                                // the walker's distance along the path
  std::array<std::array<rig::Point, 3>, 2> sagittal{};  // heel, ball, tip as the walker has them
};

struct Walk {
  std::vector<Frame> frames;
};

Walk walk_path(const path::Path& path, double speed, double seconds,
               const terrain::Terrain& ground = terrain::Terrain::flat(),
               const FollowerOptions& options = {}, double stature = 1.75) {
  const Humanoid humanoid = humanoid_from_stature(stature);
  gait::WalkerOptions walker_options;
  walker_options.segments = humanoid.segments();
  walker_options.speed = speed;
  walker_options.event_capacity = 0;
  gait::Walker walker(default_set(), walker_options, ground);
  PathFollower follower(humanoid, path, walker, options);
  Walk walk;
  const int count = static_cast<int>(seconds / kFrame);
  walk.frames.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    walker.advance(kFrame);
    Frame frame;
    frame.pose = follower.update(walker);
    frame.planted = {walker.in_contact(rig::Side::Left), walker.in_contact(rig::Side::Right)};
    for (const rig::Side side : rig::kSides) {
      const rig::LegPoints p = walker.points(side);
      const rig::Point points[] = {p.heel, p.ball, p.tip};
      for (std::size_t k = 0; k < 3; ++k) {
        frame.sagittal[static_cast<std::size_t>(rig::index(side))][k] = points[k];
        frame.on_ground[static_cast<std::size_t>(rig::index(side))][k] =
            points[k].y - ground.height(points[k].x) < kOnGround;
      }
    }
    frame.drop = follower.pelvis_drop();
    frame.pelvis_x = walker.pose().pelvis.x;
    walk.frames.push_back(frame);
  }
  return walk;
}

double distance(Vec3 a, Vec3 b) {
  return length(a - b);
}

// The largest horizontal move in one frame of a heel, ball or toe tip on the ground in both.
double planted_slip(const Walk& walk) {
  double worst = 0.0;
  for (std::size_t f = 1; f < walk.frames.size(); ++f) {
    const Frame& a = walk.frames[f - 1];
    const Frame& b = walk.frames[f];
    for (const rig::Side side : rig::kSides) {
      const auto i = static_cast<std::size_t>(rig::index(side));
      const Vec3 before[] = {a.pose.heel[i], a.pose[toes(side)], a.pose[toes_end(side)]};
      const Vec3 now[] = {b.pose.heel[i], b.pose[toes(side)], b.pose[toes_end(side)]};
      for (std::size_t k = 0; k < 3; ++k) {
        if (!a.on_ground[i][k] || !b.on_ground[i][k]) continue;
        worst = std::max(worst, std::hypot(now[k].x - before[k].x, now[k].z - before[k].z));
      }
    }
  }
  return worst;
}

// The same slip in the walker's own sagittal walk, before it is bent onto a path.
double sagittal_slip(const Walk& walk) {
  double worst = 0.0;
  for (std::size_t f = 1; f < walk.frames.size(); ++f) {
    const Frame& a = walk.frames[f - 1];
    const Frame& b = walk.frames[f];
    for (std::size_t i = 0; i < 2; ++i) {
      for (std::size_t k = 0; k < 3; ++k) {
        if (!a.on_ground[i][k] || !b.on_ground[i][k]) continue;
        worst = std::max(worst, std::abs(b.sagittal[i][k].x - a.sagittal[i][k].x));
      }
    }
  }
  return worst;
}

// The largest movement of each joint in one frame.
std::array<double, kJointCount> largest_moves(const Walk& walk) {
  std::array<double, kJointCount> moves{};
  for (std::size_t f = 1; f < walk.frames.size(); ++f) {
    for (std::size_t j = 0; j < kJointCount; ++j) {
      moves[j] = std::max(
          moves[j], distance(walk.frames[f - 1].pose.position[j], walk.frames[f].pose.position[j]));
    }
  }
  return moves;
}

// The least distance between the points of two segments.
double segment_distance(Vec3 p0, Vec3 p1, Vec3 q0, Vec3 q1) {
  const Vec3 u = p1 - p0, v = q1 - q0, w = p0 - q0;
  const double a = dot(u, u), b = dot(u, v), c = dot(v, v), d = dot(u, w), e = dot(v, w);
  const double denominator = a * c - b * b;
  double s = denominator > 1e-12 ? std::clamp((b * e - c * d) / denominator, 0.0, 1.0) : 0.0;
  double t = (b * s + e) / c;
  if (t < 0.0 || t > 1.0) {
    t = std::clamp(t, 0.0, 1.0);
    s = std::clamp((b * t - d) / a, 0.0, 1.0);
  }
  return length((p0 + s * u) - (q0 + t * v));
}

// How close the legs come: the least distance between a thigh, shank or foot (heel to ball to
// toe tip) of one leg and any of the other's.
double closest_legs(const Walk& walk) {
  double least = 1e9;
  for (const Frame& frame : walk.frames) {
    std::array<std::array<std::array<Vec3, 2>, 4>, 2> bones{};
    for (const rig::Side side : rig::kSides) {
      const BodyPose& p = frame.pose;
      bones[static_cast<std::size_t>(rig::index(side))] = {
          {{p[upper_leg(side)], p[lower_leg(side)]},
           {p[lower_leg(side)], p[foot(side)]},
           {p.heel[static_cast<std::size_t>(rig::index(side))], p[toes(side)]},
           {p[toes(side)], p[toes_end(side)]}}};
    }
    for (const auto& l : bones[0]) {
      for (const auto& r : bones[1])
        least = std::min(least, segment_distance(l[0], l[1], r[0], r[1]));
    }
  }
  return least;
}

// Whether a foot ever crosses over: while the ankles are side by side (within 15 cm along the
// body), the least lateral distance of the left ankle to the left of the right one.
double least_side_by_side(const Walk& walk) {
  double least = 1e9;
  for (const Frame& frame : walk.frames) {
    const Quat pelvis = frame.pose.rotation[index(Joint::hips)];
    const Vec3 apart = frame.pose[Joint::left_foot] - frame.pose[Joint::right_foot];
    if (std::abs(dot(apart, rotate(pelvis, {0, 0, 1}))) > 0.15) continue;
    least = std::min(least, dot(apart, rotate(pelvis, {1, 0, 0})));
  }
  return least;
}

double farthest_from_path(const Walk& walk, const path::Path& path) {
  std::vector<path::GroundPoint> dense;
  for (double d = -1.0; d <= path.length() + 20.0; d += 0.002)
    dense.push_back(path.at(d).point);
  double farthest = 0.0;
  for (const Frame& frame : walk.frames) {
    const Vec3 hips = frame.pose[Joint::hips];
    double nearest = 1e9;
    for (const path::GroundPoint p : dense) {
      nearest = std::min(nearest, std::hypot(hips.x - p.x, hips.z - p.z));
    }
    farthest = std::max(farthest, nearest);
  }
  return farthest;
}

void expect_bones_keep_their_lengths(const Walk& walk, const Humanoid& humanoid) {
  for (const Frame& frame : walk.frames) {
    for (std::size_t j = 1; j < kJointCount; ++j) {
      const auto joint = static_cast<Joint>(j);
      const Joint p = *parent(joint);
      ASSERT_NEAR(distance(frame.pose[joint], frame.pose[p]), length(humanoid.offset[j]), 1e-9)
          << name(joint);
    }
  }
}

TEST(PathFollower, StraightPathKeepsTheWalkersLegs) {
  const Humanoid humanoid = humanoid_from_stature(1.75);
  gait::WalkerOptions options;
  options.segments = humanoid.segments();
  options.speed = 1.3;
  const terrain::Terrain flat = terrain::Terrain::flat();
  gait::Walker walker(default_set(), options, flat);
  const path::Path straight;
  FollowerOptions same_width;
  same_width.step_width_per_leg_length = humanoid.hip_width() / humanoid.segments().leg_length();
  PathFollower follower(humanoid, straight, walker, same_width);
  for (int frame = 0; frame < 300; ++frame) {
    walker.advance(kFrame);
    const BodyPose& pose = follower.update(walker);
    EXPECT_LT(follower.pelvis_drop(), 1e-9);
    for (const rig::Side side : rig::kSides) {
      const rig::LegPoints p = walker.points(side);
      auto expect_at = [&](Joint joint, rig::Point q) {
        EXPECT_NEAR(pose[joint].z, q.x, 1e-9) << name(joint);
        EXPECT_NEAR(pose[joint].y, q.y, 1e-9) << name(joint);
      };
      expect_at(lower_leg(side), p.knee);
      expect_at(foot(side), p.ankle);
      expect_at(toes(side), p.ball);
      expect_at(toes_end(side), p.tip);
      EXPECT_NEAR(pose.heel[static_cast<std::size_t>(rig::index(side))].z, p.heel.x, 1e-9);
      EXPECT_NEAR(pose[foot(side)].x, (side == rig::Side::Left ? 0.5 : -0.5) * humanoid.hip_width(),
                  1e-9);
    }
  }
}

struct Turn {
  double radius;
  double speed;
};

class Turns : public testing::TestWithParam<Turn> {};

TEST_P(Turns, FeetStayPutLegsNeverCrossHipsStayOnThePath) {
  const Turn turn = GetParam();
  // 2 m straight, a quarter turn to the left, 2 m, a quarter turn to the right, on.
  const double quarter = turn.radius * kPi / 2;
  const path::Path path({0, 0}, 0.0,
                        {{2.0, 0.0},
                         {quarter, 1.0 / turn.radius},
                         {2.0, 0.0},
                         {quarter, -1.0 / turn.radius},
                         {3.0, 0.0}});
  const double seconds = (path.length() + 1.0) / turn.speed;
  const Walk walk = walk_path(path, turn.speed, seconds);
  const Walk straight = walk_path(path::Path(), turn.speed, seconds);
  ASSERT_GT(walk.frames.back().pelvis_x, path.length());

  EXPECT_LT(planted_slip(walk), 1.0e-3);
  EXPECT_LT(planted_slip(walk), planted_slip(straight) + 0.2e-3);
  EXPECT_GT(closest_legs(walk), 0.05);
  EXPECT_GT(least_side_by_side(walk), 0.05);
  EXPECT_LT(farthest_from_path(walk, path), 0.05);
  expect_bones_keep_their_lengths(walk, humanoid_from_stature(1.75));
  double deepest = 0.0;
  for (const Frame& frame : walk.frames)
    deepest = std::max(deepest, frame.drop);
  EXPECT_LT(deepest, 0.02);
  // No pop: no joint moves in a frame much more than it does on a straight walk.
  const auto turning = largest_moves(walk);
  const auto ahead = largest_moves(straight);
  for (std::size_t j = 0; j < kJointCount; ++j) {
    EXPECT_LT(turning[j], 1.3 * ahead[j] + 0.005) << name(static_cast<Joint>(j));
  }
  RecordProperty("planted_slip_mm", std::to_string(planted_slip(walk) * 1e3));
  RecordProperty("pelvis_drop_mm", std::to_string(deepest * 1e3));
  RecordProperty("closest_legs_mm", std::to_string(closest_legs(walk) * 1e3));
}

INSTANTIATE_TEST_SUITE_P(Radii, Turns,
                         testing::Values(Turn{1.0, 1.0}, Turn{2.0, 1.2}, Turn{4.0, 1.3}),
                         [](const auto& param_info) {
                           return "radius_" +
                                  std::to_string(static_cast<int>(param_info.param.radius)) + "m";
                         });

TEST(PathFollower, FigureEight) {
  const path::Path eight({0, 0}, 0.0, {{4 * kPi, 0.5}, {4 * kPi, -0.5}});
  const Walk walk = walk_path(eight, 1.2, (eight.length() + 1.0) / 1.2);
  ASSERT_GT(walk.frames.back().pelvis_x, eight.length());
  EXPECT_LT(planted_slip(walk), 1.0e-3);
  EXPECT_GT(closest_legs(walk), 0.05);
  EXPECT_GT(least_side_by_side(walk), 0.05);
  EXPECT_LT(farthest_from_path(walk, eight), 0.05);
  // Back where it started, facing the way it set off.
  EXPECT_NEAR(eight.at(eight.length()).point.x, 0.0, 1e-9);
  EXPECT_NEAR(eight.at(eight.length()).point.z, 0.0, 1e-9);
}

TEST(PathFollower, SameFramesSamePoses) {
  const path::Path path({0, 0}, 0.0, {{1.0, 0.0}, {3.0, 0.7}, {3.0, -0.4}});
  const Walk a = walk_path(path, 1.4, 5.0);
  const Walk b = walk_path(path, 1.4, 5.0);
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (std::size_t f = 0; f < a.frames.size(); ++f) {
    ASSERT_EQ(std::memcmp(&a.frames[f].pose, &b.frames[f].pose, sizeof(BodyPose)), 0) << f;
  }
}

TEST(PathFollower, RandomPathsOverRandomGround) {
  std::mt19937_64 random(20261207);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int walked = 0;
  int slipping = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<path::GroundPoint> points{{0, 0}};
    double heading = 0.0;
    for (int corner = 0; corner < 4; ++corner) {
      heading += (unit(random) - 0.5) * 2.0 * (100.0 * kPi / 180.0);
      const double leg = 3.0 + 3.0 * unit(random);
      points.push_back(
          {points.back().x + leg * std::sin(heading), points.back().z + leg * std::cos(heading)});
    }
    const path::Path path = path::Path::polyline(points, 1.0 + 3.0 * unit(random));
    std::vector<rig::Point> profile{{-5.0, 0.0}};
    double height = 0.0;
    for (double x = 2.0; x < path.length() + 5.0; x += 1.0 + unit(random)) {
      height += (unit(random) - 0.5) * 0.2;  // slopes up to about 6 deg
      profile.push_back({x, height});
    }
    const terrain::Terrain ground = terrain::Terrain::polyline(profile);
    const double speed = 0.8 + 0.8 * unit(random);
    const double stature = 1.5 + 0.5 * unit(random);
    const Walk walk =
        walk_path(path, speed, std::min(8.0, (path.length() + 1.0) / speed), ground, {}, stature);
    bool finite = true;
    for (const Frame& frame : walk.frames) {
      for (const Vec3& p : frame.pose.position) {
        finite = finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
      }
    }
    EXPECT_TRUE(finite) << "trial " << trial;
    double tightest = 1e9;
    for (const path::Piece& piece : path.pieces()) {
      if (piece.curvature != 0.0) tightest = std::min(tightest, 1.0 / std::abs(piece.curvature));
    }
    // The walker's own slip on this ground, stretched at most 20 % where a foot that drags in
    // its swing turns with the path.
    EXPECT_LT(planted_slip(walk), 1.2 * sagittal_slip(walk) + 0.1e-3)
        << "trial " << trial << " radius " << tightest << " sagittal " << sagittal_slip(walk);
    EXPECT_GT(closest_legs(walk), 0.03) << "trial " << trial << " radius " << tightest;
    EXPECT_GT(least_side_by_side(walk), 0.03) << "trial " << trial;
    walked += finite ? 1 : 0;
    slipping += sagittal_slip(walk) > 1e-3 ? 1 : 0;
  }
  EXPECT_EQ(walked, 200);
  RecordProperty("walks_whose_walker_slips_over_1mm", slipping);
}

TEST(PathFollower, RefusesAWalkerOfAnotherBody) {
  const Humanoid humanoid = humanoid_from_stature(1.75);
  gait::WalkerOptions options;
  options.segments = rig::segments_from_stature(1.60);
  const terrain::Terrain flat = terrain::Terrain::flat();
  gait::Walker walker(default_set(), options, flat);
  const path::Path path;
  EXPECT_THROW(PathFollower(humanoid, path, walker), std::invalid_argument);
  options.segments = humanoid.segments();
  gait::Walker same(default_set(), options, flat);
  FollowerOptions bad;
  bad.swing_release = 0.0;
  EXPECT_THROW(PathFollower(humanoid, path, same, bad), std::invalid_argument);
}

}  // namespace
}  // namespace fuzzygait::body

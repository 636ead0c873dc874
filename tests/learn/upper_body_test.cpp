// Learning the upper body's controllers: from the walker's own whole body the fit finds the set's
// constants again; from the CMU walks it comes closer to people's arms, pelvis and chest than the
// shipped numbers do; the series measure what the follower poses; refusals.
#include "fuzzygait/learn/upper_body.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzzygait/body/follower.hpp"
#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/io/mocap.hpp"

namespace fuzzygait {
namespace {

namespace fs = std::filesystem;
using body::Joint;
using body::Vec3;

const fs::path kClips = fs::path(FUZZYGAIT_SOURCE_DIR) / "data" / "mocap" / "cmu";

// A walk of `set` on a straight path at 120 Hz: the legs' motion and the body's joints.
struct OwnWalk {
  eval::Motion motion;
  std::vector<learn::UpperBodyPoints> points;
};

OwnWalk walk_whole_body(const gait::ControllerSet& set, double speed, double seconds) {
  const body::Humanoid humanoid = body::humanoid_from_stature(1.75);
  gait::WalkerOptions options;
  options.segments = humanoid.segments();
  options.speed = speed;
  const terrain::Terrain flat = terrain::Terrain::flat();
  gait::Walker walker(set, options, flat);
  const path::Path straight;
  body::PathFollower follower(humanoid, straight, walker);
  OwnWalk walk;
  walk.motion.fps = 120.0;
  walk.motion.segments = options.segments;
  const double dt = 1.0 / walk.motion.fps;
  for (int i = 0; i * dt < seconds; ++i) {
    if (i > 0) walker.advance(dt);
    const body::BodyPose& pose = follower.update(walker);
    const double time = i * dt;
    walk.motion.frames.push_back(eval::capture_frame(walker, time));
    learn::UpperBodyPoints p;
    p.time = time;
    p.hip = {pose[Joint::left_upper_leg], pose[Joint::right_upper_leg]};
    p.shoulder = {pose[Joint::left_upper_arm], pose[Joint::right_upper_arm]};
    p.elbow = {pose[Joint::left_lower_arm], pose[Joint::right_lower_arm]};
    p.wrist = {pose[Joint::left_hand], pose[Joint::right_hand]};
    walk.points.push_back(p);
  }
  return walk;
}

// The shipped set with its upper body's constants scaled: what the fit must undo.
gait::ControllerSet scaled_upper_body(const gait::ControllerSet& set, double factor) {
  gait::ControllerSet out = set;
  for (auto& controller : out.upper_body) {
    if (!controller) continue;
    fuzzy::Engine engine = controller->engine();
    for (fuzzy::Term& t : engine.outputs[0].terms)
      t.parameters[0] = factor * t.parameters[0] + (factor == 1.0 ? 0.0 : 1.0);
    const std::string source = controller->source();  // (emplace destroys the old one first)
    controller.emplace(std::move(engine), source);
  }
  return out;
}

TEST(UpperBodyLearning, FindsTheSetsOwnNumbersFromItsWalk) {
  const gait::ControllerSet shipped = gait::ControllerSet::builtin("default");
  const OwnWalk walk = walk_whole_body(shipped, 1.3, 8.0);
  const learn::TrainClip legs =
      learn::make_train_clip("own", walk.motion, terrain::Terrain::flat());
  const std::vector<learn::UpperBodyClip> clips = {
      {"own", &legs,
       learn::measure_upper_body(walk.points, {0.0, 0.0, 1.0}, {0.0, 1.0, 0.0},
                                 walk.motion.segments.leg_length())}};
  const gait::ControllerSet start = scaled_upper_body(shipped, 0.3);
  const learn::UpperBodyFit fit = learn::fit_upper_body(start, clips);
  for (int p = 0; p < gait::kUpperBodyCount; ++p) {
    const auto i = static_cast<std::size_t>(p);
    const std::string name(gait::upper_body_name(static_cast<gait::UpperBody>(p)));
    if (static_cast<gait::UpperBody>(p) == gait::UpperBody::TrunkLean) {
      // It answers the ground's incline: level clips have nothing to fit it to.
      EXPECT_FALSE(fit.fitted[i]);
      continue;
    }
    ASSERT_TRUE(fit.fitted[i]) << name;
    ASSERT_EQ(fit.rmse_after[i].size(), 1u);
    // The shrunk and shifted numbers were well off; the fitted ones answer as the shipped do.
    EXPECT_GT(fit.rmse_before[i][0], 0.4) << name;
    EXPECT_LT(fit.rmse_after[i][0], 0.25 * fit.rmse_before[i][0]) << name;
    const auto& want = shipped.upper_body[i]->engine().outputs[0].terms;
    const auto& got = fit.set.upper_body[i]->engine().outputs[0].terms;
    ASSERT_EQ(want.size(), got.size());
    for (std::size_t t = 0; t < want.size(); ++t) {
      // A constant shared by both sides' answers is not seen in their difference: only the
      // arms' are compared as numbers.
      if (p > static_cast<int>(gait::UpperBody::Elbow)) break;
      EXPECT_NEAR(got[t].parameters[0], want[t].parameters[0],
                  0.1 * std::abs(want[t].parameters[0]) + 1.0)
          << name << " " << want[t].name;
    }
    RecordProperty(name + "_rmse_after", std::to_string(fit.rmse_after[i][0]));
  }
}

TEST(UpperBodyLearning, ComesCloserToTheCmuWalkersThanTheShippedNumbers) {
  const gait::ControllerSet shipped = gait::ControllerSet::builtin("default");
  std::vector<learn::TrainClip> legs;
  std::vector<learn::UpperBodyClip> clips;
  const std::vector<std::string> names = {"07_01", "08_02"};
  legs.reserve(names.size());
  for (const std::string& name : names) {
    const io::BvhClip bvh = io::read_bvh_file(kClips / (name + ".bvh"));
    io::CapturedClip captured = io::analyse_clip(bvh, name);
    std::string why;
    std::optional<learn::UpperBodySeries> series = learn::capture_upper_body(bvh, captured, &why);
    ASSERT_TRUE(series.has_value()) << why;
    EXPECT_EQ(series->size(), captured.motion.frames.size());
    legs.push_back(learn::make_train_clip(name, captured.motion, captured.ground));
    clips.push_back({name, nullptr, std::move(*series)});
  }
  for (std::size_t c = 0; c < clips.size(); ++c)
    clips[c].legs = &legs[c];
  const learn::UpperBodyFit fit = learn::fit_upper_body(shipped, clips);
  for (int p = 0; p < gait::kUpperBodyCount; ++p) {
    const auto i = static_cast<std::size_t>(p);
    const std::string name(gait::upper_body_name(static_cast<gait::UpperBody>(p)));
    if (static_cast<gait::UpperBody>(p) == gait::UpperBody::TrunkLean) {
      EXPECT_FALSE(fit.fitted[i]);
      EXPECT_EQ(fit.set.upper_body[i]->engine().outputs[0].terms[2].parameters[0], 5.6);
      continue;
    }
    ASSERT_TRUE(fit.fitted[i]) << name;
    const double before =
        std::accumulate(fit.rmse_before[i].begin(), fit.rmse_before[i].end(), 0.0);
    const double after = std::accumulate(fit.rmse_after[i].begin(), fit.rmse_after[i].end(), 0.0);
    EXPECT_LE(after, before + 1e-9) << name;
    RecordProperty(name + "_rmse_before", std::to_string(before / 2.0));
    RecordProperty(name + "_rmse_after", std::to_string(after / 2.0));
  }
  // Where the words can follow the clips, they do (measured: the shoulder 9.3 -> 7.4 deg, the
  // pelvis's roll 5.5 -> 3.9, its sway 1.41 -> 1.06 % of a leg, the means of both clips).
  auto mean_of = [](const std::vector<double>& v) {
    return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  };
  for (const gait::UpperBody part :
       {gait::UpperBody::Shoulder, gait::UpperBody::PelvisObliquity, gait::UpperBody::PelvisSway}) {
    const auto i = static_cast<std::size_t>(part);
    EXPECT_LT(mean_of(fit.rmse_after[i]), 0.85 * mean_of(fit.rmse_before[i]))
        << gait::upper_body_name(part);
  }
}

TEST(UpperBodyLearning, MeasuresWhatTheFollowerPoses) {
  // Hips 0.2 m apart turned -10, 0, +10 deg (left hip forward +), the left -0.035, 0, +0.035 m
  // above the right; the arms as below.
  std::vector<learn::UpperBodyPoints> frames(3);
  const double b = 20.0 * std::numbers::pi / 180.0;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    learn::UpperBodyPoints& f = frames[k];
    const double step = static_cast<double>(k) - 1.0;
    const double a = step * 10.0 * std::numbers::pi / 180.0;
    f.time = 0.1 * static_cast<double>(k);
    const double z = 1.3 * f.time;  // walking along +z, the hips' centre on x = 0
    f.hip = {Vec3{0.1 * std::cos(a), 0.9 + step * 0.0175, z + 0.1 * std::sin(a)},
             Vec3{-0.1 * std::cos(a), 0.9 - step * 0.0175, z - 0.1 * std::sin(a)}};
    f.shoulder = {Vec3{0.2, 1.4, z}, Vec3{-0.2, 1.4, z}};
    // The left upper arm 20 deg forward, the elbow bent 90 deg; the right arm hanging straight.
    f.elbow = {Vec3{0.2, 1.4 - 0.3 * std::cos(b), z + 0.3 * std::sin(b)}, Vec3{-0.2, 1.1, z}};
    f.wrist = {f.elbow[0] + Vec3{0.0, 0.25 * std::sin(b), 0.25 * std::cos(b)}, Vec3{-0.2, 0.85, z}};
  }
  const learn::UpperBodySeries s =
      learn::measure_upper_body(frames, {0.0, 0.0, 1.0}, {0.0, 1.0, 0.0}, 0.9);
  ASSERT_EQ(s.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const double step = static_cast<double>(k) - 1.0;
    EXPECT_NEAR(s.shoulder[0][k], 20.0, 1e-9);
    EXPECT_NEAR(s.shoulder[1][k], 0.0, 1e-9);
    EXPECT_NEAR(s.elbow[0][k], 90.0, 1e-9);
    EXPECT_NEAR(s.elbow[1][k], 0.0, 1e-9);
    EXPECT_NEAR(s.pelvis_rotation[k], 10.0 * step, 1e-9);
    EXPECT_NEAR(s.thorax_rotation[k], 0.0, 1e-9);
    EXPECT_NEAR(s.pelvis_obliquity[k], std::atan2(0.035 * step, 0.2) * 180.0 / std::numbers::pi,
                1e-9);
    EXPECT_NEAR(s.pelvis_sway[k], 0.0, 1e-9);
  }
}

TEST(UpperBodyLearning, Refuses) {
  std::vector<learn::UpperBodyPoints> one(1);
  EXPECT_THROW(learn::measure_upper_body(one, {0, 0, 1}, {0, 1, 0}, 0.9), std::invalid_argument);
  std::vector<learn::UpperBodyPoints> two(2);
  EXPECT_THROW(learn::measure_upper_body(two, {0, 0, 2}, {0, 1, 0}, 0.9), std::invalid_argument);
  EXPECT_THROW(learn::measure_upper_body(two, {0, 0, 1}, {0, 0, 1}, 0.9), std::invalid_argument);
  EXPECT_THROW(learn::measure_upper_body(two, {0, 0, 1}, {0, 1, 0}, 0.0), std::invalid_argument);
  two[1].elbow[0].x = std::nan("");
  EXPECT_THROW(learn::measure_upper_body(two, {0, 0, 1}, {0, 1, 0}, 0.9), std::invalid_argument);
  const gait::ControllerSet shipped = gait::ControllerSet::builtin("default");
  EXPECT_THROW(learn::fit_upper_body(shipped, {}), std::invalid_argument);
  const std::vector<learn::UpperBodyClip> legless = {{"legless", nullptr, {}}};
  EXPECT_THROW(learn::fit_upper_body(shipped, legless), std::invalid_argument);
}

TEST(UpperBodyLearning, SaysWhyAClipWithoutArmsTeachesNothing) {
  // 07_01 with its arms renamed: the legs are found, the arms are not.
  io::BvhClip bvh = io::read_bvh_file(kClips / "07_01.bvh");
  for (io::BvhJoint& j : bvh.joints) {
    if (j.name.find("Arm") != std::string::npos || j.name.find("Hand") != std::string::npos) {
      j.name = "Limb" + std::to_string(j.line);
    }
  }
  const io::CapturedClip captured = io::analyse_clip(bvh, "07_01");
  std::string why;
  EXPECT_FALSE(learn::capture_upper_body(bvh, captured, &why).has_value());
  EXPECT_NE(why.find("UpperArm"), std::string::npos) << why;
}

}  // namespace
}  // namespace fuzzygait

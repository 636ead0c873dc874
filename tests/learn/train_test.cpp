// Training on a CMU clip with a small budget: the set walks the clip's body and step closer to the
// clip than the base does, its words keep their promises and its knots their order, the clip's
// body and step travel in its manifest, and training stops when asked with the best set so far.
#include "fuzzygait/learn/train.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/io/controller_files.hpp"
#include "fuzzygait/io/mocap.hpp"
#include "fuzzygait/learn/fit.hpp"
#include "fuzzygait/learn/network.hpp"
#include "fuzzygait/learn/tune.hpp"
#include "support/walks.hpp"

namespace fuzzygait {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

const fs::path kClips = fs::path(FUZZYGAIT_SOURCE_DIR) / "data" / "mocap" / "cmu";

learn::TrainClip clip(const std::string& name) {
  io::CapturedClip c = io::read_clip(kClips / (name + ".bvh"));
  return learn::make_train_clip(name, std::move(c.motion), std::move(c.ground));
}

// A budget a test affords: a few seconds.
learn::TrainOptions small_budget() {
  learn::TrainOptions o = learn::default_train_options();
  o.fit.max_iterations = 5;
  o.polish.generations = 40;
  o.polish.polish_generations = 10;
  o.polish.population = 24;
  return o;
}

double sum(const learn::ClipScore& s) {
  return s.thigh + s.knee + s.ankle;
}

TEST(TrainClip, MeasuresTheClipAndTheStepItsRigTakes) {
  const learn::TrainClip c = clip("07_01");
  EXPECT_EQ(c.report.cycles, 2);
  EXPECT_NEAR(c.report.stance_percent, 63.0, 0.1);
  EXPECT_NEAR(c.report.cadence, 112.1, 0.1);
  // The rig lays each segment's full length in the sagittal plane: its heels land 0.733 m apart,
  // where the skeleton's ankles land 0.656 m apart.
  EXPECT_NEAR(c.step_length, 0.733, 0.001);
  EXPECT_TRUE(c.motion.captured);
}

TEST(TrainClip, RefusesAClipWithoutACycle) {
  io::CapturedClip c = io::read_clip(kClips / "07_01.bvh");
  c.motion.frames.resize(60);  // half a second: no cycle
  try {
    learn::make_train_clip("short", std::move(c.motion), std::move(c.ground));
    ADD_FAILURE() << "a clip without a cycle was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("short"), std::string::npos) << e.what();
  }
}

// What a training cannot learn from is refused, naming the clip and why: feet off the floor the
// clip's own frames fit (uneven ground, or a skeleton whose feet are not where they seem), a
// backward walk, a slowed-down clip.
std::string refusal(const std::string& name, io::CapturedClip c) {
  try {
    learn::make_train_clip(name, std::move(c.motion), std::move(c.ground));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(TrainClip, RefusesWhatIsNoLevelForwardWalk) {
  {
    io::CapturedClip c = io::read_clip(kClips / "07_01.bvh");
    c.ground = terrain::Terrain::polyline({{-100.0, 0.10}, {100.0, 0.10}});
    const std::string why = refusal("raised", std::move(c));
    EXPECT_NE(why.find("raised: not a level forward walk"), std::string::npos) << why;
    EXPECT_NE(why.find("cm below the floor"), std::string::npos) << why;
  }
  {
    io::CapturedClip c = io::read_clip(kClips / "07_01.bvh");
    // The clip walked the other way along the x axis, on its floor's level.
    const double floor = c.ground.height(c.motion.frames.front().pose.pelvis.x);
    c.ground = terrain::Terrain::polyline({{-100.0, floor}, {100.0, floor}});
    for (eval::Frame& f : c.motion.frames) {
      f.pose.pelvis.x = -f.pose.pelvis.x;
      for (rig::LegPoints& leg : f.points) {
        for (rig::Point* q : {&leg.hip, &leg.knee, &leg.ankle, &leg.heel, &leg.ball, &leg.tip})
          q->x = -q->x;
      }
    }
    const std::string why = refusal("backward", std::move(c));
    EXPECT_NE(why.find("backward: not a level forward walk"), std::string::npos) << why;
    EXPECT_NE(why.find("a backward walk"), std::string::npos) << why;
  }
  {
    io::CapturedClip c = io::read_clip(kClips / "07_01.bvh");
    c.motion.fps /= 4.0;
    for (eval::Frame& f : c.motion.frames)
      f.time *= 4.0;
    const std::string why = refusal("slowed", std::move(c));
    EXPECT_NE(why.find("slowed: not a level forward walk"), std::string::npos) << why;
    EXPECT_NE(why.find("slowed or sped-up"), std::string::npos) << why;
  }
  // Every shared clip is one (the check's tolerances are not tighter than real capture).
  for (const char* name :
       {"07_01", "07_02", "07_03", "07_06", "08_01", "08_02", "08_03", "08_06", "05_01"}) {
    EXPECT_EQ(refusal(name, io::read_clip(kClips / (std::string(name) + ".bvh"))), "") << name;
  }
}

// One short training on 07_01, checked for what it promises (one test: each test runs in a
// process of its own, and a training is the test's cost).
class TrainedOn0701 : public ::testing::Test {
 protected:
  void SetUp() override {
    clips_ = {clip("07_01")};
    result_ = learn::train(test::default_set(), clips_, small_budget());
  }
  // The stated margin: the three curves' RMSE together at most 60 % of the base's, the knee alone
  // under half, the timing within the issue's bounds.
  void WalksTheClipsBodyCloserToTheClipThanTheBase() const;
  // The base's rules and words, and the words the training added (a slight knee in both knees).
  void KeepsTheBaseSetsRulesAndWordsWithReadableValues() const;
  std::vector<learn::TrainClip> clips_;
  learn::TrainResult result_;
};

TEST_F(TrainedOn0701, WalksCloserToTheClipKeepingTheRulesWordsAndReadableValues) {
  WalksTheClipsBodyCloserToTheClipThanTheBase();
  KeepsTheBaseSetsRulesAndWordsWithReadableValues();
}

void TrainedOn0701::WalksTheClipsBodyCloserToTheClipThanTheBase() const {
  const learn::ClipScore& before = result_.before.at(0);
  const learn::ClipScore& after = result_.after.at(0);
  ASSERT_TRUE(before.walked);
  ASSERT_TRUE(after.walked);
  EXPECT_LT(sum(after), 0.6 * sum(before))
      << "before " << before.thigh << " " << before.knee << " " << before.ankle << ", after "
      << after.thigh << " " << after.knee << " " << after.ankle;
  EXPECT_LT(after.knee, 0.5 * before.knee);
  const learn::TrainClip& c = clips_.at(0);
  EXPECT_NEAR(after.stance, c.report.stance_percent, 3.0);
  EXPECT_NEAR(after.cadence, c.report.cadence, 0.05 * c.report.cadence);
  EXPECT_LT(result_.cost_after, result_.cost_before);
  EXPECT_FALSE(result_.stopped);
  // Each stage is on record, the polish last.
  ASSERT_FALSE(result_.stages.empty());
  EXPECT_EQ(result_.stages.back().stage, "polish");
}

void TrainedOn0701::KeepsTheBaseSetsRulesAndWordsWithReadableValues() const {
  const gait::ControllerSet& base = test::default_set();
  const gait::ControllerSet& trained = result_.set;
  EXPECT_EQ(learn::word_penalty(trained), 0.0);
  ASSERT_EQ(result_.added.size(), 2u);
  const learn::SetNetwork before(base);
  const learn::SetNetwork after(trained);      // every slot still a partition controller
  EXPECT_EQ(after.size(), before.size() + 2);  // the two new words' peaks
  int moved = 0;
  for (std::size_t i = 0; i < after.size(); ++i) {
    const double v = after.values()[i];
    // Three significant digits at most, or a knot moved to its gap.
    EXPECT_TRUE(v == learn::readable(after, after.values())[i]) << after.weight(i).name;
    if (after.weight(i).kind == learn::WeightKind::Knot) {
      EXPECT_LT(after.knot_below(i, after.values()), v) << after.weight(i).name;
    }
    const std::size_t was = before.find(after.weight(i).name);
    if (was == before.size()) {
      EXPECT_NE(after.weight(i).name.find(".knee.slight"), std::string::npos);
      continue;
    }
    moved += v != before.values()[was] ? 1 : 0;
  }
  EXPECT_GT(moved, 10);
  for (const learn::AddedWord& w : result_.added)
    EXPECT_EQ(w.peak,
              after.values()[after.find(std::string(gait::slot_name(w.slot)) + ".knee.slight")]);
  for (int s = 0; s < gait::kSlotCount; ++s) {
    const fuzzy::Engine& a = base.controllers[static_cast<std::size_t>(s)].engine();
    const fuzzy::Engine& b = trained.controllers[static_cast<std::size_t>(s)].engine();
    std::set<std::string> rules;
    for (const fuzzy::Rule& r : b.rule_blocks[0].rules)
      rules.insert(r.text());
    for (const fuzzy::Rule& r : a.rule_blocks[0].rules)
      EXPECT_TRUE(rules.count(r.text()) == 1) << gait::slot_name(s) << ": " << r.text();
    const std::size_t extra = b.rule_blocks[0].rules.size() - a.rule_blocks[0].rules.size();
    EXPECT_EQ(extra, s == 1 || s == 5 ? 4u : 0u) << gait::slot_name(s);
  }
  EXPECT_EQ(trained.terrain_controllers.size(), base.terrain_controllers.size());
}

// The same clips and options give the same set, to the bit (two threads and all).
TEST(Training, TrainsTheSameSetAgain) {
  const std::vector<learn::TrainClip> clips = {clip("08_02")};
  learn::TrainOptions o = learn::default_train_options();
  o.fit.max_iterations = 3;
  o.polish.generations = 6;
  o.polish.polish_generations = 2;
  o.polish.population = 12;
  const learn::TrainResult first = learn::train(test::default_set(), clips, o);
  const learn::TrainResult again = learn::train(test::default_set(), clips, o);
  EXPECT_EQ(learn::SetNetwork(again.set).values(), learn::SetNetwork(first.set).values());
  EXPECT_EQ(again.cost_after, first.cost_after);
  EXPECT_NE(learn::SetNetwork(first.set).values(), learn::SetNetwork(test::default_set()).values());
}

// Steps around the clip's are walked and priced in the closed loop: the base's cost grows by
// what it misses there, and the training still ends on a set.
TEST(Training, PricesTheStepsAroundTheClipsStep) {
  const std::vector<learn::TrainClip> clips = {clip("07_01")};
  learn::TrainOptions o = learn::default_train_options();
  o.fits = false;
  o.polish.generations = 2;
  o.polish.polish_generations = 1;
  o.polish.population = 8;
  const learn::TrainResult alone = learn::train(test::default_set(), clips, o);
  o.steps_around = {0.7, 1.2};
  const learn::TrainResult around = learn::train(test::default_set(), clips, o);
  EXPECT_GT(around.cost_before, alone.cost_before);
  EXPECT_TRUE(around.after.at(0).walked);
}

TEST(TrainedSet, ItsManifestCarriesTheClipsBodyAndStep) {
  gait::ControllerSet trained = test::default_set();
  const learn::TrainClip c = clip("07_01");
  trained.body = c.motion.segments;
  trained.body_step_length = c.step_length;
  const fs::path dir = fs::path(::testing::TempDir()) / "fuzzygait_trained_body";
  fs::remove_all(dir);
  io::save_controller_set(trained, dir);
  const gait::ControllerSet read = gait::ControllerSet::load(dir);
  ASSERT_TRUE(read.body.has_value());
  ASSERT_TRUE(read.body_step_length.has_value());
  EXPECT_NEAR(read.body->thigh, c.motion.segments.thigh, 5e-5);
  EXPECT_NEAR(read.body->shank, c.motion.segments.shank, 5e-5);
  EXPECT_NEAR(read.body->ankle_height, c.motion.segments.ankle_height, 5e-5);
  EXPECT_NEAR(read.body->toe, c.motion.segments.toe, 5e-5);
  EXPECT_NEAR(*read.body_step_length, c.step_length, 5e-5);
  EXPECT_FALSE(gait::ControllerSet::builtin("default").body.has_value());
  fs::remove_all(dir);
}

TEST(Training, StopsWhenAskedWithTheBestSetSoFar) {
  const std::vector<learn::TrainClip> clips = {clip("07_01")};
  learn::TrainOptions o = small_budget();
  o.polish.generations = 100000;
  o.polish.population = 12;
  int polish_generations = 0;
  o.progress = [&](const learn::TrainProgress& p) {
    if (p.stage == "polish") ++polish_generations;
  };
  o.stop = [&] { return polish_generations >= 5; };
  const learn::TrainResult r = learn::train(test::default_set(), clips, o);
  EXPECT_TRUE(r.stopped);
  EXPECT_LE(r.cost_after, r.cost_before);
  ASSERT_TRUE(r.after.at(0).walked);
  EXPECT_LT(sum(r.after.at(0)), sum(r.before.at(0)));
  EXPECT_EQ(learn::word_penalty(r.set), 0.0);
}

// The check prices what the terrain tests hold: the terrain contact bounds (slip, penetration,
// swing clearance) and the continuity bound, so a walk that snaps a joint or slides a foot cannot
// pass. This documents a known failure: the shipped default misses them on all four walks today
// (docs/terrain.md, "How well it walks them"): its climb slips the toe tip 78.61 mm a frame and
// snaps the stance toes up 98.8 deg in one frame, its descent slips the toe tip 34.37 mm, and on
// the ramps its joints turn at 797 and 1078 deg/s where people's fastest is 455.
TEST(TerrainCheck, PricesSlipsAndJointSnapsSoTheDefaultsKnownMissesShow) {
  const rig::Segments body = rig::segments_from_stature(1.75);
  const learn::WalksCheck shipped = learn::check_terrain(test::default_set(), body, 0.70);
  EXPECT_EQ(shipped.walks, 4);
  EXPECT_EQ(shipped.within, 0);
  ASSERT_EQ(shipped.misses.size(), 4u);
  EXPECT_THAT(shipped.misses[0], AllOf(StartsWith("stairs up 0.17 x 0.28 m: "),
                                       HasSubstr("tip slip 78.61 mm a frame (bound 1 mm)"),
                                       HasSubstr("left toe turned 98.8 deg in one frame")));
  EXPECT_THAT(shipped.misses[1], AllOf(StartsWith("stairs down 0.17 x 0.28 m: "),
                                       HasSubstr("tip slip 34.37 mm a frame (bound 1 mm)")));
  EXPECT_THAT(shipped.misses[2], AllOf(StartsWith("ramp up 10 deg: "),
                                       HasSubstr("heel slip 1.27 mm a frame (bound 1 mm)")));
  EXPECT_THAT(shipped.misses[3], AllOf(StartsWith("ramp down 10 deg: "),
                                       HasSubstr("(1078 deg/s; people's fastest 455 deg/s")));
  for (const std::string& miss : shipped.misses)
    EXPECT_THAT(miss, Not(HasSubstr("in the ground"))) << miss;

  // A set whose joints follow their commands ten times as slowly misses them too.
  const learn::SetNetwork network(test::default_set());
  std::vector<double> w = network.values();
  w[network.find("inertia")] *= 10.0;
  const learn::WalksCheck stiff = learn::check_terrain(network.apply(w), body, 0.70);
  EXPECT_EQ(stiff.walks, 4);
  EXPECT_EQ(stiff.within, 0);
  ASSERT_FALSE(stiff.misses.empty());
  EXPECT_EQ(stiff.misses.front().rfind("stairs up 0.17 x 0.28 m: ", 0), 0u) << stiff.misses.front();
}

TEST(ManifestBody, IsRefusedWithTheLineAndFieldWhenIncomplete) {
  const std::string manifest_start = R"({"name": "x", "controllers": {}, "body": )";
  auto refused = [&](const std::string& body, const std::string& expected) {
    try {
      gait::ControllerSet::parse(manifest_start + body + "}", {}, "set");
      ADD_FAILURE() << body << " was taken";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("set/manifest.json:1:"), std::string::npos) << what;
      EXPECT_NE(what.find(expected), std::string::npos) << what;
    }
  };
  refused("[1, 2]", "'body' must be an object");
  refused(R"({"thigh_m": 0.4})", "'body' needs 'shank_m'");
  refused(R"({"thigh_m": 0.4, "knee_m": 0.1})", "no field 'knee_m'");
  refused(R"({"thigh_m": -0.4, "shank_m": 0.4, "ankle_height_m": 0.03, "heel_m": 0.06,
              "ball_m": 0.11, "toe_m": 0.06, "step_length_m": 0.7})",
          "'thigh_m' must be a number");
}

}  // namespace
}  // namespace fuzzygait

namespace fuzzygait {
namespace {

// Two walks at nearby paces show a step, not how it grows with the pace: fitting a slope to them
// once asked for a step of 0.07 leg lengths at a stroll, a stride the loader refuses, so the
// trained set could not be walked. The fit shifts the stride instead; across a wide spread of
// paces it fits the slope too; every result passes the loader's check.
TEST(FitStride, NearbyPacesShiftTheStrideAndEveryResultLoads) {
  const gait::ControllerSet base = gait::ControllerSet::builtin("default");
  const std::vector<learn::StridePoint> nearby = {{0.40, 0.80, 1.0}, {0.43, 0.86, 1.0}};
  const gait::ControllerSet shifted = learn::fit_stride(base, nearby);
  EXPECT_EQ(shifted.stride_problem(), "");
  // The shift puts the stride through the walks' mean step.
  const double mean_error =
      0.5 * (shifted.step_at_pace(0.40) - 0.80) + 0.5 * (shifted.step_at_pace(0.43) - 0.86);
  EXPECT_NEAR(mean_error, 0.0, 0.01);
  // The slope of two close points is steep: it is not taken.
  const double base_rise = base.step_at_pace(0.8) - base.step_at_pace(0.15);
  EXPECT_NEAR(shifted.step_at_pace(0.8) - shifted.step_at_pace(0.15), base_rise, 0.02);
  const std::vector<learn::StridePoint> spread = {{0.25, 0.55, 1.0}, {0.55, 0.95, 1.0}};
  const gait::ControllerSet sloped = learn::fit_stride(base, spread);
  EXPECT_EQ(sloped.stride_problem(), "");
  EXPECT_NEAR(sloped.step_at_pace(0.25), 0.55, 0.05);
  EXPECT_NEAR(sloped.step_at_pace(0.55), 0.95, 0.05);
  // A stride no fit can keep loadable is left as it was.
  const std::vector<learn::StridePoint> tiny = {{0.40, 0.02, 1.0}};
  EXPECT_EQ(learn::fit_stride(base, tiny).stride_problem(), "");
}

}  // namespace
}  // namespace fuzzygait

// A controller set's terrain words (the manifest's "terrain"): how they are read, refused with the
// file, line and field, and blended; the walker's incline and stairs metrics that choose them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/learn/terrain_tune.hpp"
#include "runtime/gait/walker_stages.hpp"
#include "support/walks.hpp"

using namespace fuzzygait;
using ::testing::HasSubstr;

namespace {

// A one-input controller whose command is `value` whatever its delta.
std::string constant_fll(const std::string& name, double value) {
  return "Engine: " + name +
         "\nInputVariable: delta\n  enabled: true\n  range: -1 1\n  lock-range: true\n"
         "  term: start Triangle -3 -1 1\n  term: end Triangle -1 1 3\n"
         "OutputVariable: velocity\n  enabled: true\n  range: -1000 1000\n  lock-range: false\n"
         "  aggregation: none\n  defuzzifier: WeightedAverage TakagiSugeno\n  default: 0\n"
         "  lock-previous: false\n  term: v Constant " +
         std::to_string(value) +
         "\nRuleBlock: r\n  enabled: true\n  conjunction: none\n  disjunction: none\n"
         "  implication: none\n  activation: General\n  rule: if delta is start then velocity is "
         "v\n"
         "  rule: if delta is end then velocity is v\n";
}

// The eight slots commanding 1, 2, ... 8, and the terrain files given.
std::map<std::string, std::string> files(const std::map<std::string, double>& terrain) {
  std::map<std::string, std::string> f;
  for (int s = 0; s < gait::kSlotCount; ++s) {
    const std::string name(gait::slot_name(s));
    f[name + ".fll"] = constant_fll(name, s + 1.0);
  }
  for (const auto& [name, value] : terrain)
    f[name] = constant_fll("t", value);
  return f;
}

std::string manifest(const std::string& terrain) {
  std::string m = "{\n  \"name\": \"t\",\n  \"controllers\": {\n";
  for (int s = 0; s < gait::kSlotCount; ++s) {
    const std::string name(gait::slot_name(s));
    m +=
        "    \"" + name + "\": \"" + name + ".fll\"" + (s + 1 < gait::kSlotCount ? "," : "") + "\n";
  }
  return m + "  }" + (terrain.empty() ? "" : ",\n  \"terrain\": " + terrain) + "\n}\n";
}

const std::string kStairs = R"({"stairs": {"incline_deg": {"up": 30, "level": 0, "down": -30},
  "ascent": ["up"], "landing_knee_deg": {"down": 30},
  "controllers": {"stance_knee": {"up": "knee_up.fll", "down": "knee_down.fll"}}}})";

gait::MetricValues on(double incline, bool stairs) {
  gait::MetricValues m{};
  m[static_cast<std::size_t>(gait::Metric::Incline)] = incline;
  m[static_cast<std::size_t>(gait::Metric::Stairs)] = stairs ? 1.0 : 0.0;
  return m;
}

std::string error_of(const std::string& terrain) {
  try {
    gait::ControllerSet::parse(manifest(terrain), files({{"knee_up.fll", 100.0}}), "set");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

TEST(TerrainWords, AreReadInTheOrderOfTheirPeaks) {
  const gait::ControllerSet set = gait::ControllerSet::parse(
      manifest(kStairs), files({{"knee_up.fll", 100.0}, {"knee_down.fll", -50.0}}), "set");
  const gait::ControllerSet::GroundWords& g =
      set.ground[static_cast<std::size_t>(gait::Ground::Stairs)];
  EXPECT_EQ(g.words, (std::vector<std::string>{"down", "level", "up"}));
  EXPECT_EQ(g.peaks, (std::vector<double>{-30.0, 0.0, 30.0}));
  EXPECT_EQ(g.ascent, (std::vector<bool>{false, false, true}));
  EXPECT_DOUBLE_EQ(g.landing_knee[0], rig::radians(30.0));
  EXPECT_TRUE(set.ground[static_cast<std::size_t>(gait::Ground::Slopes)].empty());
  EXPECT_EQ(set.terrain_controllers.size(), 2u);
  EXPECT_EQ(set.controller_count(), 10u);
  const int knee = gait::slot(gait::LegPhase::Stance, gait::Joint::Knee);
  EXPECT_EQ(
      set.controller(knee, gait::Ground::Stairs, 2).engine().outputs[0].terms[0].parameters[0],
      100.0);
  EXPECT_EQ(&set.controller(knee, gait::Ground::Stairs, 1), &set.controllers[knee]);
}

TEST(TerrainWords, BlendTheWordsCommandsByTheirDegrees) {
  const gait::ControllerSet set = gait::ControllerSet::parse(
      manifest(kStairs), files({{"knee_up.fll", 100.0}, {"knee_down.fll", -50.0}}), "set");
  std::vector<fuzzy::Workspace> workspaces;
  for (const gait::Controller& c : set.controllers)
    workspaces.push_back(c.make_workspace());
  for (const gait::Controller& c : set.terrain_controllers)
    workspaces.push_back(c.make_workspace());
  const int knee = gait::slot(gait::LegPhase::Stance, gait::Joint::Knee);  // commands 6
  const int hip = gait::slot(gait::LegPhase::Stance, gait::Joint::Hip);    // 5, no terrain files
  // On level ground the slot's own controller, to the bit; on stairs the words' blend.
  EXPECT_EQ(set.evaluate(knee, on(0.0, true), workspaces), 6.0);
  EXPECT_EQ(set.evaluate(knee, on(30.0, true), workspaces), 100.0);
  EXPECT_DOUBLE_EQ(set.evaluate(knee, on(10.0, true), workspaces), 6.0 * 2 / 3 + 100.0 / 3);
  EXPECT_DOUBLE_EQ(set.evaluate(knee, on(-15.0, true), workspaces), 0.5 * 6.0 - 0.5 * 50.0);
  EXPECT_EQ(set.evaluate(knee, on(45.0, true), workspaces), 100.0);  // beyond the last peak
  EXPECT_EQ(set.evaluate(hip, on(20.0, true), workspaces), 5.0);
  // The stairs' words say nothing of ramps: a ramp of 30 deg walks with the own controllers.
  EXPECT_EQ(set.evaluate(knee, on(30.0, false), workspaces), 6.0);
  EXPECT_TRUE(set.own_controllers_at(gait::LegPhase::Stance, on(0.0, true)));
  EXPECT_FALSE(set.own_controllers_at(gait::LegPhase::Stance, on(10.0, true)));
  EXPECT_TRUE(set.own_controllers_at(gait::LegPhase::Swing, on(10.0, true)));
  EXPECT_DOUBLE_EQ(set.own_degree(knee, on(10.0, true)), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(set.ascent_weight(on(20.0, true)), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(set.landing_knee(on(-15.0, true)), 0.5 * rig::radians(30.0));
  EXPECT_EQ(set.landing_knee(on(-15.0, false)), 0.0);
}

TEST(TerrainWords, MistakesNameTheManifestLineAndField) {
  EXPECT_THAT(error_of(R"({"hills": {}})"), HasSubstr("'terrain' has words for 'slopes'"));
  EXPECT_THAT(error_of(R"({"stairs": {"incline_deg": {"up": 30}}})"),
              HasSubstr("needs 'incline_deg': two or more words"));
  EXPECT_THAT(error_of(R"({"stairs": {"incline_deg": {"up": 30, "level": 30}}})"),
              HasSubstr("peak at the same incline"));
  EXPECT_THAT(error_of(R"({"stairs": {"incline_deg": {"up": 300, "level": 0}}})"),
              HasSubstr("between -90 and 90"));
  EXPECT_THAT(error_of(R"({"stairs": {"incline_deg": {"up": 30, "level": 0},
    "ascent": ["down"]}})"),
              HasSubstr("'terrain.stairs.ascent' names 'down', not a word"));
  EXPECT_THAT(error_of(R"({"stairs": {"incline_deg": {"up": 30, "level": 0},
    "landing_knee_deg": {"up": 120}}})"),
              HasSubstr("the landing knee of 'up' must be between 0 and 90 degrees"));
  EXPECT_THAT(error_of(R"({"stairs": {"incline_deg": {"up": 30, "level": 0},
    "controllers": {"stance_knee": {"up": "missing.fll"}}}})"),
              HasSubstr("names 'missing.fll', which is not in the set"));
  EXPECT_THAT(error_of(R"({"stairs": {"incline_deg": {"up": 30, "level": 0},
    "controllers": {"stance_kne": {"up": "knee_up.fll"}}}})"),
              HasSubstr("unknown controller slot 'stance_kne'"));
  // The line of the mistake (the manifest's 13th line opens "terrain"; the file name is on the
  // next).
  EXPECT_THAT(error_of(R"({"stairs": {"incline_deg": {"up": 30, "level": 0},
    "controllers": {"stance_knee": {"up": 5}}}})"),
              HasSubstr("set/manifest.json:14:"));
}

// The walker's metrics, as a controller back end sees them: incline and stairs 0 on level ground,
// a stair's pitch and 1 on stairs, the slope on a ramp.
TEST(TerrainWords, TheWalkerSaysWhatGroundItWalks) {
  const gait::ControllerSet& set = test::default_set();
  struct Seen {
    double max_incline = -1e9;
    double min_incline = 1e9;
    double max_stairs = 0.0;
  };
  auto walk = [&](const terrain::Terrain& ground) {
    Seen seen;
    gait::detail::ControllerBackend backend{[&](int controller, const gait::MetricValues& m) {
      const double incline = m[static_cast<std::size_t>(gait::Metric::Incline)];
      seen.max_incline = std::max(seen.max_incline, incline);
      seen.min_incline = std::min(seen.min_incline, incline);
      seen.max_stairs =
          std::max(seen.max_stairs, m[static_cast<std::size_t>(gait::Metric::Stairs)]);
      const auto c = static_cast<std::size_t>(controller);
      fuzzy::Workspace none;
      return c < set.controllers.size()
                 ? set.controllers[c].evaluate(m, none)
                 : set.terrain_controllers[c - set.controllers.size()].evaluate(m, none);
    }};
    gait::Walker w =
        gait::detail::WalkerStages::make_walker(set, gait::WalkerOptions{}, ground, &backend);
    for (int f = 0; f < 600; ++f)
      w.advance(1.0 / 60.0);
    return seen;
  };
  const Seen flat = walk(terrain::Terrain::flat());
  EXPECT_EQ(flat.max_incline, 0.0);
  EXPECT_EQ(flat.min_incline, 0.0);
  EXPECT_EQ(flat.max_stairs, 0.0);
  const Seen up = walk(terrain::Terrain::stairs(0.17, 0.28, 10));
  EXPECT_NEAR(up.max_incline, rig::degrees(std::atan2(0.17, 0.279)), 0.01);
  EXPECT_EQ(up.max_stairs, 1.0);
  const Seen ramp = walk(terrain::Terrain::ramp(-10.0));
  EXPECT_NEAR(ramp.min_incline, -10.0, 1e-9);
  EXPECT_EQ(ramp.max_stairs, 0.0);
}

}  // namespace

// The words of the shipped sets' terrain files say what their numbers do ("slow" slower than
// "fast", "hold" near zero, "extend" negative for a knee): an artist reads the rules, not the
// numbers (learn::word_penalty's promises).
TEST(TerrainWords, TheShippedSetsTerrainWordsKeepTheirPromises) {
  for (const std::string& name : gait::ControllerSet::builtin_names()) {
    EXPECT_EQ(learn::terrain_word_penalty(gait::ControllerSet::builtin(name)), 0.0) << name;
  }
}

// The studio's API called in-process as the page calls it over HTTP: what it shows of a set, its
// walk against the library's own walk, edits with their history, refusals that name the field
// and change nothing, save and open, comparison and downloads.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "fuzzygait/body/follower.hpp"
#include "fuzzygait/eval/evaluation.hpp"
#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/io/controller_files.hpp"
#include "fuzzygait/io/normative.hpp"
#include "fuzzygait/io/walk_csv.hpp"
#include "fuzzygait/path/path.hpp"
#include "fuzzygait/studio/studio.hpp"
#include "scratch.hpp"

namespace fuzzygait {
namespace {

using nlohmann::json;
using studio::RequestError;
using studio::Studio;
using studio::StudioOptions;
using ::testing::HasSubstr;

std::filesystem::path scratch(const std::string& name) {
  return test::studio_scratch("api", name);
}

StudioOptions quick(const std::string& workspace) {
  StudioOptions o;
  o.workspace = scratch(workspace);
  o.cycles = 4;
  return o;
}

const json& controller(const json& state, const std::string& id) {
  for (const json& c : state.at("set").at("controllers")) {
    if (c.at("id") == id) return c;
  }
  throw std::runtime_error("no controller " + id);
}

// A walk's view without the time it took to make, which differs from run to run.
json timeless(json walk) {
  walk.erase("timing_ms");
  return walk;
}

// The status and field of the RequestError `call` throws; {0, ""} when it throws none.
std::pair<int, std::string> refusal(const std::function<void()>& call) {
  try {
    call();
  } catch (const RequestError& e) {
    return {e.status(), e.field()};
  }
  return {0, ""};
}

TEST(StudioApi, StateShowsEveryControllerWithItsWordsKnotsAndRules) {
  Studio studio(quick("state"));
  const json state = studio.state();
  EXPECT_EQ(state.at("set").at("name"), "default");
  // The eight slots, the default set's 22 terrain words' controllers and its seven upper body
  // ones.
  EXPECT_EQ(state.at("set").at("controllers").size(), 37u);
  const json& knee = controller(state, "swing_knee");
  EXPECT_EQ(knee.at("title"), "swing knee");
  const json& delta = knee.at("inputs").at(0);
  EXPECT_EQ(delta.at("name"), "delta");
  EXPECT_TRUE(delta.at("partition").get<bool>());
  EXPECT_EQ(delta.at("knots"), json({-1.0, 0.513, 1.29, 1.5}));
  EXPECT_EQ(delta.at("terms").at(1).at("name"), "center");
  const json& words = knee.at("outputs").at(0).at("words");
  EXPECT_EQ(words.at(0), json({{"name", "flex_fast"}, {"value", 880.0}}));
  EXPECT_EQ(knee.at("rules").at("text").at(0),
            "if delta is start and knee is straight then velocity is flex_fast");
  // The grid reads down delta's terms and across knee's.
  EXPECT_EQ(knee.at("rules").at("grid").at(2), json({"hold", "extend_fast", "extend_fast"}));
  // Its output over both inputs, a 31 x 31 grid: flex_fast where delta starts and the knee is
  // straight.
  EXPECT_DOUBLE_EQ(knee.at("response").at("z").at(0).at(0).get<double>(), 880.0);
  const json& stairs = controller(state, "stairs_swing_knee_up");
  EXPECT_EQ(stairs.at("ground"), "stairs");
  EXPECT_EQ(stairs.at("word"), "up");
  EXPECT_EQ(state.at("settings").at("step"), 0.70);
  EXPECT_EQ(state.at("history").at("undo"), 0);
  EXPECT_EQ(state.at("reference").at("name"), "schwartz2008_free");
}

TEST(StudioApi, WalkIsTheLibrarysWalkMeasuredTheSameWay) {
  StudioOptions options = quick("walk");
  options.cycles = 10;
  Studio studio(options);
  const json walk = studio.walk().at("walk");

  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  gait::WalkerOptions o;
  o.segments = rig::segments_from_stature(1.75);
  o.step_length = 0.70;
  const terrain::Terrain flat = terrain::Terrain::flat();
  gait::Walker walker(set, o, flat);
  const eval::Motion motion = eval::record_cycles(walker, 10, 120.0);
  const eval::Normative reference = io::load_normative("schwartz2008_free");
  const eval::GaitReport report = eval::evaluate(motion, flat, &reference, 0.70);

  EXPECT_TRUE(walk.at("completed").get<bool>());
  EXPECT_EQ(walk.at("scores").at("knee").at("rmse").get<double>(), report.knee_score->rmse);
  EXPECT_EQ(walk.at("scores").at("thigh").at("rmse").get<double>(), report.thigh_score->rmse);
  EXPECT_EQ(walk.at("curves").at("knee").at("mean").get<std::vector<double>>(),
            std::vector<double>(report.knee.mean.begin(), report.knee.mean.end()));
  EXPECT_EQ(walk.at("figures").at(0).at("name"), "foot slip");
  EXPECT_EQ(walk.at("figures").at(0).at("value").get<double>(), report.max_slip * 1e3);
  EXPECT_TRUE(walk.at("warnings").empty());
  // Frames at 30 a second, every fourth of the 120 recorded, points to 0.1 mm.
  const json& frames = walk.at("frames");
  EXPECT_EQ(frames.at("count").get<std::size_t>(), (motion.frames.size() + 3) / 4);
  EXPECT_NEAR(frames.at("legs").at(12 + 2 * 5).get<double>(), motion.frames[0].points[1].tip.x,
              5e-5);
  EXPECT_NEAR(frames.at("legs").at(24 * 3 + 2 + 1).get<double>(),
              motion.frames[3 * 4].points[0].knee.y, 5e-5);
  EXPECT_NEAR(frames.at("time").at(3).get<double>(), motion.frames[3 * 4].time, 5e-5);
}

// Walking at a speed: the walk is the library's walk by that speed, its step error measured
// against the stride's step; a step walks by step length again; the set's cadence is one of its
// own numbers.
TEST(StudioApi, WalksAtASpeedAsTheLibraryDoes) {
  Studio studio(quick("speed"));
  const json limits = studio.state().at("settings").at("limits").at("speed");
  ASSERT_TRUE(limits.is_array());
  EXPECT_LT(limits.at(0).get<double>(), 0.7);
  EXPECT_GT(limits.at(1).get<double>(), 2.0);
  const json answer = studio.change_settings({{"speed", 1.6}});
  EXPECT_EQ(answer.at("settings").at("speed"), 1.6);

  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  gait::WalkerOptions o;
  o.segments = rig::segments_from_stature(1.75);
  o.speed = 1.6;
  const terrain::Terrain flat = terrain::Terrain::flat();
  gait::Walker walker(set, o, flat);
  const double step = walker.step_length();
  const eval::Motion motion = eval::record_cycles(walker, 4, 120.0);
  const eval::Normative reference = io::load_normative("schwartz2008_free");
  const eval::GaitReport report = eval::evaluate(motion, flat, &reference, step);
  const json& walk = answer.at("walk");
  EXPECT_TRUE(walk.at("completed").get<bool>());
  EXPECT_EQ(walk.at("scores").at("knee").at("rmse").get<double>(), report.knee_score->rmse);
  EXPECT_NEAR(walk.at("gait").at("speed").get<double>(), 1.6, 0.05);

  const json by_step = studio.change_settings({{"step", 0.7}});
  EXPECT_EQ(by_step.at("settings").at("speed"), 0.0);
  EXPECT_NEAR(by_step.at("walk").at("gait").at("step_length").get<double>(), 0.7, 0.021);

  std::vector<std::string> names;
  const json state = studio.state();
  for (const json& p : state.at("set").at("parameters"))
    names.push_back(p.at("name"));
  EXPECT_THAT(names, ::testing::Contains("cadence_steps_per_min"));
  studio.edit({{"set", "cadence_steps_per_min"}, {"value", 100}});
  studio.change_settings({{"speed", 1.2}});
  EXPECT_EQ(studio.state().at("settings").at("speed"), 1.2);
}

TEST(StudioApi, MovingAKnotChangesTheControllerAndTheWalkAndUndoRestoresBoth) {
  Studio studio(quick("knot"));
  const json before = studio.walk().at("walk");
  const json answer = studio.edit(
      {{"controller", "swing_knee"}, {"variable", "delta"}, {"knot", 1}, {"value", 0.7}});
  const json& delta = answer.at("controller").at("inputs").at(0);
  EXPECT_EQ(delta.at("knots"), json({-1.0, 0.7, 1.29, 1.5}));
  // The neighbours' feet moved with the knot: the partition holds.
  EXPECT_EQ(delta.at("terms").at(0).at("parameters"), json({-2.0, -1.0, 0.7}));
  EXPECT_EQ(delta.at("terms").at(2).at("parameters"), json({0.7, 1.29, 1.5}));
  EXPECT_NE(answer.at("walk").at("curves").at("knee"), before.at("curves").at("knee"));
  EXPECT_EQ(answer.at("history").at("undo"), 1);
  EXPECT_THAT(answer.at("history").at("undo_label").get<std::string>(),
              HasSubstr("swing_knee: delta knot 1 (center) 0.513 -> 0.7"));

  const json undone = studio.undo();
  EXPECT_EQ(timeless(undone.at("walk")), timeless(before));
  EXPECT_EQ(controller(undone, "swing_knee").at("inputs").at(0).at("knots"),
            json({-1.0, 0.513, 1.29, 1.5}));
  EXPECT_EQ(undone.at("history").at("redo"), 1);
  const json redone = studio.redo();
  EXPECT_EQ(timeless(redone.at("walk")), timeless(answer.at("walk")));
  EXPECT_EQ(refusal([&] { studio.redo(); }), std::make_pair(409, std::string("redo")));
}

std::vector<std::string> rules_of(const json& controller) {
  return controller.at("rules").at("text").get<std::vector<std::string>>();
}

TEST(StudioApi, RulesAreEditedAddedAndDeletedAsStepsOfTheHistory) {
  Studio studio(quick("rules"));
  const json before = studio.walk().at("walk");
  std::vector<std::string> rules = rules_of(controller(studio.state(), "swing_knee"));
  ASSERT_EQ(rules.size(), 12u);
  EXPECT_EQ(rules[4], "if delta is center and knee is bent then velocity is extend");

  // Edited: the knee unfolds fast mid-swing; the walk changes, one step "rule 5 edited".
  rules[4] = "if delta is center and knee is bent then velocity is extend_fast";
  const json edited = studio.edit_rules({{"controller", "swing_knee"}, {"rules", rules}});
  EXPECT_EQ(rules_of(edited.at("controller")), rules);
  EXPECT_NE(edited.at("walk").at("curves").at("knee"), before.at("curves").at("knee"));
  EXPECT_EQ(edited.at("history").at("undo"), 1);
  EXPECT_EQ(edited.at("history").at("undo_label"), "swing_knee: rule 5 edited");

  // Added (with a weight, spaced loosely: the parser's text is kept), then deleted.
  std::vector<std::string> more = rules;
  more.insert(more.begin() + 2, "if  delta is start and knee is very bent then velocity is flex");
  const json added = studio.edit_rules({{"controller", "swing_knee"}, {"rules", more}});
  EXPECT_EQ(added.at("history").at("undo_label"), "swing_knee: rule 3 added");
  EXPECT_EQ(rules_of(added.at("controller")).at(2),
            "if delta is start and knee is very bent then velocity is flex");
  std::vector<std::string> fewer = rules;
  fewer.erase(fewer.begin());
  const json deleted = studio.edit_rules({{"controller", "swing_knee"}, {"rules", fewer}});
  EXPECT_EQ(deleted.at("history").at("undo_label"), "swing_knee: rules edited (13 -> 11 rules)");
  EXPECT_EQ(rules_of(deleted.at("controller")), fewer);
  const json one_deleted =
      studio.edit_rules({{"controller", "swing_knee"},
                         {"rules", std::vector<std::string>(fewer.begin(), fewer.end() - 1)}});
  EXPECT_EQ(one_deleted.at("history").at("undo_label"), "swing_knee: rule 11 deleted");
  EXPECT_EQ(one_deleted.at("history").at("undo"), 4);

  // The same rules again: no step.
  const json same =
      studio.edit_rules({{"controller", "swing_knee"},
                         {"rules", std::vector<std::string>(fewer.begin(), fewer.end() - 1)}});
  EXPECT_EQ(same.at("history").at("undo"), 4);

  // Undo all the way: the rules and the walk as they were.
  for (int i = 0; i < 3; ++i)
    studio.undo();
  const json undone = studio.undo();
  EXPECT_EQ(rules_of(controller(undone, "swing_knee")).at(4),
            "if delta is center and knee is bent then velocity is extend");
  EXPECT_EQ(timeless(undone.at("walk")), timeless(before));
  const json redone = studio.redo();
  EXPECT_EQ(timeless(redone.at("walk")), timeless(edited.at("walk")));
}

const json& input_of(const json& controller, const std::string& name) {
  for (const json& input : controller.at("inputs")) {
    if (input.at("name") == name) return input;
  }
  throw std::runtime_error("no input " + name);
}

std::vector<std::string> term_names(const json& input) {
  std::vector<std::string> names;
  for (const json& term : input.at("terms"))
    names.push_back(term.at("name"));
  return names;
}

const json& term_of(const json& input, const std::string& name) {
  for (const json& term : input.at("terms")) {
    if (term.at("name") == name) return term;
  }
  throw std::runtime_error("no term " + name);
}

TEST(StudioApi, ATermIsAddedReadByARuleAndRemovedEachAStepOfTheHistory) {
  Studio studio(quick("terms-add"));
  const json walk_before = timeless(studio.walk().at("walk"));
  EXPECT_EQ(studio.state().at("term_shapes"), (json{"Triangle", "Trapezoid", "Ramp", "Gaussian"}));
  EXPECT_TRUE(controller(studio.state(), "swing_knee").at("fast_path"));

  // Added: no rule reads it yet, so the walk is the same, but the controller is no partition.
  const json added = studio.edit_term({{"controller", "swing_knee"},
                                       {"variable", "knee"},
                                       {"term", "far"},
                                       {"action", "add"},
                                       {"shape", "Gaussian"},
                                       {"parameters", {70, 8}}});
  const json knee = input_of(added.at("controller"), "knee");
  EXPECT_EQ(term_names(knee), (std::vector<std::string>{"straight", "bent", "deep", "far"}));
  EXPECT_EQ(term_of(knee, "far").at("shape"), "Gaussian");
  EXPECT_EQ(term_of(knee, "far").at("samples").size(), 101u);
  EXPECT_FALSE(added.at("controller").at("fast_path"));
  EXPECT_EQ(added.at("history").at("undo"), 1);
  EXPECT_EQ(added.at("history").at("undo_label"),
            "swing_knee: knee term 'far' added (Gaussian 70 8), off the walker's fast path");

  // A rule reads it: the walk changes; then it cannot be removed, the refusal naming the rule.
  std::vector<std::string> rules = rules_of(added.at("controller"));
  rules.push_back("if delta is center and knee is far then velocity is extend_fast");
  const json ruled = studio.edit_rules({{"controller", "swing_knee"}, {"rules", rules}});
  EXPECT_EQ(ruled.at("history").at("undo"), 2);
  EXPECT_NE(ruled.at("walk").at("curves").at("knee"), walk_before.at("curves").at("knee"));
  const json remove = {
      {"controller", "swing_knee"}, {"variable", "knee"}, {"term", "far"}, {"action", "remove"}};
  try {
    studio.edit_term(remove);
    ADD_FAILURE() << "a term a rule reads was removed";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.status(), 422);
    EXPECT_EQ(e.field(), "term");
    EXPECT_THAT(e.what(), HasSubstr("rule 13"));
  }
  try {
    studio.edit_term({{"controller", "swing_knee"},
                      {"variable", "knee"},
                      {"term", "bent"},
                      {"action", "remove"}});
    ADD_FAILURE() << "a term rules read was removed";
  } catch (const RequestError& e) {
    EXPECT_THAT(e.what(), HasSubstr("rules 2, 5, 8, 11"));
  }
  EXPECT_EQ(studio.state().at("history").at("undo"), 2);

  // Without the rule it goes, one step; undo brings it back, undo again the set as it was.
  studio.undo();
  const json removed = studio.edit_term(remove);
  EXPECT_EQ(term_names(input_of(removed.at("controller"), "knee")),
            (std::vector<std::string>{"straight", "bent", "deep"}));
  EXPECT_EQ(removed.at("history").at("undo_label"),
            "swing_knee: knee term 'far' removed, on the walker's fast path");
  EXPECT_TRUE(removed.at("controller").at("fast_path"));
  EXPECT_EQ(timeless(removed.at("walk")), walk_before);
  const json undone = studio.undo();
  EXPECT_EQ(term_names(input_of(controller(undone, "swing_knee"), "knee")).size(), 4u);
  const json first = studio.undo();
  EXPECT_EQ(term_names(input_of(controller(first, "swing_knee"), "knee")).size(), 3u);
  EXPECT_EQ(timeless(first.at("walk")), walk_before);
  const json redone = studio.redo();
  EXPECT_EQ(term_names(input_of(controller(redone, "swing_knee"), "knee")).size(), 4u);
}

TEST(StudioApi, ATermTakesAnotherShapeFromItsFeetAndPeakOrFromParameters) {
  Studio studio(quick("terms-shape"));
  const json walk_before = timeless(studio.walk().at("walk"));
  const auto shape = [&](const std::string& term, const std::string& kind) {
    return studio.edit_term({{"controller", "swing_knee"},
                             {"variable", "delta"},
                             {"term", term},
                             {"action", "shape"},
                             {"shape", kind}});
  };
  // center: Triangle -1 0.513 1.29, its feet and peak kept by each shape.
  const json gaussian = shape("center", "Gaussian");
  const json center = term_of(input_of(gaussian.at("controller"), "delta"), "center");
  EXPECT_EQ(center.at("shape"), "Gaussian");
  EXPECT_EQ(center.at("parameters").at(0), 0.513);
  EXPECT_NEAR(center.at("parameters").at(1).get<double>(), 2.29 / 4, 1e-12);
  EXPECT_EQ(gaussian.at("history").at("undo_label"),
            "swing_knee: delta term 'center' Triangle -> Gaussian 0.513 0.5725, off the walker's "
            "fast path");
  EXPECT_FALSE(gaussian.at("controller").at("fast_path"));
  EXPECT_NE(gaussian.at("walk").at("curves").at("knee"), walk_before.at("curves").at("knee"));
  // Which rules fire is told for the reshaped controller as for any other.
  const json fired = studio.fired({{"time", 2.0}});
  EXPECT_EQ(fired.at("controllers").at("swing_knee").at("rules").size(), 12u);

  const json trapezoid = shape("end", "Trapezoid");
  const std::vector<double> plateau =
      term_of(input_of(trapezoid.at("controller"), "delta"), "end").at("parameters");
  const std::vector<double> expected = {0.513, 0.9015, 1.395, 1.5};
  ASSERT_EQ(plateau.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_NEAR(plateau[i], expected[i], 1e-12) << i;
  // A ramp rises to a peak in the upper half of the input's span and falls from one in the lower.
  const json past = shape("past", "Ramp");
  EXPECT_EQ(term_of(input_of(past.at("controller"), "delta"), "past").at("parameters"),
            (json{1.29, 1.5}));
  const json start = shape("start", "Ramp");
  EXPECT_EQ(term_of(input_of(start.at("controller"), "delta"), "start").at("parameters"),
            (json{0.513, -1}));
  // Parameters given are taken as they are.
  const json exact = studio.edit_term({{"controller", "swing_knee"},
                                       {"variable", "delta"},
                                       {"term", "center"},
                                       {"action", "shape"},
                                       {"shape", "Gaussian"},
                                       {"parameters", {0.4, 0.3}}});
  EXPECT_EQ(term_of(input_of(exact.at("controller"), "delta"), "center").at("parameters"),
            (json{0.4, 0.3}));
  EXPECT_EQ(exact.at("history").at("undo_label"),
            "swing_knee: delta term 'center' Gaussian 0.513 0.5725 -> 0.4 0.3");
  EXPECT_EQ(exact.at("history").at("undo"), 5);

  // Back through the history to triangles: the partition and its walk exactly as they were.
  json back;
  for (int i = 0; i < 5; ++i)
    back = studio.undo();
  EXPECT_TRUE(controller(back, "swing_knee").at("fast_path"));
  EXPECT_EQ(timeless(back.at("walk")), walk_before);
}

TEST(StudioApi, ATermTheInputCannotHoldIsRefusedNamingWhy) {
  Studio studio(quick("terms-refused"));
  const json state = studio.state();
  const auto refused = [&](json request, const std::string& field, const std::string& why) {
    request["controller"] = "swing_knee";
    request["variable"] = "delta";
    try {
      studio.edit_term(request);
      ADD_FAILURE() << "taken: " << request.dump();
    } catch (const RequestError& e) {
      EXPECT_EQ(e.status(), 422) << e.what();
      EXPECT_EQ(e.field(), field) << e.what();
      EXPECT_THAT(e.what(), HasSubstr(why)) << request.dump();
    }
  };
  refused({{"term", "center"}, {"action", "shape"}, {"shape", "Constant"}}, "shape",
          "an output's term");
  refused({{"term", "center"}, {"action", "shape"}, {"shape", "Bell"}}, "shape",
          "Triangle, Trapezoid, Ramp, Gaussian");
  refused(
      {{"term", "center"}, {"action", "shape"}, {"shape", "Triangle"}, {"parameters", {1, 0, 2}}},
      "parameters", "must be in order");
  refused(
      {{"term", "center"}, {"action", "shape"}, {"shape", "Triangle"}, {"parameters", {1, 1, 1}}},
      "parameters", "feet must be apart");
  refused({{"term", "center"}, {"action", "shape"}, {"shape", "Gaussian"}, {"parameters", {0, 0}}},
          "parameters", "standardDeviation must be above 0");
  refused({{"term", "center"}, {"action", "shape"}, {"shape", "Ramp"}, {"parameters", {1, 1}}},
          "parameters", "must differ");
  refused({{"term", "center"}, {"action", "shape"}, {"shape", "Trapezoid"}, {"parameters", {1, 2}}},
          "parameters", "takes 4 parameters");
  refused({{"term", "nowhere"}, {"action", "shape"}, {"shape", "Ramp"}}, "term",
          "its terms: start, center, end, past");
  refused({{"term", "center"}, {"action", "add"}, {"shape", "Ramp"}}, "term", "already");
  refused({{"term", "two words"}, {"action", "add"}, {"shape", "Ramp"}}, "term", "a letter then");
  refused({{"term", "center"}, {"action", "rename"}}, "action", "\"add\", \"remove\" or \"shape\"");
  EXPECT_EQ(studio.state().at("history").at("undo"), 0);
  EXPECT_EQ(studio.state().at("set"), state.at("set"));
}

TEST(StudioApi, ARuleThatDoesNotReadIsRefusedNamingItsLineAndWord) {
  Studio studio(quick("rule-refusals"));
  const json state = studio.state();
  const json walk = studio.walk();
  const std::vector<std::string> rules = rules_of(controller(state, "swing_knee"));
  const auto with = [&](std::size_t i, const std::string& text) {
    std::vector<std::string> r = rules;
    r.at(i) = text;
    return json{{"controller", "swing_knee"}, {"rules", r}};
  };
  const auto message = [&](const json& request) -> std::string {
    try {
      studio.edit_rules(request);
    } catch (const RequestError& e) {
      EXPECT_EQ(e.field(), "rules") << e.what();
      EXPECT_EQ(e.status(), 422) << e.what();
      return e.what();
    }
    ADD_FAILURE() << "taken: " << request.dump();
    return "";
  };
  EXPECT_EQ(message(with(2, "if delta is start and knee is deep then velocity is fastt")),
            "rule 3: 'fastt' is neither a hedge nor a term of 'velocity' (its terms: flex_fast, "
            "flex, hold, extend, extend_fast)");
  EXPECT_EQ(message(with(0, "if delta is strat and knee is straight then velocity is hold")),
            "rule 1: 'strat' is neither a hedge nor a term of 'delta' (its terms: start, center, "
            "end, past)");
  EXPECT_THAT(message(with(5, "if speed is high then velocity is hold")),
              HasSubstr("rule 6: expected an input or output variable, 'and' or 'or' but found "
                        "'speed' (inputs: delta, knee; outputs: velocity)"));
  EXPECT_EQ(message(with(1, "if delta is start then")), "rule 2: nothing follows 'then'");
  EXPECT_EQ(message(with(1, "when delta is start then velocity is hold")),
            "rule 2 must start with 'if', found 'when'");
  EXPECT_THAT(message(with(1, "")), HasSubstr("empty rule"));
  EXPECT_THAT(message(with(3, "if delta is start then velocity is hold\nif")),
              HasSubstr("rule 4 holds a line break"));
  EXPECT_THAT(message(with(3, "if delta is start then velocity is hold # why")),
              HasSubstr("rule 4 holds"));
  EXPECT_THAT(
      message(with(3, "if delta is start then velocity is hold with " + std::string(1000, '1'))),
      HasSubstr("rule 4 is longer than 1000 characters"));
  EXPECT_THAT(message({{"controller", "swing_knee"}, {"rules", json::array()}}),
              HasSubstr("1 to 400 rules, got 0"));
  EXPECT_THAT(
      message({{"controller", "swing_knee"}, {"rules", std::vector<std::string>(401, rules[0])}}),
      HasSubstr("got 401"));

  EXPECT_EQ(refusal([&] {
              studio.edit_rules({{"controller", "swing_kne"}, {"rules", rules}});
            }),
            std::make_pair(422, std::string("controller")));
  EXPECT_EQ(refusal([&] {
              studio.edit_rules({{"controller", 3}, {"rules", rules}});
            }),
            std::make_pair(400, std::string("controller")));
  EXPECT_EQ(refusal([&] {
              studio.edit_rules({{"controller", "swing_knee"}});
            }),
            std::make_pair(400, std::string("rules")));
  EXPECT_EQ(refusal([&] {
              studio.edit_rules({{"controller", "swing_knee"}, {"rules", rules[0]}});
            }),
            std::make_pair(400, std::string("rules")));
  EXPECT_EQ(refusal([&] {
              studio.edit_rules({{"controller", "swing_knee"}, {"rules", {rules[0], 5}}});
            }),
            std::make_pair(400, std::string("rules")));
  EXPECT_EQ(
      refusal([&] {
        studio.edit_rules({{"controller", "swing_knee"}, {"rules", rules}, {"gesture", "g1"}});
      }),
      std::make_pair(400, std::string("gesture")));
  EXPECT_EQ(refusal([&] { studio.edit_rules(json::array()); }).first, 400);
  // Nothing changed.
  EXPECT_EQ(studio.state(), state);
  EXPECT_EQ(timeless(studio.walk().at("walk")), timeless(walk.at("walk")));
}

// The knee's flexion (degrees) at a page frame, from the walk's points of the leg (0 left).
double knee_flexion(const json& frames, std::size_t frame, std::size_t leg) {
  const json& legs = frames.at("legs");
  const std::size_t at = (frame * 2 + leg) * 12;  // hip, knee, ankle, heel, ball, tip as x, y
  const auto x = [&](std::size_t k) { return legs.at(at + 2 * k).get<double>(); };
  const auto y = [&](std::size_t k) { return legs.at(at + 2 * k + 1).get<double>(); };
  const double thigh = std::atan2(x(1) - x(0), -(y(1) - y(0)));
  const double shank = std::atan2(x(2) - x(1), -(y(2) - y(1)));
  return (thigh - shank) * 180.0 / M_PI;
}

TEST(StudioApi, FiredRulesAreTheLibrarysEvaluationAtTheInputsTheWalkRead) {
  Studio studio(quick("fired"));
  const json frames = studio.walk().at("walk").at("frames");
  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  int checked_frames = 0;
  // Six times, and a frame of double support, where no leg is in the swing controllers' phase.
  std::vector<double> times{0.0, 0.5, 1.03, 2.0, 2.5, 3.3};
  const json& contacts = frames.at("contact");
  for (std::size_t f = 30; 2 * f + 1 < contacts.size(); ++f) {
    if (contacts.at(2 * f) != 0 && contacts.at(2 * f + 1) != 0) {
      times.push_back(static_cast<double>(f) / 30.0);
      break;
    }
  }
  ASSERT_EQ(times.size(), 7u) << "the walk has a frame of double support";
  int idle_swing_slots = 0;
  for (const double time : times) {
    const json fired = studio.fired({{"time", time}});
    const auto frame = fired.at("frame").get<std::size_t>();
    EXPECT_EQ(frame, static_cast<std::size_t>(std::lround(time * 30.0)));
    EXPECT_NEAR(fired.at("time").get<double>(), frames.at("time").at(frame).get<double>(), 1e-4);
    const json& controllers = fired.at("controllers");
    EXPECT_EQ(controllers.size(), 15u) << "the eight slots and the seven upper body controllers";
    for (int slot = 0; slot < gait::kSlotCount; ++slot) {
      const std::string id(gait::slot_name(slot));
      const json& c = controllers.at(id);
      const bool swing = id.starts_with("swing");
      const json& contact = frames.at("contact");
      const bool left_swings = contact.at(2 * frame) == 0;
      const bool right_swings = contact.at(2 * frame + 1) == 0;
      if (left_swings != swing && right_swings != swing) {
        // No leg in the slot's phase: it drives nothing, and says so.
        EXPECT_EQ(c, json({{"leg", nullptr}})) << id << " at " << time;
        ++idle_swing_slots;
        continue;
      }
      const gait::Controller& controller = set.controllers.at(static_cast<std::size_t>(slot));
      const fuzzy::Engine& engine = controller.engine();
      ASSERT_EQ(c.at("inputs").size(), controller.input_count()) << id;
      ASSERT_EQ(c.at("rules").size(), engine.rule_blocks.at(0).rules.size()) << id;
      // The leg: the one in the slot's phase (the walk's contacts), the left when both are.
      const std::string leg = left_swings == swing ? "left" : "right";
      EXPECT_EQ(c.at("leg"), leg) << id << " at " << time;
      // The inputs are that leg's at that frame: its knee as the walk's points bend it.
      for (std::size_t i = 0; i < controller.input_count(); ++i) {
        if (controller.input(i) != gait::Metric::Knee) continue;
        EXPECT_NEAR(c.at("inputs").at(i).get<double>(),
                    knee_flexion(frames, frame, leg == "left" ? 0 : 1), 0.2)
            << id << " at " << time;
      }
      // Each rule's strength: its terms' memberships at the inputs (the library's) multiplied
      // (the shipped sets' conjunction, AlgebraicProduct), times its weight.
      if (controller.input_count() == 2) {
        ASSERT_EQ(engine.rule_blocks.at(0).conjunction, fuzzy::TNorm::AlgebraicProduct) << id;
      }
      fuzzy::Evaluator evaluator(engine);
      fuzzy::Workspace workspace = evaluator.make_workspace();
      std::vector<double> x;
      for (const json& v : c.at("inputs"))
        x.push_back(v.get<double>());
      const std::vector<fuzzy::Rule>& rules = engine.rule_blocks.at(0).rules;
      double strongest = 0.0;
      for (std::size_t r = 0; r < rules.size(); ++r) {
        double expected = rules[r].weight;
        for (const fuzzy::Proposition& p : rules[r].propositions) {
          std::size_t input = 0;
          while (engine.inputs.at(input).name != p.variable)
            ++input;
          std::size_t term = 0;
          while (engine.inputs[input].terms.at(term).name != p.term)
            ++term;
          ASSERT_TRUE(p.hedges.empty());
          // A locked range holds the input within it, as the engine reads it.
          const fuzzy::InputVariable& v = engine.inputs[input];
          const double at =
              v.lock_range ? std::clamp(x.at(input), v.minimum, v.maximum) : x.at(input);
          expected *= evaluator.input_membership(input, term, at, workspace);
        }
        EXPECT_NEAR(c.at("rules").at(r).get<double>(), expected, 1e-4)
            << id << " rule " << r + 1 << " at " << time;
        strongest = std::max(strongest, expected);
      }
      EXPECT_GT(strongest, 0.2) << id << ": some rule fires at " << time;
      // And the controller's output at those inputs.
      gait::MetricValues metrics{};
      for (std::size_t i = 0; i < controller.input_count(); ++i)
        metrics[static_cast<std::size_t>(controller.input(i))] = x[i];
      fuzzy::Workspace own = controller.make_workspace();
      EXPECT_NEAR(c.at("output").get<double>(), controller.evaluate(metrics, own), 1e-4)
          << id << " at " << time;
    }
    ++checked_frames;
  }
  EXPECT_EQ(checked_frames, 7);
  EXPECT_GE(idle_swing_slots, 4) << "the four swing controllers idle in double support";
  // Past the walk's end: its last frame.
  EXPECT_EQ(studio.fired({{"time", 1000.0}}).at("frame"), frames.at("count").get<int>() - 1);
  EXPECT_EQ(refusal([&] {
              studio.fired({{"time", -1.0}});
            }),
            std::make_pair(422, std::string("time")));
  EXPECT_EQ(refusal([&] {
              studio.fired({{"time", "1"}});
            }),
            std::make_pair(400, std::string("time")));
  EXPECT_EQ(refusal([&] {
              studio.fired({{"frame", 1}});
            }),
            std::make_pair(400, std::string("frame")));
  EXPECT_EQ(refusal([&] { studio.fired(json::object()); }),
            std::make_pair(400, std::string("time")));
}

TEST(StudioApi, TheHistoryIsAListOfStepsToGoBackAndForthTo) {
  Studio studio(quick("history-list"));
  const json start = studio.walk().at("walk");
  studio.edit({{"controller", "swing_knee"}, {"variable", "delta"}, {"knot", 1}, {"value", 0.346}});
  const json knot = studio.walk().at("walk");
  studio.edit(
      {{"controller", "swing_knee"}, {"variable", "velocity"}, {"term", "hold"}, {"value", 50}});
  std::vector<std::string> rules = rules_of(controller(studio.state(), "swing_knee"));
  rules[2] = "if delta is start and knee is deep then velocity is flex";
  const json last = studio.edit_rules({{"controller", "swing_knee"}, {"rules", rules}});
  const json steps = last.at("history").at("steps");
  EXPECT_EQ(steps, json({"swing_knee: delta knot 1 (center) 0.513 -> 0.346",
                         "swing_knee: velocity hold 37.6 -> 50", "swing_knee: rule 3 edited"}));

  // Back to before them all: the walk as it began, the three steps still listed, to redo.
  const json back = studio.go_to({{"to", 0}});
  EXPECT_EQ(timeless(back.at("walk")), timeless(start));
  EXPECT_EQ(back.at("history").at("undo"), 0);
  EXPECT_EQ(back.at("history").at("redo"), 3);
  EXPECT_EQ(back.at("history").at("steps"), steps);
  EXPECT_FALSE(back.at("history").at("unsaved").get<bool>());
  // Forward to all three, then to the first: each the walk of that point.
  EXPECT_EQ(timeless(studio.go_to({{"to", 3}}).at("walk")), timeless(last.at("walk")));
  const json first = studio.go_to({{"to", 1}});
  EXPECT_EQ(timeless(first.at("walk")), timeless(knot));
  EXPECT_EQ(first.at("history").at("undo_label"), steps.at(0));
  EXPECT_EQ(first.at("history").at("redo_label"), steps.at(1));
  EXPECT_EQ(controller(first, "swing_knee").at("inputs").at(0).at("knots").at(1), 0.346);
  EXPECT_EQ(rules_of(controller(first, "swing_knee")).at(2),
            "if delta is start and knee is deep then velocity is hold");
  // Where it stands: nothing changes.
  EXPECT_EQ(studio.go_to({{"to", 1}}).at("history"), first.at("history"));

  EXPECT_EQ(refusal([&] { studio.go_to({{"to", 4}}); }), std::make_pair(422, std::string("to")));
  EXPECT_EQ(refusal([&] { studio.go_to({{"to", -1}}); }), std::make_pair(422, std::string("to")));
  EXPECT_EQ(refusal([&] { studio.go_to({{"to", "1"}}); }), std::make_pair(400, std::string("to")));
  EXPECT_EQ(refusal([&] { studio.go_to({{"to", 1.5}}); }), std::make_pair(400, std::string("to")));
  EXPECT_EQ(refusal([&] {
              studio.go_to({{"step", 1}});
            }),
            std::make_pair(400, std::string("step")));
  EXPECT_EQ(refusal([&] { studio.go_to(json::object()); }), std::make_pair(400, std::string("to")));
  EXPECT_EQ(studio.state().at("history"), first.at("history"));

  // An edit from there drops the steps undone, as after an undo.
  const json edited = studio.edit(
      {{"controller", "swing_knee"}, {"variable", "velocity"}, {"term", "flex"}, {"value", 500}});
  EXPECT_EQ(edited.at("history").at("steps"),
            json({steps.at(0), "swing_knee: velocity flex 532 -> 500"}));
}

TEST(StudioApi, TheEndKnotsCarryTheInputsRange) {
  Studio studio(quick("end_knot"));
  const json answer = studio.edit(
      {{"controller", "swing_knee"}, {"variable", "delta"}, {"knot", 3}, {"value", 1.6}});
  const json& delta = answer.at("controller").at("inputs").at(0);
  EXPECT_EQ(delta.at("range"), json({-1.0, 1.6}));
  EXPECT_EQ(delta.at("terms").at(3).at("parameters"), json({1.29, 1.6, 2.1}));
  EXPECT_TRUE(delta.at("partition").get<bool>());
}

TEST(StudioApi, OutputWordsAndTheSetsOwnNumbersAreEdited) {
  Studio studio(quick("words"));
  const json word = studio.edit(
      {{"controller", "swing_knee"}, {"variable", "velocity"}, {"term", "hold"}, {"value", 50}});
  EXPECT_EQ(word.at("controller").at("outputs").at(0).at("words").at(2),
            json({{"name", "hold"}, {"value", 50.0}}));
  const json inertia = studio.edit({{"set", "inertia_s"}, {"value", 0.05}});
  EXPECT_EQ(inertia.at("parameters").at(0).at("value"), 0.05);
  EXPECT_NE(inertia.at("walk").at("curves"), word.at("walk").at("curves"));
  const json parameter = studio.edit({{"controller", "stairs_swing_knee_up"},
                                      {"variable", "knee"},
                                      {"term", "bent"},
                                      {"parameter", 0},
                                      {"value", -5}});
  EXPECT_EQ(parameter.at("controller").at("inputs").at(1).at("terms").at(1).at("parameters").at(0),
            -5.0);
  EXPECT_EQ(parameter.at("history").at("undo"), 3);
}

TEST(StudioApi, EditsOfOneGestureAreOneStepOfTheHistory) {
  Studio studio(quick("gesture"));
  for (double v : {0.55, 0.6, 0.65}) {
    studio.edit({{"controller", "swing_hip"},
                 {"variable", "delta"},
                 {"knot", 1},
                 {"value", v},
                 {"gesture", "drag-1"}});
  }
  const json next = studio.edit({{"controller", "swing_hip"},
                                 {"variable", "delta"},
                                 {"knot", 1},
                                 {"value", 0.5},
                                 {"gesture", "drag-2"}});
  EXPECT_EQ(next.at("history").at("undo"), 2);
  EXPECT_EQ(next.at("history").at("undo_label"), "swing_hip: delta knot 1 (center) 0.65 -> 0.5");
  const json undone = studio.undo();
  EXPECT_EQ(controller(undone, "swing_hip").at("inputs").at(0).at("knots").at(1), 0.65);
  // The drag's step reads from where it began to where it ended.
  EXPECT_EQ(undone.at("history").at("undo_label"),
            "swing_hip: delta knot 1 (center) 0.828 -> 0.65");
  const json first = studio.undo();
  EXPECT_EQ(controller(first, "swing_hip"),
            controller(Studio(quick("gesture_fresh")).state(), "swing_hip"));
}

TEST(StudioApi, RefusalsNameTheFieldAndChangeNothing) {
  const StudioOptions options = quick("refusals");
  Studio studio(options);
  studio.edit(
      {{"controller", "swing_knee"}, {"variable", "velocity"}, {"term", "hold"}, {"value", 40}});
  const json state = studio.state();
  const json walk = studio.walk();
  struct Case {
    const char* what;
    std::function<void()> call;
    int status;
    const char* field;
  };
  const auto edit = [&](json r) { return [&studio, r] { studio.edit(r); }; };
  const auto settings = [&](json r) { return [&studio, r] { studio.change_settings(r); }; };
  const std::vector<Case> cases = {
      {"a knot past its neighbour",
       edit({{"controller", "swing_knee"}, {"variable", "delta"}, {"knot", 1}, {"value", 1.3}}),
       422, "value"},
      {"a knot given as the text nan",
       edit({{"controller", "swing_knee"}, {"variable", "delta"}, {"knot", 1}, {"value", "nan"}}),
       400, "value"},
      {"a knot that is null",
       edit({{"controller", "swing_knee"}, {"variable", "delta"}, {"knot", 1}, {"value", nullptr}}),
       400, "value"},
      {"a knot that does not exist",
       edit({{"controller", "swing_knee"}, {"variable", "delta"}, {"knot", 4}, {"value", 1}}), 422,
       "knot"},
      {"a fractional knot index",
       edit({{"controller", "swing_knee"}, {"variable", "delta"}, {"knot", 0.5}, {"value", 1}}),
       400, "knot"},
      {"a value too large",
       edit({{"controller", "swing_knee"},
             {"variable", "velocity"},
             {"term", "hold"},
             {"value", 1e6}}),
       422, "value"},
      {"a term's points put out of order (a triangle 0.9 5 1.29)",
       edit({{"controller", "swing_knee"},
             {"variable", "delta"},
             {"term", "center"},
             {"parameter", 1},
             {"value", 5}}),
       422, "value"},
      {"an unknown controller", edit({{"controller", "neck"}, {"variable", "delta"}}), 422,
       "controller"},
      {"an unknown variable",
       edit({{"controller", "swing_knee"}, {"variable", "speed"}, {"knot", 0}, {"value", 0}}), 422,
       "variable"},
      {"an unknown word",
       edit({{"controller", "swing_knee"},
             {"variable", "velocity"},
             {"term", "sprint"},
             {"value", 1}}),
       422, "term"},
      {"an unknown field", edit({{"controller", "swing_knee"}, {"colour", "red"}}), 400, "colour"},
      {"a body that is not an object", edit(json::array({1, 2})), 400, "body"},
      {"a set parameter out of range", edit({{"set", "inertia_s"}, {"value", 2}}), 422, "value"},
      {"a set parameter that does not exist", edit({{"set", "mass"}, {"value", 2}}), 422, "set"},
      {"a shortest step the current step is under",
       edit({{"set", "shortest_step_leg_lengths"}, {"value", 1.1}}), 422, "value"},
      {"a step the legs cannot reach", settings({{"step", 3.0}}), 422, "step"},
      {"a step shorter than the set walks", settings({{"step", 0.2}}), 422, "step"},
      {"a speed faster than the set walks", settings({{"speed", 9.0}}), 422, "speed"},
      {"a negative speed", settings({{"speed", -1.0}}), 422, "speed"},
      {"a step and a speed", settings({{"step", 0.7}, {"speed", 1.2}}), 422, "speed"},
      {"a stature out of range", settings({{"stature", 0.5}}), 422, "stature"},
      {"too many cycles", settings({{"cycles", 1000}}), 422, "cycles"},
      {"stairs too steep", settings({{"terrain", "stairs:0.5:0.28:6"}}), 422, "terrain"},
      {"a profile file", settings({{"terrain", "profile:/etc/passwd"}}), 422, "terrain"},
      {"an unknown reference", settings({{"reference", "robots"}}), 422, "reference"},
      {"a style that does not exist",
       [&] {
         studio.open({{"set", "style:nope"}});
       },
       422, "set"},
      {"a saved set outside the workspace",
       [&] {
         studio.open({{"set", "saved:../../etc"}});
       },
       422, "set"},
      {"a folder not given",
       [&] {
         studio.open({{"set", "folder:3"}});
       },
       422, "set"},
      {"a save name with a path",
       [&] {
         studio.save({{"name", "../escape"}});
       },
       422, "name"},
      {"an empty save name",
       [&] {
         studio.save({{"name", ""}});
       },
       422, "name"},
      {"a comparison with nothing",
       [&] {
         studio.compare({{"with", "style:nope"}});
       },
       422, "with"},
      {"a download that does not exist", [&] { studio.download("../../etc/passwd"); }, 404, "file"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(refusal(c.call), std::make_pair(c.status, std::string(c.field))) << c.what;
  }
  EXPECT_EQ(studio.state(), state);
  EXPECT_EQ(studio.walk(), walk);
  EXPECT_FALSE(std::filesystem::exists(options.workspace.parent_path() / "escape"));
}

TEST(StudioApi, NothingToUndoIsAConflict) {
  Studio studio(quick("nothing"));
  EXPECT_EQ(refusal([&] { studio.undo(); }), std::make_pair(409, std::string("undo")));
}

TEST(StudioApi, ASavedSetLoadsBackWithItsEditsAndWalksTheSame) {
  StudioOptions options = quick("save");
  Studio studio(options);
  const json edited = studio.edit(
      {{"controller", "stance_knee"}, {"variable", "delta"}, {"knot", 1}, {"value", -0.2}});
  studio.edit({{"set", "pelvis_tilt_deg"}, {"value", 8.5}});
  const json saved = studio.save({{"name", "my_walk"}});
  EXPECT_EQ(saved.at("saved"), "saved:my_walk");
  const gait::ControllerSet loaded = gait::ControllerSet::load(options.workspace / "my_walk");
  EXPECT_EQ(loaded.name, "my_walk");
  EXPECT_NEAR(rig::degrees(loaded.pelvis_tilt), 8.5, 1e-9);
  EXPECT_EQ(loaded.at(gait::LegPhase::Stance, gait::Joint::Knee)
                .engine()
                .inputs[0]
                .terms[1]
                .parameters[1],
            -0.2);
  const json walk = studio.walk().at("walk");
  studio.open({{"set", "style:heavy"}});
  EXPECT_NE(studio.walk().at("walk").at("curves"), walk.at("curves"));
  const json sets = studio.state().at("sets");
  EXPECT_TRUE(std::any_of(sets.begin(), sets.end(),
                          [](const json& s) { return s.at("id") == "saved:my_walk"; }));
  const json opened = studio.open({{"set", "saved:my_walk"}});
  EXPECT_EQ(opened.at("walk").at("curves"), walk.at("curves"));
  EXPECT_EQ(controller(opened, "stance_knee").at("inputs").at(0).at("knots").at(1), -0.2);
  EXPECT_EQ(controller(opened, "stance_knee").at("inputs").at(0),
            edited.at("controller").at("inputs").at(0));
}

// A link planted in the workspace (the set's folder, or a file in it) would let a save write
// elsewhere: the save is refused naming the link, and nothing outside changes. A file the studio
// did not write stays.
TEST(StudioApi, SaveNeverFollowsALinkOutOfTheWorkspaceNorDeletesOthersFiles) {
  namespace fs = std::filesystem;
  const auto put = [](const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
  };
  const auto read = [](const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  StudioOptions options = quick("save_links");
  const fs::path outside = scratch("save_links_outside");
  put(outside / "unrelated.fll", "Engine: precious\n");
  put(outside / "swing_knee.fll", "Engine: mine\n");
  const auto outside_files = [&] {
    std::vector<std::string> names;
    for (const fs::directory_entry& e : fs::directory_iterator(outside))
      names.push_back(e.path().filename().string() + "=" + read(e.path()));
    std::sort(names.begin(), names.end());
    return names;
  };
  const std::vector<std::string> before = outside_files();
  Studio studio(options);

  // The set's folder a link to a folder outside.
  fs::create_directory_symlink(outside, options.workspace / "linked");
  const auto [status, field] = refusal([&] { studio.save({{"name", "linked"}}); });
  EXPECT_EQ(status, 422);
  EXPECT_EQ(field, "name");
  try {
    studio.save({{"name", "linked"}});
  } catch (const RequestError& e) {
    EXPECT_THAT(e.what(), HasSubstr((options.workspace / "linked").string()));
    EXPECT_THAT(e.what(), HasSubstr("symbolic link"));
  }
  EXPECT_EQ(outside_files(), before);

  // A set saved before, then one of its files replaced by a link to a file outside.
  studio.save({{"name", "mine"}});
  fs::remove(options.workspace / "mine" / "swing_knee.fll");
  fs::create_symlink(outside / "swing_knee.fll", options.workspace / "mine" / "swing_knee.fll");
  try {
    studio.save({{"name", "mine"}});
    ADD_FAILURE() << "a save wrote through a link";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.status(), 422);
    EXPECT_THAT(e.what(), HasSubstr((options.workspace / "mine" / "swing_knee.fll").string()));
  }
  EXPECT_EQ(outside_files(), before);

  // A file of one's own beside a saved set's files survives saving over it.
  fs::remove(options.workspace / "mine" / "swing_knee.fll");
  put(options.workspace / "mine" / "notes.fll", "Engine: notes\n");
  studio.save({{"name", "mine"}});
  EXPECT_EQ(read(options.workspace / "mine" / "notes.fll"), "Engine: notes\n");
  EXPECT_TRUE(fs::is_regular_file(options.workspace / "mine" / "swing_knee.fll"));
}

// The set's folder swapped for a link to a folder outside while saves run, over and over (the
// studio checked the folder, then wrote by its path): no save writes there, whatever the timing.
TEST(StudioApi, SaveFollowsNoLinkSwappedInAfterItsCheck) {
  namespace fs = std::filesystem;
  StudioOptions options = quick("save_race");
  const fs::path outside = scratch("save_race_outside");
  std::ofstream(outside / "unrelated.fll") << "Engine: precious\n";
  Studio studio(options);
  studio.save({{"name", "raced"}});
  const fs::path folder = options.workspace / "raced";
  const fs::path parked = options.workspace / "raced_parked";
  std::atomic<bool> swapping{true};
  std::thread swapper([&] {
    std::error_code ignored;
    while (swapping) {
      fs::rename(folder, parked, ignored);
      fs::create_directory_symlink(outside, folder, ignored);
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      fs::remove(folder, ignored);
      fs::rename(parked, folder, ignored);
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  });
  int saved = 0;
  int refused = 0;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (std::chrono::steady_clock::now() < end) {
    try {
      studio.save({{"name", "raced"}, {"overwrite", true}});
      ++saved;
    } catch (const RequestError&) {
      ++refused;
    }
  }
  swapping = false;
  swapper.join();
  std::vector<std::string> outside_names;
  for (const fs::directory_entry& e : fs::directory_iterator(outside))
    outside_names.push_back(e.path().filename().string());
  std::printf("%d saves while the folder was swapped for a link: %d written, %d refused\n",
              saved + refused, saved, refused);
  EXPECT_EQ(outside_names, std::vector<std::string>{"unrelated.fll"});
  EXPECT_GT(saved + refused, 20);
}

// The history says whether the set has edits not saved; a save over another set saved under
// the name is refused (409) unless asked to overwrite it, and changes nothing then.
TEST(StudioApi, UnsavedEditsAreMarkedAndASaveDoesNotReplaceAnotherSetUnasked) {
  StudioOptions options = quick("unsaved");
  Studio studio(options);
  const auto unsaved = [&] { return studio.state().at("history").at("unsaved").get<bool>(); };
  EXPECT_FALSE(unsaved());
  studio.edit(
      {{"controller", "swing_knee"}, {"variable", "velocity"}, {"term", "hold"}, {"value", 30}});
  EXPECT_TRUE(unsaved());
  EXPECT_FALSE(studio.save({{"name", "first"}}).at("history").at("unsaved").get<bool>());
  studio.undo();
  EXPECT_TRUE(unsaved());
  studio.redo();
  EXPECT_FALSE(unsaved());
  studio.edit(
      {{"controller", "swing_knee"}, {"variable", "velocity"}, {"term", "hold"}, {"value", 40}});
  EXPECT_TRUE(unsaved());
  studio.save({{"name", "first"}});  // saved there by this session: no question
  studio.open({{"set", "style:heavy"}});
  EXPECT_FALSE(unsaved());
  studio.edit(
      {{"controller", "swing_knee"}, {"variable", "velocity"}, {"term", "hold"}, {"value", 20}});
  const std::string manifest = [&] {
    std::ifstream in(options.workspace / "first" / "manifest.json");
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  try {
    studio.save({{"name", "first"}});
    ADD_FAILURE() << "the heavy set replaced the set saved as 'first' unasked";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.status(), 409);
    EXPECT_EQ(e.field(), "name");
    EXPECT_THAT(e.what(), HasSubstr("overwrite"));
  }
  std::ifstream in(options.workspace / "first" / "manifest.json");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), manifest);
  EXPECT_TRUE(unsaved());
  EXPECT_EQ(refusal([&] {
              studio.save({{"name", "first"}, {"overwrite", "yes"}});
            }),
            std::make_pair(400, std::string("overwrite")));
  studio.save({{"name", "first"}, {"overwrite", true}});
  EXPECT_FALSE(unsaved());
  std::ifstream replaced(options.workspace / "first" / "manifest.json");
  EXPECT_NE(std::string(std::istreambuf_iterator<char>(replaced), {}), manifest);
  // The set opened from a saved folder saves back to it.
  studio.open({{"set", "saved:first"}});
  studio.edit(
      {{"controller", "swing_knee"}, {"variable", "velocity"}, {"term", "hold"}, {"value", 25}});
  EXPECT_NO_THROW(studio.save({{"name", "first"}}));
}

TEST(StudioApi, OpeningAStyleIsAResetThatCanBeUndone) {
  Studio studio(quick("reset"));
  studio.edit(
      {{"controller", "swing_knee"}, {"variable", "velocity"}, {"term", "flex"}, {"value", 400}});
  const json edited = studio.state();
  const json reset = studio.open({{"set", "style:default"}});
  EXPECT_EQ(controller(reset, "swing_knee"),
            controller(Studio(quick("reset_fresh")).state(), "swing_knee"));
  EXPECT_EQ(reset.at("history").at("undo"), 2);
  studio.open({{"set", "style:heavy"}});
  EXPECT_EQ(studio.state().at("opened").at("id"), "style:heavy");
  studio.undo();
  EXPECT_EQ(studio.state().at("opened").at("id"), "style:default");
  studio.undo();
  EXPECT_EQ(studio.state().at("set"), edited.at("set"));
}

TEST(StudioApi, TheSetAsOpenedFollowsOpensAndTheirUndo) {
  Studio studio(quick("opened_follows"));
  studio.compare({{"with", "opened"}});
  const json default_walk = timeless(studio.walk().at("compare").at("walk"));
  const json heavy = studio.open({{"set", "style:heavy"}});
  EXPECT_EQ(heavy.at("compare").at("label"), "heavy (shipped style) as opened");
  EXPECT_EQ(timeless(heavy.at("compare").at("walk")), timeless(heavy.at("walk")));
  const json undone = studio.undo();
  EXPECT_EQ(undone.at("opened").at("id"), "style:default");
  EXPECT_EQ(timeless(undone.at("compare").at("walk")), default_walk);
}

TEST(StudioApi, CompareWalksTheSetAsOpenedBesideTheEditedOne) {
  Studio studio(quick("compare"));
  const json before = studio.walk().at("walk");
  studio.edit({{"controller", "swing_knee"},
               {"variable", "velocity"},
               {"term", "flex_fast"},
               {"value", 600}});
  const json compared = studio.compare({{"with", "opened"}});
  EXPECT_EQ(timeless(compared.at("compare").at("walk")), timeless(before));
  const json both = studio.walk();
  EXPECT_NE(both.at("walk").at("curves"), both.at("compare").at("walk").at("curves"));
  const json heavy = studio.compare({{"with", "style:heavy"}});
  EXPECT_EQ(heavy.at("compare").at("id"), "style:heavy");
  // A change of settings walks both again.
  const json longer = studio.change_settings({{"step", 0.75}});
  EXPECT_NE(longer.at("compare").at("walk").at("curves"),
            heavy.at("compare").at("walk").at("curves"));
  EXPECT_TRUE(studio.compare({{"with", nullptr}}).at("compare").is_null());
  EXPECT_TRUE(studio.walk().at("compare").is_null());
}

TEST(StudioApi, DownloadsAreTheFilesTheLibraryWritesOfTheWalk) {
  Studio studio(quick("downloads"));
  studio.change_settings({{"terrain", "slope:8"}});
  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  gait::WalkerOptions o;
  const terrain::Terrain ramp = terrain::Terrain::ramp(8.0);
  gait::Walker walker(set, o, ramp);
  const eval::Motion motion = eval::record_cycles(walker, 4, 120.0);
  std::ostringstream csv;
  io::write_walk_csv(csv, motion);
  EXPECT_EQ(studio.download("walk.csv").bytes, csv.str());
  EXPECT_EQ(studio.download("walk.bvh").bytes.substr(0, 9), "HIERARCHY");
  const studio::Download glb = studio.download("walk.glb");
  EXPECT_EQ(glb.content_type, "model/gltf-binary");
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error;
  std::string warning;
  ASSERT_TRUE(loader.LoadBinaryFromMemory(&model, &error, &warning,
                                          reinterpret_cast<const unsigned char*>(glb.bytes.data()),
                                          static_cast<unsigned int>(glb.bytes.size())))
      << error;
  EXPECT_EQ(model.animations.size(), 1u);
  EXPECT_EQ(studio.download("walk.terrain.csv").bytes.substr(0, 4), "x,y\n");
}

TEST(StudioApi, EveryOfferedTerrainWalksWithTheDefaultSet) {
  Studio studio(quick("terrains"));
  const json terrains = studio.state().at("terrains");
  for (const json& t : terrains) {
    const json answer = studio.change_settings({{"terrain", t.at("spec")}});
    EXPECT_EQ(answer.at("settings").at("terrain"), t.at("spec"));
    EXPECT_TRUE(answer.at("walk").at("completed").get<bool>()) << t.at("spec");
    EXPECT_GT(answer.at("walk").at("ground").size(), 2u) << t.at("spec");
  }
  // Off level ground the figures are the terrain's: every leg point, the swing's clearance.
  EXPECT_EQ(studio.walk().at("walk").at("figures").at(2).at("name"), "swing clearance");
}

TEST(StudioApi, AWalkThatStallsIsShownWithAWarning) {
  Studio studio(quick("stall"));
  // A swinging hip that never flexes: the leg cannot reach its target.
  for (const char* word : {"slow", "fast", "stay", "back"}) {
    studio.edit(
        {{"controller", "swing_hip"}, {"variable", "velocity"}, {"term", word}, {"value", 0}});
  }
  const json walk = studio.walk().at("walk");
  EXPECT_FALSE(walk.at("completed").get<bool>());
  EXPECT_THAT(walk.at("warnings").at(0).get<std::string>(), HasSubstr("did not complete"));
  EXPECT_GT(walk.at("frames").at("count").get<int>(), 100);
}

TEST(StudioApi, FoldersGivenAtTheStartOpenFirstAndAnyShapeOfTermIsShown) {
  // A set of one's own whose swing toe has a Gaussian term: no partition, no knots to drag; its
  // terms' parameters are edited instead.
  const std::filesystem::path folder = scratch("own_set") / "gaussian";
  gait::ControllerSet set = gait::ControllerSet::builtin("default");
  fuzzy::Engine toe = set.at(gait::LegPhase::Swing, gait::Joint::Toe).engine();
  toe.inputs[0].terms[0] =
      fuzzy::make_term(toe.inputs[0].terms[0].name, fuzzy::TermKind::Gaussian, "-30 10");
  set.controllers[static_cast<std::size_t>(gait::slot(gait::LegPhase::Swing, gait::Joint::Toe))] =
      gait::Controller(toe, "swing_toe.fll");
  set.name = "gaussian";
  io::save_controller_set(set, folder);
  StudioOptions options = quick("own");
  options.folders = {folder};
  Studio studio(options);
  const json state = studio.state();
  EXPECT_EQ(state.at("opened").at("id"), "folder:0");
  EXPECT_EQ(state.at("set").at("name"), "gaussian");
  const json& input = controller(state, "swing_toe").at("inputs").at(0);
  EXPECT_FALSE(input.at("partition").get<bool>());
  EXPECT_EQ(input.at("terms").at(0).at("shape"), "Gaussian");
  EXPECT_EQ(input.at("terms").at(0).at("samples").size(), 101u);
  // Sampled over the input's range (-30 to 60 deg) from the engine's own Gaussian: 1 at its
  // mean, -30, and exp(-0.99^2 / 2) at sample 11, 9.9 deg (0.99 standard deviations) on.
  const json& samples = input.at("terms").at(0).at("samples");
  EXPECT_DOUBLE_EQ(samples.at(0).get<double>(), 1.0);
  EXPECT_NEAR(samples.at(11).get<double>(), std::exp(-0.5 * 0.99 * 0.99), 1e-12);
  const std::string name = input.at("name");
  EXPECT_EQ(
      refusal([&] {
        studio.edit({{"controller", "swing_toe"}, {"variable", name}, {"knot", 0}, {"value", 0}});
      }),
      std::make_pair(422, std::string("knot")));
  const json moved = studio.edit({{"controller", "swing_toe"},
                                  {"variable", name},
                                  {"term", input.at("terms").at(0).at("name")},
                                  {"parameter", 1},
                                  {"value", 0.5}});
  EXPECT_EQ(moved.at("controller").at("inputs").at(0).at("terms").at(0).at("parameters"),
            json({-30.0, 0.5}));
  EXPECT_THROW(
      {
        StudioOptions missing = quick("missing");
        missing.folders = {scratch("empty_folder")};
        Studio broken(missing);
      },
      std::exception);
}

// ---- the upper body ----------------------------------------------------------------------------

// A walk's body as the page reads it: each frame's joints in metres (x along the walk, y up, z to
// the left), the running sum of the millimetres' changes sent.
struct BodyTrack {
  std::vector<std::string> joints;
  std::vector<double> metres;  // [frame][joint][x, y, z]

  explicit BodyTrack(const json& walk)
      : joints(walk.at("body").at("joints").get<std::vector<std::string>>()) {
    EXPECT_EQ(walk.at("body").at("unit"), "mm");
    const auto changes = walk.at("body").at("changes").get<std::vector<long long>>();
    const std::size_t stride = joints.size() * 3;
    std::vector<long long> mm(changes.size());
    for (std::size_t k = 0; k < changes.size(); ++k)
      mm[k] = (k < stride ? 0 : mm[k - stride]) + changes[k];
    for (const long long v : mm)
      metres.push_back(static_cast<double>(v) / 1e3);
  }
  std::size_t frames() const { return metres.size() / (joints.size() * 3); }
  std::array<double, 3> at(std::size_t frame, const std::string& name) const {
    const auto j = static_cast<std::size_t>(
        std::distance(joints.begin(), std::find(joints.begin(), joints.end(), name)));
    if (j == joints.size()) throw std::runtime_error("no joint " + name);
    const std::size_t k = (frame * joints.size() + j) * 3;
    return {metres.at(k), metres.at(k + 1), metres.at(k + 2)};
  }
};

// The left upper arm's inclination forward of the vertical at each frame sent, degrees.
std::vector<double> left_arm_inclination(const BodyTrack& body) {
  std::vector<double> angles;
  for (std::size_t f = 0; f < body.frames(); ++f) {
    const auto shoulder = body.at(f, "leftUpperArm");
    const auto elbow = body.at(f, "leftLowerArm");
    angles.push_back(rig::degrees(std::atan2(elbow[0] - shoulder[0], shoulder[1] - elbow[1])));
  }
  return angles;
}

// The largest distance of joint `name` between two walks' bodies over their frames, m.
double largest_move(const json& a, const json& b, const std::string& name) {
  const BodyTrack one(a);
  const BodyTrack other(b);
  double largest = 0.0;
  for (std::size_t f = 0; f < one.frames(); ++f) {
    const auto p = one.at(f, name);
    const auto q = other.at(f, name);
    largest = std::max(largest, std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]));
  }
  return largest;
}

gait::Walker default_walker(const gait::ControllerSet& set, const terrain::Terrain& ground) {
  gait::WalkerOptions o;
  o.segments = rig::segments_from_stature(1.75);
  o.step_length = 0.70;
  return gait::Walker(set, o, ground);
}

TEST(StudioApi, TheWalkCarriesTheWholeBodyAsTheLibraryPosesIt) {
  Studio studio(quick("body"));
  const json walk = studio.walk().at("walk");
  const json& joints = walk.at("body").at("joints");
  ASSERT_EQ(joints.size(), body::kJointCount + 2);
  EXPECT_EQ(joints.at(0), "hips");
  EXPECT_EQ(joints.at(body::kJointCount), "leftHeel");
  // Every other page frame: 15 a second.
  const auto count = walk.at("frames").at("count").get<std::size_t>();
  EXPECT_EQ(walk.at("body").at("fps"), 15.0);
  const auto body_count = walk.at("body").at("count").get<std::size_t>();
  EXPECT_EQ(body_count, (count + 1) / 2);
  ASSERT_EQ(walk.at("body").at("changes").size(), body_count * joints.size() * 3);
  const BodyTrack track(walk);
  ASSERT_EQ(track.frames(), body_count);

  // A game's follower on the straight path, updated every frame the walk is recorded at: at the
  // frames sent every joint is where the studio sends it (to the millimetre it is sent at).
  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  const terrain::Terrain flat = terrain::Terrain::flat();
  gait::Walker walker = default_walker(set, flat);
  const path::Path straight;
  const body::Humanoid humanoid = body::humanoid_from_stature(1.75);
  body::PathFollower follower(humanoid, straight, walker);
  double worst = 0.0;
  for (std::size_t i = 0; i < 8 * body_count; ++i) {
    if (i > 0) walker.advance(1.0 / 120.0);
    const body::BodyPose& pose = follower.update(walker);
    if (i % 8 != 0) continue;
    for (std::size_t j = 0; j < joints.size(); ++j) {
      const body::Vec3& p =
          j < body::kJointCount ? pose.position[j] : pose.heel[j - body::kJointCount];
      const auto sent = track.at(i / 8, joints.at(j).get<std::string>());
      worst = std::max(
          {worst, std::abs(sent[0] - p.z), std::abs(sent[1] - p.y), std::abs(sent[2] - p.x)});
    }
  }
  EXPECT_LE(worst, 5e-4 + 1e-9);
  // The left side is +z, and the feet stand apart there.
  EXPECT_GT(track.at(0, "leftUpperArm")[2], 0.1);
  EXPECT_LT(track.at(0, "rightFoot")[2], 0.0);
}

TEST(StudioApi, UpperBodyControllersAreEditedAsTheLegsAndMoveTheBody) {
  Studio studio(quick("upper_body"));
  const json state = studio.state();
  const json& shoulder = controller(state, "upper_body_shoulder");
  EXPECT_EQ(shoulder.at("title"), "upper body: shoulder");
  EXPECT_EQ(shoulder.at("group"), "upper body");
  EXPECT_EQ(shoulder.at("part"), "shoulder");
  EXPECT_TRUE(shoulder.at("slot").is_null());
  EXPECT_EQ(shoulder.at("inputs").at(0).at("knots"), json({-20.0, 11.0, 42.0}));
  for (const char* id :
       {"upper_body_elbow", "upper_body_pelvis_rotation", "upper_body_thorax_rotation",
        "upper_body_pelvis_obliquity", "upper_body_pelvis_sway", "upper_body_trunk_lean"}) {
    EXPECT_EQ(controller(state, id).at("group"), "upper body") << id;
  }
  const json before = studio.walk().at("walk");

  // A knot: the arms move, the legs' walk and the pelvis do not.
  const json knot = studio.edit(
      {{"controller", "upper_body_shoulder"}, {"variable", "hip"}, {"knot", 1}, {"value", 25}});
  EXPECT_EQ(knot.at("controller").at("inputs").at(0).at("knots"), json({-20.0, 25.0, 42.0}));
  EXPECT_EQ(knot.at("history").at("undo_label"),
            "upper_body_shoulder: hip knot 1 (neutral) 11 -> 25");
  EXPECT_EQ(knot.at("walk").at("frames"), before.at("frames"));
  EXPECT_GT(largest_move(knot.at("walk"), before, "leftHand"), 0.05);
  EXPECT_EQ(largest_move(knot.at("walk"), before, "leftFoot"), 0.0);
  EXPECT_EQ(largest_move(knot.at("walk"), before, "hips"), 0.0);

  // The word the arm reaches forward with: the arm swings further forward.
  const json word = studio.edit({{"controller", "upper_body_shoulder"},
                                 {"variable", "angle"},
                                 {"term", "ahead"},
                                 {"value", 60}});
  const std::vector<double> was = left_arm_inclination(BodyTrack(before));
  const std::vector<double> now = left_arm_inclination(BodyTrack(word.at("walk")));
  EXPECT_GT(*std::max_element(now.begin(), now.end()),
            *std::max_element(was.begin(), was.end()) + 10.0);

  // A rule: the pelvis turns forward, not back, on the side whose other leg lands.
  std::vector<std::string> rules = rules_of(controller(state, "upper_body_pelvis_rotation"));
  ASSERT_EQ(rules.size(), 6u);
  EXPECT_EQ(rules[3], "if hip is neutral and knee is bent then angle is ahead");
  EXPECT_EQ(rules[4], "if hip is flexed and knee is straight then angle is back");
  rules[4] = "if hip is flexed and knee is straight then angle is forward";
  const json ruled =
      studio.edit_rules({{"controller", "upper_body_pelvis_rotation"}, {"rules", rules}});
  EXPECT_EQ(ruled.at("history").at("undo_label"), "upper_body_pelvis_rotation: rule 5 edited");
  EXPECT_GT(largest_move(ruled.at("walk"), word.at("walk"), "leftUpperLeg"), 0.007);
  EXPECT_EQ(ruled.at("walk").at("frames"), before.at("frames"));

  // Undone to the set as opened: the body exactly as it was; redone: as edited.
  studio.undo();
  studio.undo();
  const json undone = studio.undo();
  EXPECT_EQ(timeless(undone.at("walk")), timeless(before));
  EXPECT_EQ(controller(undone, "upper_body_shoulder").at("inputs"), shoulder.at("inputs"));
  studio.redo();
  studio.redo();
  EXPECT_EQ(timeless(studio.redo().at("walk")), timeless(ruled.at("walk")));
  EXPECT_EQ(rules_of(controller(studio.state(), "upper_body_pelvis_rotation")), rules);
}

TEST(StudioApi, AnUpperBodyEditIsSavedToItsFileAndOpensAgain) {
  StudioOptions options = quick("upper_body_save");
  Studio studio(options);
  studio.edit(
      {{"controller", "upper_body_elbow"}, {"variable", "hip"}, {"knot", 1}, {"value", 20}});
  const json walk = studio.walk().at("walk");
  studio.save({{"name", "arms"}});
  const std::filesystem::path folder = options.workspace / "arms";
  ASSERT_TRUE(std::filesystem::is_regular_file(folder / "upper_body_elbow.fll"));
  std::ifstream manifest(folder / "manifest.json");
  const json names = json::parse(manifest).at("upper_body");
  EXPECT_EQ(names.size(), 7u);
  EXPECT_EQ(names.at("elbow"), "upper_body_elbow.fll");
  const gait::ControllerSet loaded = gait::ControllerSet::load(folder);
  const auto& elbow = loaded.upper_body[static_cast<std::size_t>(gait::UpperBody::Elbow)];
  ASSERT_TRUE(elbow.has_value());
  EXPECT_EQ(elbow->engine().inputs.at(0).terms.at(1).parameters.at(1), 20.0);
  studio.open({{"set", "style:default"}});
  EXPECT_NE(timeless(studio.walk().at("walk")), timeless(walk));
  const json opened = studio.open({{"set", "saved:arms"}});
  EXPECT_EQ(controller(opened, "upper_body_elbow").at("inputs").at(0).at("knots").at(1), 20.0);
  EXPECT_EQ(timeless(opened.at("walk")), timeless(walk));
}

TEST(StudioApi, AnUpperBodyControllerReadingTheSoleOrAWordItLacksIsRefused) {
  StudioOptions options = quick("upper_body_refusals");
  Studio studio(options);
  // A set whose shoulder reads the sole (as a file of one's own might) does not open: the loader
  // refuses it, and the studio answers naming the file and the metric.
  studio.save({{"name", "reads_sole"}});
  const std::filesystem::path fll = options.workspace / "reads_sole" / "upper_body_shoulder.fll";
  std::string text;
  {
    std::ifstream in(fll);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::vector<std::pair<std::string, std::string>> changes = {
      {"InputVariable: hip", "InputVariable: sole"}, {"if hip is", "if sole is"}};
  for (const auto& [from, to] : changes) {
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at))
      text.replace(at, from.size(), to);
  }
  std::ofstream(fll) << text;
  const json state = studio.state();
  const json walk = studio.walk();
  try {
    studio.open({{"set", "saved:reads_sole"}});
    ADD_FAILURE() << "a set whose upper body reads the sole opened";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.status(), 422);
    EXPECT_EQ(e.field(), "set");
    EXPECT_THAT(e.what(), HasSubstr("upper_body_shoulder.fll"));
    EXPECT_THAT(e.what(), HasSubstr("not 'sole'"));
  }
  // A rule naming a metric the shoulder does not read: it has no such input (the trunk's lean
  // reads the incline; the sole no upper body controller may read).
  for (const char* metric : {"sole", "incline", "stairs"}) {
    std::vector<std::string> rules = rules_of(controller(state, "upper_body_shoulder"));
    rules.at(0) = std::string("if ") + metric + " is level then angle is ahead";
    try {
      studio.edit_rules({{"controller", "upper_body_shoulder"}, {"rules", rules}});
      ADD_FAILURE() << "a rule reading " << metric << " was taken";
    } catch (const RequestError& e) {
      EXPECT_EQ(e.status(), 422);
      EXPECT_EQ(e.field(), "rules");
      EXPECT_THAT(e.what(), HasSubstr(std::string("rule 1")));
      EXPECT_THAT(e.what(), HasSubstr(std::string("'") + metric + "'"));
      EXPECT_THAT(e.what(), HasSubstr("(inputs: hip;"));
    }
  }
  EXPECT_EQ(
      refusal([&] {
        studio.edit(
            {{"controller", "upper_body_wrist"}, {"variable", "hip"}, {"knot", 1}, {"value", 12}});
      }),
      std::make_pair(422, std::string("controller")));
  EXPECT_EQ(studio.state(), state);
  EXPECT_EQ(timeless(studio.walk().at("walk")), timeless(walk.at("walk")));
}

TEST(StudioApi, FiredRulesOfTheUpperBodyAreTheLeftSidesReading) {
  Studio studio(quick("upper_body_fired"));
  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  const terrain::Terrain flat = terrain::Terrain::flat();
  gait::Walker walker = default_walker(set, flat);
  std::size_t at = 0;
  for (const std::size_t frame : {15u, 40u, 66u}) {
    for (; at < frame * 4; ++at)
      walker.advance(1.0 / 120.0);
    const json fired = studio.fired({{"time", static_cast<double>(frame) / 30.0}});
    for (int p = 0; p < gait::kUpperBodyCount; ++p) {
      const auto part = static_cast<gait::UpperBody>(p);
      const std::string id = "upper_body_" + std::string(gait::upper_body_name(part));
      const json& c = fired.at("controllers").at(id);
      // The left side's: its own leg, or the other for the turns.
      const bool turn =
          part == gait::UpperBody::PelvisRotation || part == gait::UpperBody::ThoraxRotation;
      EXPECT_EQ(c.at("side"), "left") << id;
      EXPECT_EQ(c.at("leg"), turn ? "right" : "left") << id;
      const gait::Controller& controller = *set.upper_body[static_cast<std::size_t>(p)];
      const gait::MetricValues read = body::PathFollower::leg_metrics(walker, turn ? 1 : 0);
      gait::MetricValues metrics{};
      ASSERT_EQ(c.at("inputs").size(), controller.input_count()) << id;
      for (std::size_t i = 0; i < controller.input_count(); ++i) {
        const auto m = static_cast<std::size_t>(controller.input(i));
        EXPECT_NEAR(c.at("inputs").at(i).get<double>(), read[m], 5e-5) << id << " at " << frame;
        metrics[m] = c.at("inputs").at(i).get<double>();
      }
      fuzzy::Workspace workspace = controller.make_workspace();
      EXPECT_NEAR(c.at("output").get<double>(), controller.evaluate(metrics, workspace), 1e-4)
          << id;
      ASSERT_EQ(c.at("rules").size(), controller.engine().rule_blocks.at(0).rules.size()) << id;
      EXPECT_GT(*std::max_element(c.at("rules").begin(), c.at("rules").end()), 0.2) << id;
    }
  }
}

// ---- a path drawn on the ground
// ------------------------------------------------------------------

// An L: 6 m ahead (+z), a right angle to the left (+x), 6 m on; corners rounded at 1 m.
const json kLPath =
    json::array({json::array({0.0, 0.0}), json::array({0.0, 6.0}), json::array({6.0, 6.0})});

// The rounded path every centimetre, to find how far a point lies from it.
std::vector<path::GroundPoint> dense(const path::Path& route) {
  std::vector<path::GroundPoint> points;
  for (double s = 0.0; s <= route.length(); s += 0.01)
    points.push_back(route.at(s).point);
  return points;
}

// How far the ground point (x, z) lies from the path (m).
double off_path(const std::vector<path::GroundPoint>& curve, double x, double z) {
  double nearest = 1e9;
  for (const path::GroundPoint& p : curve)
    nearest = std::min(nearest, std::hypot(p.x - x, p.z - z));
  return nearest;
}

// The largest horizontal move of a heel, ball or toe tip between two frames of the body sent (1/15
// s apart), where the walk's frames (1/30 s apart) have that point within 2 mm of the ground at
// both and the frame between: a planted foot's slip, as tests/body/follower_test.cpp measures it
// at 60 Hz but over the four such frames of a body frame.
// Also counts the moves measured.
double planted_slip(const json& walk, const BodyTrack& body, int& measured) {
  const auto legs = walk.at("frames").at("legs").get<std::vector<double>>();
  const auto frames = walk.at("frames").at("count").get<std::size_t>();
  const auto on_ground = [&](std::size_t frame, std::size_t side, std::size_t point) {
    return legs.at(frame * 24 + side * 12 + point * 2 + 1) < 0.002;
  };
  double worst = 0.0;
  for (std::size_t k = 0; k + 1 < body.frames() && 2 * k + 2 < frames; ++k) {
    for (std::size_t side = 0; side < 2; ++side) {
      const std::string name = side == 0 ? "left" : "right";
      const std::string joints[] = {name + "Heel", name + "Toes", name + "ToesEnd"};
      for (std::size_t p = 0; p < 3; ++p) {  // heel, ball, tip: the walk's points 3, 4, 5
        if (!on_ground(2 * k, side, p + 3) || !on_ground(2 * k + 1, side, p + 3) ||
            !on_ground(2 * k + 2, side, p + 3)) {
          continue;
        }
        const auto a = body.at(k, joints[p]);
        const auto b = body.at(k + 1, joints[p]);
        worst = std::max(worst, std::hypot(b[0] - a[0], b[2] - a[2]));
        ++measured;
      }
    }
  }
  return worst;
}

TEST(StudioApi, TheWholeBodyWalksAPathDrawnOnTheGround) {
  Studio studio(quick("path"));
  const json answer = studio.change_settings({{"path", kLPath}, {"corner_radius", 1.0}});
  EXPECT_EQ(answer.at("settings").at("path"), kLPath);
  EXPECT_EQ(answer.at("settings").at("corner_radius"), 1.0);
  const json& walk = answer.at("walk");
  EXPECT_TRUE(walk.at("completed").get<bool>()) << walk.at("warnings");
  const std::vector<path::GroundPoint> corners = {{0, 0}, {0, 6}, {6, 6}};
  const path::Path route = path::Path::polyline(corners, 1.0);
  EXPECT_NEAR(walk.at("path").at("length").get<double>(), route.length(), 1e-12);
  // The rounded path as sent: the library's every 0.1 m, to the millimetre.
  const auto samples = walk.at("path").at("samples").get<std::vector<double>>();
  ASSERT_EQ(samples.size(), 2 * static_cast<std::size_t>(std::ceil(route.length() / 0.1) + 1));
  for (std::size_t i = 0; i < samples.size() / 2; ++i) {
    const path::GroundPoint p =
        route.at(std::min(0.1 * static_cast<double>(i), route.length())).point;
    EXPECT_NEAR(samples[2 * i], p.x, 5e-4 + 1e-9);
    EXPECT_NEAR(samples[2 * i + 1], p.z, 5e-4 + 1e-9);
  }
  // Walked to the path's end, and no further than a frame past it.
  const auto pelvis = walk.at("frames").at("pelvis").get<std::vector<double>>();
  EXPECT_GE(pelvis.at(pelvis.size() - 3), route.length() - 0.05);

  // The hips on the path all the way (the body's x is the path's z, its z the path's x), round the
  // corner to its end.
  const BodyTrack body(walk);
  const std::vector<path::GroundPoint> curve = dense(route);
  double farthest = 0.0;
  double sum = 0.0;
  for (std::size_t f = 0; f < body.frames(); ++f) {
    const auto hips = body.at(f, "hips");
    const double off = off_path(curve, hips[2], hips[0]);
    farthest = std::max(farthest, off);
    sum += off;
  }
  EXPECT_LT(farthest, 0.05);
  const auto end = body.at(body.frames() - 1, "hips");
  EXPECT_GT(end[2], 5.0);  // past the corner, along +x
  EXPECT_NEAR(end[0], 6.0, 0.05);
  // Planted feet stay put: at most 1 mm a 60 Hz frame (tests/body/follower_test.cpp's bound),
  // four of them to a body frame, and the millimetres sent (half of one each way, on x and z).
  // Every joint where a game's follower on that path, updated every frame the walk is recorded
  // at, puts it (to the millimetre sent).
  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  const terrain::Terrain flat = terrain::Terrain::flat();
  gait::Walker walker = default_walker(set, flat);
  const body::Humanoid humanoid = body::humanoid_from_stature(1.75);
  body::PathFollower follower(humanoid, route, walker);
  double worst = 0.0;
  for (std::size_t i = 0; i < 8 * body.frames(); ++i) {
    if (i > 0) walker.advance(1.0 / 120.0);
    const body::BodyPose& pose = follower.update(walker);
    if (i % 8 != 0) continue;
    for (std::size_t j = 0; j < body.joints.size(); ++j) {
      const body::Vec3& p =
          j < body::kJointCount ? pose.position[j] : pose.heel[j - body::kJointCount];
      const auto sent = body.at(i / 8, body.joints[j]);
      worst = std::max(
          {worst, std::abs(sent[0] - p.z), std::abs(sent[1] - p.y), std::abs(sent[2] - p.x)});
    }
  }
  EXPECT_LE(worst, 5e-4 + 1e-9);
  int measured = 0;
  const double slip = planted_slip(walk, body, measured);
  EXPECT_LT(slip, 4 * 1e-3 + std::sqrt(2.0) * 1e-3);
  EXPECT_GT(measured, 100);  // a foot point stands for most of every step
  RecordProperty("hips_farthest_from_path_mm", std::to_string(farthest * 1e3));
  RecordProperty("hips_mean_from_path_mm",
                 std::to_string(sum / static_cast<double>(body.frames()) * 1e3));
  RecordProperty("planted_slip_per_body_frame_mm", std::to_string(slip * 1e3));
  RecordProperty("planted_moves_measured", measured);
  RecordProperty("frames", std::to_string(walk.at("frames").at("count").get<int>()));
  RecordProperty("walk_ms", std::to_string(walk.at("timing_ms").at("walk").get<double>()));
  RecordProperty("body_ms", std::to_string(walk.at("timing_ms").at("body").get<double>()));
}

TEST(StudioApi, ADrawnPathIsKeptThroughEditsUndoAndCompareUntilStraightAgain) {
  Studio studio(quick("path_kept"));
  const json straight = studio.walk().at("walk");
  EXPECT_TRUE(straight.at("path").is_null());
  EXPECT_TRUE(studio.state().at("settings").at("path").is_null());
  studio.change_settings({{"path", kLPath}});
  EXPECT_EQ(studio.state().at("settings").at("path"), kLPath);
  EXPECT_EQ(studio.state().at("settings").at("limits").at("corner_radius"), json({0.5, 20.0}));
  // An edit walks the set again on the path; its undo too (the path is a setting, not a step).
  const json edited = studio.edit({{"controller", "upper_body_shoulder"},
                                   {"variable", "angle"},
                                   {"term", "ahead"},
                                   {"value", 60}});
  EXPECT_EQ(edited.at("walk").at("path").at("points"), kLPath);
  EXPECT_GT(BodyTrack(edited.at("walk")).at(BodyTrack(edited.at("walk")).frames() - 1, "hips")[2],
            5.0);
  const json undone = studio.undo();
  EXPECT_EQ(undone.at("settings").at("path"), kLPath);
  EXPECT_EQ(undone.at("walk").at("path").at("points"), kLPath);
  // A compared set walks the same path.
  const json compared = studio.compare({{"with", "style:heavy"}});
  EXPECT_EQ(compared.at("compare").at("walk").at("path").at("points"), kLPath);
  // The radius alone rounds the same points anew.
  const json wider = studio.change_settings({{"corner_radius", 2.5}});
  EXPECT_EQ(wider.at("settings").at("path"), kLPath);
  EXPECT_EQ(wider.at("walk").at("path").at("corner_radius"), 2.5);
  EXPECT_LT(wider.at("walk").at("path").at("length").get<double>(),
            undone.at("walk").at("path").at("length").get<double>());
  // Straight again: the walk is the straight one, as before the path.
  const json back = studio.change_settings({{"path", nullptr}, {"corner_radius", 1.0}});
  EXPECT_TRUE(back.at("settings").at("path").is_null());
  EXPECT_TRUE(back.at("walk").at("path").is_null());
  EXPECT_EQ(timeless(back.at("walk")), timeless(straight));
}

TEST(StudioApi, ABadPathIsRefusedNamingItsFieldAndPointAndChangesNothing) {
  Studio studio(quick("path_refusals"));
  studio.change_settings({{"path", kLPath}});
  const json state = studio.state();
  const json walk = studio.walk();
  struct Case {
    const char* what;
    json request;
    int status;
    const char* field;
    const char* says;
  };
  json many = json::array();
  for (int i = 0; i < 257; ++i)
    many.push_back({0.0, 0.1 * i});
  const std::vector<Case> cases = {
      {"a NaN coordinate", {{"path", {{0, 0}, {NAN, 3}}}}, 422, "path", "path point 2"},
      {"an infinite coordinate",
       {{"path", {{0, 0}, {0, 3}, {INFINITY, 3}}}},
       422,
       "path",
       "path point 3"},
      {"a point as text", {{"path", {{0, 0}, {"1", 3}}}}, 400, "path", "path point 2"},
      {"a point of three numbers", {{"path", {{0, 0}, {1, 2, 3}}}}, 400, "path", "path point 2"},
      {"a path that is not a list", {{"path", 5}}, 400, "path", "list"},
      {"one point", {{"path", {{0, 0}}}}, 422, "path", "2 to 256 points, got 1"},
      {"257 points", {{"path", many}}, 422, "path", "got 257"},
      {"a point repeated",
       {{"path", {{0, 0}, {0, 3}, {0, 3}}}},
       422,
       "path",
       "path point 3 is the same"},
      {"a corner too sharp for the radius its legs leave",
       {{"path", {{0, 0}, {0, 0.4}, {0.4, 0.4}}}},
       422,
       "path",
       "path point 2: the corner is too sharp"},
      {"a path turning back on itself",
       {{"path", {{0, 0}, {0, 5}, {0.1, 0}}}},
       422,
       "path",
       "path point 2: the path turns back"},
      {"a path too long", {{"path", {{0, 0}, {0, 30}, {30, 30}}}}, 422, "path", "up to 50 m"},
      {"a corner radius below the path's smallest",
       {{"corner_radius", 0.3}},
       422,
       "corner_radius",
       "between 0.5 and 20"},
      {"a corner radius as text", {{"corner_radius", "1"}}, 400, "corner_radius", "number"},
  };
  for (const Case& c : cases) {
    try {
      studio.change_settings(c.request);
      ADD_FAILURE() << c.what << " was taken";
    } catch (const RequestError& e) {
      EXPECT_EQ(e.status(), c.status) << c.what;
      EXPECT_EQ(e.field(), c.field) << c.what;
      EXPECT_THAT(e.what(), HasSubstr(c.says)) << c.what;
    }
  }
  EXPECT_EQ(studio.state(), state);
  EXPECT_EQ(studio.walk(), walk);
}

}  // namespace
}  // namespace fuzzygait

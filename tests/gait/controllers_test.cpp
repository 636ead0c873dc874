// Controller sets: loading from files, clear errors naming the file, and the fast path that must
// agree with the general fuzzy evaluator.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/fuzzy/partition.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "support/controller_sets.hpp"
#include "support/text.hpp"

using namespace fuzzygait;
using ::testing::HasSubstr;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

namespace {

std::map<std::string, std::string> default_files() {
  std::map<std::string, std::string> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(fuzzygait::test::controllers_dir() / "default")) {
    files[entry.path().filename().string()] = fuzzygait::test::read_text(entry.path());
  }
  return files;
}

std::string error_of(const std::string& manifest, const std::map<std::string, std::string>& files) {
  try {
    gait::ControllerSet::parse(manifest, files, "set");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

// Every set compiled into the library is the one in controllers/, and every set there (a folder
// with a manifest) is compiled in.
TEST(ControllerSet, BuiltinMatchesTheFilesOnDisk) {
  const std::vector<std::string> shipped = fuzzygait::test::shipped_set_names();
  const std::vector<std::string> names = gait::ControllerSet::builtin_names();
  EXPECT_EQ(names, shipped);
  EXPECT_THAT(names, ::testing::Contains("default"));
  // Compiled-in files outside a set (the paper's example engine) are not a set.
  EXPECT_THROW(gait::ControllerSet::builtin("paper"), std::invalid_argument);
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const gait::ControllerSet builtin = gait::ControllerSet::builtin(name);
    const gait::ControllerSet loaded =
        gait::ControllerSet::load(fuzzygait::test::controllers_dir() / name);
    ASSERT_EQ(builtin.controllers.size(), static_cast<std::size_t>(gait::kSlotCount));
    ASSERT_EQ(loaded.controllers.size(), builtin.controllers.size());
    for (std::size_t s = 0; s < builtin.controllers.size(); ++s) {
      EXPECT_EQ(builtin.controllers[s].engine(), loaded.controllers[s].engine())
          << gait::slot_name(static_cast<int>(s));
    }
    EXPECT_EQ(builtin.name, loaded.name);
    EXPECT_EQ(builtin.description, loaded.description);
    EXPECT_EQ(builtin.inertia, loaded.inertia);
    EXPECT_EQ(builtin.pelvis_tilt, loaded.pelvis_tilt);
    EXPECT_EQ(builtin.swing_knee_reference_sweep, loaded.swing_knee_reference_sweep);
  }
}

TEST(ControllerSet, ErrorsNameTheFileAndTheProblem) {
  std::map<std::string, std::string> files = default_files();
  const std::string manifest = files.at("manifest.json");
  files.erase("manifest.json");
  EXPECT_THAT(error_of("{ \"name\": ", files), HasSubstr("set/manifest.json"));
  std::string missing = manifest;
  missing.replace(missing.find("\"swing_knee\""), 12, "\"swing_kneee\"");
  EXPECT_THAT(error_of(missing, files), HasSubstr("unknown controller slot 'swing_kneee'"));
  std::map<std::string, std::string> broken = files;
  std::string& knee = broken.at("swing_knee.fll");
  knee.replace(knee.find("InputVariable: knee"), 19, "InputVariable: kne");
  for (const std::string from : {"if knee is", "and knee is"}) {
    for (std::size_t at = knee.find(from); at != std::string::npos; at = knee.find(from)) {
      knee.replace(at, from.size(), "and kne is");
    }
  }
  EXPECT_THAT(error_of(manifest, broken), HasSubstr("set/swing_knee.fll"));
  broken = files;
  broken.at("swing_toe.fll").replace(broken.at("swing_toe.fll").find("range:"), 6, "rang:");
  EXPECT_THAT(error_of(manifest, broken), HasSubstr("set/swing_toe.fll:"));
  std::string inertia = manifest;
  inertia.replace(inertia.find("\"inertia_s\""), 11, "\"inertia_s\": -1, \"x\"");
  EXPECT_THAT(error_of(inertia, files), HasSubstr("'inertia_s' must be a number between"));
  // Wrong JSON types and numbers JSON cannot hold name the file and the key.
  std::string name = manifest;
  const std::size_t named = name.find("\"name\"");
  name.replace(named, name.find(',', named) - named, "\"name\": 5");
  EXPECT_THAT(error_of(name, files),
              HasSubstr("set/manifest.json:2: 'name' must be a string, found a number"));
  std::string slot = manifest;
  const std::size_t hip = slot.find("\"swing_hip\"");
  slot.replace(hip, slot.find(',', hip) - hip, "\"swing_hip\": 5");
  EXPECT_THAT(error_of(slot, files),
              HasSubstr("set/manifest.json:11: controller 'swing_hip' must name an FLL file"));
  std::string shortest = manifest;
  const std::size_t at = shortest.find("\"shortest_step_leg_lengths\"");
  shortest.replace(at, shortest.find(',', at) - at, "\"shortest_step_leg_lengths\": 0");
  EXPECT_THAT(error_of(shortest, files),
              HasSubstr("'shortest_step_leg_lengths' must be a number between"));
  // A joint controller's numbers are finite: a NaN speed or a term over nothing walks nonsense.
  broken = files;
  std::string& hip_file = broken.at("swing_hip.fll");
  const std::size_t fast = hip_file.find("term: fast Constant ");
  hip_file.replace(fast, hip_file.find('\n', fast) - fast, "term: fast Constant nan");
  const int line =
      1 + static_cast<int>(std::count(hip_file.begin(), hip_file.begin() + fast, '\n'));
  EXPECT_THAT(
      error_of(manifest, broken),
      HasSubstr("set/swing_hip.fll:" + std::to_string(line) +
                ": term 'fast' parameter 'value' must be a finite number here, found 'nan'"));
  std::string huge = manifest;
  huge.replace(huge.find("\"inertia_s\""), 11, "\"inertia_s\": 1e400, \"x\"");
  EXPECT_THAT(error_of(huge, files),
              HasSubstr("set/manifest.json:4:16: the number 1e400 is beyond what a double holds"));
}

// The stride relation: a readable FLL file from pace to step that must rise, so that a speed
// asks for one step; the cadence and acceleration are the manifest's numbers.
TEST(ControllerSet, TheStrideRelationRisesAndInverts) {
  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  ASSERT_TRUE(set.stride.has_value());
  EXPECT_EQ(set.cadence, 110.0);
  EXPECT_EQ(set.acceleration, 0.6);
  double before = 0.0;
  for (double pace = set.slowest_pace(); pace <= set.fastest_pace(); pace += 0.01) {
    const double step = set.step_at_pace(pace);
    EXPECT_GT(step, before) << pace;
    EXPECT_NEAR(set.pace_at_step(step), pace, 1e-9) << pace;
    before = step;
  }
  // Outside the steps it gives, the pace clamps to the stride's range.
  EXPECT_EQ(set.pace_at_step(0.01), set.slowest_pace());
  EXPECT_EQ(set.pace_at_step(5.0), set.fastest_pace());

  std::map<std::string, std::string> files = default_files();
  const std::string manifest = files.at("manifest.json");
  files.erase("manifest.json");
  std::map<std::string, std::string> falling = files;
  std::string& stride = falling.at("stride.fll");
  stride.replace(stride.find("term: longest Constant 1.02"), 27, "term: longest Constant 0.50");
  EXPECT_THAT(error_of(manifest, falling),
              HasSubstr("set/stride.fll: the step must rise with the pace"));
  std::map<std::string, std::string> other = files;
  std::string& input = other.at("stride.fll");
  input.replace(input.find("InputVariable: pace"), 19, "InputVariable: knee");
  for (std::size_t at = input.find("if pace"); at != std::string::npos; at = input.find("if pace"))
    input.replace(at, 7, "if knee");
  EXPECT_THAT(error_of(manifest, other), HasSubstr("set/stride.fll: the stride reads one input"));
  std::string missing = manifest;
  missing.replace(missing.find("\"stride.fll\""), 12, "\"strides.fll\"");
  EXPECT_THAT(error_of(missing, files),
              HasSubstr("'stride' names 'strides.fll', which is not in the set"));
  std::string cadence = manifest;
  cadence.replace(cadence.find("\"cadence_steps_per_min\": 110"), 28,
                  "\"cadence_steps_per_min\": 900");
  EXPECT_THAT(error_of(cadence, files),
              HasSubstr("'cadence_steps_per_min' must be a number between"));
}

TEST(ControllerSet, MetricInputsAreCheckedByName) {
  const fuzzy::Engine e = fuzzy::read_fll(R"(Engine: bad
InputVariable: speed
  range: 0 1
  lock-range: true
  term: low Triangle -1 0 1
  term: high Triangle 0 1 2
OutputVariable: velocity
  range: -1 1
  defuzzifier: WeightedAverage TakagiSugeno
  term: stay Constant 0
  term: go Constant 1
RuleBlock: r
  rule: if speed is low then velocity is stay
  rule: if speed is high then velocity is go
)");
  try {
    gait::Controller c(e, "bad.fll");
    FAIL();
  } catch (const std::invalid_argument& error) {
    EXPECT_THAT(error.what(), HasSubstr("bad.fll: input 'speed' is not a metric"));
  }
}

TEST(ControllerSet, FastPathAgreesWithTheFuzzyEvaluator) {
  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  for (const gait::Controller& c : set.controllers) {
    ASSERT_TRUE(c.fast_path()) << c.source();
    const fuzzy::Evaluator general(c.engine());
    fuzzy::Workspace w = general.make_workspace();
    fuzzy::Workspace unused;
    for (int i = 0; i < 2000; ++i) {
      gait::MetricValues m{};
      std::array<double, 2> in{};
      for (std::size_t k = 0; k < c.input_count(); ++k) {
        const double lo = general.input_minimum(k);
        const double hi = general.input_maximum(k);
        // Inside the range, on knots, and beyond both ends.
        const double t = std::fmod(i * (k == 0 ? 0.6180339887 : 0.4142135623), 1.0);
        in[k] = i % 50 == 0 ? lo : lo - 0.2 * (hi - lo) + 1.4 * (hi - lo) * t;
        m[static_cast<std::size_t>(c.input(k))] = in[k];
      }
      double expected = 0.0;
      general.evaluate(std::span<const double>(in.data(), c.input_count()),
                       std::span<double>(&expected, 1), w);
      EXPECT_NEAR(c.evaluate(m, unused), expected, 1e-9 * (1.0 + std::abs(expected))) << c.source();
    }
  }
}

// A controller in FLL over delta (`delta_terms` terms) and, when knee_terms > 0, the knee: strong
// triangular partitions with one rule per combination, or (`gaussian`) Gaussian terms, which no
// partition form takes.
std::string controller_fll(int delta_terms, int knee_terms, bool gaussian) {
  std::string text = "Engine: wide\nInputVariable: delta\n  range: -1 1\n  lock-range: true\n";
  auto terms = [&](const std::string& prefix, int count, double lo, double hi) {
    const double step = (hi - lo) / (count - 1);
    for (int i = 0; i < count; ++i) {
      const double peak = lo + i * step;
      text += "  term: " + prefix + std::to_string(i) +
              (gaussian ? " Gaussian " + std::to_string(peak) + " " + std::to_string(0.6 * step)
                        : " Triangle " + std::to_string(peak - step) + " " + std::to_string(peak) +
                              " " + std::to_string(peak + step)) +
              "\n";
    }
  };
  terms("d", delta_terms, -1.0, 1.0);
  if (knee_terms > 0) {
    text += "InputVariable: knee\n  range: 0 60\n  lock-range: true\n";
    terms("k", knee_terms, 0.0, 60.0);
  }
  text +=
      "OutputVariable: velocity\n  range: -500 500\n  lock-range: false\n"
      "  aggregation: none\n  defuzzifier: WeightedAverage TakagiSugeno\n  default: 0\n";
  const int rules = delta_terms * std::max(knee_terms, 1);
  for (int r = 0; r < rules; ++r) {
    text +=
        "  term: c" + std::to_string(r) + " Constant " + std::to_string(37.0 * r - 211.0) + "\n";
  }
  text +=
      "RuleBlock: rules\n  conjunction: AlgebraicProduct\n  disjunction: none\n"
      "  implication: none\n  activation: General\n";
  for (int i = 0; i < delta_terms; ++i) {
    for (int j = 0; j < std::max(knee_terms, 1); ++j) {
      text += "  rule: if delta is d" + std::to_string(i) +
              (knee_terms > 0 ? " and knee is k" + std::to_string(j) : std::string()) +
              " then velocity is c" + std::to_string(i * std::max(knee_terms, 1) + j) + "\n";
    }
  }
  return text;
}

// An engine built in code is held to the numbers a controller file is: each non-finite number
// named by variable, term and parameter (Engine::non_finite_numbers), the first one refused.
TEST(Controller, RefusesAnEngineWithANumberThatIsNotFinite) {
  const fuzzy::Engine good = gait::ControllerSet::builtin("default").controllers.at(0).engine();
  EXPECT_TRUE(good.non_finite_numbers().empty());
  fuzzy::Engine bad = good;
  bad.outputs.at(0).terms.at(1).parameters.at(0) = std::numeric_limits<double>::quiet_NaN();
  bad.inputs.at(0).maximum = std::numeric_limits<double>::infinity();
  bad.rule_blocks.at(0).rules.at(0).weight = -std::numeric_limits<double>::infinity();
  const std::vector<std::string> found = bad.non_finite_numbers();
  ASSERT_EQ(found.size(), 3u);
  EXPECT_EQ(found[0], "input 'delta' range maximum is inf");
  EXPECT_EQ(found[1], "output 'velocity' term '" + bad.outputs[0].terms[1].name +
                          "' parameter 'value' is nan");
  EXPECT_THAT(found[2], ::testing::StartsWith("the weight of rule 'if delta is"));
  try {
    gait::Controller controller(bad, "built/swing_hip");
    ADD_FAILURE() << "built";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "built/swing_hip: input 'delta' range maximum is inf; a joint "
              "controller's numbers must be finite");
  }
}

// The forms the walker's packed path does not take (a partition wider than PackedPartition packs,
// a general engine) give the fuzzy evaluator's result too, a NaN input its default.
TEST(Controller, UnpackedFormsAgreeWithTheFuzzyEvaluator) {
  const int wide = static_cast<int>(fuzzy::PackedPartition::kMaxKnots) + 1;
  struct Form {
    int delta_terms;
    int knee_terms;
    bool gaussian;
  };
  for (const Form form : {Form{wide, 0, false}, Form{wide, 3, false}, Form{3, wide, false},
                          Form{5, 0, true}, Form{4, 3, true}}) {
    const std::string label = std::to_string(form.delta_terms) + " x " +
                              std::to_string(form.knee_terms) +
                              (form.gaussian ? " Gaussian" : " Triangle");
    const gait::Controller c(
        fuzzy::read_fll(controller_fll(form.delta_terms, form.knee_terms, form.gaussian)), label);
    EXPECT_EQ(c.packed(), nullptr) << label;
    EXPECT_EQ(c.fast_path(), !form.gaussian) << label;
    ASSERT_EQ(c.input_count(), form.knee_terms > 0 ? 2u : 1u) << label;
    const fuzzy::Evaluator general(c.engine());
    fuzzy::Workspace general_workspace = general.make_workspace();
    fuzzy::Workspace workspace = c.make_workspace();
    for (int i = 0; i <= 400; ++i) {
      gait::MetricValues m{};
      std::array<double, 2> in{};
      for (std::size_t k = 0; k < c.input_count(); ++k) {
        const double t = std::fmod(i * (k == 0 ? 0.6180339887 : 0.4142135623), 1.0);
        in[k] = i == 400 && k == 0 ? kNaN : (k == 0 ? -1.3 + 2.6 * t : -10.0 + 80.0 * t);
        m[static_cast<std::size_t>(c.input(k))] = in[k];
      }
      double expected = 0.0;
      general.evaluate(std::span<const double>(in.data(), c.input_count()),
                       std::span<double>(&expected, 1), general_workspace);
      const double got = c.evaluate(m, workspace);
      if (std::isnan(expected)) {
        EXPECT_TRUE(std::isnan(got)) << label << " at " << in[0] << ", " << in[1];
      } else {
        EXPECT_NEAR(got, expected, 1e-9 * (1.0 + std::abs(expected)))
            << label << " at " << in[0] << ", " << in[1];
      }
    }
  }
}

}  // namespace

// Controller sets: loading from files, clear errors naming the file, and the fast path that must
// agree with the general fuzzy evaluator.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "support/controller_sets.hpp"
#include "support/text.hpp"

using namespace fuzzygait;
using ::testing::HasSubstr;

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

}  // namespace

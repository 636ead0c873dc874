// Every FLL file shipped in controllers/ is read by libfuzzylite itself (the files as they are on
// disk), and fuzzylite's outputs over and beyond each input's range are the ones fuzzygait gives:
// its general evaluator on the same file, and the controller sets' fast path the walker runs.
#include <fl/Headers.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <memory>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "support/controller_sets.hpp"
#include "support/fuzzylite_compare.hpp"

namespace {

namespace fs = std::filesystem;
using namespace fuzzygait;

const fs::path kControllers = test::controllers_dir();

std::vector<fs::path> shipped_fll_files() {
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(kControllers)) {
    if (e.is_regular_file() && e.path().extension() == ".fll") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// The controller sets' folders: those with a manifest.
std::vector<fs::path> set_directories() {
  std::vector<fs::path> sets;
  for (const std::string& name : test::shipped_set_names())
    sets.push_back(kControllers / name);
  return sets;
}

// 41 values across [minimum, maximum] widened by a fifth on each side; the range's ends and every
// term parameter (the knots of the shapes), each with its neighbouring doubles on both sides.
std::vector<double> samples(const fuzzy::InputVariable& v) {
  const double span = v.maximum - v.minimum;
  std::vector<double> out;
  for (int i = 0; i <= 40; ++i)
    out.push_back(v.minimum - 0.2 * span + 1.4 * span * i / 40.0);
  std::vector<double> knots = {v.minimum, v.maximum};
  for (const fuzzy::Term& t : v.terms)
    knots.insert(knots.end(), t.parameters.begin(), t.parameters.end());
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (double k : knots) {
    out.push_back(k);
    out.push_back(std::nextafter(k, -kInf));
    out.push_back(std::nextafter(k, kInf));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

TEST(ShippedControllers, FuzzyliteReadsEveryFileAndGivesFuzzygaitsOutputs) {
  const std::vector<fs::path> files = shipped_fll_files();
  // Every file a manifest names is among them (the eight slots' and the terrain words'), and
  // beyond those only the FLL files outside the sets' folders (such as the paper's example).
  const std::vector<fs::path> sets = set_directories();
  ASSERT_FALSE(sets.empty()) << "no controller sets under " << kControllers;
  std::set<fs::path> named;
  std::size_t in_sets = 0;
  for (const fs::path& dir : sets) {
    const gait::ControllerSet set = gait::ControllerSet::load(dir);
    ASSERT_EQ(set.controllers.size(), static_cast<std::size_t>(gait::kSlotCount)) << dir;
    auto name = [&](const gait::Controller& c) {
      const fs::path source = fs::weakly_canonical(c.source());
      EXPECT_TRUE(named.insert(source).second) << source << " named twice";
      EXPECT_TRUE(std::any_of(files.begin(), files.end(),
                              [&](const fs::path& f) { return fs::weakly_canonical(f) == source; }))
          << source << " is not among the shipped FLL files";
    };
    for (const gait::Controller& c : set.controllers)
      name(c);
    for (const gait::Controller& c : set.terrain_controllers)
      name(c);
    if (set.stride) name(*set.stride);
    in_sets += set.controller_count() + (set.stride ? 1 : 0);
    for (const auto& c : set.upper_body) {
      if (!c) continue;
      name(*c);
      ++in_sets;
    }
  }
  const auto others =
      static_cast<std::size_t>(std::count_if(files.begin(), files.end(), [](const fs::path& f) {
        return !fs::exists(f.parent_path() / "manifest.json");
      }));
  ASSERT_EQ(files.size(), in_sets + others)
      << "FLL files in a set's folder that its manifest does not name";
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    std::unique_ptr<fl::Engine> reference;
    ASSERT_NO_THROW(reference.reset(fl::FllImporter().fromFile(file.string())));
    std::string status;
    ASSERT_TRUE(reference->isReady(&status)) << status;

    const fuzzy::Engine engine = fuzzy::read_fll_file(file);
    ASSERT_GE(engine.inputs.size(), 1u);
    ASSERT_GE(engine.outputs.size(), 1u);
    ASSERT_EQ(engine.inputs.size(), reference->numberOfInputVariables());
    ASSERT_EQ(engine.outputs.size(), reference->numberOfOutputVariables());
    ASSERT_LE(engine.inputs.size(), 2u);
    const fuzzy::Evaluator evaluator(engine);
    fuzzy::Workspace workspace = evaluator.make_workspace();
    test::FuzzyliteComparison comparison;
    comparison.label = fs::relative(file, kControllers).string();
    for (const fuzzy::InputVariable& v : engine.inputs) {
      comparison.inputs.push_back(v.name);
      comparison.values.push_back(samples(v));
    }
    for (const fuzzy::OutputVariable& v : engine.outputs)
      comparison.outputs.push_back(v.name);
    comparison.max_reported = 3;
    test::expect_fuzzylite_outputs(*reference, comparison,
                                   [&](std::span<const double> inputs, std::span<double> outputs) {
                                     evaluator.evaluate(inputs, outputs, workspace);
                                   });
  }
}

// The walker evaluates a set's controllers through their fast path; fuzzylite, fed the same
// metrics from the file the manifest names, agrees bit for bit.
TEST(ShippedControllers, EverySetsFastPathGivesFuzzylitesOutputs) {
  const std::vector<std::string> names = test::shipped_set_names();
  EXPECT_EQ(gait::ControllerSet::builtin_names(), names)
      << "the sets compared here are the built-in ones";
  for (const fs::path& dir : set_directories()) {
    SCOPED_TRACE(dir.string());
    const gait::ControllerSet set = gait::ControllerSet::load(dir);
    ASSERT_EQ(set.controllers.size(), static_cast<std::size_t>(gait::kSlotCount));
    for (const gait::Controller& c : set.controllers) {
      SCOPED_TRACE(c.source());
      EXPECT_TRUE(c.fast_path()) << "the walker would run the general evaluator";
      std::unique_ptr<fl::Engine> reference(fl::FllImporter().fromFile(c.source()));
      const fuzzy::Engine& engine = c.engine();
      ASSERT_GE(c.input_count(), 1u);
      ASSERT_EQ(reference->numberOfInputVariables(), c.input_count());
      ASSERT_EQ(reference->numberOfOutputVariables(), 1u);
      ASSERT_EQ(engine.outputs.size(), 1u);
      ASSERT_EQ(reference->getOutputVariable(0)->getName(), engine.outputs[0].name);
      fuzzy::Workspace workspace = c.make_workspace();
      test::FuzzyliteComparison comparison;
      comparison.label = c.source();
      for (std::size_t i = 0; i < c.input_count(); ++i) {
        comparison.inputs.push_back(engine.inputs[i].name);
        comparison.values.push_back(samples(engine.inputs[i]));
      }
      comparison.outputs.push_back(engine.outputs[0].name);
      comparison.max_reported = 3;
      test::expect_fuzzylite_outputs(
          *reference, comparison, [&](std::span<const double> inputs, std::span<double> outputs) {
            gait::MetricValues metrics{};
            for (std::size_t i = 0; i < inputs.size(); ++i)
              metrics[static_cast<std::size_t>(c.input(i))] = inputs[i];
            outputs[0] = c.evaluate(metrics, workspace);
          });
    }
  }
  EXPECT_GE(names.size(), 4u) << "the default set and at least three styles";
}

}  // namespace

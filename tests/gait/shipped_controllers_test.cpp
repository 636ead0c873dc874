// Every FLL file shipped in controllers/ is read by libfuzzylite itself (the files as they are on
// disk), and fuzzylite's outputs over and beyond each input's range are the ones fuzzygait gives:
// its general evaluator on the same file, and the controller sets' fast path the walker runs.
#include <fl/Headers.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/gait/controllers.hpp"

namespace {

namespace fs = std::filesystem;
using namespace fuzzygait;

const fs::path kControllers = fs::path(FUZZYGAIT_SOURCE_DIR) / "controllers";

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b) ||
         (std::isnan(a) && std::isnan(b));
}

std::vector<fs::path> shipped_fll_files() {
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(kControllers)) {
    if (e.is_regular_file() && e.path().extension() == ".fll") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// 41 values across [minimum, maximum] widened by a fifth on each side.
std::vector<double> samples(const fuzzy::InputVariable& v) {
  const double span = v.maximum - v.minimum;
  std::vector<double> out;
  for (int i = 0; i <= 40; ++i)
    out.push_back(v.minimum - 0.2 * span + 1.4 * span * i / 40.0);
  return out;
}

TEST(ShippedControllers, FuzzyliteReadsEveryFileAndGivesFuzzygaitsOutputs) {
  const std::vector<fs::path> files = shipped_fll_files();
  ASSERT_GE(files.size(), 9u) << "no controller files under " << kControllers;
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    std::unique_ptr<fl::Engine> reference;
    ASSERT_NO_THROW(reference.reset(fl::FllImporter().fromFile(file.string())));
    std::string status;
    ASSERT_TRUE(reference->isReady(&status)) << status;

    const fuzzy::Engine engine = fuzzy::read_fll_file(file);
    ASSERT_EQ(engine.inputs.size(), reference->numberOfInputVariables());
    ASSERT_EQ(engine.outputs.size(), reference->numberOfOutputVariables());
    const fuzzy::Evaluator evaluator(engine);
    fuzzy::Workspace workspace = evaluator.make_workspace();
    ASSERT_LE(engine.inputs.size(), 2u);
    const std::vector<double> xs = samples(engine.inputs[0]);
    const std::vector<double> ys =
        engine.inputs.size() == 2 ? samples(engine.inputs[1]) : std::vector<double>{0.0};
    std::vector<double> inputs(engine.inputs.size());
    std::vector<double> outputs(engine.outputs.size());
    int mismatches = 0;
    for (double x : xs) {
      for (double y : ys) {
        inputs[0] = x;
        if (inputs.size() == 2) inputs[1] = y;
        for (std::size_t i = 0; i < inputs.size(); ++i) {
          reference->getInputVariable(engine.inputs[i].name)->setValue(inputs[i]);
        }
        reference->process();
        evaluator.evaluate(inputs, outputs, workspace);
        for (std::size_t o = 0; o < outputs.size(); ++o) {
          const double expected = reference->getOutputVariable(engine.outputs[o].name)->getValue();
          if (!same_bits(expected, outputs[o]) && ++mismatches <= 3) {
            ADD_FAILURE() << "at " << x << ", " << y << ": fuzzylite " << expected << ", fuzzygait "
                          << outputs[o];
          }
        }
      }
    }
    EXPECT_EQ(mismatches, 0);
  }
}

// The walker evaluates a set's controllers through their fast path; fuzzylite, fed the same
// metrics from the file the manifest names, agrees bit for bit.
TEST(ShippedControllers, EverySetsFastPathGivesFuzzylitesOutputs) {
  int sets = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(kControllers)) {
    if (!fs::exists(e.path() / "manifest.json")) continue;
    ++sets;
    SCOPED_TRACE(e.path().string());
    const gait::ControllerSet set = gait::ControllerSet::load(e.path());
    for (const gait::Controller& c : set.controllers) {
      SCOPED_TRACE(c.source());
      std::unique_ptr<fl::Engine> reference(fl::FllImporter().fromFile(c.source()));
      fuzzy::Workspace workspace = c.make_workspace();
      const fuzzy::Engine& engine = c.engine();
      const std::vector<double> xs = samples(engine.inputs[0]);
      const std::vector<double> ys =
          c.input_count() == 2 ? samples(engine.inputs[1]) : std::vector<double>{0.0};
      int mismatches = 0;
      for (double x : xs) {
        for (double y : ys) {
          gait::MetricValues metrics{};
          metrics[static_cast<std::size_t>(c.input(0))] = x;
          reference->getInputVariable(engine.inputs[0].name)->setValue(x);
          if (c.input_count() == 2) {
            metrics[static_cast<std::size_t>(c.input(1))] = y;
            reference->getInputVariable(engine.inputs[1].name)->setValue(y);
          }
          reference->process();
          const double expected = reference->getOutputVariable(0)->getValue();
          const double got = c.evaluate(metrics, workspace);
          if (!same_bits(expected, got) && ++mismatches <= 3) {
            ADD_FAILURE() << "at " << x << ", " << y << ": fuzzylite " << expected << ", fuzzygait "
                          << got;
          }
        }
      }
      EXPECT_EQ(mismatches, 0);
    }
  }
  EXPECT_GE(sets, 4) << "the default set and at least three styles";
}

}  // namespace

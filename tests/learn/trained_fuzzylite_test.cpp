// A trained set's FLL files, as written, are read by libfuzzylite itself, and fuzzylite's answers
// over each input's range, at every knot and between, are the trained set's bit for bit.
#include <fl/Headers.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/io/controller_files.hpp"
#include "fuzzygait/io/mocap.hpp"
#include "fuzzygait/learn/network.hpp"
#include "fuzzygait/learn/train.hpp"
#include "support/fuzzylite_compare.hpp"
#include "support/walks.hpp"

namespace fuzzygait {
namespace {

namespace fs = std::filesystem;

// 31 points across the input's range and a tenth beyond it, and each knot with the doubles on
// either side of it.
std::vector<double> inputs_of(const fuzzy::InputVariable& v) {
  const double span = v.maximum - v.minimum;
  std::vector<double> out;
  for (int i = 0; i <= 30; ++i)
    out.push_back(v.minimum - 0.1 * span + 1.2 * span * i / 30.0);
  for (const fuzzy::Term& t : v.terms) {
    const double k = t.parameters[1];
    constexpr double kInf = std::numeric_limits<double>::infinity();
    out.insert(out.end(), {k, std::nextafter(k, -kInf), std::nextafter(k, kInf)});
  }
  return out;
}

TEST(TrainedControllers, FuzzyliteReadsThemAndGivesTheTrainedSetsAnswers) {
  io::CapturedClip clip =
      io::read_clip(fs::path(FUZZYGAIT_SOURCE_DIR) / "data" / "mocap" / "cmu" / "07_01.bvh");
  const std::vector<learn::TrainClip> clips = {
      learn::make_train_clip("07_01", std::move(clip.motion), std::move(clip.ground))};
  learn::TrainOptions o = learn::default_train_options();
  o.polish.generations = 10;
  o.polish.polish_generations = 5;
  const learn::TrainResult trained = learn::train(test::default_set(), clips, o);
  // The values moved: this compares a trained set, not the default again.
  EXPECT_NE(learn::SetNetwork(trained.set).values(),
            learn::SetNetwork(test::default_set()).values());
  const fs::path dir = fs::path(::testing::TempDir()) / "fuzzygait_trained_fll";
  fs::remove_all(dir);
  io::save_controller_set(trained.set, dir);
  const gait::ControllerSet set = gait::ControllerSet::load(dir);
  for (const gait::Controller& c : set.controllers) {
    SCOPED_TRACE(c.source());
    ASSERT_NE(c.packed(), nullptr);  // the walker's fast path
    std::unique_ptr<fl::Engine> reference;
    ASSERT_NO_THROW(reference.reset(fl::FllImporter().fromFile(c.source())));
    std::string status;
    ASSERT_TRUE(reference->isReady(&status)) << status;
    test::FuzzyliteComparison comparison;
    comparison.label = c.source();
    for (const fuzzy::InputVariable& v : c.engine().inputs) {
      comparison.inputs.push_back(v.name);
      comparison.values.push_back(inputs_of(v));
    }
    comparison.outputs.push_back(c.engine().outputs[0].name);
    test::expect_fuzzylite_outputs(*reference, comparison,
                                   [&](std::span<const double> in, std::span<double> out) {
                                     gait::MetricValues m{};
                                     for (std::size_t i = 0; i < in.size(); ++i)
                                       m[static_cast<std::size_t>(c.input(i))] = in[i];
                                     fuzzy::Workspace none;
                                     out[0] = c.evaluate(m, none);
                                   });
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace fuzzygait

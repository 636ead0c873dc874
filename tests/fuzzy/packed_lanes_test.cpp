// PackedPartition's batch evaluation (vector lanes across calls, for a crowd) against its scalar
// evaluation, bit for bit: every lane must take the scalar path's branch as a select, at knots,
// within fuzzylite's tolerance of them, outside the range, and for NaN and infinite inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/fuzzy/partition.hpp"
#include "fuzzygait/gait/controllers.hpp"

using namespace fuzzygait;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Inputs for one input variable of knots `knots`: random across and beyond the range, with knots
// hit exactly, within and just beyond the tolerance, and NaN and infinities.
std::vector<double> inputs_for(const std::vector<double>& knots, std::size_t n, unsigned seed) {
  std::mt19937_64 random(seed);
  const double low = knots.front();
  const double high = knots.back();
  const double margin = 0.3 * (high - low);
  std::uniform_real_distribution<double> across(low - margin, high + margin);
  std::uniform_int_distribution<std::size_t> knot(0, knots.size() - 1);
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    switch (i % 13) {
      case 3:
        x[i] = knots[knot(random)];
        break;
      case 5:
        x[i] = knots[knot(random)] + 5e-7;
        break;
      case 7:
        x[i] = knots[knot(random)] - 5e-7;
        break;
      case 9:
        x[i] = knots[knot(random)] + 2e-6;
        break;
      case 11:
        x[i] = i % 3 == 0 ? kNaN : (i % 3 == 1 ? kInf : -kInf);
        break;
      default:
        x[i] = across(random);
    }
  }
  return x;
}

void expect_batch_matches_scalar(const fuzzy::Engine& engine, const std::string& label) {
  const std::optional<fuzzy::PartitionController<double>> partition = fuzzy::as_partition(engine);
  ASSERT_TRUE(partition) << label;
  const std::optional<fuzzy::PackedPartition> packed = fuzzy::PackedPartition::pack(*partition);
  ASSERT_TRUE(packed) << label;
  const std::size_t n = 1001;
  const std::vector<double> x0 = inputs_for(partition->knots[0], n, 1);
  const std::vector<double> x1 = partition->input_count() == 2
                                     ? inputs_for(partition->knots[1], n, 2)
                                     : std::vector<double>(n, kNaN);  // not read
  const bool one_input = partition->input_count() == 1;
  // The whole batch, and short batches at every offset (the lanes left after whole vectors).
  std::vector<double> out(n);
  packed->evaluate(x0.data(), x1.data(), out.data(), n);
  if (one_input) {  // the second input may then be left out
    std::vector<double> without(n);
    packed->evaluate(x0.data(), nullptr, without.data(), n);
    EXPECT_EQ(std::memcmp(without.data(), out.data(), n * sizeof(double)), 0) << label;
  }
  for (std::size_t length = 0; length <= 9; ++length) {
    for (std::size_t at = 0; at + length <= 40; at += 1 + length) {
      std::vector<double> part(length + 1, 123.0);
      packed->evaluate(&x0[at], &x1[at], part.data(), length);
      EXPECT_EQ(part[length], 123.0) << label << ": wrote past the batch";
      for (std::size_t i = 0; i < length; ++i) {
        EXPECT_EQ(std::memcmp(&part[i], &out[at + i], sizeof(double)), 0) << label;
      }
    }
  }
  int differ = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double expected = packed->evaluate(x0[i], one_input ? 0.0 : x1[i]);
    if (std::memcmp(&expected, &out[i], sizeof expected) != 0 && ++differ <= 3) {
      ADD_FAILURE() << label << ": lane " << i << " x0 " << x0[i] << " x1 " << x1[i] << " batch "
                    << out[i] << " scalar " << expected;
    }
  }
  EXPECT_EQ(differ, 0) << label;
}

TEST(PackedLanes, EveryShippedControllerMatchesItsScalarEvaluation) {
  for (const std::string& name : gait::ControllerSet::builtin_names()) {
    for (const gait::Controller& c : gait::ControllerSet::builtin(name).controllers) {
      expect_batch_matches_scalar(c.engine(), c.source());
    }
  }
}

// The other shapes the packed form takes: minimum conjunction, the most knots it packs, a NaN
// default (what a NaN input gives).
TEST(PackedLanes, MinimumConjunctionWideInputsAndANanDefault) {
  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  const std::string knee =
      fuzzy::write_fll(set.at(gait::LegPhase::Swing, gait::Joint::Knee).engine());
  std::string minimum = knee;
  minimum.replace(minimum.find("AlgebraicProduct"), 16, "Minimum");
  expect_batch_matches_scalar(fuzzy::read_fll(minimum), "swing knee, minimum");
  std::string nan_default = knee;
  nan_default.replace(nan_default.find("default: 0"), 10, "default: nan");
  expect_batch_matches_scalar(fuzzy::read_fll(nan_default), "swing knee, NaN default");

  std::string wide =
      "Engine: wide\nInputVariable: x\n  enabled: true\n  range: 0 7\n  lock-range: true\n";
  for (int k = 0; k < 8; ++k) {
    wide += "  term: t" + std::to_string(k) + " Triangle " + std::to_string(k - 1) + " " +
            std::to_string(k) + " " + std::to_string(k + 1) + "\n";
  }
  wide +=
      "InputVariable: y\n  enabled: true\n  range: -1 1\n  lock-range: true\n"
      "  term: low Triangle -2 -1 1\n  term: high Triangle -1 1 2\n"
      "OutputVariable: out\n  enabled: true\n  range: -100 100\n  lock-range: false\n"
      "  aggregation: none\n  defuzzifier: WeightedAverage TakagiSugeno\n  default: 0\n";
  for (int k = 0; k < 16; ++k) {
    wide += "  term: c" + std::to_string(k) + " Constant " + std::to_string(3 * k - 20) + "\n";
  }
  wide +=
      "RuleBlock: rules\n  enabled: true\n  conjunction: AlgebraicProduct\n"
      "  activation: General\n";
  for (int k = 0; k < 8; ++k) {
    for (const char* y : {"low", "high"}) {
      const int c = 2 * k + (y[0] == 'h' ? 1 : 0);
      wide += "  rule: if x is t" + std::to_string(k) + " and y is " + y + " then out is c" +
              std::to_string(c) + "\n";
    }
  }
  expect_batch_matches_scalar(fuzzy::read_fll(wide), "8 x 2 knots");
}

}  // namespace

// PackedPartition's batch evaluation (vector lanes across calls, for a crowd) against its scalar
// evaluation, bit for bit: every lane must take the scalar path's branch as a select, at knots,
// within fuzzylite's tolerance of them, outside the range, and for NaN and infinite inputs. The
// batch as the machine runs it, the lane kernel with the scalar reference body (simd::scalar) and
// each vector body the machine runs all give the scalar evaluate()'s bits.
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
#include "runtime/fuzzy/packed_batch.hpp"
#include "runtime/simd/cpu.hpp"
#include "runtime/simd/lanes.hpp"

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
      case 10:  // the tolerance itself away from a knot (exactly, for a knot at zero)
        x[i] = (i % 4 == 0 ? 0.0 : knots[knot(random)]) + (i % 3 == 0 ? 1e-6 : -1e-6);
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
  fuzzy::detail::evaluate_batch(*packed, x0.data(), x1.data(), out.data(), n);
  if (one_input) {  // the second input may then be left out
    std::vector<double> without(n);
    fuzzy::detail::evaluate_batch(*packed, x0.data(), nullptr, without.data(), n);
    EXPECT_EQ(std::memcmp(without.data(), out.data(), n * sizeof(double)), 0) << label;
  }
  // Each kernel over the whole vectors: with the scalar body, and each vector body this build has
  // and this machine runs (the batch above takes the widest only).
  const fuzzy::detail::PackedView view = fuzzy::detail::PackedPartitionAccess::view(*packed);
  struct Kernel {
    const char* name;
    std::size_t width;
    std::vector<double> out;
  };
  std::vector<Kernel> kernels;
  auto run = [&](const char* name, std::size_t width, auto kernel) {
    const std::size_t whole = n - n % width;
    Kernel k{name, width, std::vector<double>(whole)};
    kernel(view, x0.data(), one_input ? nullptr : x1.data(), k.out.data(), whole);
    kernels.push_back(std::move(k));
  };
  run("scalar-body kernel", 4, fuzzy::detail::evaluate_packed_lanes<simd::scalar::Double4>);
  run("scalar-body kernel, 8 lanes", 8,
      fuzzy::detail::evaluate_packed_lanes<simd::scalar::Double8>);
#if defined(FUZZYGAIT_SIMD_AVX2)
  if (simd::has_avx2()) run("AVX2 kernel", 4, fuzzy::detail::evaluate_packed_avx2);
#endif
#if defined(FUZZYGAIT_SIMD_AVX512)
  if (simd::has_avx512()) run("AVX-512 kernel", 8, fuzzy::detail::evaluate_packed_avx512);
#endif
  for (std::size_t length = 0; length <= 9; ++length) {
    for (std::size_t at = 0; at + length <= 40; at += 1 + length) {
      std::vector<double> part(length + 1, 123.0);
      fuzzy::detail::evaluate_batch(*packed, &x0[at], &x1[at], part.data(), length);
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
    for (const Kernel& k : kernels) {
      if (i < k.out.size() && std::memcmp(&expected, &k.out[i], sizeof expected) != 0 &&
          ++differ <= 3) {
        ADD_FAILURE() << label << ": lane " << i << " x0 " << x0[i] << " x1 " << x1[i] << " "
                      << k.name << " " << k.out[i] << " scalar " << expected;
      }
    }
  }
  EXPECT_EQ(differ, 0) << label;
}

// On a machine with AVX2 or AVX-512F (x86-64, the default build) the batch runs in vector lanes,
// the widest it has, so these tests compare a vector kernel with the scalar path, not the scalar
// path with itself.
TEST(PackedLanes, RunInTheWidestVectorsTheMachineHas) {
  const std::size_t expected = simd::has_avx512() ? 8 : (simd::has_avx2() ? 4 : 1);
  EXPECT_EQ(fuzzy::detail::batch_vector_lanes(), expected);
  RecordProperty("batch_vector_lanes", std::to_string(fuzzy::detail::batch_vector_lanes()));
}

// Padding rounds up to whole vectors, and never past the next one.
TEST(PackedLanes, PaddedLanesAreWholeVectors) {
  const std::size_t width = fuzzy::detail::batch_vector_lanes();
  EXPECT_EQ(fuzzy::detail::kMaxBatchVectorLanes % width, 0u);
  for (std::size_t n = 0; n <= 3 * width + 1; ++n) {
    const std::size_t padded = fuzzy::detail::padded_lanes(n);
    EXPECT_EQ(padded % width, 0u) << n;
    EXPECT_GE(padded, n);
    EXPECT_LT(padded, n + width) << n;
  }
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
  const fuzzy::Engine wide_engine = fuzzy::read_fll(wide);
  expect_batch_matches_scalar(wide_engine, "8 x 2 knots");
  // A degree of exactly the tolerance fires (1e-6 above the knot at 0, the next at 1), one just
  // below it does not, as in fuzzylite.
  const fuzzy::PackedPartition wide_packed =
      *fuzzy::PackedPartition::pack(*fuzzy::as_partition(wide_engine));
  const double at_tolerance[4] = {1e-6, 1e-6, 0.99e-6, 0.99e-6};
  const double y_knot[4] = {-1.0, 1.0, -1.0, 1.0};
  double lanes[4];
  fuzzy::detail::evaluate_batch(wide_packed, at_tolerance, y_knot, lanes, 4);
  for (int i = 0; i < 4; ++i) {
    const double scalar = wide_packed.evaluate(at_tolerance[i], y_knot[i]);
    EXPECT_EQ(std::memcmp(&lanes[i], &scalar, sizeof scalar), 0) << i;
  }
  EXPECT_NE(wide_packed.evaluate(1e-6, -1.0), wide_packed.evaluate(0.99e-6, -1.0));

  // Knots more than the largest double apart: a degree is inf / inf, NaN, which the minimum
  // passes over (fuzzylite's Op::min), as the scalar path does.
  std::string huge = minimum;
  const std::string knee_input = huge.substr(huge.find("InputVariable: knee"));
  huge.replace(huge.find("InputVariable: knee"), knee_input.find("OutputVariable"),
               "InputVariable: knee\n  enabled: true\n  range: -1.5e308 1.5e308\n"
               "  lock-range: true\n  term: straight Triangle -1.5e308 -1.5e308 1.5e308\n"
               "  term: bent Triangle -1.5e308 1.5e308 1.5e308\n");
  std::string::size_type at = 0;
  while ((at = huge.find("knee is deep", at)) != std::string::npos) {
    const std::string::size_type line = huge.rfind('\n', at);
    huge.erase(line, huge.find('\n', at) - line);
  }
  const fuzzy::Engine huge_engine = fuzzy::read_fll(huge);
  expect_batch_matches_scalar(huge_engine, "knots 3e308 apart, minimum");
  const fuzzy::PackedPartition packed =
      *fuzzy::PackedPartition::pack(*fuzzy::as_partition(huge_engine));
  const double x0[4] = {0.5, 0.5, 0.5, 0.5};
  const double x1[4] = {-1e308, -1e308, -1e308, -1e308};
  double out[4];
  fuzzy::detail::evaluate_batch(packed, x0, x1, out, 4);
  const double scalar = packed.evaluate(0.5, -1e308);
  EXPECT_FALSE(std::isnan(scalar));
  for (const double lane : out)
    EXPECT_EQ(std::memcmp(&lane, &scalar, sizeof scalar), 0) << lane << " vs " << scalar;
}

// The batch counts the knots below an input, which finds its interval only when knots increase:
// pack() refuses others.
TEST(PackedLanes, PackRefusesKnotsThatDoNotIncrease) {
  fuzzy::PartitionController<double> c;
  c.knots[0] = {0.0, 2.0, 1.0, 3.0};
  c.consequents = {1.0, 2.0, 3.0, 4.0};
  EXPECT_FALSE(fuzzy::PackedPartition::pack(c));
  c.knots[0] = {0.0, 1.0, 1.0, 3.0};
  EXPECT_FALSE(fuzzy::PackedPartition::pack(c));
  c.knots[0] = {0.0, 1.0, 2.0, 3.0};
  EXPECT_TRUE(fuzzy::PackedPartition::pack(c));
}

}  // namespace

// The trainable core: recognising partition controllers, writing fitted values back as FLL, and
// derivatives through evaluation with dual numbers (Ceres Jets) equal to finite differences.
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <vector>

#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/fuzzy/partition.hpp"

using namespace fuzzygait::fuzzy;

namespace {

const char* kTwoInputs = R"(Engine: knee
InputVariable: delta
  range: -1 1
  lock-range: true
  term: start Triangle -2 -1 0
  term: center Triangle -1 0 1
  term: end Triangle 0 1 2
InputVariable: knee
  range: 0 60
  lock-range: true
  term: straight Triangle -30 0 30
  term: bent Triangle 0 30 60
  term: deep Triangle 30 60 90
OutputVariable: velocity
  range: -500 500
  defuzzifier: WeightedAverage TakagiSugeno
  default: 0
  term: a Constant 400
  term: b Constant 250
  term: c Constant 0
  term: d Constant -20
  term: e Constant -150
  term: f Constant -200
  term: g Constant 30
  term: h Constant -300
  term: i Constant -420
RuleBlock: r
  conjunction: AlgebraicProduct
  rule: if delta is start and knee is straight then velocity is a
  rule: if delta is start and knee is bent then velocity is b
  rule: if delta is start and knee is deep then velocity is c
  rule: if delta is center and knee is straight then velocity is d
  rule: if delta is center and knee is bent then velocity is e
  rule: if delta is center and knee is deep then velocity is f
  rule: if delta is end and knee is straight then velocity is g
  rule: if delta is end and knee is bent then velocity is h
  rule: if delta is end and knee is deep then velocity is i
)";

TEST(Partition, RecognisesAndMatchesTheEvaluator) {
  const Engine e = read_fll(kTwoInputs);
  std::string why;
  const auto p = as_partition(e, &why);
  ASSERT_TRUE(p) << why;
  const Evaluator general(e);
  Workspace w = general.make_workspace();
  for (int i = 0; i <= 40; ++i) {
    for (int j = 0; j <= 40; ++j) {
      const double in[2] = {-1.3 + 2.6 * i / 40.0, -10.0 + 80.0 * j / 40.0};
      double expected = 0.0;
      general.evaluate(in, std::span<double>(&expected, 1), w);
      EXPECT_NEAR(p->evaluate(in[0], in[1]), expected, 1e-9);
    }
  }
  Engine minimum = e;
  minimum.rule_blocks[0].conjunction = TNorm::Minimum;
  const auto pm = as_partition(minimum);
  ASSERT_TRUE(pm);
  const Evaluator general_min(minimum);
  Workspace wm = general_min.make_workspace();
  for (int i = 0; i <= 40; ++i) {
    const double in[2] = {-1.0 + 2.0 * i / 40.0, 60.0 * ((i * 7) % 41) / 40.0};
    double expected = 0.0;
    general_min.evaluate(in, std::span<double>(&expected, 1), wm);
    EXPECT_NEAR(pm->evaluate(in[0], in[1]), expected, 1e-9);
  }
}

TEST(Partition, RejectsOtherShapesWithAReason) {
  Engine e = read_fll(kTwoInputs);
  e.inputs[0].terms[1].kind = TermKind::Gaussian;
  e.inputs[0].terms[1].parameters = {0.0, 0.4};
  std::string why;
  EXPECT_FALSE(as_partition(e, &why));
  EXPECT_NE(why.find("not a unit Triangle"), std::string::npos);
  e = read_fll(kTwoInputs);
  std::swap(e.rule_blocks[0].rules[0], e.rule_blocks[0].rules[1]);
  EXPECT_FALSE(as_partition(e, &why));
  EXPECT_NE(why.find("row-major"), std::string::npos);
}

TEST(Partition, FittedValuesGoBackIntoReadableFll) {
  const Engine e = read_fll(kTwoInputs);
  PartitionController<double> p = *as_partition(e);
  p.knots[0] = {-1.0, 0.2, 1.0};
  for (double& c : p.consequents)
    c *= 0.5;
  const Engine fitted = with_partition(e, p);
  EXPECT_EQ(fitted.inputs[0].terms[1].parameters, (std::vector<double>{-1.0, 0.2, 1.0}));
  EXPECT_EQ(fitted.outputs[0].find_term("a")->parameters[0], 200.0);
  const Engine again = read_fll(write_fll(fitted));
  const auto q = as_partition(again);
  ASSERT_TRUE(q);
  EXPECT_EQ(q->knots[0], p.knots[0]);
  EXPECT_EQ(q->consequents, p.consequents);
  EXPECT_EQ(again.rule_blocks[0].rules[0].text(), e.rule_blocks[0].rules[0].text());
}

// Derivatives of the output with respect to every knot, every consequent and the inputs, by
// automatic differentiation, against central finite differences.
TEST(Partition, DualNumberDerivativesEqualFiniteDifferences) {
  const PartitionController<double> p = *as_partition(read_fll(kTwoInputs));
  constexpr int N = 20;  // 6 knots + 9 consequents + 2 inputs (+ padding)
  using Jet = ceres::Jet<double, N>;
  auto lift = [&](const std::vector<double>& theta) {
    PartitionController<Jet> j;
    int k = 0;
    for (int i = 0; i < 2; ++i) {
      for (std::size_t m = 0; m < p.knots[i].size(); ++m)
        j.knots[i].push_back(Jet(theta[k], k)), ++k;
    }
    for (std::size_t m = 0; m < p.consequents.size(); ++m)
      j.consequents.push_back(Jet(theta[k], k)), ++k;
    j.default_value = Jet(0.0);
    return j;
  };
  auto plain = [&](const std::vector<double>& theta, double x0, double x1) {
    PartitionController<double> d;
    int k = 0;
    for (int i = 0; i < 2; ++i) {
      for (std::size_t m = 0; m < p.knots[i].size(); ++m)
        d.knots[i].push_back(theta[k++]);
    }
    for (std::size_t m = 0; m < p.consequents.size(); ++m)
      d.consequents.push_back(theta[k++]);
    d.default_value = 0.0;
    return d.evaluate(x0, x1);
  };
  std::vector<double> theta;
  for (int i = 0; i < 2; ++i)
    theta.insert(theta.end(), p.knots[i].begin(), p.knots[i].end());
  theta.insert(theta.end(), p.consequents.begin(), p.consequents.end());
  const int inputs_at = static_cast<int>(theta.size());
  for (const auto& [x0, x1] : std::vector<std::pair<double, double>>{
           {-0.63, 12.0}, {0.31, 44.0}, {0.77, 7.5}, {-0.2, 33.3}}) {
    const PartitionController<Jet> j = lift(theta);
    const Jet out = j.evaluate(Jet(x0, inputs_at), Jet(x1, inputs_at + 1));
    EXPECT_NEAR(out.a, plain(theta, x0, x1), 1e-12);
    for (int k = 0; k < inputs_at; ++k) {
      const double h = 1e-6 * std::max(1.0, std::abs(theta[static_cast<std::size_t>(k)]));
      std::vector<double> up = theta, down = theta;
      up[static_cast<std::size_t>(k)] += h;
      down[static_cast<std::size_t>(k)] -= h;
      const double fd = (plain(up, x0, x1) - plain(down, x0, x1)) / (2.0 * h);
      EXPECT_NEAR(out.v[k], fd, 1e-5 * (1.0 + std::abs(fd))) << "parameter " << k;
    }
    const double h = 1e-6;
    EXPECT_NEAR(out.v[inputs_at], (plain(theta, x0 + h, x1) - plain(theta, x0 - h, x1)) / (2 * h),
                1e-4);
    EXPECT_NEAR(out.v[inputs_at + 1],
                (plain(theta, x0, x1 + h) - plain(theta, x0, x1 - h)) / (2 * h), 1e-4);
  }
}

// The shapes of the trainable core, Gaussian and bell, and the operators, by dual numbers.
TEST(Partition, ShapeDerivativesEqualFiniteDifferences) {
  using Jet = ceres::Jet<double, 4>;
  auto check = [](auto f, std::array<double, 4> at) {
    std::array<Jet, 4> j;
    for (int k = 0; k < 4; ++k)
      j[static_cast<std::size_t>(k)] = Jet(at[static_cast<std::size_t>(k)], k);
    const Jet out = f(j);
    for (int k = 0; k < 4; ++k) {
      std::array<Jet, 4> up = j, down = j;
      const double h = 1e-6;
      up[static_cast<std::size_t>(k)].a += h;
      down[static_cast<std::size_t>(k)].a -= h;
      const double fd = (f(up).a - f(down).a) / (2 * h);
      EXPECT_NEAR(out.v[k], fd, 1e-6 * (1.0 + std::abs(fd)));
    }
  };
  check([](const std::array<Jet, 4>& v) { return shapes::gaussian(v[0], v[1], v[2], v[3]); },
        {0.3, 0.1, 0.4, 0.9});
  check([](const std::array<Jet, 4>& v) { return shapes::bell(v[0], v[1], v[2], Jet(2.5), v[3]); },
        {0.3, 0.1, 0.4, 0.9});
  check(
      [](const std::array<Jet, 4>& v) {
        return apply(TNorm::AlgebraicProduct,
                     shapes::triangle(v[0], Jet(-1.0), v[1], Jet(1.0), Jet(1.0)),
                     apply(TNorm::Minimum, v[2], v[3]));
      },
      {0.3, 0.1, 0.4, 0.9});
}

}  // namespace

namespace {

bool same_bits_or_both_nan(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof a) == 0;
}

// Inputs on and around every knot (within and beyond fuzzylite's tolerance), between knots,
// beyond the range, and NaN.
std::vector<double> probes(const std::vector<double>& knots) {
  std::vector<double> x = {std::nan(""), -1e9, 1e9};
  for (std::size_t i = 0; i < knots.size(); ++i) {
    for (double d : {0.0, 1e-7, -1e-7, 1e-5, -1e-5})
      x.push_back(knots[i] + d);
    if (i + 1 < knots.size()) {
      for (double f : {0.1, 0.37, 0.5, 0.83})
        x.push_back(knots[i] + f * (knots[i + 1] - knots[i]));
    }
  }
  return x;
}

}  // namespace

// The walker's packed form gives the same bits as the controller it packs, for one input, two
// with product and with minimum, at every edge; partitions too large to pack are refused.
TEST(Partition, PackedFormGivesTheSameBits) {
  PartitionController<double> two = *as_partition(read_fll(kTwoInputs));
  two.knots[0] = {-1.0, -0.6, -0.1, 0.05, 0.3, 0.31, 0.9, 1.0};  // eight knots: the capacity
  two.consequents.clear();
  for (std::size_t i = 0; i < two.knots[0].size() * two.knots[1].size(); ++i) {
    two.consequents.push_back(std::sin(1.7 * static_cast<double>(i)) * 300.0);
  }
  two.default_value = -7.0;
  PartitionController<double> minimum = two;
  minimum.conjunction = Conjunction::Minimum;
  PartitionController<double> one = two;
  one.knots[1].clear();
  one.consequents.resize(one.knots[0].size());
  int compared = 0;
  for (const PartitionController<double>* c : {&two, &minimum, &one}) {
    const std::optional<PackedPartition> packed = PackedPartition::pack(*c);
    ASSERT_TRUE(packed);
    const std::vector<double> xs1 = c->input_count() == 2 ? probes(c->knots[1]) : probes({0.0});
    for (double x0 : probes(c->knots[0])) {
      for (double x1 : xs1) {
        const double expected = c->input_count() == 2 ? c->evaluate(x0, x1) : c->evaluate(x0);
        const double got = packed->evaluate(x0, x1);
        ASSERT_TRUE(same_bits_or_both_nan(got, expected))
            << "inputs " << x0 << ", " << x1 << ": " << got << " vs " << expected;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 3000);
  PartitionController<double> nine = one;
  nine.knots[0].push_back(2.0);
  nine.consequents.push_back(1.0);
  EXPECT_FALSE(PackedPartition::pack(nine));
}

#include "fuzzygait/learn/cmaes.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <thread>

#include "runtime/common/splitmix64.hpp"

namespace fuzzygait::learn {
namespace {

// splitmix64 with Box-Muller: the same numbers on every platform.
class Normal {
 public:
  explicit Normal(std::uint64_t seed) : random_(seed) {}
  double operator()() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u = 0.0;
    while (u <= 0.0)
      u = random_.uniform();
    const double v = random_.uniform();
    const double r = std::sqrt(-2.0 * std::log(u));
    spare_ = r * std::sin(2.0 * M_PI * v);
    has_spare_ = true;
    return r * std::cos(2.0 * M_PI * v);
  }

 private:
  gait::detail::SplitMix64 random_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace

CmaesResult minimize(const std::function<double(const std::vector<double>&)>& cost,
                     const std::vector<double>& start, const CmaesOptions& options) {
  const auto n = static_cast<Eigen::Index>(start.size());
  if (n == 0) throw std::invalid_argument("cmaes: no parameters");
  const double nd = static_cast<double>(n);
  const int lambda =
      options.population > 0 ? options.population : 4 + static_cast<int>(3.0 * std::log(nd));
  const int mu = lambda / 2;
  Eigen::VectorXd weights(mu);
  for (int i = 0; i < mu; ++i)
    weights(i) = std::log(mu + 0.5) - std::log(i + 1.0);
  weights /= weights.sum();
  const double mueff = 1.0 / weights.squaredNorm();
  const double cc = (4.0 + mueff / nd) / (nd + 4.0 + 2.0 * mueff / nd);
  const double cs = (mueff + 2.0) / (nd + mueff + 5.0);
  const double c1 = 2.0 / ((nd + 1.3) * (nd + 1.3) + mueff);
  const double cmu =
      std::min(1.0 - c1, 2.0 * (mueff - 2.0 + 1.0 / mueff) / ((nd + 2.0) * (nd + 2.0) + mueff));
  const double damps = 1.0 + 2.0 * std::max(0.0, std::sqrt((mueff - 1.0) / (nd + 1.0)) - 1.0) + cs;
  const double chi_n = std::sqrt(nd) * (1.0 - 1.0 / (4.0 * nd) + 1.0 / (21.0 * nd * nd));

  Eigen::VectorXd mean = Eigen::Map<const Eigen::VectorXd>(start.data(), n);
  double sigma = options.sigma;
  Eigen::MatrixXd C = Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd B = Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd D = Eigen::VectorXd::Ones(n);
  Eigen::VectorXd pc = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd ps = Eigen::VectorXd::Zero(n);
  Normal normal(options.seed);

  CmaesResult result;
  result.best = start;
  result.best_cost = cost(start);
  result.evaluations = 1;
  std::vector<std::vector<double>> candidates(static_cast<std::size_t>(lambda));
  std::vector<Eigen::VectorXd> steps(static_cast<std::size_t>(lambda));
  std::vector<double> costs(static_cast<std::size_t>(lambda));
  for (int generation = 1; generation <= options.max_generations; ++generation) {
    for (int k = 0; k < lambda; ++k) {
      Eigen::VectorXd z(n);
      for (Eigen::Index i = 0; i < n; ++i)
        z(i) = normal();
      steps[static_cast<std::size_t>(k)] = B * D.asDiagonal() * z;
      const Eigen::VectorXd x = mean + sigma * steps[static_cast<std::size_t>(k)];
      candidates[static_cast<std::size_t>(k)].assign(x.data(), x.data() + n);
    }
    const int threads = std::max(1, std::min(options.threads, lambda));
    std::vector<std::thread> workers;
    for (int t = 0; t < threads; ++t) {
      workers.emplace_back([&, t]() {
        for (int k = t; k < lambda; k += threads) {
          costs[static_cast<std::size_t>(k)] = cost(candidates[static_cast<std::size_t>(k)]);
        }
      });
    }
    for (std::thread& w : workers)
      w.join();
    result.evaluations += lambda;
    std::vector<int> order(static_cast<std::size_t>(lambda));
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&costs](int a, int b) {
      const double ca = costs[static_cast<std::size_t>(a)];
      const double cb = costs[static_cast<std::size_t>(b)];
      return (std::isnan(cb) && !std::isnan(ca)) || ca < cb;
    });
    const int best = order[0];
    if (costs[static_cast<std::size_t>(best)] < result.best_cost) {
      result.best_cost = costs[static_cast<std::size_t>(best)];
      result.best = candidates[static_cast<std::size_t>(best)];
    }
    Eigen::VectorXd step = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < mu; ++i)
      step += weights(i) * steps[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])];
    mean += sigma * step;
    const Eigen::VectorXd inverse_sqrt_step =
        B * D.cwiseInverse().asDiagonal() * B.transpose() * step;
    ps = (1.0 - cs) * ps + std::sqrt(cs * (2.0 - cs) * mueff) * inverse_sqrt_step;
    const double ps_norm = ps.norm();
    const bool hsig = ps_norm / std::sqrt(1.0 - std::pow(1.0 - cs, 2.0 * generation)) / chi_n <
                      1.4 + 2.0 / (nd + 1.0);
    pc = (1.0 - cc) * pc + (hsig ? std::sqrt(cc * (2.0 - cc) * mueff) : 0.0) * step;
    Eigen::MatrixXd rank_mu = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < mu; ++i) {
      const Eigen::VectorXd& y =
          steps[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])];
      rank_mu += weights(i) * y * y.transpose();
    }
    C = (1.0 - c1 - cmu) * C + c1 * (pc * pc.transpose() + (hsig ? 0.0 : cc * (2.0 - cc)) * C) +
        cmu * rank_mu;
    sigma *= std::exp((cs / damps) * (ps_norm / chi_n - 1.0));
    C = 0.5 * (C + C.transpose());
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(C);
    B = eigen.eigenvectors();
    D = eigen.eigenvalues().cwiseMax(1e-20).cwiseSqrt();
    if (options.progress) options.progress(generation, result.best_cost, result.best);
    if (result.best_cost < options.target) break;
    if (options.stop && options.stop()) break;
  }
  return result;
}

}  // namespace fuzzygait::learn

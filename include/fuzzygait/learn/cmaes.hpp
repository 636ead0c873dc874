// Covariance matrix adaptation evolution strategy (Hansen 2016, "The CMA Evolution Strategy: A
// Tutorial"), for fitting controllers where the objective runs a whole walk: derivative-free,
// robust to the discontinuities that contact events cause. Deterministic for a given seed.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

namespace fuzzygait::learn {

struct CmaesOptions {
  double sigma = 0.3;  // initial step size, in the units of the (scaled) parameters
  int population = 0;  // 0: 4 + 3 ln(n)
  int max_generations = 300;
  double target = -1e300;  // stop when the best cost falls below this
  std::uint64_t seed = 1;
  int threads = 1;  // candidates of a generation evaluated in parallel
  // Called after each generation with (generation, best cost so far, best parameters).
  std::function<void(int, double, const std::vector<double>&)> progress;
  // Asked after each generation: true stops there, with the best found so far.
  std::function<bool()> stop;
};

struct CmaesResult {
  std::vector<double> best;
  double best_cost = 0.0;
  int evaluations = 0;
};

// Minimises `cost` starting from `start`. `cost` must be thread-safe when threads > 1.
CmaesResult minimize(const std::function<double(const std::vector<double>&)>& cost,
                     const std::vector<double>& start, const CmaesOptions& options);

}  // namespace fuzzygait::learn

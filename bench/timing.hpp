// Timing shared by fuzzygait-bench's subcommands: wall seconds, calibrating a work count to a
// minimum time, running two sides in alternating order, and the median of the repetitions.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace fuzzygait::bench {

// The options every subcommand times by: the least time per repetition (`what_runs` says what
// runs that long) and how many repetitions the median is taken over.
inline void add_timing_options(CLI::App& command, double& min_seconds, int& repetitions,
                               const std::string& what_runs) {
  command.add_option("--min-time", min_seconds, what_runs)
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command.add_option("--repetitions", repetitions, "Repetitions; the median is reported")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
}

// The options of the benchmarks that time one walk: the set, the repetitions and the simulated
// seconds timed in each.
inline void add_walk_options(CLI::App& command, std::string& style, int& repetitions,
                             double& window) {
  command.add_option("--style", style, "Built-in controller set")->capture_default_str();
  command.add_option("--repetitions", repetitions, "Repetitions; the median is reported")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command.add_option("--window", window, "Simulated seconds timed per repetition")
      ->check(CLI::Range(0.1, 60.0))
      ->capture_default_str();
}

using Clock = std::chrono::steady_clock;

// Wall seconds `work()` takes.
template <class Work>
double wall_seconds(Work&& work) {
  const Clock::time_point start = Clock::now();
  work();
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The count of work units (passes, frames) that takes about `min_seconds`: doubles `count` until
// `seconds_for(count)` takes at least an eighth of that, then scales it up.
template <class SecondsFor>
long calibrate(long count, double min_seconds, SecondsFor&& seconds_for) {
  for (;;) {
    const double seconds = seconds_for(count);
    if (seconds >= min_seconds / 8) {
      return std::max(
          1L, static_cast<long>(std::ceil(static_cast<double>(count) * min_seconds / seconds)));
    }
    count *= 2;
  }
}

// Runs both sides, `a` first in even repetitions and `b` first in odd ones: alternating which
// side goes first keeps a slow phase of the machine from favouring one.
template <class A, class B>
void run_alternating(int repetition, A&& a, B&& b) {
  if (repetition % 2 == 0) {
    a();
    b();
  } else {
    b();
    a();
  }
}

inline double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace fuzzygait::bench

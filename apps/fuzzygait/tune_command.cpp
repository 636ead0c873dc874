// `fuzzygait tune`: fits a controller set's output velocities to normative gait curves and
// writes the tuned set, rounded to values an animator reads.
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "fuzzygait/io/controller_files.hpp"
#include "fuzzygait/io/normative.hpp"
#include "fuzzygait/learn/tune.hpp"

namespace fuzzygait::cli {

void add_tune_command(CLI::App& app) {
  struct Options {
    std::string controllers;
    std::string style = "default";
    std::string output;
    std::string reference = "schwartz2008_free";
    int generations = 200;
    int threads = 2;
    int digits = 3;
    std::uint64_t seed = 1;
    double sigma = 0.3;
    double duration = 10.0;
    bool grid = false;
    int recovery = 0;
  };
  auto o = std::make_shared<Options>();
  CLI::App* tune = app.add_subcommand(
      "tune", "Fit a controller set's velocities to normative curves (CMA-ES over whole walks)");
  tune->add_option("--controllers", o->controllers, "Start from this controller set folder");
  tune->add_option("--style", o->style, "Start from this built-in set (default: default)");
  tune->add_option("-o,--output", o->output, "Folder to write the tuned set to")->required();
  tune->add_option("--reference", o->reference, "Normative curves: built-in name or CSV file");
  tune->add_option("--generations", o->generations, "CMA-ES generations")->check(CLI::PositiveNumber);
  tune->add_option("--threads", o->threads, "Walks evaluated in parallel")->check(CLI::PositiveNumber);
  tune->add_option("--digits", o->digits, "Significant digits kept in the written values")
      ->check(CLI::Range(1, 17));
  tune->add_option("--seed", o->seed, "Random seed (the result is deterministic for a seed)");
  tune->add_option("--sigma", o->sigma, "Initial CMA-ES step (scaled units)");
  tune->add_option("--duration", o->duration, "Seconds walked per evaluation");
  tune->add_option("--recovery", o->recovery,
                   "Also start from this many random poses that must settle into the gait");
  tune->add_flag("--grid", o->grid,
                 "Also walk short and long steps and small and tall bodies (contact and timing)");
  tune->callback([o]() {
    const gait::ControllerSet start = o->controllers.empty()
                                          ? gait::ControllerSet::builtin(o->style)
                                          : gait::ControllerSet::load(o->controllers);
    learn::TuneOptions options;
    options.reference = io::load_normative(o->reference);
    options.generations = o->generations;
    options.threads = o->threads;
    options.seed = o->seed;
    options.sigma = o->sigma;
    options.duration = o->duration;
    if (o->grid) {
      options.conditions.push_back({1.75, 0.50, false});
      options.conditions.push_back({1.75, 0.85, false});
      options.conditions.push_back({1.50, 0.60, false});
      options.conditions.push_back({2.00, 0.80, false});
    }
    for (int seed = 0; seed < o->recovery; ++seed) {
      options.recovery_seeds.push_back(1000 + static_cast<std::uint64_t>(seed));
    }
    options.progress = [](int generation, double cost) {
      if (generation % 10 == 0) std::cerr << "generation " << generation << ": cost " << cost << "\n";
    };
    std::string report;
    std::cout << "start: cost " << learn::walk_cost(start, options, &report) << "\n" << report;
    const learn::TuneResult result = learn::tune(start, options);
    const learn::SetParameters parameters(result.set);
    const gait::ControllerSet rounded = parameters.rounded(parameters.values(), o->digits);
    report.clear();
    const double tuned = learn::walk_cost(result.set, options);
    const double final_cost = learn::walk_cost(rounded, options, &report);
    std::cout << "tuned: cost " << tuned << " (" << result.evaluations << " walks)\n";
    std::cout << "rounded to " << o->digits << " digits: cost " << final_cost << "\n" << report;
    io::save_controller_set(rounded, o->output);
    std::cout << "written to " << o->output << "\n";
  });
}

}  // namespace fuzzygait::cli

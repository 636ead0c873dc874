// `fuzzygait tune`: fits a controller set's output velocities to normative gait curves and
// writes the tuned set, rounded to values an animator reads.
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "commands.hpp"
#include "fuzzygait/io/controller_files.hpp"
#include "fuzzygait/io/normative.hpp"
#include "fuzzygait/learn/tune.hpp"

namespace fuzzygait::cli {

void add_tune_command(CLI::App& app) {
  struct Options {
    learn::TuneOptions tune;
    std::string controllers;
    std::string style = "default";
    std::string output;
    std::string reference = "schwartz2008_free";
    std::string slower = "schwartz2008_slow";
    std::string faster = "schwartz2008_fast";
    bool grid = false;
    int recovery = 0;
    // Ranges, low and high, into tune's _min and _max fields.
    std::vector<double> cycle = {tune.cycle_time_min, tune.cycle_time_max};
    std::vector<double> stance = {tune.stance_min, tune.stance_max};
    std::vector<double> knee_peak = {tune.knee_peak_min, tune.knee_peak_max};
    std::vector<double> pelvis_range = {tune.pelvis_range_min, tune.pelvis_range_max};
    double heel_bounce_mm = tune.heel_bounce_max * 1000.0;
    std::string name;         // of the written set; default: the starting set's
    std::string description;  // likewise
  };
  auto o = std::make_shared<Options>();
  learn::TuneOptions& t = o->tune;
  CLI::App* tune = app.add_subcommand(
      "tune", "Fit a controller set's velocities to normative curves (CMA-ES over whole walks)");
  tune->add_option("--controllers", o->controllers, "Start from this controller set folder");
  tune->add_option("--style", o->style, "Start from this built-in set (default: default)");
  tune->add_option("-o,--output", o->output, "Folder to write the tuned set to")->required();
  tune->add_option("--reference", o->reference, "Normative curves: built-in name or CSV file");
  tune->add_option("--generations", t.generations, "CMA-ES generations")
      ->check(CLI::PositiveNumber);
  tune->add_option("--threads", t.threads, "Walks evaluated in parallel")
      ->check(CLI::PositiveNumber);
  tune->add_option("--digits", t.digits, "Significant digits kept in the written values")
      ->check(CLI::Range(1, 17));
  tune->add_option("--polish", t.polish_generations,
                   "Generations of polishing on the rounded values (default 0)");
  tune->add_option("--seed", t.seed, "Random seed (the result is deterministic for a seed)");
  tune->add_option("--sigma", t.sigma, "Initial CMA-ES step (scaled units)");
  tune->add_option("--duration", t.duration, "Seconds walked per evaluation");
  tune->add_option("--recovery", o->recovery,
                   "Also start from this many random poses that must settle into the gait")
      ->check(CLI::Range(0, 10000));
  tune->add_option("--cycle", o->cycle, "Wanted gait cycle time range, s (default 1.0 1.2)")
      ->expected(2);
  tune->add_option("--stance", o->stance, "Wanted stance share range, % (default 58 64)")
      ->expected(2);
  tune->add_option("--knee-peak", o->knee_peak,
                   "Wanted peak swing knee flexion range, deg (default 55 70)")
      ->expected(2);
  tune->add_option("--pelvis-range", o->pelvis_range,
                   "Wanted vertical travel of the pelvis over a cycle, mm (default any)")
      ->expected(2);
  tune->add_option("--acceleration-ratio-max", t.acceleration_ratio_max,
                   "How many times people's RMS angular acceleration the thigh and knee may have "
                   "on the main walk before it costs (default: no limit)")
      ->check(CLI::PositiveNumber);
  tune->add_option("--heel-bounce-max", o->heel_bounce_mm,
                   "Highest a heel may rise after foot flat and drop back before heel-off, mm, "
                   "before it costs (default: no limit)")
      ->check(CLI::Range(0, 1000));
  tune->add_option("--minimum-inertia", t.minimum_inertia,
                   "Smallest inertia time constant the tuning may choose, s (default 0.02)");
  tune->add_option("--name", o->name, "Name written into the tuned set's manifest (a style)");
  tune->add_option("--description", o->description,
                   "Description written into the tuned set's manifest");
  tune->add_option("--slower", o->slower, "Reference for 0.55 m steps with --grid");
  tune->add_option("--faster", o->faster, "Reference for 0.85 m steps with --grid");
  tune->add_flag("--grid", o->grid,
                 "Also walk 0.55 and 0.85 m steps against the slower and faster references, and "
                 "the rest of the acceptance grid (steps 0.50-0.85 m, statures 1.50-2.00 m) for "
                 "contact and timing");
  tune->callback([o]() {
    const gait::ControllerSet start = o->controllers.empty()
                                          ? gait::ControllerSet::builtin(o->style)
                                          : gait::ControllerSet::load(o->controllers);
    learn::TuneOptions& options = o->tune;
    const eval::Normative reference = io::load_normative(o->reference);
    // The slow and fast groups of the same study, for walks with shorter and longer steps.
    std::optional<eval::Normative> slow;
    std::optional<eval::Normative> fast;
    if (o->grid) {
      slow = io::load_normative(o->slower);
      fast = io::load_normative(o->faster);
      options.conditions = learn::grid_conditions(reference, *slow, *fast);
    } else {
      options.conditions = {learn::main_condition(reference)};
    }
    options.cycle_time_min = o->cycle.at(0);
    options.cycle_time_max = o->cycle.at(1);
    options.stance_min = o->stance.at(0);
    options.stance_max = o->stance.at(1);
    options.knee_peak_min = o->knee_peak.at(0);
    options.knee_peak_max = o->knee_peak.at(1);
    options.pelvis_range_min = o->pelvis_range.at(0);
    options.pelvis_range_max = o->pelvis_range.at(1);
    options.heel_bounce_max = o->heel_bounce_mm / 1000.0;
    options.recovery_seeds = learn::recovery_seeds(o->recovery);
    options.progress = [](int generation, double cost) {
      if (generation % 10 == 0)
        std::cerr << "generation " << generation << ": cost " << cost << "\n";
    };
    // walk_cost() validates too, but only once "start: cost" is already printed.
    learn::validate(options);
    std::string report;
    std::cout << "start: cost " << learn::walk_cost(start, options, &report) << "\n" << report;
    const learn::TuneResult result = learn::tune(start, options);
    gait::ControllerSet rounded = result.rounded;
    if (!o->name.empty()) rounded.name = o->name;
    if (!o->description.empty()) rounded.description = o->description;
    report.clear();
    int failed = 0;
    const double final_cost = learn::walk_cost(rounded, options, &report, &failed);
    std::cout << "tuned: cost " << result.cost << " (" << result.evaluations << " walks)\n";
    std::cout << "rounded to " << options.digits << " digits: cost " << final_cost << "\n"
              << report;
    // A set that cannot walk is not a result (and its files might not even load back).
    if (failed > 0) {
      throw std::runtime_error("the tuned set failed " + std::to_string(failed) + " of " +
                               std::to_string(options.conditions.size()) +
                               " walks (above); nothing written to " + o->output);
    }
    io::save_controller_set(rounded, o->output);
    std::cout << "written to " << o->output << "\n";
  });
}

}  // namespace fuzzygait::cli

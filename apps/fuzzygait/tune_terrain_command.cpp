// `fuzzygait tune-terrain`: fits a controller set's terrain words (the stairs' "up", ...) by
// walking their ground and measuring the walks against published human data, and writes the set.
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "fuzzygait/io/controller_files.hpp"
#include "fuzzygait/learn/terrain_tune.hpp"

namespace fuzzygait::cli {
namespace {

// The walks a preset tunes over: the stairs and Reznick et al.'s (2021) geometries, at
// three statures.
std::vector<learn::TerrainCondition> preset_conditions(const std::string& preset) {
  if (preset == "ramps-up" || preset == "ramps-down") {
    const int sign = preset == "ramps-up" ? 1 : -1;
    std::vector<learn::TerrainCondition> ramps;
    for (const int degrees : {5, 10, 15, 20}) {
      ramps.push_back({"slope:" + std::to_string(sign * degrees), degrees == 10 ? 1.60 : 1.75,
                       degrees == 15 ? 0.60 : 0.70, 12.0, learn::ramp_bounds(sign * degrees),
                       std::nullopt});
    }
    return ramps;
  }
  const bool up = preset == "stairs-up";
  if (!up && preset != "stairs-down") {
    throw std::invalid_argument(
        "--preset must be stairs-up, stairs-down, ramps-up or ramps-down, got '" + preset + "'");
  }
  const learn::TerrainBounds bounds =
      up ? learn::stair_ascent_bounds() : learn::stair_descent_bounds();
  const std::string sign = up ? "" : "-";
  return {
      {"stairs:" + sign + "0.17:0.28:10", 1.75, 0.70, 16.0, bounds, std::nullopt},
      {"stairs:" + sign + "0.12:0.305:6", 1.60, 0.65, 12.0, bounds, std::nullopt},
      {"stairs:" + sign + "0.162:0.285:6", 2.00, 0.75, 12.0, bounds, std::nullopt},
      {"stairs:" + sign + "0.146:0.295:4", 1.75, 0.70, 10.0, bounds, std::nullopt},
  };
}

learn::TerrainWord parse_word(const std::string& text) {
  const std::size_t colon = text.find(':');
  const std::string ground = text.substr(0, colon);
  if (colon == std::string::npos || (ground != "stairs" && ground != "slopes")) {
    throw std::invalid_argument("--words: '" + text + "' must be stairs:WORD or slopes:WORD");
  }
  return {ground == "stairs" ? gait::Ground::Stairs : gait::Ground::Slopes, text.substr(colon + 1)};
}

}  // namespace

void add_tune_terrain_command(CLI::App& app) {
  struct Options {
    learn::TerrainTuneOptions tune;
    std::string controllers;
    std::string style = "default";
    std::string output;
    std::string preset;
    std::vector<std::string> words;
    std::string words_from;
  };
  auto o = std::make_shared<Options>();
  learn::TerrainTuneOptions& t = o->tune;
  CLI::App* tune = app.add_subcommand(
      "tune-terrain",
      "Fit a controller set's terrain words by walking their ground (CMA-ES over whole walks)");
  tune->add_option("--controllers", o->controllers, "Start from this controller set folder");
  tune->add_option("--style", o->style, "Start from this built-in set (default: default)");
  tune->add_option("-o,--output", o->output, "Folder to write the tuned set to")->required();
  tune->add_option("--preset", o->preset,
                   "The walks: stairs-up, stairs-down, ramps-up or ramps-down")
      ->required();
  tune->add_option("--words", o->words, "The words to tune, e.g. stairs:up (repeatable)")
      ->required();
  tune->add_option("--words-from", o->words_from,
                   "Start the terrain words (all of them: words, files, landing knees) from this "
                   "built-in set or folder, e.g. a style from the default's");
  tune->add_option("--generations", t.generations, "CMA-ES generations")
      ->check(CLI::PositiveNumber);
  tune->add_option("--threads", t.threads, "Walks evaluated in parallel")
      ->check(CLI::PositiveNumber);
  tune->add_option("--digits", t.digits, "Significant digits kept in the written values")
      ->check(CLI::Range(1, 17));
  tune->add_option("--seed", t.seed, "Random seed (the result is deterministic for a seed)");
  tune->add_option("--sigma", t.sigma, "Initial CMA-ES step (scaled units)");
  tune->callback([o]() {
    gait::ControllerSet start = o->controllers.empty() ? gait::ControllerSet::builtin(o->style)
                                                       : gait::ControllerSet::load(o->controllers);
    if (!o->words_from.empty()) {
      const bool folder = o->words_from.find('/') != std::string::npos;
      const gait::ControllerSet from = folder ? gait::ControllerSet::load(o->words_from)
                                              : gait::ControllerSet::builtin(o->words_from);
      start.ground = from.ground;
      start.terrain_controllers = from.terrain_controllers;
    }
    learn::TerrainTuneOptions& options = o->tune;
    options.conditions = preset_conditions(o->preset);
    options.words.clear();
    for (const std::string& w : o->words)
      options.words.push_back(parse_word(w));
    learn::validate(options, start);
    std::string before;
    std::cout << "start: cost " << learn::terrain_cost(start, options, &before) << "\n" << before;
    options.progress = [](int generation, double cost) {
      if (generation % 10 == 0)
        std::cout << "generation " << generation << ": cost " << cost << std::endl;
    };
    const learn::TerrainTuneResult r = learn::tune_terrain(start, options);
    std::string after;
    learn::terrain_cost(r.set, options, &after);
    std::cout << "tuned: cost " << r.cost << " (from " << r.start_cost << ", " << r.evaluations
              << " walks sets)\n"
              << after;
    io::save_controller_set(r.set, o->output);
    std::cout << "wrote " << o->output << "\n";
  });
}

}  // namespace fuzzygait::cli

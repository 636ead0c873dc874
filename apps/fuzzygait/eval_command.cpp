// `fuzzygait eval`: the realism and contact figures of a walk CSV and the measures on its terrain
// (docs/measuring.md), as tables and as JSON.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "commands.hpp"
#include "fuzzygait/eval/evaluation.hpp"
#include "fuzzygait/eval/terrain_report.hpp"
#include "fuzzygait/io/files.hpp"
#include "fuzzygait/io/normative.hpp"
#include "fuzzygait/io/walk_csv.hpp"
#include "fuzzygait/plot/svg.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::cli {
namespace {

// The terrain CSV at `path`, or flat ground when `path` is empty.
terrain::Terrain load_terrain(const std::string& path) {
  if (path.empty()) return terrain::Terrain::flat();
  std::ifstream in = open_or_throw(path);
  return io::read_terrain_csv(in, path);
}

}  // namespace

void add_eval_command(CLI::App& app) {
  struct Options {
    std::string csv;
    std::string reference = "schwartz2008_free";
    std::string terrain;
    std::optional<double> step;
    std::string json;
  };
  auto o = std::make_shared<Options>();
  CLI::App* eval = app.add_subcommand("eval", "Measure a walk CSV against normative gait data");
  eval->add_option("walk", o->csv, "Walk CSV written by `fuzzygait walk` or `fuzzygait mocap`")
      ->required();
  eval->add_option("--reference", o->reference,
                   "Normative curves: built-in name (schwartz2008_veryslow, _slow, _free, _fast, "
                   "_veryfast) or a CSV file");
  eval->add_option("--terrain", o->terrain,
                   "Terrain CSV (default: the walk's .terrain.csv beside it, else flat ground)");
  eval->add_option("--step", o->step, "Commanded step length, m, for the step error");
  eval->add_option("--json", o->json, "Write the figures as JSON to this file ('-' for stdout)");
  eval->callback([o]() {
    if (o->step && !(*o->step > 0.0 && *o->step <= 10.0)) {
      throw std::invalid_argument("--step must be a step length above 0 and at most 10 m, got " +
                                  common::number_text(*o->step));
    }
    std::ifstream in = open_or_throw(o->csv);
    const eval::Motion motion = io::read_walk_csv(in, o->csv);
    std::string terrain_path = o->terrain;
    if (terrain_path.empty()) {
      std::filesystem::path guess(o->csv);
      guess.replace_extension(".terrain.csv");
      if (std::filesystem::exists(guess)) terrain_path = guess.string();
    }
    const terrain::Terrain ground = load_terrain(terrain_path);
    const eval::Normative reference = io::load_normative(o->reference);
    // The level figures need two complete cycles; the terrain's are measured on any walk.
    std::optional<eval::GaitReport> report;
    std::string not_measured;
    try {
      report = eval::evaluate(motion, ground, &reference, o->step);
    } catch (const std::invalid_argument& e) {
      not_measured = e.what();
    }
    const eval::TerrainReport on_terrain = eval::evaluate_terrain(motion, ground);
    nlohmann::ordered_json j = report ? nlohmann::ordered_json::parse(eval::to_json(*report))
                                      : nlohmann::ordered_json::object();
    if (!report) j["not_measured"] = not_measured;
    j["terrain"] = nlohmann::ordered_json::parse(eval::to_json(on_terrain));
    const std::string json = j.dump(2);
    if (o->json == "-") {
      std::cout << json << "\n";
      return;
    }
    std::cout << "reference: " << reference.name << "\n";
    if (report) {
      std::cout << eval::to_text(*report);
    } else {
      std::cout << "gait cycle figures not measured: " << not_measured << "\n";
    }
    std::cout << "\n" << eval::to_text(on_terrain);
    if (!o->json.empty()) {
      io::write_file(o->json, json + "\n");
    }
  });
}

}  // namespace fuzzygait::cli

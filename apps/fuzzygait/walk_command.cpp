// `fuzzygait walk`: walks a character with a controller set and writes its files: the walk CSV,
// the terrain, a BVH, the joint-angle curves against the normative band, and the poses.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>

#include "commands.hpp"
#include "fuzzygait/eval/evaluation.hpp"
#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/io/bvh.hpp"
#include "fuzzygait/io/files.hpp"
#include "fuzzygait/io/gltf.hpp"
#include "fuzzygait/io/normative.hpp"
#include "fuzzygait/io/walk_csv.hpp"
#include "fuzzygait/plot/svg.hpp"
#include "fuzzygait/plot/walk_plots.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::cli {
namespace {

namespace svg = plot::svg;

struct WalkOptions {
  double step = 0.70;
  double stature = 1.75;
  // Lengths given one by one replace the stature's; the rig checks each (zero and negative too).
  std::optional<double> thigh, shank, ankle_height, heel, ball, toe;
  std::string style = "default";
  std::string controllers;
  int cycles = 10;
  double duration = 0.0;
  double fps = 120.0;
  std::string start_pose = "default";
  std::string prefix = "out/walk";
  std::string reference = "schwartz2008_free";
  bool gltf = false;
};

gait::StartPose parse_start(const std::string& text) {
  gait::StartPose start;
  if (text == "default") return start;
  const std::string prefix = "random:";
  if (text.rfind(prefix, 0) == 0) {
    const std::string seed = text.substr(prefix.size());
    // Digits only: stoull alone takes "-5" (as 2^64 - 5), "+5" and leading blanks.
    const bool digits = !seed.empty() && std::all_of(seed.begin(), seed.end(),
                                                     [](char c) { return c >= '0' && c <= '9'; });
    if (digits) {
      try {
        start.seed = std::stoull(seed);
        start.random = true;
        return start;
      } catch (const std::out_of_range&) {  // past 64 bits: refused below
      }
    }
  }
  throw std::invalid_argument("--start-pose must be 'default' or 'random:SEED', got '" + text +
                              "'");
}

// The default set meets the contact bounds over its step range (docs/walk.md, "Step lengths");
// a style or a set of one's own may not, and the files are written all the same, so the reader
// is told.
void warn_about_contact(const eval::GaitReport& report) {
  const std::vector<std::string> missed = eval::missed_contact_bounds(report);
  if (missed.empty()) return;
  std::cerr << "fuzzygait: warning: this walk misses the contact bounds: ";
  for (std::size_t i = 0; i < missed.size(); ++i)
    std::cerr << (i > 0 ? "; " : "") << missed[i];
  std::cerr << "\n";
}

}  // namespace

void add_walk_command(CLI::App& app) {
  auto o = std::make_shared<WalkOptions>();
  CLI::App* walk = app.add_subcommand(
      "walk", "Walk a character with fuzzy controllers and write its files and plots");
  walk->add_option("--step", o->step, "Step length, metres heel to heel (default 0.70)");
  walk->add_option("--stature", o->stature,
                   "Body height, metres: segment lengths from anthropometric proportions");
  walk->add_option("--thigh", o->thigh, "Thigh length, m (overrides the stature's)");
  walk->add_option("--shank", o->shank, "Shank length, m");
  walk->add_option("--ankle-height", o->ankle_height, "Ankle height above the sole, m");
  walk->add_option("--heel", o->heel, "Ankle to back of the heel, m");
  walk->add_option("--ball", o->ball, "Ankle to the ball of the foot, m");
  walk->add_option("--toe", o->toe, "Ball of the foot to the toe tip, m");
  walk->add_option("--style", o->style, "Built-in controller set (default, or a style)");
  walk->add_option("--controllers", o->controllers, "Controller set folder (manifest.json + FLL)");
  walk->add_option("--cycles", o->cycles, "Gait cycles to walk after the first (default 10)")
      ->check(CLI::Range(2, 10000));
  walk->add_option("--duration", o->duration, "Seconds to walk (instead of --cycles)");
  walk->add_option("--fps", o->fps, "Frames per second of the files, 10 to 2000 (default 120)");
  walk->add_option("--start-pose", o->start_pose, "default, or random:SEED (awkward start)");
  walk->add_option("-o,--output", o->prefix, "Prefix of the files written (default out/walk)");
  walk->add_option("--reference", o->reference, "Normative curves for the plot and summary");
  walk->add_flag("--gltf", o->gltf,
                 "Also write PREFIX.glb: glTF 2.0 with the skeleton, the animation, a skinned "
                 "body and the ground");
  walk->footer(
      "Writes PREFIX.csv (one row per frame), PREFIX.terrain.csv, PREFIX.bvh, PREFIX.svg\n"
      "(joint angles over the gait cycle against the normative band) and PREFIX.poses.svg;\n"
      "with --gltf also PREFIX.glb.");
  walk->callback([o, walk]() {
    // CLI11's range checks let NaN through (every comparison with it is false).
    if (walk->count("--duration") > 0 && !(o->duration > 0.0 && o->duration <= 36000.0)) {
      throw std::invalid_argument("--duration must be between 0 and 36000 s, got " +
                                  common::number_text(o->duration));
    }
    if (!(o->fps >= 10.0 && o->fps <= 2000.0)) {
      throw std::invalid_argument("--fps must be between 10 and 2000, got " +
                                  common::number_text(o->fps));
    }
    check_output_prefix(o->prefix, "-o");
    // Everything that can be refused is refused before any file is written.
    const eval::Normative reference = io::load_normative(o->reference);
    const gait::ControllerSet set = o->controllers.empty()
                                        ? gait::ControllerSet::builtin(o->style)
                                        : gait::ControllerSet::load(o->controllers);
    gait::WalkerOptions options;
    options.segments = rig::segments_from_stature(o->stature);
    options.segments.thigh = o->thigh.value_or(options.segments.thigh);
    options.segments.shank = o->shank.value_or(options.segments.shank);
    options.segments.ankle_height = o->ankle_height.value_or(options.segments.ankle_height);
    options.segments.heel = o->heel.value_or(options.segments.heel);
    options.segments.ball = o->ball.value_or(options.segments.ball);
    options.segments.toe = o->toe.value_or(options.segments.toe);
    options.step_length = o->step;
    options.start = parse_start(o->start_pose);
    const terrain::Terrain ground = terrain::Terrain::flat();
    gait::Walker walker(set, options, ground);
    const eval::Motion motion = o->duration > 0.0 ? eval::record(walker, o->duration, o->fps)
                                                  : eval::record_cycles(walker, o->cycles, o->fps);
    const std::filesystem::path prefix(o->prefix);
    if (prefix.has_parent_path()) std::filesystem::create_directories(prefix.parent_path());
    io::write_file(o->prefix + ".csv",
                   [&motion](std::ostream& out) { io::write_walk_csv(out, motion); });
    io::write_file(o->prefix + ".terrain.csv", [&](std::ostream& out) {
      const double x0 = motion.frames.front().pose.pelvis.x - 2.0;
      const double x1 = motion.frames.back().pose.pelvis.x + 2.0;
      io::write_terrain_csv(out, ground, x0, x1);
    });
    io::write_file(o->prefix + ".bvh",
                   [&motion](std::ostream& out) { io::write_bvh(out, motion); });
    if (o->gltf) io::write_gltf(o->prefix + ".glb", motion, ground);
    std::cout << "walked " << motion.frames.size() << " frames (" << motion.frames.back().time
              << " s) with controller set '" << set.name << "'\n";
    std::vector<std::string> written = {o->prefix + ".csv", o->prefix + ".terrain.csv",
                                        o->prefix + ".bvh"};
    if (o->gltf) written.push_back(o->prefix + ".glb");
    try {
      const eval::GaitReport report = eval::evaluate(motion, ground, &reference, o->step);
      std::cout << "against " << reference.name << ":\n" << eval::to_text(report);
      warn_about_contact(report);
      plot::plot_gait_curves(report, &reference, {.title = "fuzzygait walk, " + set.name})
          .save(o->prefix + ".svg");
      written.push_back(o->prefix + ".svg");
    } catch (const std::invalid_argument& e) {
      std::cout << "not measured, no curves: " << e.what() << "\n";
    }
    try {
      const svg::Figure animation = plot::plot_walk_animation(motion, ground);
      const svg::Figure filmstrip = plot::plot_filmstrip(motion, ground);
      io::write_file(o->prefix + ".poses.svg", svg::stack_figures({&animation, &filmstrip}));
      written.push_back(o->prefix + ".poses.svg");
    } catch (const std::invalid_argument& e) {
      std::cout << "no poses: " << e.what() << "\n";
    }
    std::cout << "wrote";
    for (const std::string& f : written)
      std::cout << " " << f;
    std::cout << "\n";
  });
}

}  // namespace fuzzygait::cli

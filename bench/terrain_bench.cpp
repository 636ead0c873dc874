// `fuzzygait-bench terrain`: what a lone walker's time step costs on ramps and stairs, as a ratio
// to level ground, measured in one run with the grounds timed in turn.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/terrain/terrain.hpp"
#include "timing.hpp"

namespace fuzzygait::bench {
namespace {

struct Options {
  std::string style = "default";
  int repetitions = 7;
  double lead_in = 2.0;  // s walked before timing: the ramps and stairs begin 1 m ahead
  double window = 8.0;   // s walked while timed, all on the ramp or the stairs
};

struct Ground {
  std::string name;
  terrain::Terrain terrain;
};

// Wall nanoseconds a time step over `o.window` simulated seconds in frames of 1/60 s, on a fresh
// walker after o.lead_in seconds.
double ns_per_step(const gait::ControllerSet& set, const terrain::Terrain& ground,
                   const Options& o) {
  const gait::WalkerOptions options;
  gait::Walker walker(set, options, ground);
  constexpr double kFrame = 1.0 / 60.0;
  while (walker.time() < o.lead_in)
    walker.advance(kFrame);
  const double start = walker.time();
  const double seconds = wall_seconds([&] {
    while (walker.time() < start + o.window)
      walker.advance(kFrame);
  });
  return 1e9 * seconds * options.time_step / (walker.time() - start);
}

void run_terrain_benchmark(const Options& o) {
  const gait::ControllerSet set = gait::ControllerSet::builtin(o.style);
  const std::vector<Ground> grounds = {
      {"level", terrain::Terrain::flat()},
      {"ramp +10 deg", terrain::Terrain::ramp(10.0)},
      {"ramp -10 deg", terrain::Terrain::ramp(-10.0)},
      {"stairs 0.17 x 0.28 up", terrain::Terrain::stairs(0.17, 0.28, 80)},
      {"stairs 0.17 x 0.28 down", terrain::Terrain::stairs(-0.17, 0.28, 80)},
  };
  std::printf(
      "fuzzygait-bench terrain: controller set '%s', a lone walker, frames of 1/60 s; median of "
      "%d repetitions of %.1f s walked after %.1f s, the grounds in turn (the first one moved "
      "each repetition)\n",
      set.name.c_str(), o.repetitions, o.window, o.lead_in);
  std::vector<std::vector<double>> ns(grounds.size());
  for (int r = 0; r < o.repetitions; ++r) {
    for (std::size_t k = 0; k < grounds.size(); ++k) {
      const std::size_t g = (k + static_cast<std::size_t>(r)) % grounds.size();
      ns[g].push_back(ns_per_step(set, grounds[g].terrain, o));
    }
  }
  const double level = median(ns[0]);
  for (std::size_t g = 0; g < grounds.size(); ++g) {
    const double m = median(ns[g]);
    std::printf("%-24s %8.1f ns per step  %5.2fx level\n", grounds[g].name.c_str(), m, m / level);
  }
}

}  // namespace

void add_terrain_command(CLI::App& app) {
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "terrain", "A lone walker's time step on ramps and stairs, as a ratio to level ground");
  add_walk_options(*command, options->style, options->repetitions, options->window);
  command->callback([options]() { run_terrain_benchmark(*options); });
}

}  // namespace fuzzygait::bench

// The fuzzygait-bench program's subcommands, one file each.
#pragma once

#include <CLI/CLI.hpp>

namespace fuzzygait::bench {

// `fuzzygait-bench fuzzy`: fuzzygait's Evaluator against fuzzylite on fuzzylite's examples.
void add_fuzzy_command(CLI::App& app);
// `fuzzygait-bench gait`: character-steps per second, against fuzzylite in the walker's loop.
void add_gait_command(CLI::App& app);
// `fuzzygait-bench crowd`: crowds of 100 to 1,000,000 characters on 1, 2 and all threads.
void add_crowd_command(CLI::App& app);
// `fuzzygait-bench terrain`: a walker's time step on ramps and stairs against level ground.
void add_terrain_command(CLI::App& app);
void add_body_command(CLI::App& app);

}  // namespace fuzzygait::bench

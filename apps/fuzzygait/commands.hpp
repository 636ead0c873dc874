// The fuzzygait program's subcommands, one file each.
#pragma once

#include <CLI/CLI.hpp>

namespace fuzzygait::cli {

void add_fuzzy_command(CLI::App& app);
// `fuzzy plot`, a subcommand of `fuzzy` (fuzzy_plot_command.cpp).
void add_fuzzy_plot_command(CLI::App& fuzzy);
void add_tune_command(CLI::App& app);
void add_walk_command(CLI::App& app);
void add_eval_command(CLI::App& app);

}  // namespace fuzzygait::cli

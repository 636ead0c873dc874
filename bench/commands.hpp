// The fuzzygait-bench program's subcommands, one file each.
#pragma once

#include <CLI/CLI.hpp>

namespace fuzzygait::bench {

// `fuzzygait-bench fuzzy`: fuzzygait's Evaluator against fuzzylite on fuzzylite's examples.
void add_fuzzy_command(CLI::App& app);

}  // namespace fuzzygait::bench

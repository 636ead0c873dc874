// The fuzzygait program's subcommands, one file each.
#pragma once

#include <CLI/CLI.hpp>

namespace fuzzygait::cli {

void add_fuzzy_command(CLI::App& app);

}  // namespace fuzzygait::cli

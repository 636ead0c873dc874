// The fuzzygait program's subcommands, one file each.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace fuzzygait::cli {

// The file at `path` for reading; throws std::runtime_error naming it when it cannot be opened.
inline std::ifstream open_or_throw(const std::string& path) {
  // A directory opens as a stream that reads nothing.
  if (std::filesystem::is_directory(path)) {
    throw std::runtime_error(path + ": is a directory, not a file");
  }
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the file");
  return in;
}

// Where a command writes PREFIX.csv, PREFIX.bvh ...: a prefix naming a folder would write hidden
// files (".csv") into it, so it is refused, naming the option.
inline void check_output_prefix(const std::string& prefix, const std::string& option) {
  const std::filesystem::path path(prefix);
  if (prefix.empty() || !path.has_filename() || std::filesystem::is_directory(path)) {
    throw std::invalid_argument(option + ": '" + prefix +
                                "' names a folder, not a file prefix (for example '" +
                                (path / "walk").string() + "')");
  }
}

void add_fuzzy_command(CLI::App& app);
// `fuzzy plot`, a subcommand of `fuzzy` (fuzzy_plot_command.cpp).
void add_fuzzy_plot_command(CLI::App& fuzzy);
void add_tune_command(CLI::App& app);
void add_tune_terrain_command(CLI::App& app);
void add_walk_command(CLI::App& app);
void add_eval_command(CLI::App& app);
void add_mocap_command(CLI::App& app);
// `fuzzygait studio` (studio_command.cpp), in builds with the studio (FUZZYGAIT_STUDIO).
void add_studio_command(CLI::App& app);
void add_train_command(CLI::App& app);

}  // namespace fuzzygait::cli

// The options that say how to read a motion capture clip (--map, --up, --unit, --skip), shared by
// `fuzzygait mocap` and `fuzzygait train`.
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <optional>
#include <string>

#include "fuzzygait/io/mocap.hpp"

namespace fuzzygait::cli {

struct ClipFlags {
  std::string map;
  std::string up;
  std::optional<double> unit;
  std::optional<std::size_t> skip;
};

// Adds --map, --up, --unit and --skip to `command`, read into `flags`.
void add_clip_options(CLI::App* command, ClipFlags& flags);

// The reader's options from the flags; throws std::invalid_argument naming the option for an up
// axis other than y or z or a unit outside (0, 1000], and the mapping file's errors.
io::ClipOptions clip_options(const ClipFlags& flags);

}  // namespace fuzzygait::cli

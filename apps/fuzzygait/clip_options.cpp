#include "clip_options.hpp"

#include <stdexcept>

#include "runtime/common/format.hpp"

namespace fuzzygait::cli {

void add_clip_options(CLI::App* command, ClipFlags& flags) {
  command->add_option("--map", flags.map,
                      "JSON file naming the root and each leg's hip, knee, ankle and toe joints "
                      "(default: CMU and common names)");
  command->add_option("--up", flags.up, "Up axis, y or z (default: detected)");
  command->add_option("--unit", flags.unit,
                      "Metres per BVH unit (default: guessed from leg length)");
  command->add_option("--skip", flags.skip,
                      "Leading frames to drop (default: a calibration first frame)");
}

io::ClipOptions clip_options(const ClipFlags& flags) {
  if (!flags.up.empty() && flags.up != "y" && flags.up != "z") {
    throw std::invalid_argument("--up must be y or z, got '" + flags.up + "'");
  }
  if (flags.unit && !(*flags.unit > 0.0 && *flags.unit <= 1000.0)) {
    throw std::invalid_argument("--unit must be metres per unit, above 0 and at most 1000, got " +
                                common::number_text(*flags.unit));
  }
  io::ClipOptions options;
  if (!flags.map.empty()) options.mapping = io::read_leg_mapping_file(flags.map);
  if (!flags.up.empty()) options.up = flags.up == "y" ? io::UpAxis::Y : io::UpAxis::Z;
  options.metres_per_unit = flags.unit;
  options.skip = flags.skip;
  return options;
}

}  // namespace fuzzygait::cli

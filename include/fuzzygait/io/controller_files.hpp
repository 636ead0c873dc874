// Writing a controller set back to files: manifest.json and one FLL file per controller, the
// layout ControllerSet::load reads.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "fuzzygait/gait/controllers.hpp"

namespace fuzzygait::io {

// One file of a saved set: its name in the set's folder and its text.
struct SetFile {
  std::string name;
  std::string text;
};
// The files save_controller_set writes, manifest.json last.
std::vector<SetFile> controller_set_files(const gait::ControllerSet& set);
void save_controller_set(const gait::ControllerSet& set, const std::filesystem::path& directory);

}  // namespace fuzzygait::io

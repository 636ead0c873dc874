// Writing a controller set back to files: manifest.json and one FLL file per controller, the
// layout ControllerSet::load reads.
#pragma once

#include <filesystem>

#include "fuzzygait/gait/controllers.hpp"

namespace fuzzygait::io {

void save_controller_set(const gait::ControllerSet& set, const std::filesystem::path& directory);

}  // namespace fuzzygait::io

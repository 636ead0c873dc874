// The controller sets of controllers/, compiled into the library (cmake/EmbedFiles.cmake), so
// that the program walks without finding files.
#pragma once

#include <string_view>
#include <vector>

namespace fuzzygait::gait::detail {

struct EmbeddedFile {
  std::string_view path;  // "<set>/<file>", relative to controllers/
  std::string_view text;
};

const std::vector<EmbeddedFile>& embedded_files();

}  // namespace fuzzygait::gait::detail

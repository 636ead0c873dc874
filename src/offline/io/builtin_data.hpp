// The reference data of data/, compiled into the library (cmake/EmbedFiles.cmake).
#pragma once

#include <string_view>
#include <vector>

namespace fuzzygait::io::detail {

struct EmbeddedFile {
  std::string_view path;  // relative to data/
  std::string_view text;
};

const std::vector<EmbeddedFile>& embedded_files();

}  // namespace fuzzygait::io::detail

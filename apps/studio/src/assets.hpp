// The page's files, compiled into the program at build time (cmake/EmbedFiles.cmake): studio/'s
// own and the npm packages' files it imports.
#pragma once

#include <string_view>
#include <vector>

namespace fuzzygait::studio::detail {

struct EmbeddedFile {
  std::string_view path;  // relative to studio/, or to node_modules/ for a package's file
  std::string_view text;
};

namespace page {
const std::vector<EmbeddedFile>& embedded_files();
}
namespace vendor {
const std::vector<EmbeddedFile>& embedded_files();
}

struct Asset {
  std::string_view text;
  std::string_view content_type;
};

// The file served at `url_path` ("/" and "/index.html" the page, "/src/main.js", "/vendor/three/
// build/three.module.js"), or null.
const Asset* find_asset(std::string_view url_path);

}  // namespace fuzzygait::studio::detail

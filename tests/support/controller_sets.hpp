// The controller sets shipped in controllers/, as the tests expect the library to list them.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace fuzzygait::test {

inline std::filesystem::path controllers_dir() {
  return std::filesystem::path(FUZZYGAIT_SOURCE_DIR) / "controllers";
}

// The folders of controllers/ that hold a manifest.json, by name, sorted.
inline std::vector<std::string> shipped_set_names() {
  std::vector<std::string> names;
  for (const std::filesystem::directory_entry& e :
       std::filesystem::directory_iterator(controllers_dir())) {
    if (std::filesystem::exists(e.path() / "manifest.json")) {
      names.push_back(e.path().filename().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace fuzzygait::test

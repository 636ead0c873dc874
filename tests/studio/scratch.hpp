// An empty folder of the studio's tests' own: TEMP/fuzzygait_studio/SUITE/NAME, emptied first.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace fuzzygait::test {

inline std::filesystem::path studio_scratch(const std::string& suite, const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "fuzzygait_studio" / suite / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace fuzzygait::test

// What the fuzz targets share: reporting a broken contract so that libFuzzer keeps the input.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

namespace fuzzygait::fuzz {

// Prints the broken contract and aborts: libFuzzer saves the input as a crash.
[[noreturn]] inline void fail(const std::string& what, const std::string& detail = {}) {
  std::fprintf(stderr, "\n== fuzz contract broken: %s\n%s\n", what.c_str(), detail.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace fuzzygait::fuzz

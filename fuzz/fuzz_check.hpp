// What the fuzz targets share: reporting a broken contract so that libFuzzer keeps the input.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>

namespace fuzzygait::fuzz {

// Prints the broken contract and aborts: libFuzzer saves the input as a crash.
[[noreturn]] inline void fail(const std::string& what, const std::string& detail = {}) {
  std::fprintf(stderr, "\n== fuzz contract broken: %s\n%s\n", what.c_str(), detail.c_str());
  std::fflush(stderr);
  std::abort();
}

// A reader's error (a ParseError) must start with the name of the source it was given.
inline void check_names_source(const std::exception& error, std::string_view source) {
  if (std::string_view(error.what()).substr(0, source.size()) != source) {
    fail("a ParseError does not name the source", error.what());
  }
}

}  // namespace fuzzygait::fuzz

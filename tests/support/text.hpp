// Small text helpers of the tests that read files and drawings.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "fuzzygait/plot/svg.hpp"

namespace fuzzygait::test {

// How many times `what` occurs in `text`, overlapping occurrences included.
inline std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

// The file's bytes; empty when it cannot be read (the caller's comparison then fails).
inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Writes a drawing to the folder FUZZYGAIT_SVG_OUT names, when it is set, to look at. SVG text
// is written as it is, a write that fails is ignored; a figure is saved with Figure::save, which
// throws when it cannot write the file.
inline void keep(const std::string& svg, const std::string& name) {
  if (const char* folder = std::getenv("FUZZYGAIT_SVG_OUT")) {
    std::ofstream(std::filesystem::path(folder) / name) << svg;
  }
}
inline void keep(const plot::svg::Figure& figure, const std::string& name) {
  if (const char* folder = std::getenv("FUZZYGAIT_SVG_OUT")) {
    figure.save(std::filesystem::path(folder) / name);
  }
}

}  // namespace fuzzygait::test

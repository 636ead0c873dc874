// What the tests of real importers share (tests/io/bvh_import_test.cpp, gltf_import_test.cpp):
// running a tool through the shell, reading the CSV its script writes (the columns of
// tests/js/bvh_angles.mjs: per frame the sagittal angles in degrees and the joints' world
// positions), and the largest differences between that and the walk.
#pragma once

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/rig/rig.hpp"

namespace fuzzygait::test {

// `text` in single quotes for the shell.
inline std::string quote(const std::string& text) {
  std::string q = "'";
  for (char c : text)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Runs a shell command; its exit status, or -1 when it did not exit normally.
inline int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A CSV of numbers with a header row.
struct Table {
  std::map<std::string, std::size_t> columns;
  std::vector<std::vector<double>> rows;
  double at(std::size_t row, const std::string& column) const {
    const auto it = columns.find(column);
    if (it == columns.end()) throw std::runtime_error("the importer wrote no column " + column);
    return rows.at(row).at(it->second);
  }
};

inline Table read_table(const std::filesystem::path& path) {
  std::ifstream in(path);
  Table table;
  std::string line;
  std::getline(in, line);
  std::istringstream header(line);
  for (std::string name; std::getline(header, name, ',');) {
    table.columns.emplace(name, table.columns.size());
  }
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::istringstream cells(line);
    std::vector<double> row;
    for (std::string cell; std::getline(cells, cell, ',');)
      row.push_back(std::stod(cell));
    table.rows.push_back(std::move(row));
  }
  return table;
}

// The largest difference of each kind, and where it is.
struct Worst {
  double error = 0.0;
  std::string what;
  void note(double e, const std::string& column, std::size_t frame) {
    if (!(e <= error)) *this = {e, column + " at frame " + std::to_string(frame)};
  }
};
struct ImportDifferences {
  Worst time;      // seconds
  Worst angle;     // degrees
  Worst position;  // metres
};

// Compares what an importer saw, row by row, with `walk` (as its CSV holds it): the time, the
// pelvis and the legs' angles, the pelvis and the legs' joints in the file's axes (X left, Y up,
// Z forward; the hips `half_width` apart), positions in `units_per_metre`. The caller checks the
// number of rows first.
inline ImportDifferences compare_with_walk(const Table& seen, const eval::Motion& walk,
                                           double half_width, double units_per_metre) {
  ImportDifferences worst;
  const char* sides[] = {"l", "r"};
  for (std::size_t f = 0; f < walk.frames.size() && f < seen.rows.size(); ++f) {
    const eval::Frame& frame = walk.frames[f];
    const double tilt = rig::degrees(frame.pose.pelvis_tilt);
    const auto angle_is = [&](const std::string& column, double expected) {
      worst.angle.note(std::abs(std::remainder(seen.at(f, column) - expected, 360.0)), column, f);
    };
    const auto position_is = [&](const std::string& column, double expected_metres) {
      worst.position.note(std::abs(seen.at(f, column) / units_per_metre - expected_metres), column,
                          f);
    };
    worst.time.note(std::abs(seen.at(f, "time") - frame.time), "time", f);
    angle_is("pelvis_tilt", tilt);
    position_is("pelvis_x", 0.0);
    position_is("pelvis_y", frame.pose.pelvis.y);
    position_is("pelvis_z", frame.pose.pelvis.x);
    for (std::size_t leg = 0; leg < 2; ++leg) {
      const std::string s = sides[leg];
      const rig::LegAngles& a = frame.pose.legs[leg];
      angle_is(s + "_thigh", rig::degrees(a.hip) - tilt);
      angle_is(s + "_hip", rig::degrees(a.hip));
      angle_is(s + "_knee", rig::degrees(a.knee));
      angle_is(s + "_ankle", rig::degrees(a.ankle));
      angle_is(s + "_toe", rig::degrees(a.toe));
      const rig::LegPoints& p = frame.points[leg];
      const std::pair<const char*, rig::Point> joints[] = {
          {"hip", p.hip}, {"knee", p.knee}, {"ankle", p.ankle}, {"ball", p.ball}, {"tip", p.tip}};
      for (const auto& [joint, point] : joints) {
        const std::string column = s + "_" + joint;
        position_is(column + "_x", leg == 0 ? half_width : -half_width);  // left is +X
        position_is(column + "_y", point.y);
        position_is(column + "_z", point.x);  // forward is +Z
      }
    }
  }
  return worst;
}

}  // namespace fuzzygait::test

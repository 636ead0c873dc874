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

// What an importer's script saw of a file: its table, or why it was skipped or failed.
struct ImportRun {
  std::string skipped;  // the importer is not there
  std::string failed;   // it ran and failed, or complained: its output
  Table table;
};

// Runs `node SCRIPT INPUT` from `js` (the folder the threejs_npm_ci fixture installs three.js
// into), writing NAME.csv and NAME.err beside INPUT. `node` is the program CMake found (empty:
// none).
inline ImportRun import_with_threejs(const std::string& node, const std::filesystem::path& js,
                                     const std::string& script, const std::filesystem::path& input,
                                     const std::string& name = "threejs") {
  ImportRun seen;
  if (node.empty()) {
    seen.skipped =
        "node was not found when CMake configured: install Node.js and npm "
        "(scripts/install-deps.sh) and re-run cmake";
    return seen;
  }
  if (!std::filesystem::exists(js / "node_modules" / "three" / "package.json")) {
    seen.skipped = "three.js is not installed in " + js.string() +
                   "/node_modules: the fixture test threejs_npm_ci could not run npm ci "
                   "(offline? see its output: ctest -R threejs_npm_ci -V)";
    return seen;
  }
  const std::filesystem::path out = input.parent_path() / (name + ".csv");
  const std::filesystem::path errors = input.parent_path() / (name + ".err");
  const int status =
      run(quote(node) + " " + quote((js / script).string()) + " " + quote(input.string()) + " > " +
          quote(out.string()) + " 2> " + quote(errors.string()));
  std::ifstream complaints(errors);
  std::ostringstream text;
  text << complaints.rdbuf();
  if (status != 0 || !text.str().empty()) {
    seen.failed = "node " + script + " exited with " + std::to_string(status) + ":\n" + text.str();
    return seen;
  }
  seen.table = read_table(out);
  return seen;
}

// Runs `blender -b --python SCRIPT -- INPUT NAME.csv` (SCRIPT a path), its log in NAME.log beside
// INPUT. `blender` is the program CMake found (empty: none).
inline ImportRun import_with_blender(const std::string& blender,
                                     const std::filesystem::path& script,
                                     const std::filesystem::path& input,
                                     const std::string& name = "blender") {
  ImportRun seen;
  if (blender.empty()) {
    seen.skipped =
        "blender is not installed (optional check; Debian: apt-get install blender, "
        "then re-run cmake)";
    return seen;
  }
  const std::filesystem::path out = input.parent_path() / (name + ".csv");
  const std::filesystem::path log = input.parent_path() / (name + ".log");
  const int status = run(quote(blender) + " -b --factory-startup --python-exit-code 1 --python " +
                         quote(script.string()) + " -- " + quote(input.string()) + " " +
                         quote(out.string()) + " > " + quote(log.string()) + " 2>&1");
  if (status != 0) {
    std::ifstream in(log);
    std::ostringstream text;
    text << in.rdbuf();
    seen.failed = "Blender exited with " + std::to_string(status) + ":\n" + text.str();
    return seen;
  }
  seen.table = read_table(out);
  return seen;
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

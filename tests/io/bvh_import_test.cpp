// Our BVH files read back by real importers: three.js's BVHLoader under Node
// (tests/js/bvh_angles.mjs) and, when it is installed, Blender's own importer
// (tests/blender/bvh_angles.py). Each prints per frame the sagittal angles and the joint positions
// it sees; they must match the walk's CSV (write_walk_csv) to 0.01 degrees and 0.1 mm. A test
// skips, saying why, when its importer is not there. The files stay in the build tree
// (FUZZYGAIT_BVH_IMPORT_DIR, one folder per test) for a look.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/io/bvh.hpp"
#include "fuzzygait/io/walk_csv.hpp"
#include "fuzzygait/terrain/terrain.hpp"
#include "support/text.hpp"

namespace {

namespace fs = std::filesystem;
using fuzzygait::eval::Motion;
using fuzzygait::rig::degrees;
using fuzzygait::test::read_text;

constexpr double kAngleTolerance = 0.01;     // degrees
constexpr double kPositionTolerance = 1e-4;  // metres
constexpr double kUnitsPerMetre = 100.0;     // the BVH's centimetres

// The walk, its BVH and its CSV, written once per test process. CTest runs the importers' tests
// in parallel processes, so each writes into its own folder, named after the test: sharing one
// file let one process truncate the BVH while another's importer was reading it.
struct Walk {
  Motion motion;    // as recorded
  Motion from_csv;  // as the walk CSV holds it (degrees to 4 decimals, metres to 6)
  fs::path bvh;
};

const Walk& walk() {
  static const Walk w = [] {
    const auto controllers = fuzzygait::gait::ControllerSet::builtin("default");
    const auto ground = fuzzygait::terrain::Terrain::flat();
    fuzzygait::gait::Walker walker(controllers, fuzzygait::gait::WalkerOptions{}, ground);
    Walk made;
    made.motion = fuzzygait::eval::record(walker, 10.0, 120.0);
    const fs::path dir = fs::path(FUZZYGAIT_BVH_IMPORT_DIR) /
                         ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::create_directories(dir);
    made.bvh = dir / "walk.bvh";
    const fs::path csv = dir / "walk.csv";
    {
      std::ofstream out(made.bvh, std::ios::binary);
      fuzzygait::io::write_bvh(out, made.motion);
      std::ofstream table(csv, std::ios::binary);
      fuzzygait::io::write_walk_csv(table, made.motion);
    }
    std::ifstream in(csv, std::ios::binary);
    made.from_csv = fuzzygait::io::read_walk_csv(in, csv.string());
    return made;
  }();
  return w;
}

std::string quote(const std::string& text) {
  std::string q = "'";
  for (char c : text)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Runs a shell command; its exit status, or -1 when it did not exit normally.
int run(const std::string& command) {
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

Table read_table(const fs::path& path) {
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

// Compares what an importer saw with the walk's CSV, frame by frame, and prints the largest
// differences.
void expect_matches_walk(const Table& seen, const std::string& importer) {
  const Walk& w = walk();
  const Motion& m = w.from_csv;
  ASSERT_EQ(seen.rows.size(), m.frames.size()) << importer << " read another number of frames";
  const double half_width = 0.5 * fuzzygait::io::bvh_hip_width(w.motion.segments);
  struct Worst {
    double error = 0.0;
    std::string what;
  };
  Worst angle;
  Worst position;
  const auto note = [](Worst& worst, double error, const std::string& what, std::size_t frame) {
    if (!(error <= worst.error)) worst = {error, what + " at frame " + std::to_string(frame)};
  };
  const char* sides[] = {"l", "r"};
  for (std::size_t f = 0; f < m.frames.size(); ++f) {
    const fuzzygait::eval::Frame& frame = m.frames[f];
    const double tilt = degrees(frame.pose.pelvis_tilt);
    const auto angle_is = [&](const std::string& column, double expected) {
      note(angle, std::abs(std::remainder(seen.at(f, column) - expected, 360.0)), column, f);
    };
    const auto position_is = [&](const std::string& column, double expected_metres) {
      note(position, std::abs(seen.at(f, column) / kUnitsPerMetre - expected_metres), column, f);
    };
    EXPECT_NEAR(seen.at(f, "time"), frame.time, 1e-4) << importer << " frame " << f;
    angle_is("pelvis_tilt", tilt);
    position_is("pelvis_x", 0.0);
    position_is("pelvis_y", frame.pose.pelvis.y);
    position_is("pelvis_z", frame.pose.pelvis.x);
    for (std::size_t leg = 0; leg < 2; ++leg) {
      const std::string s = sides[leg];
      const fuzzygait::rig::LegAngles& a = frame.pose.legs[leg];
      angle_is(s + "_thigh", degrees(a.hip) - tilt);
      angle_is(s + "_hip", degrees(a.hip));
      angle_is(s + "_knee", degrees(a.knee));
      angle_is(s + "_ankle", degrees(a.ankle));
      angle_is(s + "_toe", degrees(a.toe));
      const fuzzygait::rig::LegPoints& p = frame.points[leg];
      const std::pair<const char*, fuzzygait::rig::Point> joints[] = {
          {"hip", p.hip}, {"knee", p.knee}, {"ankle", p.ankle}, {"ball", p.ball}, {"tip", p.tip}};
      for (const auto& [joint, point] : joints) {
        const std::string column = s + "_" + joint;
        position_is(column + "_x", leg == 0 ? half_width : -half_width);  // left is +X
        position_is(column + "_y", point.y);
        position_is(column + "_z", point.x);  // forward is +Z
      }
    }
  }
  std::cout << importer << ": " << seen.rows.size() << " frames; largest difference from the walk"
            << " CSV: " << angle.error << " deg (" << angle.what << "), " << position.error * 1e3
            << " mm (" << position.what << ")\n";
  ::testing::Test::RecordProperty("max_angle_difference_deg",
                                  (std::ostringstream() << angle.error).str());
  ::testing::Test::RecordProperty("max_position_difference_m",
                                  (std::ostringstream() << position.error).str());
  EXPECT_LE(angle.error, kAngleTolerance) << importer << ": " << angle.what;
  EXPECT_LE(position.error, kPositionTolerance) << importer << ": " << position.what;
}

TEST(BvhImport, ThreeJsBvhLoaderSeesTheWalksAngles) {
  const std::string node = FUZZYGAIT_NODE;
  if (node.empty()) {
    GTEST_SKIP() << "node was not found when CMake configured: install Node.js and npm "
                    "(scripts/install-deps.sh) and re-run cmake";
  }
  const fs::path js = FUZZYGAIT_THREEJS_DIR;
  if (!fs::exists(js / "node_modules" / "three" / "package.json")) {
    GTEST_SKIP() << "three.js is not installed in " << js.string()
                 << "/node_modules: the fixture test threejs_npm_ci could not run npm ci (offline?"
                    " see its output: ctest -R threejs_npm_ci -V)";
  }
  const fs::path out = walk().bvh.parent_path() / "threejs.csv";
  const fs::path errors = walk().bvh.parent_path() / "threejs.err";
  const int status = run(quote(node) + " " + quote((js / "bvh_angles.mjs").string()) + " " +
                         quote(walk().bvh.string()) + " > " + quote(out.string()) + " 2> " +
                         quote(errors.string()));
  ASSERT_EQ(status, 0) << "node bvh_angles.mjs failed:\n" << read_text(errors);
  EXPECT_EQ(read_text(errors), "") << "three.js complained";
  expect_matches_walk(read_table(out), "three.js BVHLoader");
}

TEST(BvhImport, BlenderImporterSeesTheWalksAngles) {
  const std::string blender = FUZZYGAIT_BLENDER;
  if (blender.empty()) {
    GTEST_SKIP() << "blender is not installed (optional check; Debian: apt-get install blender, "
                    "then re-run cmake)";
  }
  const fs::path out = walk().bvh.parent_path() / "blender.csv";
  const fs::path log = walk().bvh.parent_path() / "blender.log";
  const std::string script = std::string(FUZZYGAIT_SOURCE_DIR) + "/tests/blender/bvh_angles.py";
  const int status = run(quote(blender) + " -b --factory-startup --python-exit-code 1 --python " +
                         quote(script) + " -- " + quote(walk().bvh.string()) + " " +
                         quote(out.string()) + " > " + quote(log.string()) + " 2>&1");
  ASSERT_EQ(status, 0) << "Blender failed:\n" << read_text(log);
  expect_matches_walk(read_table(out), "Blender's BVH importer");
}

}  // namespace

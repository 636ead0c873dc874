// Our BVH files read back by real importers: three.js's BVHLoader under Node
// (tests/js/bvh_angles.mjs) and, when it is installed, Blender's own importer
// (tests/blender/bvh_angles.py). Each prints per frame the sagittal angles and the joint positions
// it sees; they must match the walk's CSV (write_walk_csv) to 0.01 degrees and 0.1 mm. A test
// skips, saying why, when its importer is not there. The files stay in the build tree
// (FUZZYGAIT_BVH_IMPORT_DIR, one folder per test) for a look.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/io/bvh.hpp"
#include "fuzzygait/io/walk_csv.hpp"
#include "fuzzygait/terrain/terrain.hpp"
#include "support/import_check.hpp"

namespace {

namespace fs = std::filesystem;
using fuzzygait::eval::Motion;
using fuzzygait::test::import_with_blender;
using fuzzygait::test::import_with_threejs;
using fuzzygait::test::ImportRun;
using fuzzygait::test::Table;

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

// Compares what an importer saw with the walk's CSV, frame by frame, and prints the largest
// differences.
void expect_matches_walk(const Table& seen, const std::string& importer) {
  const Walk& w = walk();
  const Motion& m = w.from_csv;
  ASSERT_EQ(seen.rows.size(), m.frames.size()) << importer << " read another number of frames";
  const double half_width = 0.5 * fuzzygait::io::bvh_hip_width(w.motion.segments);
  const fuzzygait::test::ImportDifferences worst =
      fuzzygait::test::compare_with_walk(seen, m, half_width, kUnitsPerMetre);
  const auto& [time, angle, position] = worst;
  std::cout << importer << ": " << seen.rows.size() << " frames; largest difference from the walk"
            << " CSV: " << angle.error << " deg (" << angle.what << "), " << position.error * 1e3
            << " mm (" << position.what << ")\n";
  ::testing::Test::RecordProperty("max_angle_difference_deg",
                                  (std::ostringstream() << angle.error).str());
  ::testing::Test::RecordProperty("max_position_difference_m",
                                  (std::ostringstream() << position.error).str());
  EXPECT_LE(time.error, 1e-4) << importer << ": " << time.what;
  EXPECT_LE(angle.error, kAngleTolerance) << importer << ": " << angle.what;
  EXPECT_LE(position.error, kPositionTolerance) << importer << ": " << position.what;
}

TEST(BvhImport, ThreeJsBvhLoaderSeesTheWalksAngles) {
  const ImportRun seen =
      import_with_threejs(FUZZYGAIT_NODE, FUZZYGAIT_THREEJS_DIR, "bvh_angles.mjs", walk().bvh);
  if (!seen.skipped.empty()) GTEST_SKIP() << seen.skipped;
  ASSERT_EQ(seen.failed, "");
  expect_matches_walk(seen.table, "three.js BVHLoader");
}

TEST(BvhImport, BlenderImporterSeesTheWalksAngles) {
  const ImportRun seen = import_with_blender(
      FUZZYGAIT_BLENDER, fs::path(FUZZYGAIT_SOURCE_DIR) / "tests/blender/bvh_angles.py",
      walk().bvh);
  if (!seen.skipped.empty()) GTEST_SKIP() << seen.skipped;
  ASSERT_EQ(seen.failed, "");
  expect_matches_walk(seen.table, "Blender's BVH importer");
}

}  // namespace

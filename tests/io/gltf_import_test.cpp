// Our glTF files checked by the tools people open them with: the Khronos glTF-Validator
// (tests/js/gltf_validate.mjs) must find no error and no warning; three.js's GLTFLoader under
// Node (tests/js/gltf_angles.mjs) and, when it is installed, Blender's glTF importer
// (tests/blender/gltf_import.py) must play the walk with the CSV's angles to 0.01 degrees and
// joints to 0.1 mm, and skin the body so that its lowest point is the walk's lowest sole point
// and its highest the top of the head. The walk is the program's own: `fuzzygait walk --gltf`
// with its defaults (stature 1.75 m, flat ground), which also writes the CSV compared against;
// the validator also reads a walk onto a ramp and steps. A test skips, saying why, when its tool
// is not there. The files stay in the build tree (FUZZYGAIT_GLTF_IMPORT_DIR, a folder per test)
// for a look.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/io/bvh.hpp"
#include "fuzzygait/io/gltf.hpp"
#include "fuzzygait/io/walk_csv.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "support/import_check.hpp"
#include "support/text.hpp"
#include "support/walks.hpp"

namespace {

namespace fs = std::filesystem;
using fuzzygait::eval::Motion;
using fuzzygait::test::quote;
using fuzzygait::test::read_table;
using fuzzygait::test::read_text;
using fuzzygait::test::run;
using fuzzygait::test::Table;

constexpr double kAngleTolerance = 0.01;     // degrees
constexpr double kPositionTolerance = 1e-4;  // metres
// The body's lowest point against the walk's lowest heel, ball or toe tip: the feet's capsules
// reach the soles' points where they lie flat, and round off the heel's corner.
constexpr double kSoleTolerance = 0.005;  // metres
constexpr double kStature = 1.75;         // `fuzzygait walk`'s default
constexpr int kFps = 120;                 // `fuzzygait walk`'s default

// The program's walk, written once per test process into a folder named after the test: CTest
// runs the tests in parallel processes, which must not share files.
struct Walk {
  fs::path dir;
  fs::path glb;
  Motion motion;  // as its CSV holds it
};

const Walk& walk() {
  static const Walk w = [] {
    Walk made;
    made.dir = fs::path(FUZZYGAIT_GLTF_IMPORT_DIR) /
               ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::create_directories(made.dir);
    const fs::path prefix = made.dir / "walk";
    const fs::path log = made.dir / "walk.log";
    const int status = run(quote(FUZZYGAIT_CLI) + " walk --gltf -o " + quote(prefix.string()) +
                           " > " + quote(log.string()) + " 2>&1");
    if (status != 0) throw std::runtime_error("fuzzygait walk --gltf failed:\n" + read_text(log));
    made.glb = prefix.string() + ".glb";
    std::ifstream csv(prefix.string() + ".csv", std::ios::binary);
    made.motion = fuzzygait::io::read_walk_csv(csv, prefix.string() + ".csv");
    return made;
  }();
  return w;
}

// Why a Node test cannot run, or "" when it can.
std::string node_missing() {
  if (std::string(FUZZYGAIT_NODE).empty()) {
    return "node was not found when CMake configured: install Node.js and npm "
           "(scripts/install-deps.sh) and re-run cmake";
  }
  const fs::path js = FUZZYGAIT_THREEJS_DIR;
  for (const char* package : {"three", "gltf-validator"}) {
    if (!fs::exists(js / "node_modules" / package / "package.json")) {
      return std::string(package) + " is not installed in " + js.string() +
             "/node_modules: the fixture test threejs_npm_ci could not run npm ci (offline? see "
             "its output: ctest -R threejs_npm_ci -V)";
    }
  }
  return "";
}

// Compares what a player saw with the walk's CSV, frame by frame, prints the largest
// differences and records them as test properties.
void expect_plays_the_walk(const Table& seen, const std::string& player) {
  const Motion& m = walk().motion;
  ASSERT_EQ(seen.rows.size(), m.frames.size()) << player << " read another number of frames";
  const fuzzygait::rig::Segments segments = fuzzygait::rig::segments_from_stature(kStature);
  const double half_width = 0.5 * fuzzygait::io::bvh_hip_width(segments);
  const auto [time, angle, position] = fuzzygait::test::compare_with_walk(seen, m, half_width, 1.0);

  fuzzygait::test::Worst lowest;
  fuzzygait::test::Worst highest;
  for (std::size_t f = 0; f < m.frames.size(); ++f) {
    double sole = m.frames[f].points[0].heel.y;
    for (const fuzzygait::rig::LegPoints& p : m.frames[f].points)
      sole = std::min({sole, p.heel.y, p.ball.y, p.tip.y});
    lowest.note(std::abs(seen.at(f, "body_lowest_y") - sole), "body_lowest_y", f);
    highest.note(std::abs(seen.at(f, "body_highest_y") - seen.at(f, "head_top_y")),
                 "body_highest_y", f);
  }
  std::cout << player << ": " << seen.rows.size() << " frames; largest difference from the walk"
            << " CSV: " << angle.error << " deg (" << angle.what << "), " << position.error * 1e3
            << " mm (" << position.what << "); body's lowest point to the soles' "
            << lowest.error * 1e3 << " mm, highest to the head's top " << highest.error * 1e3
            << " mm\n";
  ::testing::Test::RecordProperty("max_angle_difference_deg",
                                  (std::ostringstream() << angle.error).str());
  ::testing::Test::RecordProperty("max_position_difference_m",
                                  (std::ostringstream() << position.error).str());
  EXPECT_LE(time.error, 1e-4) << player << ": " << time.what;
  EXPECT_LE(angle.error, kAngleTolerance) << player << ": " << angle.what;
  EXPECT_LE(position.error, kPositionTolerance) << player << ": " << position.what;
  EXPECT_LE(lowest.error, kSoleTolerance) << player << ": " << lowest.what;
  EXPECT_LE(highest.error, kPositionTolerance) << player << ": " << highest.what;
}

TEST(GltfImport, KhronosValidatorFindsNoErrorOrWarning) {
  if (const std::string missing = node_missing(); !missing.empty()) GTEST_SKIP() << missing;
  // A second walk, in process, onto a ramp and two steps: slopes and risers in the ground.
  const fuzzygait::terrain::Terrain hills = fuzzygait::terrain::Terrain::polyline({{0.5, 0.0},
                                                                                   {2.0, 0.15},
                                                                                   {2.6, 0.15},
                                                                                   {2.601, 0.32},
                                                                                   {2.9, 0.32},
                                                                                   {2.901, 0.49},
                                                                                   {4.0, 0.49}});
  fuzzygait::gait::Walker walker = fuzzygait::test::make_walker(hills);
  const Motion climb = fuzzygait::eval::record(walker, 4.0, 60.0);
  const fs::path hills_glb = walk().dir / "hills.glb";
  fuzzygait::io::write_gltf(hills_glb, climb, hills);

  const fs::path report = walk().dir / "validator.json";
  const fs::path summary = walk().dir / "validator.txt";
  const fs::path script = fs::path(FUZZYGAIT_THREEJS_DIR) / "gltf_validate.mjs";
  const int status = run(quote(FUZZYGAIT_NODE) + " " + quote(script.string()) + " " +
                         quote(walk().glb.string()) + " " + quote(hills_glb.string()) + " > " +
                         quote(report.string()) + " 2> " + quote(summary.string()));
  std::cout << read_text(summary);
  const std::string text = read_text(summary);
  ::testing::Test::RecordProperty("validator_summary", text.substr(0, text.find('\n')));
  EXPECT_EQ(status, 0) << "the validator found errors or warnings, or failed:\n" << text;
  EXPECT_NE(text.find("walk.glb: glTF-Validator"), std::string::npos) << text;
  EXPECT_NE(text.find("hills.glb: glTF-Validator"), std::string::npos) << text;
  EXPECT_EQ(fuzzygait::test::count(text, ": 0 errors, 0 warnings,"), 2u) << text;
}

TEST(GltfImport, ThreeJsGltfLoaderPlaysTheWalksAngles) {
  if (const std::string missing = node_missing(); !missing.empty()) GTEST_SKIP() << missing;
  const fs::path out = walk().dir / "threejs.csv";
  const fs::path errors = walk().dir / "threejs.err";
  const fs::path script = fs::path(FUZZYGAIT_THREEJS_DIR) / "gltf_angles.mjs";
  const int status =
      run(quote(FUZZYGAIT_NODE) + " " + quote(script.string()) + " " + quote(walk().glb.string()) +
          " > " + quote(out.string()) + " 2> " + quote(errors.string()));
  ASSERT_EQ(status, 0) << "node gltf_angles.mjs failed:\n" << read_text(errors);
  EXPECT_EQ(read_text(errors), "") << "three.js complained";
  expect_plays_the_walk(read_table(out), "three.js GLTFLoader");
}

TEST(GltfImport, BlenderImporterMakesTheArmatureActionAndMeshesAndPlaysTheWalk) {
  const std::string blender = FUZZYGAIT_BLENDER;
  if (blender.empty()) {
    GTEST_SKIP() << "blender is not installed (optional check; Debian: apt-get install blender "
                    "python3-numpy, then re-run cmake)";
  }
  const fs::path out = walk().dir / "blender.csv";
  const fs::path log = walk().dir / "blender.log";
  const std::string script = std::string(FUZZYGAIT_SOURCE_DIR) + "/tests/blender/gltf_import.py";
  const int status =
      run(quote(blender) + " -b --factory-startup --python-exit-code 1 --python " + quote(script) +
          " -- " + quote(walk().glb.string()) + " " + quote(out.string()) + " " +
          std::to_string(kFps) + " > " + quote(log.string()) + " 2>&1");
  if (status == 3) {
    GTEST_SKIP() << "Blender's glTF importer needs numpy, which its Python lacks (Debian: apt-get "
                    "install python3-numpy)";
  }
  ASSERT_EQ(status, 0) << "Blender failed:\n" << read_text(log);
  const std::string text = read_text(log);
  const std::size_t imported = text.find("imported: ");
  if (imported != std::string::npos) {
    std::cout << text.substr(imported, text.find('\n', imported) - imported) << "\n";
  }
  expect_plays_the_walk(read_table(out), "Blender's glTF importer");
}

}  // namespace

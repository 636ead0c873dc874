// A posed skeleton's glTF (io::write_skeleton_gltf) checked by the tools people open it with: the
// Khronos glTF-Validator (tests/js/gltf_validate.mjs) must find no error and no warning; three.js's
// GLTFLoader under Node (tests/js/gltf_positions.mjs) and Blender's glTF importer
// (tests/blender/gltf_positions.py) must play "Walk" with every joint where the skeleton's forward
// kinematics puts it, to 0.1 mm. Two files: the program's own, `fuzzygait walk --path --gltf`'s
// PREFIX.body.glb (the stature's skeleton along a corner), against its PREFIX.body.bvh of the same
// frames read back; and a Mixamo-named rig in centimetres facing -Z with a rest rotation on every
// bone (':' in its names, which three.js renames), against the skeleton's forward kinematics. A
// test skips, saying why, when its tool is not there. The files stay in the build tree
// (FUZZYGAIT_SKELETON_GLTF_DIR, a folder per test) for a look.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "body/skeleton_fixtures.hpp"
#include "fuzzygait/body/humanoid_map.hpp"
#include "fuzzygait/body/skeleton_poser.hpp"
#include "fuzzygait/io/mocap.hpp"
#include "fuzzygait/io/skeleton_file.hpp"
#include "support/import_check.hpp"
#include "support/text.hpp"

namespace {

namespace fs = std::filesystem;
using fuzzygait::body::Quat;
using fuzzygait::body::Vec3;
using fuzzygait::test::ImportRun;
using fuzzygait::test::quote;
using fuzzygait::test::read_text;
using fuzzygait::test::run;
using fuzzygait::test::Table;

constexpr double kPositionTolerance = 1e-4;  // metres
constexpr int kFps = 30;

// A file and where its joints should be: per frame, per joint (by name), metres, glTF's axes.
struct Expected {
  fs::path glb;
  std::vector<std::string> names;
  std::vector<std::vector<Vec3>> positions;
};

fs::path test_dir() {
  const fs::path dir = fs::path(FUZZYGAIT_SKELETON_GLTF_DIR) /
                       ::testing::UnitTest::GetInstance()->current_test_info()->name();
  fs::create_directories(dir);
  return dir;
}

// `fuzzygait walk --path --gltf` along a corner, 2 s at 30 fps; the expected positions are its
// PREFIX.body.bvh's, read back and played by forward kinematics.
const Expected& program_walk() {
  static const Expected e = [] {
    Expected made;
    const fs::path dir = test_dir();
    const fs::path route = dir / "corner.csv";
    std::ofstream(route) << "x,z\n0,0\n0,2\n2,2\n";
    const fs::path prefix = dir / "walk";
    const fs::path log = dir / "walk.log";
    const int status = run(quote(FUZZYGAIT_CLI) + " walk --path " + quote(route.string()) +
                           " --gltf --fps " + std::to_string(kFps) + " --duration 2 -o " +
                           quote(prefix.string()) + " > " + quote(log.string()) + " 2>&1");
    if (status != 0) throw std::runtime_error("fuzzygait walk --gltf failed:\n" + read_text(log));
    made.glb = prefix.string() + ".body.glb";
    const fuzzygait::io::BvhClip clip = fuzzygait::io::read_bvh_file(prefix.string() + ".body.bvh");
    const fuzzygait::body::Skeleton skeleton = fuzzygait::io::skeleton_from_bvh(clip);
    for (const fuzzygait::body::SkeletonJoint& joint : skeleton.joints)
      made.names.push_back(joint.name);
    std::vector<Quat> local(skeleton.size());
    std::vector<Quat> world(skeleton.size());
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
      Vec3 root;
      fuzzygait::io::bvh_frame(clip, f, local, root);
      made.positions.emplace_back(skeleton.size());
      fuzzygait::body::forward_kinematics(skeleton, local, root, made.positions.back(), world);
      for (Vec3& p : made.positions.back())
        p = skeleton.metres_per_unit * p;
    }
    return made;
  }();
  return e;
}

// The Mixamo rig in centimetres walking 24 frames; the expected positions are its forward
// kinematics, in metres.
const Expected& mixamo_rig() {
  static const Expected e = [] {
    Expected made;
    const fuzzygait::body::Skeleton skeleton = fuzzygait::body::testing::build_skeleton(
        fuzzygait::body::testing::mixamo_joints(),
        fuzzygait::body::axis_angle({0, 1, 0}, std::numbers::pi), 0.01, 53);
    const fuzzygait::body::SkeletonPoser poser(skeleton, fuzzygait::body::map_humanoid(skeleton));
    const std::size_t n = skeleton.size();
    constexpr std::size_t kFrames = 24;
    std::vector<Quat> rotations(n * kFrames);
    std::vector<Vec3> roots(kFrames);
    std::vector<Quat> world(n);
    for (std::size_t f = 0; f < kFrames; ++f) {
      const fuzzygait::body::BodyPose pose = fuzzygait::body::testing::walking_pose(
          poser.humanoid(), 0.3 * static_cast<double>(f), 0.1 * static_cast<double>(f),
          static_cast<std::uint32_t>(f + 1));
      const std::span<Quat> local = std::span<Quat>(rotations).subspan(f * n, n);
      poser.pose(pose, local, roots[f]);
      made.positions.emplace_back(n);
      fuzzygait::body::forward_kinematics(skeleton, local, roots[f], made.positions.back(), world);
      for (Vec3& p : made.positions.back())
        p = skeleton.metres_per_unit * p;
    }
    for (const fuzzygait::body::SkeletonJoint& joint : skeleton.joints)
      made.names.push_back(joint.name);
    made.glb = test_dir() / "mixamo_cm.glb";
    fuzzygait::io::write_skeleton_gltf(made.glb, skeleton, rotations, roots,
                                       {.frame_time = 1.0 / kFps});
    return made;
  }();
  return e;
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

void expect_plays(const ImportRun& seen, const Expected& e, const std::string& what) {
  ASSERT_EQ(seen.failed, "") << what;
  const Table& table = seen.table;
  ASSERT_EQ(table.rows.size(), e.positions.size()) << what << " read another number of frames";
  fuzzygait::test::Worst worst;
  for (std::size_t f = 0; f < table.rows.size(); ++f) {
    EXPECT_NEAR(table.at(f, "time"), static_cast<double>(f) / kFps, 1e-6) << what;
    for (std::size_t j = 0; j < e.names.size(); ++j) {
      const Vec3 p = e.positions[f][j];
      const std::string& name = e.names[j];
      worst.note(std::abs(table.at(f, name + "_x") - p.x), name + "_x", f);
      worst.note(std::abs(table.at(f, name + "_y") - p.y), name + "_y", f);
      worst.note(std::abs(table.at(f, name + "_z") - p.z), name + "_z", f);
    }
  }
  std::cout << what << ": " << table.rows.size() << " frames of " << e.names.size()
            << " joints; largest difference " << worst.error * 1e3 << " mm (" << worst.what << "); "
            << fs::file_size(e.glb) << " bytes\n";
  ::testing::Test::RecordProperty("max_position_difference_m",
                                  (std::ostringstream() << worst.error).str());
  EXPECT_LE(worst.error, kPositionTolerance) << what << ": " << worst.what;
}

TEST(SkeletonGltfImport, KhronosValidatorFindsNoErrorOrWarning) {
  if (const std::string missing = node_missing(); !missing.empty()) GTEST_SKIP() << missing;
  const fs::path report = test_dir() / "validator.json";
  const fs::path summary = test_dir() / "validator.txt";
  const fs::path script = fs::path(FUZZYGAIT_THREEJS_DIR) / "gltf_validate.mjs";
  const int status =
      run(quote(FUZZYGAIT_NODE) + " " + quote(script.string()) + " " +
          quote(program_walk().glb.string()) + " " + quote(mixamo_rig().glb.string()) + " > " +
          quote(report.string()) + " 2> " + quote(summary.string()));
  const std::string text = read_text(summary);
  std::cout << text;
  ::testing::Test::RecordProperty("validator_summary", text.substr(0, text.find('\n')));
  EXPECT_EQ(status, 0) << "the validator found errors or warnings, or failed:\n" << text;
  EXPECT_NE(text.find("walk.body.glb: glTF-Validator"), std::string::npos) << text;
  EXPECT_NE(text.find("mixamo_cm.glb: glTF-Validator"), std::string::npos) << text;
  EXPECT_EQ(fuzzygait::test::count(text, ": 0 errors, 0 warnings,"), 2u) << text;
}

TEST(SkeletonGltfImport, ThreeJsPlaysTheProgramsWalkAsItsBvh) {
  if (const std::string missing = node_missing(); !missing.empty()) GTEST_SKIP() << missing;
  const ImportRun seen = fuzzygait::test::import_with_threejs(
      FUZZYGAIT_NODE, FUZZYGAIT_THREEJS_DIR, "gltf_positions.mjs", program_walk().glb);
  if (!seen.skipped.empty()) GTEST_SKIP() << seen.skipped;
  expect_plays(seen, program_walk(), "three.js GLTFLoader, walk.body.glb");
}

TEST(SkeletonGltfImport, ThreeJsPlaysTheMixamoRig) {
  if (const std::string missing = node_missing(); !missing.empty()) GTEST_SKIP() << missing;
  const ImportRun seen = fuzzygait::test::import_with_threejs(
      FUZZYGAIT_NODE, FUZZYGAIT_THREEJS_DIR, "gltf_positions.mjs", mixamo_rig().glb);
  if (!seen.skipped.empty()) GTEST_SKIP() << seen.skipped;
  expect_plays(seen, mixamo_rig(), "three.js GLTFLoader, mixamo_cm.glb");
}

ImportRun import_with_blender(const fs::path& glb) {
  ImportRun seen = fuzzygait::test::import_with_blender(
      FUZZYGAIT_BLENDER, fs::path(FUZZYGAIT_SOURCE_DIR) / "tests/blender/gltf_positions.py", glb);
  if (seen.failed.find("exited with 3:") != std::string::npos) {
    seen.skipped =
        "Blender's glTF importer needs numpy, which its Python lacks (Debian: apt-get install "
        "python3-numpy)";
  }
  return seen;
}

TEST(SkeletonGltfImport, BlenderPlaysTheProgramsWalkAsItsBvh) {
  const ImportRun seen = import_with_blender(program_walk().glb);
  if (!seen.skipped.empty()) GTEST_SKIP() << seen.skipped;
  expect_plays(seen, program_walk(), "Blender's glTF importer, walk.body.glb");
}

TEST(SkeletonGltfImport, BlenderPlaysTheMixamoRig) {
  const ImportRun seen = import_with_blender(mixamo_rig().glb);
  if (!seen.skipped.empty()) GTEST_SKIP() << seen.skipped;
  expect_plays(seen, mixamo_rig(), "Blender's glTF importer, mixamo_cm.glb");
}

}  // namespace

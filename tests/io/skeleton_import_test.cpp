// A posed skeleton's BVH (io::write_skeleton_bvh) read back by real importers: three.js's
// BVHLoader under Node (tests/js/bvh_positions.mjs) and Blender's importer
// (tests/blender/bvh_positions.py). Each prints every joint's world position per frame; they must
// match the skeleton's forward kinematics to 0.1 mm. The rig is the VRM-named one in centimetres,
// facing -Z, with a rest rotation on every bone (which BVH cannot hold: the channels carry it) and
// ZXY channels. A test skips, saying why, when its importer is not there. The files stay in the
// build tree (FUZZYGAIT_BVH_IMPORT_DIR/skeleton_<test>) for a look.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "body/skeleton_fixtures.hpp"
#include "fuzzygait/io/skeleton_file.hpp"
#include "support/import_check.hpp"

namespace {

namespace fs = std::filesystem;
using fuzzygait::body::Quat;
using fuzzygait::body::Vec3;
using fuzzygait::test::import_with_blender;
using fuzzygait::test::import_with_threejs;
using fuzzygait::test::ImportRun;
using fuzzygait::test::Table;

constexpr double kPositionTolerance = 0.01;  // centimetres: 0.1 mm
constexpr int kFrames = 24;

struct Written {
  fuzzygait::body::Skeleton skeleton;
  std::vector<std::vector<Vec3>> positions;  // per frame, per joint, centimetres
  fs::path bvh;
};

// The rig walking a few frames, written once per test process into the test's own folder.
const Written& written() {
  static const Written w = [] {
    Written made;
    made.skeleton = fuzzygait::body::testing::build_skeleton(
        fuzzygait::body::testing::vrm_joints(),
        fuzzygait::body::axis_angle({0, 1, 0}, std::numbers::pi), 0.01, 77);
    const fuzzygait::body::SkeletonPoser poser(made.skeleton,
                                               fuzzygait::body::map_humanoid(made.skeleton));
    const std::size_t n = made.skeleton.size();
    std::vector<Quat> rotations(n * kFrames);
    std::vector<Vec3> roots(kFrames);
    std::vector<Quat> world(n);
    for (int f = 0; f < kFrames; ++f) {
      const auto frame = static_cast<std::size_t>(f);
      const fuzzygait::body::BodyPose pose =
          fuzzygait::body::testing::walking_pose(poser.humanoid(), 0.3 * f, 0.1 * f, 0);
      const std::span<Quat> local = std::span<Quat>(rotations).subspan(frame * n, n);
      poser.pose(pose, local, roots[frame]);
      made.positions.emplace_back(n);
      fuzzygait::body::forward_kinematics(made.skeleton, local, roots[frame], made.positions.back(),
                                          world);
    }
    const fs::path dir =
        fs::path(FUZZYGAIT_BVH_IMPORT_DIR) /
        ("skeleton_" +
         std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir);
    made.bvh = dir / "vrm_rig.bvh";
    std::ofstream out(made.bvh, std::ios::binary);
    fuzzygait::io::write_skeleton_bvh(out, made.skeleton, rotations, roots);
    return made;
  }();
  return w;
}

void expect_matches_skeleton(const Table& seen, const std::string& importer) {
  const Written& w = written();
  ASSERT_EQ(seen.rows.size(), w.positions.size()) << importer << " read another number of frames";
  double worst = 0.0;
  std::string where;
  for (std::size_t f = 0; f < seen.rows.size(); ++f) {
    for (std::size_t j = 0; j < w.skeleton.size(); ++j) {
      const std::string& name = w.skeleton.joints[j].name;
      const Vec3 p = w.positions[f][j];
      const double d[3] = {seen.at(f, name + "_x") - p.x, seen.at(f, name + "_y") - p.y,
                           seen.at(f, name + "_z") - p.z};
      for (const double e : d) {
        if (!(std::abs(e) <= worst)) {
          worst = std::abs(e);
          where = name + " at frame " + std::to_string(f);
        }
      }
    }
  }
  std::cout << importer << ": " << seen.rows.size() << " frames of " << w.skeleton.size()
            << " joints; largest difference " << worst * 10 << " mm (" << where << ")\n";
  EXPECT_LE(worst, kPositionTolerance) << importer << ": " << where;
}

TEST(BvhSkeletonImport, ThreeJsBvhLoaderPlacesEveryJoint) {
  const ImportRun seen = import_with_threejs(FUZZYGAIT_NODE, FUZZYGAIT_THREEJS_DIR,
                                             "bvh_positions.mjs", written().bvh);
  if (!seen.skipped.empty()) GTEST_SKIP() << seen.skipped;
  ASSERT_EQ(seen.failed, "");
  expect_matches_skeleton(seen.table, "three.js BVHLoader");
}

TEST(BvhSkeletonImport, BlenderImporterPlacesEveryJoint) {
  const ImportRun seen = import_with_blender(
      FUZZYGAIT_BLENDER, fs::path(FUZZYGAIT_SOURCE_DIR) / "tests/blender/bvh_positions.py",
      written().bvh);
  if (!seen.skipped.empty()) GTEST_SKIP() << seen.skipped;
  ASSERT_EQ(seen.failed, "");
  expect_matches_skeleton(seen.table, "Blender's BVH importer");
}

}  // namespace

// The same walk on three skeletons (the yardstick): the walker walks with each skeleton's
// own legs (humanoid_from_skeleton), a PathFollower bends the walk round a corner, and a
// SkeletonPoser poses the skeleton every frame. The posed skeleton's mapped joints stay where the
// BodyPose has them and its feet stay on the ground.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "body/skeleton_fixtures.hpp"
#include "fuzzygait/body/follower.hpp"
#include "fuzzygait/body/skeleton_poser.hpp"
#include "fuzzygait/io/skeleton_file.hpp"

namespace fuzzygait::body {
namespace {

struct Rig {
  std::string label;
  Skeleton skeleton;
  double tolerance;  // m: how far the posed joints may lie from the BodyPose's
};

TEST(BodySkeletonWalk, SameWalkOnThreeSkeletonsKeepsTheFeetOnTheGround) {
  const std::vector<Rig> rigs = {
      {"CMU 07",
       io::read_bvh_skeleton(std::filesystem::path(FUZZYGAIT_SOURCE_DIR) /
                             "data/mocap/cmu/07_01.bvh"),
       0.02},  // its sides differ by 13 mm in the thigh; its clavicles are not mapped
      {"Mixamo",
       testing::build_skeleton(testing::mixamo_joints(), axis_angle({0, 1, 0}, std::numbers::pi),
                               0.01, 7),
       1e-6},
      {"VRM", testing::build_skeleton(testing::vrm_joints(), Quat{}, 1.0, 11), 1e-6},
  };
  const gait::ControllerSet controllers = gait::ControllerSet::builtin("default");
  const terrain::Terrain ground = terrain::Terrain::flat();
  const std::vector<path::GroundPoint> corners = {{0.0, 0.0}, {0.0, 4.5}, {5.5, 4.5}};
  const path::Path route = path::Path::polyline(corners, 1.5);
  for (const Rig& rig : rigs) {
    const HumanoidMap map = map_humanoid(rig.skeleton);
    const SkeletonPoser poser(rig.skeleton, map);
    gait::WalkerOptions options;
    options.segments = poser.humanoid().segments();
    options.speed = 1.2;
    gait::Walker walker(controllers, options, ground);
    PathFollower follower(poser.humanoid(), route, walker);
    std::vector<Quat> local(poser.joint_count()), world(poser.joint_count());
    std::vector<Vec3> at(poser.joint_count());
    double worst = 0.0, lowest = 1.0;
    int frames = 0;
    for (; frames < 600 && walker.pose().pelvis.x < route.length(); ++frames) {
      walker.advance(1.0 / 60.0);
      const BodyPose& pose = follower.update(walker);
      Vec3 root;
      ASSERT_TRUE(poser.pose(pose, local, root));
      forward_kinematics(rig.skeleton, local, root, at, world);
      for (Vec3& p : at)
        p = rig.skeleton.metres_per_unit * p;
      for (std::size_t i = 1; i < kJointCount; ++i) {
        const int s = map.joint[i];
        if (s >= 0)
          worst = std::max(worst, length(at[static_cast<std::size_t>(s)] - pose.position[i]));
      }
      for (const rig::Side side : rig::kSides) {
        for (const Joint j : {foot(side), toes(side), toes_end(side)}) {
          if (map[j] >= 0) lowest = std::min(lowest, at[static_cast<std::size_t>(map[j])].y);
        }
      }
    }
    std::cout << rig.label << ": " << frames << " frames round the corner; mapped joints at most "
              << worst * 1000 << " mm from the BodyPose; lowest toe base or toe end "
              << lowest * 1000 << " mm above the ground\n";
    EXPECT_LT(worst, rig.tolerance) << rig.label;
    EXPECT_GT(lowest, -0.005) << rig.label;  // no penetration beyond 5 mm
  }
}

}  // namespace
}  // namespace fuzzygait::body

// A character following a path its game AI planned: the walker walks the distance along the path,
// a PathFollower bends the walk onto the path and poses the whole body in the world, feet locked
// while planted. Each frame the game reads every joint's world position and rotation (or its
// rotation relative to its parent, to pose its own skeleton).
#include <fuzzygait/body/follower.hpp>

#include <cstdio>
#include <vector>

int main() {
  using namespace fuzzygait;
  const gait::ControllerSet controllers = gait::ControllerSet::builtin("default");
  const terrain::Terrain ground = terrain::Terrain::flat();  // the ground along the path
  // 3 m ahead, then left round a corner rounded at 1.5 m, then 4 m on.
  const std::vector<path::GroundPoint> corners = {{0.0, 0.0}, {0.0, 4.5}, {5.5, 4.5}};
  const path::Path route = path::Path::polyline(corners, 1.5);

  const body::Humanoid body = body::humanoid_from_stature(1.80);  // or a game skeleton's
  gait::WalkerOptions options;
  options.segments = body.segments();  // the walker's legs are the body's
  options.speed = 1.2;
  gait::Walker walker(controllers, options, ground);
  body::PathFollower follower(body, route, walker);

  const double dt = 1.0 / 60.0;
  for (int frame = 0; frame < 600 && walker.pose().pelvis.x < route.length(); ++frame) {
    walker.advance(dt);
    const body::BodyPose& pose = follower.update(walker);  // no allocation
    if (frame % 60 == 0) {
      const body::Vec3 hips = pose[body::Joint::hips];
      const body::Vec3 left_foot = pose[body::Joint::left_foot];
      std::printf("t=%5.2f s  hips (%5.2f, %4.2f, %5.2f)  left ankle (%5.2f, %4.2f, %5.2f)  %s\n",
                  walker.time(), hips.x, hips.y, hips.z, left_foot.x, left_foot.y, left_foot.z,
                  walker.in_contact(rig::Side::Left) ? "left foot planted" : "left foot swinging");
    }
  }
  const path::PathSample end = route.at(route.length());
  std::printf("path end (%.2f, %.2f): %s after %.2f m\n", end.point.x, end.point.z,
              walker.pose().pelvis.x >= route.length() ? "reached" : "not reached",
              walker.pose().pelvis.x);
  return 0;
}

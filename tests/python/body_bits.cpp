// The whole body the Python tests compare with, bit for bit: the default set's walker (a 1.80 m
// body at 1.2 m/s) following the S (0,0) (0,3) (3,3) (3,6) with corners rounded at 1 m, FRAMES
// frames of 1/60 s. Each line is a frame: the 26 joints' world positions (x, y, z) then their
// rotations (w, x, y, z), then the pelvis drop, as C99 hexadecimal floats (%a).
//   python_body_bits FRAMES
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <vector>

#include "fuzzygait/body/follower.hpp"

int main(int argc, char** argv) {
  using namespace fuzzygait;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s FRAMES\n", argv[0]);
    return 2;
  }
  try {
    const gait::ControllerSet set = gait::ControllerSet::builtin("default");
    const terrain::Terrain ground = terrain::Terrain::flat();
    const std::vector<path::GroundPoint> corners = {{0, 0}, {0, 3}, {3, 3}, {3, 6}};
    const path::Path route = path::Path::polyline(corners, 1.0);
    const body::Humanoid humanoid = body::humanoid_from_stature(1.80);
    gait::WalkerOptions options;
    options.segments = humanoid.segments();
    options.speed = 1.2;
    gait::Walker walker(set, options, ground);
    body::PathFollower follower(humanoid, route, walker);
    const long frames = std::strtol(argv[1], nullptr, 10);
    for (long i = 0; i < frames; ++i) {
      walker.advance(1.0 / 60.0);
      const body::BodyPose& pose = follower.update(walker);
      for (const body::Vec3& p : pose.position)
        std::printf("%a %a %a ", p.x, p.y, p.z);
      for (const body::Quat& q : pose.rotation)
        std::printf("%a %a %a %a ", q.w, q.x, q.y, q.z);
      std::printf("%a\n", follower.pelvis_drop());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}

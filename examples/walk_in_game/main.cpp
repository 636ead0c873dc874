// A game loop driving one fuzzygait character: build the rig and the walker once, then every
// frame change the speed if the player asks, advance by the frame's dt, and read the pose and the
// feet's contact state to pose the character's skeleton.
#include <fuzzygait/gait/walker.hpp>

#include <cstdio>

int main() {
  using namespace fuzzygait;
  // Loaded once: the built-in default controller set (or ControllerSet::load("my_style/")).
  const gait::ControllerSet controllers = gait::ControllerSet::builtin("default");
  const terrain::Terrain ground = terrain::Terrain::flat();

  gait::WalkerOptions options;
  options.segments = rig::segments_from_stature(1.80);  // or set each segment length
  options.speed = 1.2;  // m/s; each step the one people take at that speed (the set's stride)
  gait::Walker walker(controllers, options, ground);

  const double dt = 1.0 / 60.0;  // the game's frame time
  for (int frame = 0; frame < 600; ++frame) {
    if (frame == 300) walker.set_speed(1.8);  // the player hurries: faster, longer steps
    walker.advance(dt);                       // no allocation, no file access

    const rig::Pose pose = walker.pose();  // pelvis position and tilt, joint angles (radians)
    const rig::LegPoints left = walker.points(rig::Side::Left);
    if (frame % 60 == 0) {
      std::printf(
          "t=%5.2f s %4.2f m/s, steps %4.2f m  pelvis x=%6.3f y=%5.3f  left hip %6.1f knee %5.1f "
          "deg  heel y=%6.3f  %s\n",
          walker.time(), walker.state().speed, walker.step_length(), pose.pelvis.x, pose.pelvis.y,
          rig::degrees(pose.legs[0].hip), rig::degrees(pose.legs[0].knee), left.heel.y,
          walker.in_contact(rig::Side::Left) ? "left foot planted" : "left foot swinging");
    }
  }
  return 0;
}

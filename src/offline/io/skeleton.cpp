#include "offline/io/skeleton.hpp"

#include <cstddef>
#include <utility>

namespace fuzzygait::io::detail {
namespace {

Joint joint(std::string name, Vec3 offset, Drive drive, std::vector<Joint> children = {},
            int leg = 0) {
  return {std::move(name), offset, drive, leg, std::move(children), std::nullopt};
}

Joint leg_chain(const rig::Segments& s, rig::Side side, double half_width) {
  const int leg = rig::index(side);
  const std::string prefix = side == rig::Side::Left ? "Left" : "Right";
  const double lateral = side == rig::Side::Left ? half_width : -half_width;  // left is +X
  Joint toes = joint(prefix + "ToeBase", {0.0, -s.ankle_height, s.ball}, Drive::Toe, {}, leg);
  toes.end_site = Vec3{0.0, 0.0, s.toe};
  Joint foot = joint(prefix + "Foot", {0.0, -s.shank, 0.0}, Drive::Ankle, {toes}, leg);
  Joint shank = joint(prefix + "Leg", {0.0, -s.thigh, 0.0}, Drive::Knee, {foot}, leg);
  return joint(prefix + "UpLeg", {lateral, 0.0, 0.0}, Drive::Hip, {shank}, leg);
}

}  // namespace

Joint skeleton(const rig::Segments& s, double hip_width) {
  const double stature = stature_of(s);
  const auto up = [stature](double share) { return Vec3{0.0, share * stature, 0.0}; };
  Joint head = joint("Head", up(kChinHeight - kShoulderHeight), Drive::Still);
  head.end_site = up(1.0 - kChinHeight);
  Joint neck =
      joint("Neck", up(kShoulderHeight - kHipHeight - kSpineAboveHips), Drive::Still, {head});
  Joint spine = joint("Spine", up(kSpineAboveHips), Drive::UprightTrunk, {neck});
  const double half_width = 0.5 * hip_width;
  return joint("Hips", {}, Drive::PelvisTilt,
               {leg_chain(s, rig::Side::Left, half_width),
                leg_chain(s, rig::Side::Right, half_width), spine});
}

double x_rotation(const Joint& joint, const rig::Pose& pose) {
  const rig::LegAngles& a = pose.legs[static_cast<std::size_t>(joint.leg)];
  switch (joint.drive) {
    case Drive::PelvisTilt:
      return pose.pelvis_tilt;
    case Drive::Hip:
      return -a.hip;
    case Drive::Knee:
      return a.knee;
    case Drive::Ankle:
      return -a.ankle;
    case Drive::Toe:
      return -a.toe;
    case Drive::UprightTrunk:
      return -pose.pelvis_tilt;
    case Drive::Still:
      break;
  }
  return 0.0;
}

}  // namespace fuzzygait::io::detail

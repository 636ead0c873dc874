#include "fuzzygait/io/bvh.hpp"

#include <charconv>
#include <cmath>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace fuzzygait::io {
namespace {

// Stature proportions (Winter 2009, Fig. 4.1) for the static trunk.
constexpr double kHipHeight = 0.530;
constexpr double kSpineAboveHips = 0.100;
constexpr double kShoulderHeight = 0.818;
constexpr double kChinHeight = 0.870;

struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

// Which angle of a frame a joint's Xrotation comes from.
enum class Drive { PelvisTilt, Hip, Knee, Ankle, Toe, UprightTrunk, Still };

struct Joint {
  std::string name;
  Vec3 offset;  // metres, in the parent's frame
  Drive drive = Drive::Still;
  int leg = 0;
  std::vector<Joint> children;
  std::optional<Vec3> end_site;
};

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

Joint skeleton(const rig::Segments& s, const BvhOptions& options) {
  const double stature = s.leg_length() / kHipHeight;
  const auto up = [stature](double share) { return Vec3{0.0, share * stature, 0.0}; };
  Joint head = joint("Head", up(kChinHeight - kShoulderHeight), Drive::Still);
  head.end_site = up(1.0 - kChinHeight);
  Joint neck =
      joint("Neck", up(kShoulderHeight - kHipHeight - kSpineAboveHips), Drive::Still, {head});
  Joint spine = joint("Spine", up(kSpineAboveHips), Drive::UprightTrunk, {neck});
  const double half_width = 0.5 * bvh_hip_width(s, options);
  return joint("Hips", {}, Drive::PelvisTilt,
               {leg_chain(s, rig::Side::Left, half_width),
                leg_chain(s, rig::Side::Right, half_width), spine});
}

// Xrotation in radians: minus the joint's counter-clockwise angle in the (forward, up) plane,
// the sense in which the rig's inclinations and pitches add up (rig::orientation).
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

// Fixed decimals, independent of the C locale, and never "-0.000000".
void append(std::string& line, double value, int decimals = 6) {
  char buffer[64];
  const auto [end, error] =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals);
  if (error != std::errc()) throw std::invalid_argument("BVH: value out of range");
  std::string_view text(buffer, static_cast<std::size_t>(end - buffer));
  if (text.starts_with('-') && text.find_first_not_of("-0.") == std::string_view::npos) {
    text.remove_prefix(1);
  }
  if (!line.empty()) line += ' ';
  line += text;
}

std::string vector_text(const Vec3& v, double scale) {
  std::string text;
  append(text, v.x * scale);
  append(text, v.y * scale);
  append(text, v.z * scale);
  return text;
}

void write_joint(std::ostream& out, const Joint& joint, int depth, double scale) {
  const std::string indent(static_cast<std::size_t>(depth) * 2, ' ');
  out << indent << (depth == 0 ? "ROOT " : "JOINT ") << joint.name << "\n" << indent << "{\n";
  out << indent << "  OFFSET " << vector_text(joint.offset, scale) << "\n";
  out << indent << "  CHANNELS " << (depth == 0 ? "6 Xposition Yposition Zposition " : "3 ")
      << "Zrotation Yrotation Xrotation\n";
  for (const Joint& child : joint.children) {
    write_joint(out, child, depth + 1, scale);
  }
  if (joint.end_site) {
    out << indent << "  End Site\n" << indent << "  {\n";
    out << indent << "    OFFSET " << vector_text(*joint.end_site, scale) << "\n";
    out << indent << "  }\n";
  }
  out << indent << "}\n";
}

void append_rotations(std::string& line, const Joint& joint, const rig::Pose& pose) {
  append(line, 0.0);  // Z
  append(line, 0.0);  // Y
  append(line, rig::degrees(x_rotation(joint, pose)));
  for (const Joint& child : joint.children) {
    append_rotations(line, child, pose);
  }
}

void check_frame(const eval::Frame& frame, std::size_t number) {
  const rig::Pose& p = frame.pose;
  bool finite =
      std::isfinite(p.pelvis.x) && std::isfinite(p.pelvis.y) && std::isfinite(p.pelvis_tilt);
  for (const rig::LegAngles& a : p.legs) {
    finite = finite && std::isfinite(a.hip) && std::isfinite(a.knee) && std::isfinite(a.ankle) &&
             std::isfinite(a.toe);
  }
  if (!finite) {
    throw std::invalid_argument("BVH: frame " + std::to_string(number) +
                                " has a pose value that is not a finite number");
  }
}

}  // namespace

double bvh_hip_width(const rig::Segments& segments, const BvhOptions& options) {
  return options.hip_width_per_leg_length * segments.leg_length();
}

void write_bvh(std::ostream& out, const eval::Motion& motion, const BvhOptions& options) {
  if (!std::isfinite(options.units_per_metre) || options.units_per_metre < 1e-3 ||
      options.units_per_metre > 1e6) {
    throw std::invalid_argument("BVH: units_per_metre must be between 0.001 and 1e6");
  }
  if (!std::isfinite(options.hip_width_per_leg_length) || options.hip_width_per_leg_length < 0.0 ||
      options.hip_width_per_leg_length > 1.0) {
    throw std::invalid_argument("BVH: hip_width_per_leg_length must be between 0 and 1");
  }
  if (!std::isfinite(motion.fps) || motion.fps <= 0.0) {
    throw std::invalid_argument("BVH: the motion's fps must be a positive number");
  }
  if (motion.frames.empty()) throw std::invalid_argument("BVH: the motion has no frames");
  rig::validate(motion.segments);
  for (std::size_t i = 0; i < motion.frames.size(); ++i) {
    check_frame(motion.frames[i], i);
  }

  const double scale = options.units_per_metre;
  const Joint root = skeleton(motion.segments, options);
  out << "HIERARCHY\n";
  write_joint(out, root, 0, scale);

  std::string line;
  append(line, 1.0 / motion.fps, 8);  // 120 fps: 0.00833333, read back as 120.00000 fps
  out << "MOTION\nFrames: " << motion.frames.size() << "\nFrame Time: " << line << "\n";
  for (const eval::Frame& frame : motion.frames) {
    line.clear();
    append(line, 0.0);  // the pelvis midpoint is the walk's sagittal plane
    append(line, frame.pose.pelvis.y * scale);
    append(line, frame.pose.pelvis.x * scale);
    append_rotations(line, root, frame.pose);
    out << line << "\n";
  }
}

}  // namespace fuzzygait::io

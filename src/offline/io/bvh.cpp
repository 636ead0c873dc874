#include "fuzzygait/io/bvh.hpp"

#include <charconv>
#include <cmath>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "offline/io/bvh_text.hpp"
#include "offline/io/skeleton.hpp"

namespace fuzzygait::io {
namespace {

using detail::Joint;
using detail::Vec3;

// Six fixed decimals unless told (offline/io/bvh_text.hpp).
void append(std::string& line, double value, int decimals = 6) {
  detail::append_fixed(line, value, decimals);
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
  append(line, rig::degrees(detail::x_rotation(joint, pose)));
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
  const Joint root = detail::skeleton(motion.segments, bvh_hip_width(motion.segments, options));
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

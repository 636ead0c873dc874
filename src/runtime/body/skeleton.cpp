#include "fuzzygait/body/skeleton.hpp"

#include <cmath>
#include <stdexcept>
#include <unordered_set>

#include "runtime/common/format.hpp"

namespace fuzzygait::body {

using common::number_text;

namespace {

bool finite(Vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

[[noreturn]] void refuse(const SkeletonJoint& joint, std::size_t i, const std::string& problem) {
  throw std::invalid_argument("skeleton joint " + std::to_string(i) + " '" + joint.name +
                              "': " + problem);
}

}  // namespace

int Skeleton::find(std::string_view name) const {
  for (std::size_t i = 0; i < joints.size(); ++i) {
    if (joints[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

void validate(const Skeleton& skeleton) {
  if (skeleton.joints.empty()) throw std::invalid_argument("skeleton has no joints");
  if (!std::isfinite(skeleton.metres_per_unit) || skeleton.metres_per_unit <= 0.0) {
    throw std::invalid_argument("skeleton metres_per_unit must be finite and positive, got " +
                                number_text(skeleton.metres_per_unit));
  }
  std::unordered_set<std::string_view> names;
  for (std::size_t i = 0; i < skeleton.joints.size(); ++i) {
    const SkeletonJoint& joint = skeleton.joints[i];
    if (joint.name.empty()) refuse(joint, i, "has no name");
    if (!names.insert(joint.name).second) refuse(joint, i, "the name is used twice");
    if (i == 0 && joint.parent != -1) {
      refuse(joint, i, "the first joint is the root and has no parent (parent -1)");
    }
    if (i > 0 && (joint.parent < 0 || joint.parent >= static_cast<int>(i))) {
      refuse(joint, i,
             "parent " + std::to_string(joint.parent) +
                 " is not an earlier joint (parents come before their children; one root)");
    }
    if (!finite(joint.offset)) refuse(joint, i, "offset is not finite");
    if (joint.end && !finite(*joint.end)) refuse(joint, i, "end site is not finite");
    const Quat& q = joint.rotation;
    const double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (!std::isfinite(norm) || std::abs(norm - 1.0) > 1e-6) {
      refuse(joint, i, "rest rotation is not a unit quaternion (norm " + number_text(norm) + ")");
    }
  }
}

std::vector<Quat> rest_world_rotations(const Skeleton& skeleton) {
  std::vector<Quat> world(skeleton.size());
  for (std::size_t i = 0; i < skeleton.size(); ++i) {
    const SkeletonJoint& joint = skeleton.joints[i];
    world[i] = joint.parent < 0
                   ? joint.rotation
                   : normalized(world[static_cast<std::size_t>(joint.parent)] * joint.rotation);
  }
  return world;
}

std::vector<Vec3> rest_positions(const Skeleton& skeleton) {
  std::vector<Vec3> positions(skeleton.size());
  std::vector<Quat> rotations(skeleton.size());
  std::vector<Quat> local(skeleton.size());
  for (std::size_t i = 0; i < skeleton.size(); ++i)
    local[i] = skeleton.joints[i].rotation;
  forward_kinematics(skeleton, local, skeleton.joints.empty() ? Vec3{} : skeleton.joints[0].offset,
                     positions, rotations);
  return positions;
}

void forward_kinematics(const Skeleton& skeleton, std::span<const Quat> local_rotations,
                        Vec3 root_position, std::span<Vec3> world_positions,
                        std::span<Quat> world_rotations) {
  for (std::size_t i = 0; i < skeleton.size(); ++i) {
    const SkeletonJoint& joint = skeleton.joints[i];
    if (joint.parent < 0) {
      world_positions[i] = root_position;
      world_rotations[i] = local_rotations[i];
      continue;
    }
    const auto p = static_cast<std::size_t>(joint.parent);
    world_positions[i] = world_positions[p] + rotate(world_rotations[p], joint.offset);
    world_rotations[i] = world_rotations[p] * local_rotations[i];
  }
}

}  // namespace fuzzygait::body

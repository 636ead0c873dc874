// The C face of the whole body (include/fuzzygait/fuzzygait.h, below "The whole body on a path"):
// paths, followers and game skeletons over path::Path, body::PathFollower and
// body::SkeletonPoser; every exception stops here and becomes an fg_error.
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fuzzygait/body/follower.hpp"
#include "fuzzygait/body/humanoid.hpp"
#include "fuzzygait/body/humanoid_map.hpp"
#include "fuzzygait/body/skeleton.hpp"
#include "fuzzygait/body/skeleton_poser.hpp"
#include "fuzzygait/path/path.hpp"
#include "runtime/c_api.hpp"

using namespace fuzzygait;

struct fg_path {
  path::Path path;
};
struct fg_follower {
  body::PathFollower follower;
  fg_body_pose pose{};  // the last update's, as the C caller reads it
};
struct fg_skeleton {
  body::SkeletonPoser poser;
  body::HumanoidMap map;
  std::vector<body::Quat> local;  // pose()'s scratch
};

namespace {

using c_api::guarded;

static_assert(FG_JOINT_COUNT == static_cast<int>(body::kJointCount));
static_assert(FG_RIGHT_HAND_END == body::index(body::Joint::right_hand_end));
static_assert(FG_LEFT_SHOULDER == body::index(body::Joint::left_shoulder));
static_assert(FG_RIGHT_TOES_END == body::index(body::Joint::right_toes_end));

bool is_joint(int joint) {
  return joint >= 0 && joint < FG_JOINT_COUNT;
}

fg_vec3 c_vec(body::Vec3 v) {
  return {v.x, v.y, v.z};
}
fg_quat c_quat(body::Quat q) {
  return {q.w, q.x, q.y, q.z};
}
body::Vec3 vec_of(fg_vec3 v) {
  return {v.x, v.y, v.z};
}
body::Quat quat_of(fg_quat q) {
  return {q.w, q.x, q.y, q.z};
}

// The skeleton a def describes; throws std::invalid_argument naming what is missing.
body::Skeleton skeleton_of(const fg_skeleton_def& def) {
  if (def.joint_count == 0) throw std::invalid_argument("fg_skeleton_new: no joints");
  if (!def.names || !def.parents || !def.offsets) {
    throw std::invalid_argument("fg_skeleton_new: names, parents and offsets are needed");
  }
  body::Skeleton skeleton;
  skeleton.metres_per_unit = def.metres_per_unit;
  skeleton.joints.resize(def.joint_count);
  for (std::size_t i = 0; i < def.joint_count; ++i) {
    body::SkeletonJoint& joint = skeleton.joints[i];
    if (!def.names[i]) {
      throw std::invalid_argument("fg_skeleton_new: joint " + std::to_string(i) + " has no name");
    }
    joint.name = def.names[i];
    joint.parent = def.parents[i];
    joint.offset = vec_of(def.offsets[i]);
    if (def.rotations) joint.rotation = quat_of(def.rotations[i]);
  }
  body::validate(skeleton);
  return skeleton;
}

body::HumanoidMap map_of(const body::Skeleton& skeleton, const fg_skeleton_def& def) {
  if (!def.humanoid_names) return body::map_humanoid(skeleton);
  std::vector<body::NamedJoint> names;
  for (int j = 0; j < FG_JOINT_COUNT; ++j) {
    const char* name = def.humanoid_names[j];
    if (name && name[0] != '\0') names.push_back({static_cast<body::Joint>(j), name});
  }
  return body::map_humanoid(skeleton, names);
}

}  // namespace

extern "C" {

const char* fg_joint_name(int joint) {
  // body::name's views are of string literals: NUL-terminated.
  return is_joint(joint) ? body::name(static_cast<body::Joint>(joint)).data() : nullptr;
}

int fg_joint_parent(int joint) {
  if (!is_joint(joint)) return -1;
  const std::optional<body::Joint> parent = body::parent(static_cast<body::Joint>(joint));
  return parent ? body::index(*parent) : -1;
}

fg_path* fg_path_straight(fg_error* error) {
  return guarded(error, [&]() -> fg_path* { return new fg_path{path::Path()}; });
}

fg_path* fg_path_pieces(double start_x, double start_z, double heading, const fg_path_piece* pieces,
                        size_t count, fg_error* error) {
  return guarded(error, [&]() -> fg_path* {
    if (!pieces && count > 0) throw std::invalid_argument("fg_path_pieces: no pieces");
    std::vector<path::Piece> given(count);
    for (std::size_t i = 0; i < count; ++i)
      given[i] = {pieces[i].length, pieces[i].curvature};
    return new fg_path{path::Path({start_x, start_z}, heading, std::move(given))};
  });
}

fg_path* fg_path_polyline(const double* xz, size_t count, double corner_radius, fg_error* error) {
  return guarded(error, [&]() -> fg_path* {
    if (!xz && count > 0) throw std::invalid_argument("fg_path_polyline: no points");
    std::vector<path::GroundPoint> points(count);
    for (std::size_t i = 0; i < count; ++i)
      points[i] = {xz[2 * i], xz[2 * i + 1]};
    return new fg_path{path::Path::polyline(points, corner_radius)};
  });
}

double fg_path_length(const fg_path* path) {
  return path ? path->path.length() : c_api::kNaN;
}

void fg_path_at(const fg_path* path, double distance, fg_path_sample* sample) {
  if (!path || !sample) return;
  const path::PathSample s = path->path.at(distance);
  *sample = {s.point.x, s.point.z, s.heading, s.curvature};
}

void fg_path_free(fg_path* path) {
  delete path;
}

fg_follower_def fg_follower_def_default(void) {
  const body::FollowerOptions o;
  fg_follower_def def{};
  def.step_width_per_leg_length = o.step_width_per_leg_length;
  def.swing_release = o.swing_release;
  def.look_ahead = o.look_ahead;
  def.upper_body = o.upper_body ? 1 : 0;
  def.stature = 0.0;
  return def;
}

fg_follower* fg_follower_new(const fg_walker* walker, const fg_path* path,
                             const fg_skeleton* skeleton, const fg_follower_def* def,
                             fg_error* error) {
  return guarded(error, [&]() -> fg_follower* {
    if (!walker || !path || !def)
      throw std::invalid_argument("fg_follower_new: no walker, path or def");
    body::FollowerOptions options;
    options.step_width_per_leg_length = def->step_width_per_leg_length;
    options.swing_release = def->swing_release;
    options.look_ahead = def->look_ahead;
    options.upper_body = def->upper_body != 0;
    std::optional<double> stature;
    if (def->stature != 0.0) stature = def->stature;
    const body::Humanoid humanoid =
        skeleton ? skeleton->poser.humanoid()
                 : body::humanoid_with_legs(walker->walker.segments(), stature);
    return new fg_follower{body::PathFollower(humanoid, path->path, walker->walker, options)};
  });
}

const fg_body_pose* fg_follower_update(fg_follower* follower, const fg_walker* walker) {
  if (!follower || !walker) return nullptr;
  const body::BodyPose& pose = follower->follower.update(walker->walker);
  for (std::size_t j = 0; j < body::kJointCount; ++j) {
    follower->pose.position[j] = c_vec(pose.position[j]);
    follower->pose.rotation[j] = c_quat(pose.rotation[j]);
  }
  for (std::size_t k = 0; k < 2; ++k)
    follower->pose.heel[k] = c_vec(pose.heel[k]);
  return &follower->pose;
}

double fg_follower_pelvis_drop(const fg_follower* follower) {
  return follower ? follower->follower.pelvis_drop() : c_api::kNaN;
}

void fg_follower_free(fg_follower* follower) {
  delete follower;
}

fg_skeleton_def fg_skeleton_def_default(void) {
  fg_skeleton_def def{};
  def.metres_per_unit = 1.0;
  return def;
}

fg_skeleton* fg_skeleton_new(const fg_skeleton_def* def, fg_error* error) {
  return guarded(error, [&]() -> fg_skeleton* {
    if (!def) throw std::invalid_argument("fg_skeleton_new: no def");
    const body::Skeleton skeleton = skeleton_of(*def);
    const body::HumanoidMap map = map_of(skeleton, *def);
    body::SkeletonPoser poser(skeleton, map);
    std::vector<body::Quat> local(skeleton.size());
    return new fg_skeleton{std::move(poser), map, std::move(local)};
  });
}

void fg_skeleton_free(fg_skeleton* skeleton) {
  delete skeleton;
}

size_t fg_skeleton_joint_count(const fg_skeleton* skeleton) {
  return skeleton ? skeleton->poser.joint_count() : 0;
}

int fg_skeleton_mapped(const fg_skeleton* skeleton, int joint) {
  if (!skeleton || !is_joint(joint)) return -1;
  return skeleton->map[static_cast<body::Joint>(joint)];
}

int fg_skeleton_segments(const fg_skeleton* skeleton, fg_walker_def* def) {
  if (!skeleton || !def) return 0;
  c_api::set_segments(*def, skeleton->poser.humanoid().segments());
  return 1;
}

int fg_skeleton_pose(fg_skeleton* skeleton, const fg_body_pose* pose, fg_quat* local_rotations,
                     fg_vec3* root_position) {
  if (!skeleton || !pose || !local_rotations || !root_position) return 0;
  body::BodyPose body;
  for (std::size_t j = 0; j < body::kJointCount; ++j) {
    body.position[j] = vec_of(pose->position[j]);
    body.rotation[j] = quat_of(pose->rotation[j]);
  }
  for (std::size_t k = 0; k < 2; ++k)
    body.heel[k] = vec_of(pose->heel[k]);
  body::Vec3 root;
  const bool posed = skeleton->poser.pose(body, skeleton->local, root);
  for (std::size_t i = 0; i < skeleton->local.size(); ++i)
    local_rotations[i] = c_quat(skeleton->local[i]);
  *root_position = c_vec(root);
  return posed ? 1 : 0;
}

}  // extern "C"

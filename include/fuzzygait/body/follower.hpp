// The whole body walking a path: poses a Humanoid from a walker's sagittal walk, bent onto a
// path::Path. The walker walks the distance along the path (its x, with the terrain under the
// path as its ground); the follower places the body in the world each frame:
//   hips     on the path at the walker's pelvis distance (but for the sway), facing along it,
//            tilted as the walker's pelvis; lowered only as far as the legs need to reach their
//            feet (pelvis_drop(), at most 0.1 of a leg: past that a foot falls short of where it
//            is drawn to be).
//   feet     on the path's ground frame at their own distance, step_width apart; a foot found
//            planted is locked in the world until it lifts, so it never slides on a turn; a
//            lifted foot eases from its stance frame onto the path's over the first part of its
//            swing (swing_release), following the path meanwhile, so nothing pops; a foot's
//            frame turns about its heel.
//   legs     hip to ankle by two-bone IK in 3-D, the knee bending towards the walker's knee
//            (along the foot's heading); thigh and shank keep their lengths.
//   upper    the walker's controller set's upper body (ControllerSet::upper_body): the arms
//   body     swing at shoulder and elbow against their own legs, the pelvis and the chest turn
//            about the vertical with the legs, the chest against the pelvis; the pelvis rolls
//            (obliquity) and sways sideways over the feet; a set without them hangs the arms and
//            keeps pelvis and chest square to the path, over it, as a standing walker does
//            (the answers fade out over half a second as it stands, and in as it walks on).
//            The trunk leans forward on slopes and stairs (trunk_lean, from the ground under
//            the feet); the head stays upright and turns to the path look_ahead metres ahead.
// On a straight path with step_width equal to the hip width the legs are the walker's to
// rounding.
#pragma once

#include <array>
#include <vector>

#include "fuzzygait/body/humanoid.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/path/path.hpp"

namespace fuzzygait::body {

struct FollowerOptions {
  // Distance between the feet's centre lines over leg length: 0.11 x 0.93 m = 0.10 m, adults'
  // step width at free speed (8-12 cm).
  double step_width_per_leg_length = 0.11;
  // Share of the way from lift-off to the swing's target by which a lifted foot has moved from
  // the frame it stood in to the path's frame (0.3 to 1); it starts at 0.15, toes clear.
  double swing_release = 0.6;
  // How far ahead along the path the head looks (m, 0 to 5).
  double look_ahead = 0.5;
  // false: the set's upper body controllers are not played (arms hang, pelvis and chest square).
  bool upper_body = true;
};

class PathFollower {
 public:
  // `path` must outlive the follower. Throws std::invalid_argument when the humanoid is not
  // valid (validate), the walker's segments are not the humanoid's legs, or an option is out of
  // range.
  PathFollower(const Humanoid& humanoid, const path::Path& path, const gait::Walker& walker,
               const FollowerOptions& options = {});
  PathFollower(const Humanoid&, path::Path&&, const gait::Walker&,
               const FollowerOptions& = {}) = delete;  // a temporary path would be gone

  // Poses the body for the walker's state now: call it once a frame after advance(), at least
  // once while each foot is planted, with the walker it was made with (another walker's set plays
  // no upper body). A walker whose time went back (started again) unlocks the feet.
  // Deterministic: the same frames give the same poses.
  const BodyPose& update(const gait::Walker& walker) noexcept;
  const BodyPose& pose() const noexcept { return pose_; }
  // How far the hips were lowered below the walker's pelvis at the last update (m, >= 0).
  double pelvis_drop() const noexcept { return drop_; }
  const Humanoid& humanoid() const noexcept { return humanoid_; }

  // The metrics an upper body controller reads of leg `leg` (0 left, 1 right) of the walker now:
  // delta, other_delta, hip, knee, ankle, toe, pace, and its ground's incline and stairs as the
  // walker's controllers read them (Walker::ground_metrics()); sole 0.
  static gait::MetricValues leg_metrics(const gait::Walker& walker, int leg) noexcept;

 private:
  // A ground frame of a foot: where the walker's sagittal x `anchor` lies on the ground, and the
  // heading the sagittal plane takes there.
  struct FootFrame {
    path::GroundPoint origin;
    double heading = 0.0;
    double anchor = 0.0;
  };
  struct FootState {
    bool locked = false;
    bool releasing = false;
    FootFrame frame;      // locked: the stance frame
    Vec3 locked_forward;  // locked: its heading's forward and yaw, kept from the landing
    Quat locked_yaw;
    FootFrame drawn;           // the frame the foot was drawn in at the last update
    double release_x = 0.0;    // the heel's x when it lifted
    double release_way = 0.0;  // from there to the swing's target then (m, at least 0.05)
    double share = 0.0;        // how far the release has gone, 0 to 1, never back
    // Releasing: how far the stance frame lay off the path's frame at lift-off, in the path's
    // frame (m along, m to the left, radians).
    double offset_along = 0.0;
    double offset_left = 0.0;
    double offset_turn = 0.0;
  };

  FootFrame path_frame(double x, double lateral) const noexcept;
  // The set's answer for `part` from a leg's metrics, as its controller gives it; 0 without one.
  double upper_body_answer(const gait::ControllerSet& set, gait::UpperBody part,
                           const gait::MetricValues& metrics) noexcept;
  // The same for an angle, radians.
  double upper_body_angle(const gait::ControllerSet& set, gait::UpperBody part,
                          const gait::MetricValues& metrics) noexcept;

  Humanoid humanoid_;
  const path::Path* path_;
  FollowerOptions options_;
  double step_width_ = 0.0;
  std::array<FootState, 2> feet_{};
  const gait::ControllerSet* set_;            // the walker's set, whose upper body plays
  std::vector<fuzzy::Workspace> workspaces_;  // one per upper body controller of set_
  double last_time_ = -1.0;                   // the walker's time at the last update
  // How much of the upper body's answers plays: 1 walking, easing to 0 (arms hanging, pelvis and
  // chest square) over kUpperBodyEasing seconds once the walker stands, and back when it walks.
  double upper_body_share_ = 1.0;
  static constexpr double kUpperBodyEasing = 0.5;
  // The trunk's lean (radians, forward +) follows the controller's answer with this time constant
  // (s): a foothold's incline changes from one step to the next, the lean over about a step.
  double lean_ = 0.0;
  bool updated_ = false;
  static constexpr double kLeanEasing = 0.3;
  BodyPose pose_{};
  double drop_ = 0.0;
};

}  // namespace fuzzygait::body

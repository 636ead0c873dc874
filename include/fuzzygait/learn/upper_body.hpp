// Learning a set's upper body (ControllerSet::upper_body) from motion capture: what a clip's arms,
// pelvis and chest do at each frame, against the legs' metrics at that frame. Each upper body
// controller answers a weighted average of its output constants (Takagi-Sugeno), so its answer is
// linear in them: the fit is a linear least squares on the constants, the words and rules kept,
// pulled gently towards the base's values (a sum of a left and a right answer cannot tell a
// constant added to every word, which then stays as the base has it).
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fuzzygait/body/math.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/io/mocap.hpp"
#include "fuzzygait/learn/train.hpp"

namespace fuzzygait::learn {

// The upper body as body::PathFollower poses it and a capture shows it, frame by frame: degrees,
// the sway in percent of the leg's length.
struct UpperBodySeries {
  std::vector<double> time;                     // s, the frames'
  std::array<std::vector<double>, 2> shoulder;  // rig::Side order: the upper arm's inclination
                                                // forward of the downward vertical, in the walk's
                                                // sagittal plane
  std::array<std::vector<double>, 2> elbow;     // flexion: the angle between upper and forearm
  // About their means over the frames (one held all along is the subject's stance or the
  // markers'; the follower's turns and roll are the two sides' answers' difference):
  std::vector<double> pelvis_rotation;   // the hip joints' line, left hip forward +
  std::vector<double> thorax_rotation;   // the shoulder joints' line, left forward +
  std::vector<double> pelvis_obliquity;  // the hip joints' line, left hip up +
  std::vector<double> pelvis_sway;       // the hips' centre to the left of its straight-line fit
  std::size_t size() const { return time.size(); }
};

// One frame's joints in the world, any units.
struct UpperBodyPoints {
  double time = 0.0;
  std::array<body::Vec3, 2> hip;       // the hip joint centres, rig::Side order
  std::array<body::Vec3, 2> shoulder;  // the upper arms' joints
  std::array<body::Vec3, 2> elbow;
  std::array<body::Vec3, 2> wrist;
};

// The series of `frames` walking along `forward` (horizontal, unit) with `up` (unit); the sway is
// measured against the hips' centre's straight-line fit over the frames, over `leg_length` (the
// points' units). Throws std::invalid_argument for fewer than two frames, axes that are not unit
// and square to each other, a leg length that is not positive, or a point that is not finite.
UpperBodySeries measure_upper_body(std::span<const UpperBodyPoints> frames, body::Vec3 forward,
                                   body::Vec3 up, double leg_length);

// A captured clip's upper body: its frames from the first analyse_clip kept, their joints found
// by body::map_humanoid (CMU, Mixamo, VRM, ... names). std::nullopt when the skeleton has no
// upper arm, forearm or hand on a side (the reason in `why`); throws as map_humanoid does for a
// skeleton without legs.
std::optional<UpperBodySeries> capture_upper_body(const io::BvhClip& bvh,
                                                  const io::CapturedClip& captured,
                                                  std::string* why = nullptr);

// A clip to learn the upper body from: the legs' motion as train takes it, and its upper body.
struct UpperBodyClip {
  std::string name;
  const TrainClip* legs = nullptr;
  UpperBodySeries series;
};

// Per part (gait::UpperBody order) and clip: the RMSE of the set's answer against the clip's
// (degrees; the sway percent of a leg), before and after, and whether the part was fitted.
struct UpperBodyFit {
  gait::ControllerSet set;
  std::array<bool, gait::kUpperBodyCount> fitted{};
  // [part][clip]
  std::array<std::vector<double>, gait::kUpperBodyCount> rmse_before, rmse_after;
  std::vector<std::string> notes;  // parts left as they were, and why
};

// Fits the output constants of each of `base`'s upper body controllers whose output words are all
// Constant to the clips' frames (those the legs' training data knows), rounded to three
// significant digits. The legs' metrics are the walker's own code's (learn::training_data); each
// part reads the side the follower gives it. Throws std::invalid_argument for no clip or a clip
// without its legs.
UpperBodyFit fit_upper_body(const gait::ControllerSet& base, std::span<const UpperBodyClip> clips);

}  // namespace fuzzygait::learn

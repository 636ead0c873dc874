// Motion capture in: a BVH reader for any skeleton, the mapping of its two leg chains, and the
// sagittal leg angles, foot contacts and gait events of a walking clip as an eval::Motion (the
// walk CSV's frames, so every measure of a walk applies to a clip too).
//
// The method is that of the reference extractor tests/tools/bvh_sagittal.py:
//   * forward kinematics of the hierarchy: a joint's rotation is R(ch1) R(ch2) R(ch3) in the order
//     its CHANNELS line lists them, position channels add to its OFFSET;
//   * the sagittal plane: up axis u (Y or Z) and walking direction f, the root's horizontal
//     displacement from the first to the last frame;
//   * thigh inclination: the hip->knee vector's angle from the downward vertical in the (f, u)
//     plane, forward +; knee: the 3-D angle between thigh and shank (>= 0); ankle: the 3-D angle
//     between shank and foot (ankle->toe base) minus its rest-pose value (dorsiflexion +); toe:
//     the 3-D angle between foot and toes (toe base->its first child) minus its rest value;
//   * foot contacts, ground lines and events as ClipOptions describes.
// A BVH carries no pelvis orientation one can trust (its root turns the whole body): pelvis tilt
// is 0 and hip flexion is the thigh's inclination.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::io {

// A problem in a mocap file (a BVH or a leg mapping): "SOURCE:LINE: message" (the line left out
// when it is 0, for a problem of the whole file).
class MocapError : public std::invalid_argument {
 public:
  MocapError(std::string source, int line, const std::string& message);
  const std::string& source() const { return source_; }
  int line() const { return line_; }

 private:
  std::string source_;
  int line_;
};

enum class BvhChannel : std::uint8_t {
  Xposition,
  Yposition,
  Zposition,
  Xrotation,
  Yrotation,
  Zrotation
};
bool is_rotation(BvhChannel channel);
// 0, 1, 2 for X, Y, Z.
int axis_of(BvhChannel channel);

struct BvhJoint {
  std::string name;  // "End Site" for end sites
  int parent = -1;   // index into BvhClip::joints; -1 for the root
  std::array<double, 3> offset{};
  std::vector<BvhChannel> channels;  // in the file's order; none for end sites
  std::size_t first_column = 0;      // where its channels begin in a frame's values
  bool end_site = false;
  int line = 0;  // where the joint is declared
};

// A BVH file as written, nothing interpreted: one ROOT, its joints in file order (a parent
// before its children), and the frames' channel values.
struct BvhClip {
  std::vector<BvhJoint> joints;
  std::size_t channel_count = 0;  // values in a frame, all joints' channels together
  double frame_time = 0.0;        // s
  std::vector<double> values;     // frame after frame, channel_count each

  std::size_t frame_count() const { return channel_count == 0 ? 0 : values.size() / channel_count; }
  std::span<const double> frame(std::size_t i) const {
    return std::span<const double>(values).subspan(i * channel_count, channel_count);
  }
  // The joint named `name` (end sites never match), or -1.
  int find(std::string_view name) const;
};

// Reads BVH text: HIERARCHY, one ROOT with JOINTs and End Sites to a depth of kMaxBvhDepth,
// OFFSET x y z, CHANNELS n followed by n distinct channel names (0 to 6, any order), MOTION,
// "Frames: n" (1 to kMaxBvhFrames), "Frame Time: t" (1e-4 to 1 s), then exactly n lines of
// exactly channel_count numbers each. Whitespace is spaces, tabs and line ends (LF or CRLF).
// Throws MocapError "SOURCE:LINE: expected ... found ..." for anything else: a missing brace, a
// wrong count, a value that is not a finite number or exceeds 1e9 in magnitude, a duplicate
// joint name. Memory grows with the text read, never with a count the text claims.
inline constexpr int kMaxBvhDepth = 64;
inline constexpr std::size_t kMaxBvhFrames = 10'000'000;
BvhClip read_bvh(std::string_view text, std::string_view source);
// The same for a file; `path` names it in errors.
BvhClip read_bvh_file(const std::filesystem::path& path);

// Which joints make a leg, by name.
struct LegJoints {
  std::string hip;    // the hip joint centre (the thigh's first joint)
  std::string knee;   // the knee
  std::string ankle;  // the ankle
  // The toe base (MTP joint); its first child marks the tip of the toes (no toe angle without
  // one). Empty: the ankle's first child stands for it (an End Site on a foot without toes).
  std::string toe;
};
struct LegMapping {
  std::string root;               // walking direction and speed come from it
  std::array<LegJoints, 2> legs;  // rig::Side order: left, right
  std::string source;             // the mapping's file name, for errors; empty if built in
};

// The built-in names: root "Hips" (else the file's ROOT); per side, with the prefixes "Left",
// "L" and "l" (and "Right", "R", "r"), the first of UpLeg, Hip, Thigh, femur; Leg, Knee, Shin,
// tibia; Foot, Ankle, foot; ToeBase, Toe, toes that the skeleton has (CMU, MotionBuilder and
// ASF-style names), the toe base else the ankle's first child.
// A mapping file is a JSON object:
//   {"root": "pelvis",
//    "left":  {"hip": "thigh_l", "knee": "calf_l", "ankle": "foot_l", "toe": "ball_l"},
//    "right": {"hip": "thigh_r", "knee": "calf_r", "ankle": "foot_r", "toe": "ball_r"}}
// "root" and "toe" may be left out. Throws std::invalid_argument naming the file and line for
// anything else: text that is not JSON (its column too), an unknown key, a missing field, a
// name that is not a non-empty string (a MocapError naming the field).
LegMapping read_leg_mapping(std::string_view json, std::string_view source);
LegMapping read_leg_mapping_file(const std::filesystem::path& path);

enum class UpAxis { Y, Z };

// Options of the analysis; the defaults are the reference extractor's.
struct ClipOptions {
  std::optional<LegMapping> mapping;  // none: the built-in names
  // none: the axis, of +Y and +Z, along which the hips stand above the ankles over the clip.
  std::optional<UpAxis> up;
  // none: of m, cm, mm, inch and CMU units (1/0.45 inch), the one that makes the rest pose's
  // hip-to-ankle length closest to 0.80 m.
  std::optional<double> metres_per_unit;
  // Leading frames to drop. none: the first frame when it is a calibration pose (every rotation
  // a whole number of degrees, more than 80 % of them zero).
  std::optional<std::size_t> skip;
  // A foot is on the ground while its ankle or its toe base is less than contact_height above
  // that point's ground line and moves horizontally slower than contact_speed, or while either
  // moves slower than still_speed in 3-D (a contact on raised ground). A ground line is fitted
  // (height against distance along f) to the frames where that point of either foot moves
  // slower than ground_speed. Speeds are central differences over 5 frames. Runs of contact or
  // of no contact shorter than min_run seconds merge into the run before them.
  double contact_height = 0.04;  // m
  double contact_speed = 1.0;    // m/s
  double still_speed = 0.3;      // m/s
  double ground_speed = 0.2;     // m/s
  double min_run = 0.05;         // s
  // Left cycles (left heel strike to the next) that count for `cycles`: this long.
  double min_cycle = 0.6;  // s
  double max_cycle = 2.0;  // s
};

// One leg as the skeleton measures it, metres.
struct MeasuredLeg {
  std::string hip, knee, ankle, toe, tip;  // the joints used ("End Site" for an end site)
  double thigh = 0.0;                      // hip to knee
  double shank = 0.0;                      // knee to ankle
  double foot = 0.0;                       // ankle to toe base
  double toes = 0.0;                       // toe base to its first child; 0 without one
  bool has_toes = false;                   // a toe angle was measured
};

struct GaitEvents {
  std::array<std::vector<std::size_t>, 2> heel_strikes;  // frames where contact begins
  std::array<std::vector<std::size_t>, 2> toe_offs;      // frames where contact has ended
};

// A walking clip read into the rig's terms.
//   motion     frames from the first frame kept (time 0), fps = 1 / frame time, captured;
//              pose: pelvis at the hip joint centres' midpoint (x along f from the root's first
//              position, y above the ground at x = 0), pelvis tilt 0, per leg the angles above
//              (radians; toe 0 without toes); points: rig::forward_kinematics of the pose with
//              `motion.segments`; contacts as ClipOptions describes.
//   ground     the toe bases' ground line in those coordinates (y = slope * x): where the rig's
//              sole lies when the foot is flat.
//   segments   thigh and shank the mean of the two legs; the foot from the rest pose's ankle to
//              toe base (ball along the ground, ankle_height its drop, or Winter's 0.039 stature
//              when the drop is under 5 mm); heel, and toe without toes, from Winter's
//              proportions with stature (thigh + shank) / 0.491. `notes` says which.
struct CapturedClip {
  eval::Motion motion;
  terrain::Terrain ground = terrain::Terrain::flat();
  std::array<MeasuredLeg, 2> legs;  // rig::Side order
  std::string root;                 // the joint whose path gives f
  double metres_per_unit = 1.0;
  bool unit_guessed = false;
  UpAxis up = UpAxis::Y;
  bool up_detected = false;
  std::size_t skipped_frames = 0;
  std::array<double, 3> forward{};  // f in the file's axes
  GaitEvents events;
  // Left cycles within ClipOptions' duration range, in order: (strike frame, next strike frame).
  std::vector<std::array<std::size_t, 2>> cycles;
  // Each 0 when the clip has no such strikes.
  double cadence = 0.0;            // steps/min, from strikes of alternate feet 0 to 1 s apart
  double step_length = 0.0;        // m, ankle to ankle along f at each heel strike, mean
  double speed = 0.0;              // m/s, root along f from the first heel strike to the last
  std::vector<std::string> notes;  // estimates and doubts, one sentence each
};

// Analyses a clip read by read_bvh. `source` names it in errors. Throws MocapError naming the
// source (and the mapping's file and the joint) for a leg joint not found or not below the one
// before it, legs of zero length, an option out of range, fewer than 2 frames left after
// skipping, a root that does not move horizontally, a skeleton whose up axis cannot be told,
// positions beyond 100 km, ground rising more than 0.5 m per metre.
CapturedClip analyse_clip(const BvhClip& bvh, std::string_view source,
                          const ClipOptions& options = {});
// read_bvh_file, then analyse_clip.
CapturedClip read_clip(const std::filesystem::path& path, const ClipOptions& options = {});

const char* unit_name(double metres_per_unit);  // "m", "cm", "mm", "inch", "CMU", or "custom"

}  // namespace fuzzygait::io

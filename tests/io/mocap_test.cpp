// Motion capture in: the BVH reader on small hand-written and generated files (every channel
// order, Y and Z up, units, End Sites, calibration frames, and each malformed case with its line),
// leg mappings, the sagittal angles of a synthetic walk whose angles are known, a walk written by
// io::write_bvh read back, the nine CMU clips frame by frame against the Python reference
// (tests/tools/bvh_sagittal.py, when python3 is there), and `fuzzygait mocap` as a user runs it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fuzzygait/eval/evaluation.hpp"
#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/io/bvh.hpp"
#include "fuzzygait/io/mocap.hpp"
#include "fuzzygait/io/walk_csv.hpp"
#include "support/program.hpp"
#include "support/text.hpp"
#include "support/walks.hpp"

namespace fuzzygait {
namespace {

using io::MocapError;
using rig::degrees;
using rig::radians;
using ::testing::HasSubstr;

const std::filesystem::path kSourceDir = FUZZYGAIT_SOURCE_DIR;
const std::filesystem::path kClips = kSourceDir / "data/mocap/cmu";
const std::vector<std::string> kClipNames = {"05_01", "07_01", "07_02", "07_03", "07_06",
                                             "08_01", "08_02", "08_03", "08_06"};

std::filesystem::path scratch(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "fuzzygait_mocap";
  std::filesystem::create_directories(dir);
  return dir / name;
}

std::string shell_quoted(const std::filesystem::path& p) {
  return "\"" + p.string() + "\"";
}

// Runs a shell command; its exit status and everything it printed.
test::ProgramRun run_shell(const std::string& command) {
  test::ProgramRun result{-1, {}};
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((command + " 2>&1").c_str(), "r"), pclose);
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  while (const std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe.get()))
    result.output.append(buffer.data(), n);
  const int status = pclose(pipe.release());
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// The message read_bvh throws for `text`, or "" when it reads.
std::string bvh_error(const std::string& text) {
  try {
    io::read_bvh(text, "tiny.bvh");
  } catch (const MocapError& e) {
    return e.what();
  }
  return "";
}

// ---------------------------------------------------------------------------------------------
// A synthetic walk with known sagittal angles, written as BVH.

struct SyntheticOptions {
  io::UpAxis up = io::UpAxis::Y;
  double units_per_metre = 100.0;
  std::string rotation_order = "Zrotation Yrotation Xrotation";  // every joint's
  bool toe_joints = true;                      // else the ankle ends in an End Site
  bool toe_end_sites = true;                   // the toe joints' End Sites
  bool calibration = false;                    // a first frame of zeros
  std::map<std::string, std::string> renamed;  // joint names replaced
  int frames = 300;
  double frame_time = 0.01;
  double speed = 1.2;  // m/s, the root's along the walking direction
};

struct SyntheticWalk {
  std::string text;
  std::vector<std::array<rig::LegAngles, 2>> angles;  // per frame written (calibration excluded)
};

// Segments of the synthetic skeleton, metres.
constexpr double kHalfHipWidth = 0.09;
constexpr double kThigh = 0.42;
constexpr double kShank = 0.41;
constexpr double kFootDrop = 0.05;
constexpr double kFootLength = 0.13;
constexpr double kToeLength = 0.06;
constexpr double kHipHeight = 0.90;
constexpr double kCycleTime = 1.1;  // s

rig::LegAngles synthetic_angles(double t, int side) {
  const double phase =
      2.0 * std::numbers::pi * t / kCycleTime + (side == 0 ? 0.0 : std::numbers::pi);
  return {0.1 + 0.35 * std::sin(phase), 0.5 + 0.45 * std::sin(phase + 1.0),
          0.2 * std::sin(phase - 0.5), 0.3 + 0.25 * std::sin(phase)};
}

SyntheticWalk synthetic_walk(const SyntheticOptions& o) {
  // (lateral to the left, up, forward) in the file's axes: X left; Y up and Z forward, or Z up
  // and -Y forward (both right-handed, so +Xrotation turns up towards forward in both).
  auto axes = [&](double left, double up, double forward) {
    return o.up == io::UpAxis::Y ? std::array<double, 3>{left, up, forward}
                                 : std::array<double, 3>{left, -forward, up};
  };
  auto name = [&](const std::string& n) {
    const auto it = o.renamed.find(n);
    return it == o.renamed.end() ? n : it->second;
  };
  auto number = [](double v) {
    char text[64];
    std::snprintf(text, sizeof text, "%.9f", v);
    return std::string(text);
  };
  auto offset = [&](const std::string& indent, double left, double up, double forward) {
    const auto v = axes(left, up, forward);
    std::string line = indent + "OFFSET";
    for (double c : v)
      line += " " + number(c * o.units_per_metre);
    return line + "\n";
  };
  std::string h = "HIERARCHY\nROOT " + name("Hips") + "\n{\n" + offset("  ", 0, 0, 0) +
                  "  CHANNELS 6 Xposition Yposition Zposition " + o.rotation_order + "\n";
  for (const char* side : {"Left", "Right"}) {
    const double left = side[0] == 'L' ? kHalfHipWidth : -kHalfHipWidth;
    const std::string s = side;
    const std::string channels = "CHANNELS 3 " + o.rotation_order + "\n";
    h +=
        "  JOINT " + name(s + "UpLeg") + "\n  {\n" + offset("    ", left, 0, 0) + "    " + channels;
    h += "    JOINT " + name(s + "Leg") + "\n    {\n" + offset("      ", 0, -kThigh, 0) + "      " +
         channels;
    h += "      JOINT " + name(s + "Foot") + "\n      {\n" + offset("        ", 0, -kShank, 0) +
         "        " + channels;
    if (o.toe_joints) {
      h += "        JOINT " + name(s + "ToeBase") + "\n        {\n" +
           offset("          ", 0, -kFootDrop, kFootLength) + "          " + channels;
      if (o.toe_end_sites) {
        h += "          End Site\n          {\n" + offset("            ", 0, 0, kToeLength) +
             "          }\n";
      }
      h += "        }\n";
    } else {
      h += "        End Site\n        {\n" + offset("          ", 0, -kFootDrop, kFootLength) +
           "        }\n";
    }
    h += "      }\n    }\n  }\n";
  }
  h += "}\n";
  // Where Xrotation falls among a joint's three rotation channels.
  std::istringstream order(o.rotation_order);
  std::vector<std::string> names{std::istream_iterator<std::string>(order), {}};
  auto rotations = [&](double x_degrees) {
    std::string row;
    for (const std::string& c : names)
      row += " " + number(c == "Xrotation" ? x_degrees : 0.0);
    return row;
  };
  SyntheticWalk walk;
  std::string rows;
  const int joints_per_leg = o.toe_joints ? 4 : 3;
  if (o.calibration) {
    for (double c : axes(0.0, kHipHeight, 0.0))
      rows += number(c * o.units_per_metre) + " ";
    rows += "0 0 0";
    for (int k = 0; k < 2 * joints_per_leg; ++k)
      rows += " 0 0 0";
    rows += "\n";
  }
  for (int i = 0; i < o.frames; ++i) {
    const double t = i * o.frame_time;
    const auto root = axes(
        0.0, kHipHeight + 0.02 * std::sin(4.0 * std::numbers::pi * t / kCycleTime), o.speed * t);
    std::string row;
    for (double c : root)
      row += (row.empty() ? "" : " ") + number(c * o.units_per_metre);
    row += rotations(0.0);
    std::array<rig::LegAngles, 2> a{};
    for (int side = 0; side < 2; ++side) {
      a[side] = synthetic_angles(t, side);
      // The writer's conventions (io/bvh.hpp): UpLeg -hip, Leg +knee, Foot -ankle, ToeBase -toe.
      row += rotations(-degrees(a[side].hip)) + rotations(degrees(a[side].knee)) +
             rotations(-degrees(a[side].ankle));
      if (o.toe_joints) row += rotations(-degrees(a[side].toe));
    }
    rows += row + "\n";
    walk.angles.push_back(a);
  }
  walk.text = h + "MOTION\nFrames: " + std::to_string(o.frames + (o.calibration ? 1 : 0)) +
              "\nFrame Time: " + number(o.frame_time) + "\n" + rows;
  return walk;
}

io::CapturedClip analyse(const SyntheticWalk& walk, const io::ClipOptions& options = {}) {
  return io::analyse_clip(io::read_bvh(walk.text, "synthetic.bvh"), "synthetic.bvh", options);
}

// The largest difference, degrees, between the clip's angles and the walk's known ones (toe
// only where the clip measures it).
double largest_angle_error(const io::CapturedClip& clip, const SyntheticWalk& walk) {
  EXPECT_EQ(clip.motion.frames.size(), walk.angles.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < std::min(clip.motion.frames.size(), walk.angles.size()); ++i) {
    for (std::size_t s = 0; s < 2; ++s) {
      const rig::LegAngles& got = clip.motion.frames[i].pose.legs[s];
      const rig::LegAngles& want = walk.angles[i][s];
      worst = std::max({worst, std::abs(degrees(got.hip - want.hip)),
                        std::abs(degrees(got.knee - want.knee)),
                        std::abs(degrees(got.ankle - want.ankle))});
      if (clip.legs[s].has_toes) worst = std::max(worst, std::abs(degrees(got.toe - want.toe)));
    }
  }
  return worst;
}

TEST(MocapSynthetic, EveryRotationOrderGivesBackTheAnglesWritten) {
  for (const char* order : {"Xrotation Yrotation Zrotation", "Xrotation Zrotation Yrotation",
                            "Yrotation Xrotation Zrotation", "Yrotation Zrotation Xrotation",
                            "Zrotation Xrotation Yrotation", "Zrotation Yrotation Xrotation"}) {
    SyntheticOptions o;
    o.rotation_order = order;
    const SyntheticWalk walk = synthetic_walk(o);
    const io::CapturedClip clip = analyse(walk);
    EXPECT_LT(largest_angle_error(clip, walk), 1e-5) << order;
    EXPECT_EQ(clip.up, io::UpAxis::Y) << order;
    EXPECT_TRUE(clip.up_detected);
    EXPECT_EQ(clip.skipped_frames, 0u);
    EXPECT_NEAR(clip.forward[2], 1.0, 1e-9);
  }
}

TEST(MocapSynthetic, ZUpIsDetectedAndReadAsYUp) {
  SyntheticOptions o;
  o.up = io::UpAxis::Z;
  o.rotation_order = "Xrotation Yrotation Zrotation";
  const SyntheticWalk walk = synthetic_walk(o);
  const io::CapturedClip clip = analyse(walk);
  EXPECT_EQ(clip.up, io::UpAxis::Z);
  EXPECT_TRUE(clip.up_detected);
  EXPECT_NEAR(clip.forward[1], -1.0, 1e-9);
  EXPECT_LT(largest_angle_error(clip, walk), 1e-5);
  // The same clip in Y up: the same motion, point for point.
  const io::CapturedClip y_up = analyse(synthetic_walk({}));
  ASSERT_EQ(y_up.motion.frames.size(), clip.motion.frames.size());
  for (std::size_t i = 0; i < clip.motion.frames.size(); ++i) {
    EXPECT_NEAR(clip.motion.frames[i].pose.pelvis.x, y_up.motion.frames[i].pose.pelvis.x, 1e-9);
    EXPECT_NEAR(clip.motion.frames[i].pose.pelvis.y, y_up.motion.frames[i].pose.pelvis.y, 1e-9);
    EXPECT_NEAR(clip.motion.frames[i].points[0].tip.y, y_up.motion.frames[i].points[0].tip.y, 1e-9);
  }
  // Given, the same as detected.
  io::ClipOptions given;
  given.up = io::UpAxis::Z;
  EXPECT_FALSE(analyse(walk, given).up_detected);
  EXPECT_LT(largest_angle_error(analyse(walk, given), walk), 1e-5);
}

TEST(MocapSynthetic, TheUnitIsGuessedFromTheLegOrTakenAsGiven) {
  const std::pair<double, const char*> units[] = {
      {1.0, "m"}, {100.0, "cm"}, {1000.0, "mm"}, {1.0 / 0.0254, "inch"}, {0.45 / 0.0254, "CMU"}};
  for (const auto& [per_metre, name] : units) {
    SyntheticOptions o;
    o.units_per_metre = per_metre;
    const SyntheticWalk walk = synthetic_walk(o);
    const io::CapturedClip clip = analyse(walk);
    EXPECT_STREQ(io::unit_name(clip.metres_per_unit), name);
    EXPECT_TRUE(clip.unit_guessed);
    EXPECT_NEAR(clip.motion.segments.thigh, kThigh, 1e-6) << name;
    EXPECT_NEAR(clip.motion.segments.shank, kShank, 1e-6) << name;
    EXPECT_NEAR(clip.motion.segments.ankle_height, kFootDrop, 1e-6) << name;
    EXPECT_NEAR(clip.motion.segments.ball, kFootLength, 1e-6) << name;
    EXPECT_NEAR(clip.motion.segments.toe, kToeLength, 1e-6) << name;
    EXPECT_NEAR(clip.motion.frames.back().pose.pelvis.x, 1.2 * 2.99, 1e-6) << name;
  }
  // Given, the unit is used as it is.
  io::ClipOptions given;
  given.metres_per_unit = 0.01;
  const io::CapturedClip clip = analyse(synthetic_walk({}), given);
  EXPECT_FALSE(clip.unit_guessed);
  EXPECT_NEAR(clip.motion.segments.thigh, kThigh, 1e-9);
  // A file in mm read as cm has legs of 4 m: refused, naming the unit.
  SyntheticOptions mm;
  mm.units_per_metre = 1000.0;
  try {
    analyse(synthetic_walk(mm), given);
    ADD_FAILURE() << "legs of 4 m read";
  } catch (const MocapError& e) {
    EXPECT_THAT(e.what(), HasSubstr("synthetic.bvh: expected the skeleton to make a plausible leg "
                                    "(at 0.01 m per unit): segment 'thigh' must be between"));
  }
}

TEST(MocapSynthetic, EndSitesMakeTheToesAndTheirAbsenceIsNoted) {
  SyntheticOptions o;
  o.toe_end_sites = false;
  io::CapturedClip clip = analyse(synthetic_walk(o));
  for (const io::MeasuredLeg& leg : clip.legs)
    EXPECT_FALSE(leg.has_toes);
  EXPECT_EQ(clip.motion.frames[10].pose.legs[0].toe, 0.0);
  EXPECT_THAT(clip.notes.back(), HasSubstr("toe length from proportions"));

  // No toe joints at all: the ankle's End Site stands for the toe base.
  o.toe_joints = false;
  const SyntheticWalk walk = synthetic_walk(o);
  clip = analyse(walk);
  EXPECT_EQ(clip.legs[0].toe, "End Site");
  EXPECT_LT(largest_angle_error(clip, walk), 1e-5);
  EXPECT_THAT(clip.notes.front(), HasSubstr("no left toe joint found: the End Site of line 18, the "
                                            "first child of the ankle 'LeftFoot', stands for the "
                                            "toe base"));
}

TEST(MocapSynthetic, ACalibrationFirstFrameIsSkippedUnlessToldOtherwise) {
  SyntheticOptions o;
  o.calibration = true;
  const SyntheticWalk walk = synthetic_walk(o);
  EXPECT_EQ(analyse(walk).skipped_frames, 1u);
  EXPECT_LT(largest_angle_error(analyse(walk), walk), 1e-5);
  io::ClipOptions keep;
  keep.skip = 0;
  EXPECT_EQ(analyse(walk, keep).motion.frames.size(), walk.angles.size() + 1);
  keep.skip = 301;
  EXPECT_THROW(analyse(walk, keep), MocapError);
  // Motion frames are not a calibration pose.
  EXPECT_EQ(analyse(synthetic_walk({})).skipped_frames, 0u);
}

TEST(MocapSynthetic, TheMotionIsTheRigsPoseAndItsPoints) {
  const SyntheticWalk walk = synthetic_walk({});
  const io::CapturedClip clip = analyse(walk);
  const eval::Motion& m = clip.motion;
  EXPECT_TRUE(m.captured);
  EXPECT_NEAR(m.fps, 100.0, 1e-9);
  EXPECT_NEAR(m.frames[0].pose.pelvis.x, 0.0, 1e-12);
  for (std::size_t i = 0; i < m.frames.size(); i += 37) {
    const eval::Frame& f = m.frames[i];
    EXPECT_NEAR(f.time, 0.01 * static_cast<double>(i), 1e-12);
    EXPECT_EQ(f.pose.pelvis_tilt, 0.0);
    EXPECT_NEAR(f.pose.pelvis.x, 1.2 * f.time, 1e-6);
    for (std::size_t s = 0; s < 2; ++s) {
      const rig::LegPoints p =
          rig::forward_kinematics(m.segments, f.pose.pelvis, 0.0, f.pose.legs[s]);
      EXPECT_EQ(p.tip.x, f.points[s].tip.x);
      EXPECT_EQ(p.tip.y, f.points[s].tip.y);
    }
  }
  // The ground passes under the first frame's root at height 0.
  EXPECT_NEAR(clip.ground.height(0.0), 0.0, 1e-12);
}

TEST(MocapSynthetic, TheRotationsComposeInTheChannelsOrder) {
  // A left hip turned by Zrotation 30, Xrotation 40, Yrotation 50 in that order (the root
  // unturned, walking towards +Z): the thigh is R = Rz(30) Rx(40) Ry(50) applied to (0, -1, 0),
  // and its inclination atan2(forward, -up).
  auto rot = [](int axis, double deg) {
    const double c = std::cos(radians(deg));
    const double s = std::sin(radians(deg));
    std::array<double, 9> m{};
    if (axis == 0) m = {1, 0, 0, 0, c, -s, 0, s, c};
    if (axis == 1) m = {c, 0, s, 0, 1, 0, -s, 0, c};
    if (axis == 2) m = {c, -s, 0, s, c, 0, 0, 0, 1};
    return m;
  };
  auto mul = [](const std::array<double, 9>& a, const std::array<double, 9>& b) {
    std::array<double, 9> m{};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k)
          m[3 * r + c] += a[3 * r + k] * b[3 * k + c];
    return m;
  };
  // R (0, -1, 0) is minus R's middle column: forward (z) -r[7], up (y) -r[4].
  auto inclination = [](const std::array<double, 9>& r) {
    return degrees(std::atan2(-r[7], r[4]));
  };
  const double expected = inclination(mul(mul(rot(2, 30), rot(0, 40)), rot(1, 50)));
  SyntheticOptions o;
  o.rotation_order = "Zrotation Xrotation Yrotation";
  SyntheticWalk walk = synthetic_walk(o);
  // Replace the left hip's three rotation values of every frame by 30 40 50: the row's columns
  // are root 6, left UpLeg 3, ...
  std::istringstream in(walk.text);
  std::string line;
  std::string text;
  bool rows = false;
  while (std::getline(in, line)) {
    if (rows) {
      std::istringstream cells(line);
      std::vector<std::string> v{std::istream_iterator<std::string>(cells), {}};
      v[6] = "30";
      v[7] = "40";
      v[8] = "50";
      line.clear();
      for (const std::string& c : v)
        line += (line.empty() ? "" : " ") + c;
    }
    if (line.rfind("Frame Time", 0) == 0) rows = true;
    text += line + "\n";
  }
  walk.text = text;
  const io::CapturedClip clip = analyse(walk);
  EXPECT_NEAR(degrees(clip.motion.frames[5].pose.legs[0].hip), expected, 1e-6);
  // Composed the other way round, the same values make another rotation.
  EXPECT_GT(std::abs(expected - inclination(mul(mul(rot(1, 50), rot(0, 40)), rot(2, 30)))), 1.0);
}

// ---------------------------------------------------------------------------------------------
// Leg mappings.

TEST(MocapMapping, OtherNamesAreReadThroughAMappingFile) {
  SyntheticOptions o;
  o.renamed = {{"Hips", "pelvis"},     {"LeftUpLeg", "thigh_l"},  {"LeftLeg", "calf_l"},
               {"LeftFoot", "foot_l"}, {"LeftToeBase", "ball_l"}, {"RightUpLeg", "thigh_r"},
               {"RightLeg", "calf_r"}, {"RightFoot", "foot_r"},   {"RightToeBase", "ball_r"}};
  const SyntheticWalk walk = synthetic_walk(o);
  // The built-in names do not find them, and say how to go on.
  try {
    analyse(walk);
    ADD_FAILURE() << "read without a mapping";
  } catch (const MocapError& e) {
    EXPECT_THAT(e.what(), HasSubstr("synthetic.bvh: expected a left hip joint (one of LeftUpLeg"));
    EXPECT_THAT(e.what(), HasSubstr("--map"));
  }
  const std::string json = R"({
  "root": "pelvis",
  "left":  {"hip": "thigh_l", "knee": "calf_l", "ankle": "foot_l", "toe": "ball_l"},
  "right": {"hip": "thigh_r", "knee": "calf_r", "ankle": "foot_r", "toe": "ball_r"}
})";
  const std::filesystem::path file = scratch("map.json");
  std::ofstream(file) << json;
  io::ClipOptions options;
  options.mapping = io::read_leg_mapping_file(file);
  const io::CapturedClip clip = analyse(walk, options);
  EXPECT_EQ(clip.root, "pelvis");
  EXPECT_EQ(clip.legs[1].knee, "calf_r");
  EXPECT_LT(largest_angle_error(clip, walk), 1e-5);
  // A joint the skeleton lacks: the mapping's file, the field and the joint.
  options.mapping = io::read_leg_mapping(
      R"({"left": {"hip": "thigh_l", "knee": "shin_l", "ankle": "foot_l"},
          "right": {"hip": "thigh_r", "knee": "calf_r", "ankle": "foot_r"}})",
      "legs.json");
  try {
    analyse(walk, options);
    ADD_FAILURE() << "read with a joint missing";
  } catch (const MocapError& e) {
    EXPECT_STREQ(e.what(), "legs.json: left.knee: no joint 'shin_l' in synthetic.bvh");
  }
  // A chain out of order.
  options.mapping = io::read_leg_mapping(
      R"({"left": {"hip": "calf_l", "knee": "thigh_l", "ankle": "foot_l"},
          "right": {"hip": "thigh_r", "knee": "calf_r", "ankle": "foot_r"}})",
      "legs.json");
  EXPECT_THROW(
      {
        try {
          analyse(walk, options);
        } catch (const MocapError& e) {
          EXPECT_THAT(e.what(),
                      HasSubstr("expected the left knee 'thigh_l' below the hip 'calf_l'"));
          throw;
        }
      },
      MocapError);
}

TEST(MocapMapping, AMalformedMappingFileIsRefusedNamingTheLineAndField) {
  auto error = [](const std::string& json) {
    try {
      io::read_leg_mapping(json, "legs.json");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error("[]"), "legs.json:1: expected a JSON object found an array");
  EXPECT_EQ(
      error("{\n\"left\": {\"hip\": \"a\", \"knee\": \"b\", \"ankle\": \"c\"},\n"
            "\"right\": {\"hip\": \"d\", \"knee\": \"e\", \"ankle\": \"f\", \"heel\": \"g\"}}"),
      "legs.json:3: expected 'hip', 'knee', 'ankle', 'toe' in 'right' found 'heel'");
  EXPECT_EQ(error("{\"left\": {\"hip\": \"a\", \"knee\": \"b\", \"ankle\": \"c\"}}"),
            "legs.json:1: expected the field 'right'");
  EXPECT_EQ(error("{\"left\": {\"hip\": \"a\", \"ankle\": \"c\"}, \"right\": {}}"),
            "legs.json:1: expected the field 'left.knee'");
  EXPECT_EQ(
      error("{\"left\": {\"hip\": \"a\", \"knee\": 3, \"ankle\": \"c\"}, \"right\": {}}"),
      "legs.json:1: expected a joint name (a non-empty string) in 'left.knee' found a number");
  EXPECT_EQ(error("{\"lefty\": {}}"),
            "legs.json:1: expected 'root', 'left', 'right' in the mapping found 'lefty'");
  EXPECT_THAT(error("{\"left\": "), HasSubstr("legs.json:1:"));
  EXPECT_THAT(error(""), HasSubstr("legs.json:1:"));
}

// ---------------------------------------------------------------------------------------------
// The reader on malformed text.

// A tiny skeleton (one joint and an End Site) with two frames; the tests below break it.
const std::string kTiny =
    "HIERARCHY\n"                                                                 // 1
    "ROOT Hips\n"                                                                 // 2
    "{\n"                                                                         // 3
    "  OFFSET 0 0 0\n"                                                            // 4
    "  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"  // 5
    "  JOINT Leg\n"                                                               // 6
    "  {\n"                                                                       // 7
    "    OFFSET 0 -40 0\n"                                                        // 8
    "    CHANNELS 3 Zrotation Yrotation Xrotation\n"                              // 9
    "    End Site\n"                                                              // 10
    "    {\n"                                                                     // 11
    "      OFFSET 0 -40 0\n"                                                      // 12
    "    }\n"                                                                     // 13
    "  }\n"                                                                       // 14
    "}\n"                                                                         // 15
    "MOTION\n"                                                                    // 16
    "Frames: 2\n"                                                                 // 17
    "Frame Time: 0.01\n"                                                          // 18
    "0 90 0 0 0 0 0 0 10\n"                                                       // 19
    "1 90 0 0 0 0 0 0 20\n";                                                      // 20

// kTiny with line `number` (from 1) replaced by `text` (several lines, or none).
std::string with_line(int number, const std::string& text) {
  std::istringstream in(kTiny);
  std::string line;
  std::string out;
  for (int n = 1; std::getline(in, line); ++n) {
    if (n != number) {
      out += line + "\n";
    } else if (!text.empty()) {
      out += text + "\n";
    }
  }
  return out;
}

TEST(BvhReader, ReadsTheHierarchyAndTheFrames) {
  const io::BvhClip clip = io::read_bvh(kTiny, "tiny.bvh");
  ASSERT_EQ(clip.joints.size(), 3u);
  EXPECT_EQ(clip.joints[0].name, "Hips");
  EXPECT_EQ(clip.joints[1].name, "Leg");
  EXPECT_EQ(clip.joints[1].parent, 0);
  EXPECT_EQ(clip.joints[1].offset[1], -40.0);
  EXPECT_EQ(clip.joints[1].first_column, 6u);
  EXPECT_EQ(clip.joints[1].line, 6);
  EXPECT_TRUE(clip.joints[2].end_site);
  EXPECT_EQ(clip.joints[2].parent, 1);
  EXPECT_EQ(clip.channel_count, 9u);
  ASSERT_EQ(clip.frame_count(), 2u);
  EXPECT_EQ(clip.frame(1)[8], 20.0);
  EXPECT_EQ(clip.frame_time, 0.01);
  EXPECT_EQ(clip.joints[0].channels[3], io::BvhChannel::Zrotation);
  EXPECT_EQ(clip.find("Leg"), 1);
  EXPECT_EQ(clip.find("End Site"), -1);
}

TEST(BvhReader, ReadsWhatWritersVaryIn) {
  // CRLF line ends.
  std::string crlf;
  for (char c : kTiny) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  EXPECT_EQ(io::read_bvh(crlf, "crlf.bvh").frame_count(), 2u);
  // Tabs, a name with a space and its brace on the same line.
  std::string text = with_line(6, "\tJOINT Left Leg {");
  text.erase(text.find("  {\n    OFFSET 0 -40"), 4);
  EXPECT_EQ(io::read_bvh(text, "brace.bvh").joints[1].name, "Left Leg");
  // "Frames :" and "Frame Time :", a leading '+', ".5e2", blank lines between and after rows.
  text = with_line(17, "Frames : 2");
  text = text.replace(text.find("Frame Time:"), 11, "Frame Time :");
  text = text.replace(text.find("0 90 0"), 6, "+0 .5e2 0");
  text = text.replace(text.find("\n1 90"), 1, "\n\n");
  const io::BvhClip varied = io::read_bvh(text + "\n\n", "varied.bvh");
  EXPECT_EQ(varied.frame(0)[1], 50.0);
  // A joint without channels.
  text = with_line(9, "    CHANNELS 0");
  text = text.replace(text.find("0 90 0 0 0 0 0 0 10"), 19, "0 90 0 0 0 0");
  text = text.replace(text.find("1 90 0 0 0 0 0 0 20"), 19, "1 90 0 0 0 0");
  EXPECT_EQ(io::read_bvh(text, "none.bvh").channel_count, 6u);
}

TEST(BvhReader, EachMalformedCaseIsRefusedNamingTheLine) {
  const std::pair<std::string, std::string> cases[] = {
      {"", "tiny.bvh:1: expected 'HIERARCHY' found the end of the file"},
      {with_line(1, "HIERARCHIE"), "tiny.bvh:1: expected 'HIERARCHY' found 'HIERARCHIE'"},
      {with_line(2, "JOINT Hips"), "tiny.bvh:2: expected 'ROOT' found 'JOINT'"},
      {with_line(2, "ROOT"),
       "tiny.bvh:2: expected a joint name after ROOT found the end of the line"},
      {with_line(6, "  JOINT {"), "tiny.bvh:6: expected a joint name after JOINT found '{'"},
      {with_line(6, "  JOINT Hips"),
       "tiny.bvh:6: expected a joint name not used before found 'Hips' (also on line 2)"},
      // A missing opening brace.
      {with_line(7, ""), "tiny.bvh:7: expected '{' found 'OFFSET'"},
      // A missing closing brace: MOTION arrives inside the root.
      {with_line(14, ""),
       "tiny.bvh:15: expected 'JOINT', 'End Site' or '}' in joint 'Hips' found 'MOTION'"},
      {with_line(13, ""),
       "tiny.bvh:15: expected 'JOINT', 'End Site' or '}' in joint 'Hips' found 'MOTION'"},
      {with_line(10, "    End Sight"), "tiny.bvh:10: expected 'Site' after 'End' found 'Sight'"},
      {with_line(8, "    OFFSET 0 -40"),
       "tiny.bvh:9: expected an OFFSET coordinate (a finite number of magnitude at most 1e9) found "
       "'CHANNELS'"},
      {with_line(8, "    OFFSET 0 nan 0"),
       "tiny.bvh:8: expected an OFFSET coordinate (a finite number of magnitude at most 1e9) found "
       "'nan'"},
      {with_line(8, "    OFFSET 0 1e400 0"),
       "tiny.bvh:8: expected an OFFSET coordinate (a finite number of magnitude at most 1e9) found "
       "'1e400'"},
      {with_line(9, ""), "tiny.bvh:9: expected 'CHANNELS' in joint 'Leg' found 'End'"},
      {with_line(9, "    CHANNELS 7 Zrotation"),
       "tiny.bvh:9: expected a channel count (a whole number from 0 to 6) found '7'"},
      {with_line(9, "    CHANNELS -3 Zrotation"),
       "tiny.bvh:9: expected a channel count (a whole number from 0 to 6) found '-3'"},
      {with_line(9, "    CHANNELS 3 Zrotation Yrotation"),
       "tiny.bvh:10: expected channel 3 of 3 (Xposition, Yposition, Zposition, Xrotation, "
       "Yrotation or Zrotation) found 'End'"},
      {with_line(9, "    CHANNELS 3 Zrotation Yrotation Wrotation"),
       "tiny.bvh:9: expected channel 3 of 3"},
      {with_line(9, "    CHANNELS 3 Zrotation Yrotation Zrotation"),
       "tiny.bvh:9: expected a channel not listed before in joint 'Leg' found 'Zrotation'"},
      {with_line(12, "      OFFSET 0 -40 0\n      CHANNELS 3 Xrotation Yrotation Zrotation"),
       "tiny.bvh:13: expected '}' closing the End Site of line 10 found 'CHANNELS'"},
      {with_line(16, "MOTON"), "tiny.bvh:16: expected 'MOTION' found 'MOTON'"},
      {with_line(15, "}\nROOT Other"), "tiny.bvh:16: expected 'MOTION' found 'ROOT'"},
      {with_line(17, "Frames: two"),
       "tiny.bvh:17: expected the frame count (a whole number from 0 to 10000000) found 'two'"},
      {with_line(17, "Frames: 0"), "tiny.bvh:17: expected at least one frame found '0'"},
      {with_line(17, "Frames: 99999999999999999999"),
       "tiny.bvh:17: expected the frame count (a whole number from 0 to 10000000) found "
       "'99999999999999999999'"},
      {with_line(18, "Frame Time: 0"),
       "tiny.bvh:18: expected a frame time from 0.0001 to 1 s found '0'"},
      {with_line(18, "Frame Time: -0.01"),
       "tiny.bvh:18: expected a frame time from 0.0001 to 1 s found '-0.01'"},
      {with_line(18, "Frame Time: nan"),
       "tiny.bvh:18: expected the frame time (a finite number of magnitude at most 1e9) found "
       "'nan'"},
      {with_line(18, "Frame Time: 0.01 0.02"),
       "tiny.bvh:18: expected the end of the line after the frame time found '0.02'"},
      {with_line(19, "0 nan 0 0 0 0 0 0 10"),
       "tiny.bvh:19: expected value 2 of frame 1 (a finite number of magnitude at most 1e9) found "
       "'nan'"},
      {with_line(19, "0 90 0 0 0 0 0 0 inf"),
       "tiny.bvh:19: expected value 9 of frame 1 (a finite number of magnitude at most 1e9) found "
       "'inf'"},
      {with_line(19, "0 90 0 0 0 0 0 0 1O"),
       "tiny.bvh:19: expected value 9 of frame 1 (a finite number of magnitude at most 1e9) found "
       "'1O'"},
      {with_line(19, "0 90 0 0 0 0 0 0 2e9"),
       "tiny.bvh:19: expected value 9 of frame 1 (a finite number of magnitude at most 1e9) found "
       "'2e9'"},
      {with_line(20, "1 90 0 0 0 0 0 0 20 30"),
       "tiny.bvh:20: expected 9 values in frame 2 (the channels' count) found more"},
      {with_line(20, "1 90 0 0 0 0 0 0"),
       "tiny.bvh:20: expected 9 values in frame 2 (the channels' count) found 8"},
      {with_line(20, ""), "tiny.bvh:20: expected 2 frames (the 'Frames:' count) found 1"},
      {with_line(17, "Frames: 1"),
       "tiny.bvh:20: expected the end of the file after 1 frame (the 'Frames:' count) found '1'"},
      {"HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 0\n}\nMOTION\nFrames: 1\nFrame Time: 0.01\n\n",
       "tiny.bvh:2: expected channels: no joint has any"},
      {"HIERARCHY\nROOT \x01\x02\n",
       "tiny.bvh:2: expected a joint name (printable characters) found '?"
       "?'"},
  };
  for (const auto& [text, message] : cases) {
    const std::string got = bvh_error(text);
    EXPECT_THAT(got, HasSubstr(message)) << text;
    EXPECT_EQ(got.rfind("tiny.bvh:", 0), 0u) << got;
  }
}

TEST(BvhReader, HugeCountsAndDeepNestingAreRefusedQuickly) {
  // A count of ten million frames and no data: refused without making room for them.
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(bvh_error(with_line(17, "Frames: 10000000")),
            "tiny.bvh:21: expected 10000000 frames (the 'Frames:' count) found 2");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  // Joints nested 64 deep read; 65 do not.
  auto nested = [](int depth) {
    std::string text =
        "HIERARCHY\nROOT J0\n{\nOFFSET 0 0 0\nCHANNELS 3 Xrotation Yrotation Zrotation\n";
    for (int k = 1; k < depth; ++k)
      text += "JOINT J" + std::to_string(k) + "\n{\nOFFSET 0 1 0\nCHANNELS 0\n";
    for (int k = 0; k < depth; ++k)
      text += "}\n";
    return text + "MOTION\nFrames: 1\nFrame Time: 0.01\n0 0 0\n";
  };
  EXPECT_EQ(bvh_error(nested(io::kMaxBvhDepth)), "");
  EXPECT_THAT(bvh_error(nested(io::kMaxBvhDepth + 1)),
              HasSubstr("expected joints nested at most 64 deep found a deeper one"));
  EXPECT_THAT(bvh_error(nested(100000)), HasSubstr("nested at most 64 deep"));
}

TEST(BvhReader, AFileIsNamedInItsErrors) {
  const std::filesystem::path file = scratch("broken.bvh");
  std::ofstream(file) << with_line(19, "0 90 0 0 0 0 0 0 x");
  try {
    io::read_bvh_file(file);
    ADD_FAILURE() << "read a broken file";
  } catch (const MocapError& e) {
    EXPECT_EQ(e.source(), file.string());
    EXPECT_EQ(e.line(), 19);
  }
  EXPECT_THROW(io::read_bvh_file(scratch("absent.bvh")), MocapError);
  EXPECT_THROW(io::read_bvh_file(scratch("")), MocapError);  // a directory
}

TEST(MocapClip, ASkeletonThatCannotWalkIsRefusedWithTheReason) {
  auto error = [](const std::string& text) {
    try {
      io::analyse_clip(io::read_bvh(text, "tiny.bvh"), "tiny.bvh");
    } catch (const MocapError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_THAT(error(kTiny), HasSubstr("tiny.bvh: expected a left hip joint"));
  // A walk whose root stands still.
  SyntheticOptions in_place;
  in_place.speed = 0.0;
  EXPECT_THAT(error(synthetic_walk(in_place).text),
              HasSubstr("expected the root 'Hips' to travel found it in place"));
  // Options out of range.
  const SyntheticWalk walk = synthetic_walk({});
  io::ClipOptions bad;
  bad.contact_height = std::nan("");
  EXPECT_THROW(analyse(walk, bad), MocapError);
  bad = {};
  bad.metres_per_unit = 0.0;
  EXPECT_THROW(analyse(walk, bad), MocapError);
}

// ---------------------------------------------------------------------------------------------
// A walk written by io::write_bvh comes back.

TEST(MocapClip, AWalkWrittenAsBvhReadsBackToItsAngles) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::Walker walker = test::make_walker(ground);
  const eval::Motion walk = eval::record(walker, 4.0, 60.0);
  std::ostringstream bvh;
  io::write_bvh(bvh, walk);
  const io::CapturedClip clip = io::analyse_clip(io::read_bvh(bvh.str(), "walk.bvh"), "walk.bvh");
  EXPECT_STREQ(io::unit_name(clip.metres_per_unit), "cm");
  EXPECT_EQ(clip.skipped_frames, 0u);
  ASSERT_EQ(clip.motion.frames.size(), walk.frames.size());
  const rig::Segments& s = clip.motion.segments;
  EXPECT_NEAR(s.thigh, walk.segments.thigh, 1e-7);
  EXPECT_NEAR(s.shank, walk.segments.shank, 1e-7);
  EXPECT_NEAR(s.ankle_height, walk.segments.ankle_height, 1e-7);
  EXPECT_NEAR(s.ball, walk.segments.ball, 1e-7);
  EXPECT_NEAR(s.toe, walk.segments.toe, 1e-7);
  EXPECT_NEAR(s.heel, walk.segments.heel, 1e-7);
  double worst = 0.0;
  for (std::size_t i = 0; i < walk.frames.size(); ++i) {
    const rig::Pose& want = walk.frames[i].pose;
    const rig::Pose& got = clip.motion.frames[i].pose;
    for (std::size_t k = 0; k < 2; ++k) {
      worst = std::max({worst,
                        std::abs(degrees(got.legs[k].hip - (want.legs[k].hip - want.pelvis_tilt))),
                        std::abs(degrees(got.legs[k].knee - want.legs[k].knee)),
                        std::abs(degrees(got.legs[k].ankle - want.legs[k].ankle)),
                        std::abs(degrees(got.legs[k].toe - std::abs(want.legs[k].toe)))});
    }
    // The pelvis where the walk had it, from its first position.
    EXPECT_NEAR(got.pelvis.x, want.pelvis.x - walk.frames[0].pose.pelvis.x, 1e-6);
  }
  EXPECT_LT(worst, 1e-4);  // the file's six decimals
}

// ---------------------------------------------------------------------------------------------
// The nine CMU clips against the Python reference.

// What tests/tools/bvh_sagittal_dump.py prints for a clip.
struct Reference {
  std::size_t skip = 0;
  double scale = 0.0;
  std::vector<std::array<double, 10>> frames;  // 8 angles (degrees), 2 contacts
  int cycles = 0;
  double cadence = 0.0, step = 0.0, speed = 0.0;
  std::map<std::string, std::vector<double>> means;  // thigh, knee, ankle
};

bool have_python() {
  return std::string(FUZZYGAIT_PYTHON3).size() > 0;
}

Reference python_reference(const std::filesystem::path& clip) {
  const auto run = run_shell(shell_quoted(FUZZYGAIT_PYTHON3) + " " +
                             shell_quoted(kSourceDir / "tests/tools/bvh_sagittal_dump.py") + " " +
                             shell_quoted(clip));
  EXPECT_EQ(run.status, 0) << run.output;
  Reference r;
  std::istringstream in(run.output);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "skip") {
      std::string scale;
      words >> r.skip >> scale >> r.scale;
    } else if (key == "frame") {
      std::array<double, 10> v{};
      for (double& x : v)
        words >> x;
      r.frames.push_back(v);
    } else if (key == "cycles") {
      std::string word;
      words >> r.cycles >> word >> r.cadence >> word >> r.step >> word >> r.speed;
    } else if (key == "mean") {
      std::string joint;
      words >> joint;
      for (double x; words >> x;)
        r.means[joint].push_back(x);
    }
  }
  return r;
}

TEST(MocapCmuClips, EveryClipMatchesThePythonReferenceFrameByFrame) {
  if (!have_python()) GTEST_SKIP() << "python3 not found when CMake configured";
  const char* joints[8] = {"l_hip", "l_knee", "l_ankle", "l_toe",
                           "r_hip", "r_knee", "r_ankle", "r_toe"};
  std::array<double, 8> overall{};
  std::printf("clip   frames skip cycles cadence step  | largest |C++ - Python| per joint, deg\n");
  for (const std::string& name : kClipNames) {
    const std::filesystem::path path = kClips / (name + ".bvh");
    const io::CapturedClip clip = io::read_clip(path);
    const Reference ref = python_reference(path);
    EXPECT_EQ(clip.skipped_frames, ref.skip) << name;
    EXPECT_EQ(clip.metres_per_unit, ref.scale) << name;
    ASSERT_EQ(clip.motion.frames.size(), ref.frames.size()) << name;
    std::array<double, 8> largest{};
    std::size_t contact_differences = 0;
    for (std::size_t i = 0; i < ref.frames.size(); ++i) {
      const eval::Frame& f = clip.motion.frames[i];
      for (std::size_t s = 0; s < 2; ++s) {
        const rig::LegAngles& a = f.pose.legs[s];
        const double got[4] = {a.hip, a.knee, a.ankle, a.toe};
        for (std::size_t j = 0; j < 4; ++j) {
          const double d = std::abs(degrees(got[j]) - ref.frames[i][4 * s + j]);
          largest[4 * s + j] = std::max(largest[4 * s + j], d);
        }
        contact_differences += f.contact[s] != (ref.frames[i][8 + s] == 1.0) ? 1 : 0;
      }
    }
    std::printf("%s %6zu %4zu %6zu %7.1f %5.3f |", name.c_str(), clip.motion.frames.size(),
                clip.skipped_frames, clip.cycles.size(), clip.cadence, clip.step_length);
    for (std::size_t j = 0; j < 8; ++j) {
      std::printf(" %s %.1e", joints[j], largest[j]);
      EXPECT_LT(largest[j], 0.5) << name << " " << joints[j];
      overall[j] = std::max(overall[j], largest[j]);
    }
    std::printf("\n");
    EXPECT_EQ(contact_differences, 0u) << name;
    EXPECT_EQ(static_cast<int>(clip.cycles.size()), ref.cycles) << name;
    EXPECT_NEAR(clip.cadence, ref.cadence, 1e-9) << name;
    EXPECT_NEAR(clip.step_length, ref.step, 1e-9) << name;
    EXPECT_NEAR(clip.speed, ref.speed, 1e-9) << name;
  }
  for (std::size_t j = 0; j < 8; ++j)
    RecordProperty(std::string("largest_difference_deg_") + joints[j], std::to_string(overall[j]));
}

TEST(MocapCmuClips, EveryClipReadsWithoutPython) {
  // The figures data/SOURCES.md gives for each clip (rounded as there).
  const std::map<std::string, std::array<double, 3>> table = {
      {"07_01", {1.37, 112, 0.66}}, {"07_02", {1.33, 110, 0.63}}, {"07_03", {1.02, 99, 0.55}},
      {"07_06", {1.24, 104, 0.63}}, {"08_01", {1.59, 120, 0.72}}, {"08_02", {1.55, 118, 0.71}},
      {"08_03", {1.52, 118, 0.70}}, {"08_06", {1.74, 130, 0.71}}, {"05_01", {0.92, 98, 0.50}}};
  for (const std::string& name : kClipNames) {
    const io::CapturedClip clip = io::read_clip(kClips / (name + ".bvh"));
    EXPECT_EQ(clip.skipped_frames, 1u) << name;
    EXPECT_STREQ(io::unit_name(clip.metres_per_unit), "CMU") << name;
    EXPECT_EQ(clip.up, io::UpAxis::Y) << name;
    EXPECT_EQ(clip.root, "Hips");
    EXPECT_EQ(clip.legs[0].hip, "LeftUpLeg");
    EXPECT_EQ(clip.legs[1].toe, "RightToeBase");
    EXPECT_GE(clip.cycles.size(), 1u) << name;
    const auto& [speed, cadence, step] = table.at(name);
    EXPECT_NEAR(clip.speed, speed, 0.006) << name;
    EXPECT_NEAR(clip.cadence, cadence, 0.6) << name;
    EXPECT_NEAR(clip.step_length, step, 0.006) << name;
    EXPECT_TRUE(clip.notes.empty()) << name << ": " << clip.notes.front();
  }
}

// The body's travel and the curve features `fuzzygait eval` reports, measured on people: each
// clip's pelvis keeps its forward speed within 0.6-1.45 of its stride's mean and rises no faster
// than 0.5 m/s, its ankle pushes off (plantarflexed 5 deg or more; 05_01, a dancer's walk, keeps
// its ankle at +5) and its thigh lands without
// swinging more than 5 deg past its contact angle. (The walker's default surges to 2.2-2.7 times
// its mean: docs/walk.md, "Speed".)
TEST(MocapCmuClips, BodyTravelAndCurveFeaturesArePeoples) {
  for (const std::string& name : kClipNames) {
    const io::CapturedClip clip = io::read_clip(kClips / (name + ".bvh"));
    const eval::GaitReport r = eval::evaluate(clip.motion, clip.ground);
    EXPECT_GE(r.pelvis_speed_ratio_min, 0.6) << name;
    EXPECT_LT(r.pelvis_speed_ratio_min, 1.0) << name;
    EXPECT_GT(r.pelvis_speed_ratio_max, 1.0) << name;
    EXPECT_LE(r.pelvis_speed_ratio_max, 1.45) << name;
    EXPECT_GT(r.pelvis_rise_speed, 0.05) << name;
    EXPECT_LE(r.pelvis_rise_speed, 0.5) << name;
    if (name != "05_01") {
      EXPECT_LE(r.ankle_push_off, -5.0) << name;
    }
    EXPECT_LE(r.thigh_overshoot, 5.0) << name;
    std::printf(
        "%s: pelvis speed %.2f-%.2f of its mean, rising at most %.2f m/s; thigh overshoot "
        "%.1f, knee in loading %.1f, push off %.1f deg\n",
        name.c_str(), r.pelvis_speed_ratio_min, r.pelvis_speed_ratio_max, r.pelvis_rise_speed,
        r.thigh_overshoot, r.knee_loading_peak, r.ankle_push_off);
  }
}

// ---------------------------------------------------------------------------------------------
// `fuzzygait mocap` as a user runs it.

// The left mean cycle the reference prints with --cycles: 51 rows "pct thigh knee ankle".
std::map<std::string, std::vector<double>> python_cycle_means(const std::filesystem::path& clip) {
  const auto run = run_shell(shell_quoted(FUZZYGAIT_PYTHON3) + " " +
                             shell_quoted(kSourceDir / "tests/tools/bvh_sagittal.py") + " " +
                             shell_quoted(clip) + " --cycles");
  EXPECT_EQ(run.status, 0) << run.output;
  std::map<std::string, std::vector<double>> means;
  std::istringstream in(run.output);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    int percent = 0;
    double thigh = 0.0, knee = 0.0, ankle = 0.0;
    if (words >> percent >> thigh >> knee >> ankle) {
      means["thigh"].push_back(thigh);
      means["knee"].push_back(knee);
      means["ankle"].push_back(ankle);
    }
  }
  return means;
}

TEST(MocapCommand, WritesAWalksFilesAndEvalMeasuresThemAsThePythonToolDoes) {
  for (const std::string& name : kClipNames) {
    const std::filesystem::path prefix = scratch("cli_" + name);
    const std::vector<std::string> files = {".csv", ".terrain.csv", ".bvh", ".svg", ".poses.svg"};
    for (const std::string& ext : files)
      std::filesystem::remove(prefix.string() + ext);
    const std::filesystem::path clip = kClips / (name + ".bvh");
    const auto run =
        test::run_program("mocap " + shell_quoted(clip) + " -o " + shell_quoted(prefix));
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_THAT(run.output,
                HasSubstr("unit 0.05644444444444444 m (CMU, guessed), up +Y (detected)"));
    EXPECT_THAT(run.output, HasSubstr("thigh RMSE"));
    for (const std::string& ext : files)
      EXPECT_TRUE(std::filesystem::exists(prefix.string() + ext)) << name << ext;
    EXPECT_THAT(test::read_text(prefix.string() + ".bvh"), HasSubstr("ROOT Hips"));

    const auto eval =
        test::run_program("eval " + shell_quoted(prefix.string() + ".csv") + " --json -");
    ASSERT_EQ(eval.status, 0) << eval.output;
    const nlohmann::json report = nlohmann::json::parse(eval.output);
    const io::CapturedClip read = io::read_clip(clip);
    EXPECT_EQ(report["cycles"].get<std::size_t>(), read.cycles.size()) << name;
    if (!have_python()) continue;
    const auto means = python_cycle_means(clip);
    for (const char* joint : {"thigh", "knee", "ankle"}) {
      const std::vector<double> ours = report["mean_cycle"][joint].get<std::vector<double>>();
      ASSERT_EQ(means.at(joint).size(), ours.size()) << name << " " << joint;
      double largest = 0.0;
      for (std::size_t k = 0; k < ours.size(); ++k)
        largest = std::max(largest, std::abs(ours[k] - means.at(joint)[k]));
      // The tool prints one decimal: 0.05 of the difference is its rounding.
      EXPECT_LT(largest, 0.5) << name << " " << joint;
      EXPECT_LT(largest, 0.051) << name << " " << joint;
    }
  }
}

TEST(MocapCommand, SameClipSameBytes) {
  const std::filesystem::path clip = kClips / "05_01.bvh";
  const std::filesystem::path a = scratch("same_a");
  const std::filesystem::path b = scratch("same_b");
  for (const auto& prefix : {a, b}) {
    const auto run =
        test::run_program("mocap " + shell_quoted(clip) + " -o " + shell_quoted(prefix));
    ASSERT_EQ(run.status, 0) << run.output;
  }
  for (const char* ext : {".csv", ".terrain.csv", ".bvh", ".svg", ".poses.svg"}) {
    EXPECT_EQ(test::read_text(a.string() + ext), test::read_text(b.string() + ext)) << ext;
    EXPECT_FALSE(test::read_text(a.string() + ext).empty()) << ext;
  }
}

TEST(MocapCommand, OptionsTakeEffect) {
  SyntheticOptions o;
  o.up = io::UpAxis::Z;
  o.units_per_metre = 1000.0;
  o.calibration = true;
  const std::filesystem::path bvh = scratch("z_up_clip.bvh");
  std::ofstream(bvh) << synthetic_walk(o).text;
  const std::filesystem::path prefix = scratch("z_up");
  auto run = test::run_program("mocap " + shell_quoted(bvh) + " -o " + shell_quoted(prefix) +
                               " --up z --unit 0.001 --skip 1 --reference schwartz2008_slow");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("skipped 1 frame"));
  EXPECT_THAT(run.output, HasSubstr("unit 0.001 m (mm, given), up +Z (given)"));
  EXPECT_THAT(run.output, HasSubstr("against schwartz2008_slow"));
  run =
      test::run_program("mocap " + shell_quoted(bvh) + " -o " + shell_quoted(prefix) + " --skip 0");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("read 301 frames"));
  EXPECT_THAT(run.output, HasSubstr("up +Z (detected)"));
}

TEST(MocapCommand, ErrorsNameTheFileLineAndField) {
  const std::filesystem::path prefix = scratch("refused");
  auto refused = [&](const std::string& arguments, const std::string& reason) {
    const auto run = test::run_program("mocap " + arguments + " -o " + shell_quoted(prefix));
    EXPECT_EQ(run.status, 1) << arguments << "\n" << run.output;
    EXPECT_THAT(run.output, HasSubstr(reason)) << arguments;
  };
  const std::filesystem::path broken = scratch("broken_cli.bvh");
  std::ofstream(broken) << with_line(20, "1 90 0 0 0 0 0 0");
  refused(shell_quoted(broken), broken.string() + ":20: expected 9 values in frame 2");
  refused(shell_quoted(scratch("absent.bvh")), "absent.bvh: cannot open the file");
  const std::filesystem::path clip = kClips / "07_01.bvh";
  refused(shell_quoted(clip) + " --up x", "--up must be y or z, got 'x'");
  refused(shell_quoted(clip) + " --unit -1", "--unit must be metres per unit");
  refused(shell_quoted(clip) + " --unit nan", "--unit must be metres per unit");
  const std::filesystem::path map = scratch("bad_map.json");
  std::ofstream(map) << "{\"left\": {\"hip\": \"LeftUpLeg\", \"knee\": \"LeftKnee\", \"ankle\": "
                        "\"LeftFoot\"},\n \"right\": {\"hip\": \"RightUpLeg\", \"knee\": "
                        "\"RightLeg\", \"ankle\": \"RightFoot\"}}";
  refused(shell_quoted(clip) + " --map " + shell_quoted(map),
          map.string() + ": left.knee: no joint 'LeftKnee' in " + clip.string());
  std::ofstream(map) << "{\"left\": 1}";
  refused(shell_quoted(clip) + " --map " + shell_quoted(map),
          map.string() + ":1: expected an object");
  refused(shell_quoted(clip) + " --skip 400",
          "expected at least 2 frames after skipping 400 found 0");
  EXPECT_FALSE(std::filesystem::exists(prefix.string() + ".csv"));
  // The clip is not overwritten by PREFIX.bvh.
  const std::filesystem::path copy = scratch("own.bvh");
  std::filesystem::copy_file(clip, copy, std::filesystem::copy_options::overwrite_existing);
  const auto run =
      test::run_program("mocap " + shell_quoted(copy) + " -o " + shell_quoted(scratch("own")));
  EXPECT_EQ(run.status, 1);
  EXPECT_THAT(run.output, HasSubstr("-o: '" + scratch("own").string() + ".bvh' would overwrite"));
  EXPECT_EQ(test::read_text(copy), test::read_text(clip));
}

}  // namespace
}  // namespace fuzzygait

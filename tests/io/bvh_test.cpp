// BVH export: a small parser written here from the format's description (not from bvh.cpp) reads
// the file back, forward kinematics of its hierarchy and channels must land on the walk's joint
// points and give back its clinical angles; the hierarchy follows the rig, the rest pose stands,
// the output is byte for byte deterministic, and bad input is refused.
#include "fuzzygait/io/bvh.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace {

using fuzzygait::eval::Frame;
using fuzzygait::eval::Motion;
using fuzzygait::io::BvhOptions;
using fuzzygait::io::write_bvh;
using fuzzygait::rig::degrees;
using fuzzygait::rig::LegAngles;
using fuzzygait::rig::LegPoints;
using fuzzygait::rig::Point;
using fuzzygait::rig::radians;
using fuzzygait::rig::Segments;
using ::testing::HasSubstr;
using ::testing::Not;

// Tolerances the file's six decimals allow (degrees, metres).
constexpr double kAngleTolerance = 1e-4;
constexpr double kPositionTolerance = 1e-5;

using Vec3 = std::array<double, 3>;
using Mat3 = std::array<Vec3, 3>;  // rows

Mat3 multiply(const Mat3& a, const Mat3& b) {
  Mat3 m{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 3; ++k)
        m[i][j] += a[i][k] * b[k][j];
    }
  }
  return m;
}

Vec3 transform(const Mat3& a, const Vec3& v) {
  return {a[0][0] * v[0] + a[0][1] * v[1] + a[0][2] * v[2],
          a[1][0] * v[0] + a[1][1] * v[1] + a[1][2] * v[2],
          a[2][0] * v[0] + a[2][1] * v[1] + a[2][2] * v[2]};
}

// Right-handed rotation about one axis (0 = X, 1 = Y, 2 = Z).
Mat3 rotation(int axis, double angle_degrees) {
  const double c = std::cos(radians(angle_degrees));
  const double s = std::sin(radians(angle_degrees));
  const int u = (axis + 1) % 3;
  const int v = (axis + 2) % 3;
  Mat3 m{};
  m[axis][axis] = 1.0;
  m[u][u] = c;
  m[u][v] = -s;
  m[v][u] = s;
  m[v][v] = c;
  return m;
}

// ---- A BVH reader for the test -------------------------------------------------------------

struct BvhNode {
  std::string name;  // "End Site" for end sites
  int parent = -1;
  Vec3 offset{};
  std::vector<std::string> channels;
  std::size_t first_value = 0;  // index of its first channel in a frame's values
};

struct Bvh {
  std::vector<BvhNode> nodes;  // file order, parents before children
  std::size_t channel_count = 0;
  std::size_t frame_count = 0;
  double frame_time = 0.0;
  std::vector<std::vector<double>> frames;

  int find(const std::string& name) const {
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      if (nodes[i].name == name) return static_cast<int>(i);
    }
    throw std::runtime_error("no joint " + name);
  }
  int end_site_of(const std::string& name) const {
    const int parent = find(name);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      if (nodes[i].parent == parent && nodes[i].name == "End Site") return static_cast<int>(i);
    }
    throw std::runtime_error("no End Site under " + name);
  }
};

class BvhReader {
 public:
  explicit BvhReader(const std::string& text) : in_(text) {}

  Bvh read() {
    expect("HIERARCHY");
    expect("ROOT");
    node(-1, word());
    expect("MOTION");
    expect("Frames:");
    bvh_.frame_count = static_cast<std::size_t>(std::stoul(word()));
    expect("Frame");
    expect("Time:");
    bvh_.frame_time = number();
    for (std::size_t f = 0; f < bvh_.frame_count; ++f) {
      std::vector<double> values(bvh_.channel_count);
      for (double& v : values)
        v = number();
      bvh_.frames.push_back(std::move(values));
    }
    std::string extra;
    if (in_ >> extra) throw std::runtime_error("text after the last frame: " + extra);
    return bvh_;
  }

 private:
  std::string word() {
    std::string w;
    if (!(in_ >> w)) throw std::runtime_error("unexpected end of file");
    return w;
  }
  double number() {
    const std::string w = word();
    std::size_t used = 0;
    const double v = std::stod(w, &used);
    if (used != w.size()) throw std::runtime_error("not a number: " + w);
    return v;
  }
  void expect(const std::string& what) {
    const std::string w = word();
    if (w != what) throw std::runtime_error("expected " + what + ", got " + w);
  }
  void node(int parent, const std::string& name) {
    BvhNode n;
    n.name = name;
    n.parent = parent;
    expect("{");
    expect("OFFSET");
    for (double& v : n.offset)
      v = number();
    const bool end_site = name == "End Site";
    if (!end_site) {
      expect("CHANNELS");
      const std::size_t count = std::stoul(word());
      for (std::size_t i = 0; i < count; ++i)
        n.channels.push_back(word());
      n.first_value = bvh_.channel_count;
      bvh_.channel_count += count;
    }
    const int index = static_cast<int>(bvh_.nodes.size());
    bvh_.nodes.push_back(n);
    for (std::string w = word(); w != "}"; w = word()) {
      if (end_site) throw std::runtime_error("an End Site has no children");
      if (w == "JOINT") {
        node(index, word());
      } else if (w == "End") {
        expect("Site");
        node(index, "End Site");
      } else {
        throw std::runtime_error("unexpected " + w);
      }
    }
  }

  std::istringstream in_;
  Bvh bvh_;
};

Bvh read(const std::string& text) {
  return BvhReader(text).read();
}

struct Transform {
  Mat3 rotation;
  Vec3 position;
};

// World transforms of every node in one frame: local = translate(offset, or the position
// channels for the root) then the rotation channels multiplied in the order listed.
std::vector<Transform> forward_kinematics(const Bvh& bvh, std::size_t frame) {
  std::vector<Transform> world(bvh.nodes.size());
  for (std::size_t i = 0; i < bvh.nodes.size(); ++i) {
    const BvhNode& n = bvh.nodes[i];
    Vec3 translation = n.offset;
    Mat3 local = rotation(0, 0.0);
    for (std::size_t c = 0; c < n.channels.size(); ++c) {
      const double value = bvh.frames[frame][n.first_value + c];
      const std::string& channel = n.channels[c];
      const int axis = channel[0] - 'X';
      if (channel.substr(1) == "position") {
        translation[static_cast<std::size_t>(axis)] += value;
      } else {
        local = multiply(local, rotation(axis, value));
      }
    }
    if (n.parent < 0) {
      world[i] = {local, translation};
    } else {
      const Transform& p = world[static_cast<std::size_t>(n.parent)];
      const Vec3 moved = transform(p.rotation, translation);
      world[i] = {multiply(p.rotation, local),
                  {p.position[0] + moved[0], p.position[1] + moved[1], p.position[2] + moved[2]}};
    }
  }
  return world;
}

// Counter-clockwise angle (degrees) of a node's forward axis in the (Z forward, Y up) plane.
double sagittal(const Transform& t) {
  return degrees(std::atan2(t.rotation[1][2], t.rotation[2][2]));
}

// ---- Motions -------------------------------------------------------------------------------

Motion walk(double seconds, double fps) {
  static const fuzzygait::gait::ControllerSet controllers =
      fuzzygait::gait::ControllerSet::builtin("default");
  static const fuzzygait::terrain::Terrain ground = fuzzygait::terrain::Terrain::flat();
  fuzzygait::gait::Walker walker(controllers, fuzzygait::gait::WalkerOptions{}, ground);
  return fuzzygait::eval::record(walker, seconds, fps);
}

// A motion made of the given poses, with the rig's own joint points.
Motion from_poses(const Segments& segments, const std::vector<fuzzygait::rig::Pose>& poses) {
  Motion m;
  m.fps = 30.0;
  m.segments = segments;
  for (const fuzzygait::rig::Pose& pose : poses) {
    Frame f;
    f.time = static_cast<double>(m.frames.size()) / m.fps;
    f.pose = pose;
    for (std::size_t leg = 0; leg < 2; ++leg) {
      f.points[leg] = fuzzygait::rig::forward_kinematics(segments, pose.pelvis, pose.pelvis_tilt,
                                                         pose.legs[leg]);
    }
    m.frames.push_back(f);
  }
  return m;
}

std::string bvh_text(const Motion& motion, const BvhOptions& options = {}) {
  std::ostringstream out;
  write_bvh(out, motion, options);
  return out.str();
}

void expect_near(const Vec3& got, const Vec3& expected) {
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(got[i], expected[i], 1e-6) << "component " << i;
}

double wrap_degrees(double d) {
  return std::remainder(d, 360.0);
}

// Checks every frame of `bvh` against `motion`: the sagittal joint points (BVH z, y against the
// walk's x, y), the legs' lateral places, the clinical angles, and purely sagittal rotations.
void expect_reproduces(const Bvh& bvh, const Motion& motion, double units_per_metre) {
  ASSERT_EQ(bvh.frame_count, motion.frames.size());
  const double half_width = 0.5 * fuzzygait::io::bvh_hip_width(motion.segments);
  const char* side_names[] = {"Left", "Right"};
  double worst_angle = 0.0;
  double worst_position = 0.0;
  for (std::size_t f = 0; f < motion.frames.size(); ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    const Frame& frame = motion.frames[f];
    const std::vector<Transform> world = forward_kinematics(bvh, f);
    const Transform& hips = world[static_cast<std::size_t>(bvh.find("Hips"))];
    const double pelvis = sagittal(hips);
    const auto angle_error = [&](double bvh_degrees, double radians_expected) {
      const double e = std::abs(wrap_degrees(bvh_degrees - degrees(radians_expected)));
      worst_angle = std::max(worst_angle, e);
      return e;
    };
    EXPECT_LT(angle_error(-pelvis, frame.pose.pelvis_tilt), kAngleTolerance);
    for (std::size_t leg = 0; leg < 2; ++leg) {
      const std::string side = side_names[leg];
      const auto at = [&](const std::string& joint) -> const Transform& {
        return world[static_cast<std::size_t>(bvh.find(side + joint))];
      };
      const double thigh = sagittal(at("UpLeg"));
      const double shank = sagittal(at("Leg"));
      const double foot = sagittal(at("Foot"));
      const double toes = sagittal(at("ToeBase"));
      const LegAngles& a = frame.pose.legs[leg];
      EXPECT_LT(angle_error(thigh - pelvis, a.hip), kAngleTolerance) << side << " hip";
      EXPECT_LT(angle_error(thigh, a.hip - frame.pose.pelvis_tilt), kAngleTolerance)
          << side << " thigh inclination";
      EXPECT_LT(angle_error(thigh - shank, a.knee), kAngleTolerance) << side << " knee";
      EXPECT_LT(angle_error(foot - shank, a.ankle), kAngleTolerance) << side << " ankle";
      EXPECT_LT(angle_error(toes - foot, a.toe), kAngleTolerance) << side << " toe";
      // Every joint turns about the lateral axis only: X stays X.
      for (const char* joint : {"UpLeg", "Leg", "Foot", "ToeBase"}) {
        EXPECT_NEAR(at(joint).rotation[0][0], 1.0, 1e-12) << side << joint;
      }

      const LegPoints& p = frame.points[leg];
      const std::pair<Point, Vec3> pairs[] = {
          {p.hip, at("UpLeg").position},
          {p.knee, at("Leg").position},
          {p.ankle, at("Foot").position},
          {p.ball, at("ToeBase").position},
          {p.tip, world[static_cast<std::size_t>(bvh.end_site_of(side + "ToeBase"))].position}};
      for (const auto& [expected, got] : pairs) {
        const double lateral = leg == 0 ? half_width : -half_width;  // left is +X
        for (const double e : {std::abs(got[0] / units_per_metre - lateral),
                               std::abs(got[1] / units_per_metre - expected.y),
                               std::abs(got[2] / units_per_metre - expected.x)}) {
          worst_position = std::max(worst_position, e);
          EXPECT_LT(e, kPositionTolerance) << side;
        }
      }
    }
    if (::testing::Test::HasFailure()) return;  // one frame's failures say it all
  }
  ::testing::Test::RecordProperty("worst_angle_error_deg",
                                  (std::ostringstream() << worst_angle).str());
  ::testing::Test::RecordProperty("worst_position_error_m",
                                  (std::ostringstream() << worst_position).str());
}

// ---- Tests ---------------------------------------------------------------------------------

TEST(Bvh, ForwardKinematicsOfTheFileReproducesTheWalk) {
  const Motion motion = walk(6.0, 120.0);
  const Bvh bvh = read(bvh_text(motion));
  EXPECT_EQ(bvh.frame_count, 721u);
  EXPECT_NEAR(bvh.frame_time, 1.0 / 120.0, 1e-8);
  expect_reproduces(bvh, motion, 100.0);
}

TEST(Bvh, PosesAcrossAndBeyondTheJointRangesComeBackExactly) {
  Segments segments = fuzzygait::rig::segments_from_stature(1.62);
  segments.toe = 0.061;  // lengths given one by one must come through too
  std::vector<fuzzygait::rig::Pose> poses;
  const fuzzygait::rig::JointLimits limits;
  for (int i = 0; i <= 20; ++i) {
    const double t = i / 20.0;
    fuzzygait::rig::Pose pose;
    pose.pelvis = {-1.0 + 3.0 * t, 0.8 + 0.1 * std::sin(7.0 * t)};
    pose.pelvis_tilt = radians(-20.0 + 45.0 * t);
    const auto lerp = [t](double low, double high) { return low + (high - low) * t; };
    pose.legs[0] = {lerp(limits.minimum.hip, limits.maximum.hip),
                    lerp(limits.minimum.knee, limits.maximum.knee),
                    lerp(limits.minimum.ankle, limits.maximum.ankle),
                    lerp(limits.minimum.toe, limits.maximum.toe)};
    // The other leg runs the ranges backwards, and past them at both ends.
    pose.legs[1] = {lerp(radians(170.0), radians(-60.0)), lerp(radians(175.0), radians(-10.0)),
                    lerp(radians(80.0), radians(-89.0)), lerp(radians(100.0), radians(-60.0))};
    poses.push_back(pose);
  }
  const Motion motion = from_poses(segments, poses);
  expect_reproduces(read(bvh_text(motion)), motion, 100.0);

  BvhOptions metres;
  metres.units_per_metre = 1.0;
  expect_reproduces(read(bvh_text(motion, metres)), motion, 1.0);
}

TEST(Bvh, HierarchyIsTheRigsLegsWithAStaticTrunk) {
  Segments s = fuzzygait::rig::segments_from_stature(1.80);
  s.heel = 0.03;
  s.toe = 0.05;
  const Motion motion = from_poses(s, {fuzzygait::rig::Pose{}});
  const Bvh bvh = read(bvh_text(motion));
  std::vector<std::string> names;
  for (const BvhNode& n : bvh.nodes)
    names.push_back(n.name);
  EXPECT_THAT(names, ::testing::ElementsAre("Hips", "LeftUpLeg", "LeftLeg", "LeftFoot",
                                            "LeftToeBase", "End Site", "RightUpLeg", "RightLeg",
                                            "RightFoot", "RightToeBase", "End Site", "Spine",
                                            "Neck", "Head", "End Site"));
  const BvhNode& hips = bvh.nodes[0];
  EXPECT_THAT(hips.channels, ::testing::ElementsAre("Xposition", "Yposition", "Zposition",
                                                    "Zrotation", "Yrotation", "Xrotation"));
  EXPECT_EQ(hips.offset, (Vec3{0.0, 0.0, 0.0}));
  for (std::size_t i = 1; i < bvh.nodes.size(); ++i) {
    if (bvh.nodes[i].name == "End Site") continue;
    EXPECT_THAT(bvh.nodes[i].channels,
                ::testing::ElementsAre("Zrotation", "Yrotation", "Xrotation"))
        << bvh.nodes[i].name;
  }
  const auto offset = [&](const std::string& name) {
    return bvh.nodes[static_cast<std::size_t>(bvh.find(name))].offset;
  };
  const auto cm = [](double metres) { return 100.0 * metres; };
  const double half_width = cm(0.5 * 0.19 * s.leg_length());
  for (const auto& [side, lateral] :
       {std::pair{"Left", half_width}, std::pair{"Right", -half_width}}) {
    const std::string p = side;
    expect_near(offset(p + "UpLeg"), {lateral, 0.0, 0.0});
    expect_near(offset(p + "Leg"), {0.0, -cm(s.thigh), 0.0});
    expect_near(offset(p + "Foot"), {0.0, -cm(s.shank), 0.0});
    expect_near(offset(p + "ToeBase"), {0.0, -cm(s.ankle_height), cm(s.ball)});
    expect_near(bvh.nodes[static_cast<std::size_t>(bvh.end_site_of(p + "ToeBase"))].offset,
                {0.0, 0.0, cm(s.toe)});
  }
  // The trunk from stature with Winter's proportions: waist, shoulders, chin, top of the head.
  const double stature = cm(s.leg_length() / 0.530);
  expect_near(offset("Spine"), {0.0, 0.100 * stature, 0.0});
  expect_near(offset("Neck"), {0.0, (0.818 - 0.630) * stature, 0.0});
  expect_near(offset("Head"), {0.0, (0.870 - 0.818) * stature, 0.0});
  expect_near(bvh.nodes[static_cast<std::size_t>(bvh.end_site_of("Head"))].offset,
              {0.0, (1.0 - 0.870) * stature, 0.0});
  EXPECT_DOUBLE_EQ(bvh.frame_time, 0.03333333);
}

TEST(Bvh, RestPoseStandsUprightFacingForwardWithTheLegsApart) {
  const Segments s = fuzzygait::rig::segments_from_stature(1.75);
  fuzzygait::rig::Pose standing;
  standing.pelvis = {0.0, s.leg_length()};
  // A pelvis tilt the trunk must not follow, and values that would print as "-0.000000".
  fuzzygait::rig::Pose tilted = standing;
  tilted.pelvis_tilt = radians(11.0);
  tilted.legs[0] = tilted.legs[1] = {radians(11.0), -1e-12, -1e-12, -1e-12};
  const std::string text = bvh_text(from_poses(s, {standing, tilted}));
  EXPECT_THAT(text, Not(HasSubstr("-0.000000")));
  const Bvh bvh = read(text);
  for (std::size_t frame = 0; frame < 2; ++frame) {
    SCOPED_TRACE("frame " + std::to_string(frame));
    const std::vector<Transform> w = forward_kinematics(bvh, frame);
    const auto at = [&](int node) { return w[static_cast<std::size_t>(node)].position; };
    const Vec3 head_top = at(bvh.end_site_of("Head"));
    const Vec3 neck = at(bvh.find("Neck"));
    if (frame == 0) {
      EXPECT_NEAR(head_top[1], 175.0, 1e-3);  // stature = leg length / 0.530
    }
    EXPECT_NEAR(head_top[2], neck[2], 1e-6);  // the trunk is upright: head above the neck
    EXPECT_GT(neck[1], at(bvh.find("Hips"))[1] + 40.0);
    for (const char* side : {"Left", "Right"}) {
      const std::string p = side;
      const Vec3 ankle = at(bvh.find(p + "Foot"));
      const Vec3 ball = at(bvh.find(p + "ToeBase"));
      const Vec3 tip = at(bvh.end_site_of(p + "ToeBase"));
      EXPECT_NEAR(ball[1], 0.0, 1e-3) << p;  // feet flat on the ground, toes forward (+Z)
      EXPECT_NEAR(tip[1], 0.0, 1e-3) << p;
      EXPECT_GT(ball[2], ankle[2] + 10.0) << p;
      EXPECT_GT(tip[2], ball[2]) << p;
      EXPECT_NEAR(ankle[2], at(bvh.find(p + "UpLeg"))[2], 1e-9) << p;  // legs straight down
    }
    EXPECT_NEAR(at(bvh.find("LeftUpLeg"))[0] - at(bvh.find("RightUpLeg"))[0],
                100.0 * 0.19 * s.leg_length(), 1e-3);
  }
}

TEST(Bvh, FramesAreFixedDecimalsAndTheSameMotionGivesTheSameBytes) {
  const Segments s = fuzzygait::rig::segments_from_stature(1.75);
  fuzzygait::rig::Pose pose;
  pose.pelvis = {1.5, 0.9};
  pose.pelvis_tilt = radians(10.0);
  pose.legs[0] = {radians(20.0), radians(30.0), radians(-5.0), radians(12.5)};
  Motion motion = from_poses(s, {pose});
  motion.fps = 120.0;
  const std::string text = bvh_text(motion);
  EXPECT_THAT(text, HasSubstr("MOTION\nFrames: 1\nFrame Time: 0.00833333\n"));
  // Hips position and Z Y X rotations, then each leg and the trunk in file order.
  EXPECT_THAT(text, HasSubstr("\n0.000000 90.000000 150.000000 0.000000 0.000000 10.000000"
                              " 0.000000 0.000000 -20.000000 0.000000 0.000000 30.000000"
                              " 0.000000 0.000000 5.000000 0.000000 0.000000 -12.500000"
                              " 0.000000 0.000000 0.000000 0.000000 0.000000 0.000000"
                              " 0.000000 0.000000 0.000000 0.000000 0.000000 0.000000"
                              " 0.000000 0.000000 -10.000000 0.000000 0.000000 0.000000"
                              " 0.000000 0.000000 0.000000\n"));
  EXPECT_EQ(text.back(), '\n');
  EXPECT_THAT(text, Not(HasSubstr("\r")));

  const Motion walked = walk(3.0, 60.0);
  EXPECT_EQ(bvh_text(walked), bvh_text(walked));
  EXPECT_EQ(bvh_text(walked), bvh_text(walk(3.0, 60.0)));
}

TEST(Bvh, RefusesWhatNoImporterCouldRead) {
  const Segments s = fuzzygait::rig::segments_from_stature(1.75);
  const auto throws = [](const Motion& m, const BvhOptions& o, const char* says) {
    std::ostringstream out;
    try {
      write_bvh(out, m, o);
      ADD_FAILURE() << "no exception, expected one saying " << says;
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(says));
    }
  };
  Motion empty;
  empty.fps = 30.0;
  empty.segments = s;
  throws(empty, {}, "no frames");

  Motion good = from_poses(s, std::vector<fuzzygait::rig::Pose>(5));
  Motion bad_fps = good;
  bad_fps.fps = 0.0;
  throws(bad_fps, {}, "fps");
  Motion not_a_number = good;
  not_a_number.frames[3].pose.legs[1].knee = std::numeric_limits<double>::quiet_NaN();
  throws(not_a_number, {}, "frame 3");
  Motion bad_rig = good;
  bad_rig.segments.thigh = 0.0;
  throws(bad_rig, {}, "thigh");
  BvhOptions no_units;
  no_units.units_per_metre = 0.0;
  throws(good, no_units, "units_per_metre");
  BvhOptions wide;
  wide.hip_width_per_leg_length = std::numeric_limits<double>::infinity();
  throws(good, wide, "hip_width");
}

}  // namespace

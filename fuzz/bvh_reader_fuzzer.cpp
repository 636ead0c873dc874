// libFuzzer target for the BVH reader and the clip analysis behind `fuzzygait mocap`,
// fuzzygait::io::read_bvh and analyse_clip.
//
// Contract: any bytes either parse or are refused with a MocapError naming the source; a crash,
// a hang, a sanitizer report or any other exception is a bug. A clip that parses is consistent:
// one root, every parent declared before its child, channel columns adding up to the frame
// width, as many values as frames times that width, each finite, and a frame time in range. Its
// analysis either is refused with a MocapError naming the source, or gives a captured motion of
// the frames kept whose every number is finite, on a plausible rig.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/io/mocap.hpp"
#include "fuzzygait/rig/rig.hpp"

namespace {

using namespace fuzzygait;
using fuzzygait::fuzz::check_names_source;
using fuzzygait::fuzz::fail;

constexpr std::string_view kSource = "fuzz.bvh";

void check_clip(const io::BvhClip& clip) {
  if (clip.joints.empty() || clip.joints[0].parent != -1) fail("a clip without a root parsed");
  std::size_t columns = 0;
  for (std::size_t j = 0; j < clip.joints.size(); ++j) {
    const io::BvhJoint& joint = clip.joints[j];
    if (j > 0 && (joint.parent < 0 || static_cast<std::size_t>(joint.parent) >= j)) {
      fail("a joint's parent is not declared before it", joint.name);
    }
    if (j > 0 && clip.joints[static_cast<std::size_t>(joint.parent)].end_site) {
      fail("an End Site has a child", joint.name);
    }
    if (joint.first_column != columns) fail("a joint's channel columns do not follow on");
    if (joint.end_site && !joint.channels.empty()) fail("an End Site has channels");
    columns += joint.channels.size();
    for (double v : joint.offset) {
      if (!std::isfinite(v)) fail("an offset is not finite", joint.name);
    }
  }
  if (columns != clip.channel_count || columns == 0) fail("the channel count does not add up");
  if (clip.frame_count() < 1 || clip.values.size() != clip.frame_count() * clip.channel_count) {
    fail("the values are not whole frames");
  }
  for (double v : clip.values) {
    if (!std::isfinite(v) || std::abs(v) > 1e9) fail("a value out of range was read");
  }
  if (!(clip.frame_time >= 1e-4 && clip.frame_time <= 1.0)) fail("a frame time out of range");
}

void check_motion(const io::BvhClip& bvh, const io::CapturedClip& clip) {
  const eval::Motion& m = clip.motion;
  if (!m.captured) fail("a clip's motion is not marked captured");
  if (m.frames.size() + clip.skipped_frames != bvh.frame_count()) fail("frames were lost");
  if (!(m.fps > 0.0) || !std::isfinite(m.fps)) fail("the frame rate is not finite");
  try {
    rig::validate(m.segments);
  } catch (const std::exception& e) {
    fail("the clip's rig is not plausible", e.what());
  }
  for (const eval::Frame& f : m.frames) {
    bool finite = std::isfinite(f.time) && std::isfinite(f.pose.pelvis.x) &&
                  std::isfinite(f.pose.pelvis.y) && std::isfinite(f.pose.pelvis_tilt);
    for (std::size_t s = 0; s < 2; ++s) {
      const rig::LegAngles& a = f.pose.legs[s];
      const rig::LegPoints& p = f.points[s];
      for (double v : {a.hip, a.knee, a.ankle, a.toe, p.knee.x, p.knee.y, p.ankle.x, p.ankle.y,
                       p.heel.x, p.heel.y, p.ball.x, p.ball.y, p.tip.x, p.tip.y}) {
        finite = finite && std::isfinite(v);
      }
    }
    if (!finite) fail("a frame of the motion holds a number that is not finite");
  }
  for (double v : {clip.cadence, clip.step_length, clip.speed, clip.metres_per_unit}) {
    if (!std::isfinite(v)) fail("a figure of the clip is not finite");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  io::BvhClip bvh;
  try {
    bvh = io::read_bvh(text, kSource);
  } catch (const io::MocapError& e) {
    check_names_source(e, kSource);
    return 0;
  } catch (const std::exception& e) {
    fail("read_bvh threw something other than a MocapError", e.what());
  }
  check_clip(bvh);
  io::CapturedClip clip;
  try {
    clip = io::analyse_clip(bvh, kSource);
  } catch (const io::MocapError& e) {
    check_names_source(e, kSource);
    return 0;
  } catch (const std::exception& e) {
    fail("analyse_clip threw something other than a MocapError", e.what());
  }
  check_motion(bvh, clip);
  return 0;
}

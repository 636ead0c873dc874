// A walk as sampled frames: what the walk CSV holds, what evaluation and export read.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::eval {

struct Frame {
  double time = 0.0;
  rig::Pose pose;  // radians
  std::array<rig::LegPoints, 2> points;
  std::array<bool, 2> contact{};  // any part of the foot bears on the ground
};

struct Motion {
  double fps = 0.0;
  rig::Segments segments;
  std::vector<Frame> frames;
  // Motion capture: in its stride from the first frame. A walker's motion (false) starts from
  // standing, and evaluate() leaves its first cycle out.
  bool captured = false;
};

// The walker as it stands now: its pose, foot points and contacts, stamped with `time` (s).
Frame capture_frame(const gait::Walker& walker, double time);

// Runs a walker for `duration` seconds and samples it at `fps` (frame 0 is the start pose).
Motion record(gait::Walker& walker, double duration, double fps);

// Whether frame i begins a strike of `side`: its contact begins there, at least 0.35 s after the
// last of `strikes` (earlier strikes of that side, in order). The strikes that part gait cycles,
// for evaluate() and record_cycles() alike.
bool begins_strike(const Motion& motion, std::size_t i, rig::Side side,
                   const std::vector<std::size_t>& strikes);

// Runs a walker until `cycles` left gait cycles have completed after the first, i.e. until the
// left foot has struck (begins_strike) cycles + 2 times (evaluate() skips the cycle before the
// second strike), sampling it at `fps` (frame 0 is the start pose). Throws std::runtime_error when
// that has not happened within 3 s per cycle, cycles + 2 of them; std::invalid_argument for an fps
// outside 1..10000 or fewer than one cycle.
Motion record_cycles(gait::Walker& walker, int cycles, double fps);

}  // namespace fuzzygait::eval

// A walk as sampled frames: what the walk CSV holds, what evaluation and export read.
#pragma once

#include <array>
#include <vector>

#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::gait {

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
};

// Runs a walker for `duration` seconds and samples it at `fps` (frame 0 is the start pose).
Motion record(Walker& walker, double duration, double fps);

}  // namespace fuzzygait::gait

#include "fuzzygait/eval/motion.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace fuzzygait::eval {
namespace {

void check_fps(double fps) {
  if (!std::isfinite(fps) || fps < 1.0 || fps > 10000.0) {
    throw std::invalid_argument("fps must be between 1 and 10000");
  }
}

}  // namespace

Frame capture_frame(const gait::Walker& walker, double time) {
  Frame f;
  f.time = time;
  f.pose = walker.pose();
  for (rig::Side side : rig::kSides) {
    f.points[rig::index(side)] = walker.points(side);
    f.contact[rig::index(side)] = walker.in_contact(side);
  }
  return f;
}

Motion record(gait::Walker& walker, double duration, double fps) {
  check_fps(fps);
  if (!std::isfinite(duration) || duration < 0.0 || duration > 3600.0) {
    throw std::invalid_argument("duration must be between 0 and 3600 s");
  }
  Motion motion;
  motion.fps = fps;
  motion.segments = walker.segments();
  const auto count = static_cast<std::size_t>(std::floor(duration * fps + 1e-9)) + 1;
  motion.frames.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (i > 0) walker.advance(1.0 / fps);
    motion.frames.push_back(capture_frame(walker, static_cast<double>(i) / fps));
  }
  return motion;
}

bool begins_strike(const Motion& m, std::size_t i, rig::Side side,
                   const std::vector<std::size_t>& strikes) {
  if (i == 0 || i >= m.frames.size()) return false;
  const auto s = static_cast<std::size_t>(rig::index(side));
  const auto min_gap = static_cast<std::size_t>(std::max(1.0, 0.35 * m.fps));
  return m.frames[i].contact[s] && !m.frames[i - 1].contact[s] &&
         (strikes.empty() || i - strikes.back() >= min_gap);
}

Motion record_cycles(gait::Walker& walker, int cycles, double fps) {
  check_fps(fps);
  if (cycles < 1) throw std::invalid_argument("cycles must be at least 1");
  Motion motion;
  motion.fps = fps;
  motion.segments = walker.segments();
  const long long limit = 3 * (static_cast<long long>(cycles) + 2);  // s
  std::vector<std::size_t> left_strikes;
  for (std::size_t i = 0;; ++i) {
    if (i > 0) walker.advance(1.0 / fps);
    motion.frames.push_back(capture_frame(walker, static_cast<double>(i) / fps));
    if (begins_strike(motion, i, rig::Side::Left, left_strikes)) left_strikes.push_back(i);
    if (left_strikes.size() >= static_cast<std::size_t>(cycles) + 2) break;
    if (motion.frames.back().time > static_cast<double>(limit)) {
      // Where it was then: a walk frozen at a stair's edge is told by its place.
      char where[96];
      std::snprintf(where, sizeof where, " (the pelvis at x = %.2f m, %.2f m up, at the end)",
                    motion.frames.back().pose.pelvis.x, motion.frames.back().pose.pelvis.y);
      throw std::runtime_error("the walker did not complete " + std::to_string(cycles) +
                               " cycles in " + std::to_string(limit) + " s" + where);
    }
  }
  return motion;
}

}  // namespace fuzzygait::eval

#include "fuzzygait/gait/motion.hpp"

#include <cmath>
#include <stdexcept>

namespace fuzzygait::gait {

Motion record(Walker& walker, double duration, double fps) {
  if (!std::isfinite(fps) || fps < 1.0 || fps > 10000.0) {
    throw std::invalid_argument("fps must be between 1 and 10000");
  }
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
    Frame f;
    f.time = static_cast<double>(i) / fps;
    f.pose = walker.pose();
    for (rig::Side side : rig::kSides) {
      f.points[rig::index(side)] = walker.points(side);
      f.contact[rig::index(side)] = walker.in_contact(side);
    }
    motion.frames.push_back(f);
  }
  return motion;
}

}  // namespace fuzzygait::gait

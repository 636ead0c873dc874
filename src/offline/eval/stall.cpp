#include "fuzzygait/eval/stall.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace fuzzygait::eval {
namespace {

bool finite_pelvis(const Frame& f) {
  return std::isfinite(f.pose.pelvis.x);
}

}  // namespace

std::optional<Stall> find_stall(const Motion& motion, const terrain::Terrain& ground, double window,
                                double distance) {
  const std::vector<Frame>& frames = motion.frames;
  std::size_t end = 0;  // the first frame at least `window` after frame i
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (!finite_pelvis(frames[i])) continue;
    if (end < i) end = i;
    while (end < frames.size() && frames[end].time < frames[i].time + window)
      ++end;
    if (end == frames.size()) return std::nullopt;  // too little walk left to tell
    if (!finite_pelvis(frames[end])) continue;
    const double progress = frames[end].pose.pelvis.x - frames[i].pose.pelvis.x;
    if (progress >= distance) continue;
    Stall stall;
    stall.time = frames[i].time;
    stall.pelvis_x = frames[i].pose.pelvis.x;
    stall.progress = progress;
    stall.window = frames[end].time - frames[i].time;
    stall.front_x = std::max(frames[i].points[0].tip.x, frames[i].points[1].tip.x);
    stall.run = std::isfinite(stall.front_x) ? ground.run_at(stall.front_x) : 0;
    stall.runs = ground.runs().size();
    return stall;
  }
  return std::nullopt;
}

std::string describe(const Stall& s, const terrain::Terrain& ground) {
  char line[320];
  std::string where;
  if (s.runs <= 1) {
    std::snprintf(line, sizeof line, "the front foot at x = %.2f m", s.front_x);
    where = line;
  } else {
    std::snprintf(line, sizeof line, "the front foot on run %zu of 0-%zu", s.run, s.runs - 1);
    where = line;
    if (s.run + 1 < s.runs) {
      const double riser = ground.runs()[s.run].end;
      const double rise = ground.height(ground.runs()[s.run + 1].begin) - ground.height(riser);
      std::snprintf(line, sizeof line, " (before the %.3f m %s at x = %.2f m)", std::abs(rise),
                    rise >= 0.0 ? "riser up" : "drop", riser);
      where += line;
    } else {
      where += " (the last)";
    }
  }
  std::snprintf(line, sizeof line,
                "the walk stalled at %.2f s with the pelvis at x = %.2f m and %s: it went %.3f m "
                "forward in the next %.1f s (a walk goes at least %.2f m)",
                s.time, s.pelvis_x, where.c_str(), s.progress, s.window, kStallDistance);
  return line;
}

}  // namespace fuzzygait::eval

#include "fuzzygait/eval/recovery.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "runtime/common/format.hpp"

namespace fuzzygait::eval {

int RecoveryReport::unsettled_steps(double step_length) const {
  int wrong = 0;
  for (std::size_t k = 4; k < 9; ++k) {
    if (k >= strikes.size() ||
        std::abs(strikes[k] - strikes[k - 1] - step_length) > 0.05 * step_length) {
      ++wrong;
    }
  }
  return wrong;
}

RecoveryReport walk_from_random_start(const gait::ControllerSet& set, gait::WalkerOptions options,
                                      std::uint64_t seed, const terrain::Terrain& ground,
                                      double seconds) {
  options.start.random = true;
  options.start.seed = seed;
  // The steps are counted from the strikes: room for a time step's events, whatever was asked.
  options.event_capacity = std::max<std::size_t>(options.event_capacity, 8);
  gait::Walker walker(set, options, ground);
  RecoveryReport r;
  r.start = {walker.state().legs[0].angles, walker.state().legs[1].angles};
  const rig::JointLimits& limits = options.limits;
  double last_strike_time = -1.0;
  const double h = options.time_step;
  for (long i = 0; i < std::lround(seconds / h); ++i) {
    const rig::Point pelvis = walker.state().pelvis;
    walker.advance(h);
    const rig::Point moved = walker.state().pelvis;
    r.largest_pelvis_move =
        std::max(r.largest_pelvis_move, std::hypot(moved.x - pelvis.x, moved.y - pelvis.y));
    for (rig::Side side : rig::kSides) {
      const rig::LegPoints p = walker.points(side);
      for (const rig::Point& q : {p.hip, p.knee, p.ankle, p.heel, p.ball, p.tip}) {
        if (!std::isfinite(q.x) || !std::isfinite(q.y)) {
          r.failure = "a point is not finite at " + common::number_text(walker.time()) + " s";
        } else if (q.y < ground.height(q.x) - 1e-6) {
          r.failure = "a point is below the ground at " + common::number_text(walker.time()) + " s";
        }
        if (!r.sound()) return r;
      }
      const rig::LegAngles& a =
          walker.state().legs[static_cast<std::size_t>(rig::index(side))].angles;
      r.worst_limit_excess =
          std::max({r.worst_limit_excess, a.hip - limits.maximum.hip, limits.minimum.hip - a.hip,
                    a.knee - limits.maximum.knee, limits.minimum.knee - a.knee,
                    a.ankle - limits.maximum.ankle, limits.minimum.ankle - a.ankle});
    }
    for (const gait::EventRecord& e : walker.events()) {
      if (e.event != gait::Event::HeelStrike && e.event != gait::Event::ForefootStrike) continue;
      // Where the walker counts the step from: the heel, or for a forefoot strike where the
      // heel will come down (steps are heel to heel).
      if (last_strike_time < 0.0 || e.time - last_strike_time >= 0.1) {
        r.strikes.push_back(
            walker.state().legs[static_cast<std::size_t>(rig::index(e.side))].strike_x);
      }
      last_strike_time = e.time;
    }
    walker.clear_events();
  }
  return r;
}

}  // namespace fuzzygait::eval

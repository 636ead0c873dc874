// Recovery from an awkward start: a walker started from a random pose (gait::StartPose::random),
// checked at every time step. One check for the acceptance tests and the tuner's cost alike.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::eval {

struct RecoveryReport {
  std::array<rig::LegAngles, 2> start;  // the random start's joint angles, left and right
  // Empty while the walk stayed sound: every point finite and none below the ground (1e-6 m)
  // at any time step. Otherwise what went wrong first, and when; the walk stops there.
  std::string failure;
  double worst_limit_excess = 0.0;   // rad past a hip, knee or ankle limit (toes follow the ground)
  double largest_pelvis_move = 0.0;  // m, in one time step
  // Where the feet struck (the heel's x; for a forefoot strike where the heel comes down), in
  // order; both feet touching down within 0.1 s (landing from a fall, replanting both feet) is
  // one strike, not two steps.
  std::vector<double> strikes;

  bool sound() const { return failure.empty(); }
  // The steps after the third (the first touchdown is not a step), up to the eighth, within 5 %
  // of `step_length`; each one missing or wrong counts.
  int unsettled_steps(double step_length) const;
};

// Walks `seconds` from the random start `seed` with `options` (its start is replaced) on
// `ground`, at the options' time step.
RecoveryReport walk_from_random_start(const gait::ControllerSet& set, gait::WalkerOptions options,
                                      std::uint64_t seed, const terrain::Terrain& ground,
                                      double seconds = 8.0);

}  // namespace fuzzygait::eval

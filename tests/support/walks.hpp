// Walkers for the gait tests: the built-in default controller set, loaded once, and a walker of
// a given step length and stature on the given ground.
#pragma once

#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::test {

inline const gait::ControllerSet& default_set() {
  static const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  return set;
}

// The ground and the set must outlive the walker.
inline gait::Walker make_walker(const terrain::Terrain& ground, double step = 0.70,
                                double stature = 1.75, gait::StartPose start = {},
                                const gait::ControllerSet& set = default_set()) {
  gait::WalkerOptions o;
  o.segments = rig::segments_from_stature(stature);
  o.step_length = step;
  o.start = start;
  return gait::Walker(set, o, ground);
}

}  // namespace fuzzygait::test

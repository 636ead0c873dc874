// Walkers for the gait tests: the built-in default controller set, loaded once, a walker of a
// given step length and stature on the given ground, and two walker states compared to the bit.
#pragma once

#include <bit>
#include <cstdint>
#include <string>

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

// The first field in which two walker states differ, bit for bit ("" when they are the same).
inline std::string state_difference(const gait::WalkerState& a, const gait::WalkerState& b) {
  auto differ = [](double x, double y) {
    return std::bit_cast<std::uint64_t>(x) != std::bit_cast<std::uint64_t>(y);
  };
  if (differ(a.time, b.time)) return "time";
  if (differ(a.speed, b.speed)) return "speed";
  if (differ(a.tempo_gain, b.tempo_gain)) return "tempo gain";
  if (differ(a.tempo_gain_target, b.tempo_gain_target)) return "tempo gain target";
  if (differ(a.pelvis.x, b.pelvis.x) || differ(a.pelvis.y, b.pelvis.y)) return "pelvis";
  if (differ(a.pelvis_tilt, b.pelvis_tilt)) return "pelvis tilt";
  if (a.lead != b.lead) return "lead";
  if (differ(a.fall_velocity, b.fall_velocity)) return "fall velocity";
  if (a.heel_strikes != b.heel_strikes) return "heel strikes";
  if (a.locomotion != b.locomotion) return "locomotion";
  if (a.placed_leg != b.placed_leg) return "placed leg";
  if (a.go_when_standing != b.go_when_standing) return "go when standing";
  if (differ(a.stop_x, b.stop_x)) return "stop x";
  if (differ(a.brake_distance, b.brake_distance)) return "brake distance";
  if (differ(a.pelvis_velocity.x, b.pelvis_velocity.x) ||
      differ(a.pelvis_velocity.y, b.pelvis_velocity.y)) {
    return "pelvis velocity";
  }
  if (differ(a.start_tempo, b.start_tempo)) return "start tempo";
  if (differ(a.placed_from.x, b.placed_from.x) || differ(a.placed_from.y, b.placed_from.y) ||
      differ(a.placed_pitch, b.placed_pitch) || differ(a.placed_duration, b.placed_duration)) {
    return "placed step";
  }
  for (std::size_t k = 0; k < 2; ++k) {
    const gait::LegState& l = a.legs[k];
    const gait::LegState& m = b.legs[k];
    const std::string leg = k == 0 ? "left " : "right ";
    if (l.phase != m.phase) return leg + "phase";
    const std::pair<const char*, std::pair<double, double>> fields[] = {
        {"hip", {l.angles.hip, m.angles.hip}},
        {"knee", {l.angles.knee, m.angles.knee}},
        {"ankle", {l.angles.ankle, m.angles.ankle}},
        {"toe", {l.angles.toe, m.angles.toe}},
        {"hip velocity", {l.velocity.hip, m.velocity.hip}},
        {"knee velocity", {l.velocity.knee, m.velocity.knee}},
        {"ankle velocity", {l.velocity.ankle, m.velocity.ankle}},
        {"toe velocity", {l.velocity.toe, m.velocity.toe}},
        {"anchor x", {l.anchor.x, m.anchor.x}},
        {"anchor y", {l.anchor.y, m.anchor.y}},
        {"sweep start", {l.sweep_start, m.sweep_start}},
        {"sweep end", {l.sweep_end, m.sweep_end}},
        {"target", {l.target_x, m.target_x}},
        {"swing start", {l.swing_start, m.swing_start}},
        {"strike", {l.strike_x, m.strike_x}},
        {"delta", {l.delta, m.delta}}};
    for (const auto& [name, values] : fields) {
      if (differ(values.first, values.second)) return leg + name;
    }
  }
  return "";
}

// Advances both walkers by `frames` frames of 1/60 s side by side: the first frame after which
// their states differ to the bit, and where ("frame 12: left knee"), or "" if they never do.
inline std::string walk_side_by_side(gait::Walker& a, gait::Walker& b, int frames) {
  for (int frame = 0; frame < frames; ++frame) {
    a.advance(1.0 / 60.0);
    b.advance(1.0 / 60.0);
    const std::string difference = state_difference(a.state(), b.state());
    if (!difference.empty()) return "frame " + std::to_string(frame) + ": " + difference;
  }
  return "";
}

}  // namespace fuzzygait::test

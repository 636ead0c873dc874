// Training data from a walk (a motion capture clip, or a walker's own recording): at every time
// step of the walker, for each leg, what the walker would measure in that pose (the metrics its
// controllers read), which controllers would drive which joint, and how fast each joint moves as
// the walker's integrator moves it. The metrics come from the walker's own code, so a set trained
// on them answers the walker's questions.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::learn {

// How a planted foot bears on the ground (gait::Phase), estimated from the sole's angle.
enum class FootContact : std::uint8_t { Swing, Heel, Flat, Ball };

// One leg at one time step.
struct LegStep {
  // False before the leg's first change of phase (the clip begins mid-phase: where its sweep
  // began is unknown) and after the last frame: the step is not used.
  bool known = false;
  gait::LegPhase phase = gait::LegPhase::Swing;
  FootContact foot = FootContact::Swing;
  // A planted leg that carries the body: its hip and knee follow their controllers. (In double
  // support the newly planted leg's hip and knee close the chain instead.)
  bool carrying = false;
  rig::LegAngles angles;     // radians, the walker's convention (hip = thigh + the set's tilt)
  rig::LegAngles velocity;   // rad/s: (angles - the previous step's angles) / time step
  double sweep_start = 0.0;  // the thigh's inclination at delta -1 and +1, radians
  double sweep_end = 0.0;
  double slope = 0.0;  // the ground's pitch under the ankle, radians
  gait::MetricValues metrics{};
};

// Whether the walker's controller of (phase, joint) drives the joint at this step.
bool driven(const LegStep& step, gait::Joint joint);

struct TrainingOptions {
  double time_step = 1.0 / 240.0;  // s: the walker's (WalkerOptions::time_step)
  // A planted sole within this angle of the ground (degrees) is flat: before it first is, the
  // foot is on its heel; after it last is, on its ball.
  double flat_sole = 4.0;
};

struct TrainingClip {
  double time_step = 0.0;
  double pelvis_tilt = 0.0;                 // the set's (radians)
  double swing_knee_reference_sweep = 0.0;  // the set's (radians)
  rig::Segments segments;
  double step_length = 0.0;                   // m, the walker's command
  std::vector<std::array<LegStep, 2>> steps;  // [step][rig::Side]
};

// Resamples `motion` at the time step (cubic through the frames) and measures it as a walker with
// `set`'s pelvis tilt, the motion's segments and this step length would: a planted leg's delta
// runs from its thigh at the strike to the set's stance target, a swinging leg's from its thigh at
// toe off to where its heel points one step length ahead of the other foot's strike on `ground`.
// The pelvis tilt of the motion is taken out (thigh = hip - tilt). Throws std::invalid_argument for
// a motion of fewer than two frames, a non-positive frame rate, time step or step length.
TrainingClip training_data(const eval::Motion& motion, const terrain::Terrain& ground,
                           double step_length, const gait::ControllerSet& set,
                           const TrainingOptions& options = {});

}  // namespace fuzzygait::learn

// Training a controller set on motion capture clips, the whole pipeline behind `fuzzygait train`:
//   1. commands      a per-frame fit of every controller (learn::fit, FitData::Commands);
//   2. joints        trajectory fits joint by joint, the other joints from the clips;
//   3. coupled       a trajectory fit of every controller with the legs' joints together;
//   4. polish        the closed loop: the existing tuner (learn::tune, CMA-ES) walks the set at
//   each
//                    clip's legs and step against the clip's mean cycle, stance share, cycle time
//                    and knee peak (clip_condition()), with the set's words and contacts priced.
// After each fit, each controller's fitted values are kept only where the closed-loop cost of the
// walk (walk_cost) improves: the fits see the clips frame by frame, the walk sees landing,
// hand-over and timing. The result keeps the base set's rules and words, its values rounded for
// people.
#pragma once

#include <array>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "fuzzygait/eval/evaluation.hpp"
#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/learn/fit.hpp"
#include "fuzzygait/learn/structure.hpp"
#include "fuzzygait/learn/tune.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::learn {

// A clip to train on, measured.
struct TrainClip {
  std::string name;
  eval::Motion motion;  // captured
  terrain::Terrain ground = terrain::Terrain::flat();
  eval::GaitReport report;  // evaluate() of the motion: its mean cycle, timing, step length
  // The step the walker takes for this clip (m): the rig's heel-to-heel step in the clip
  // (report.step_length), at which the rig's legs take the clip's angles.
  double step_length = 0.0;
};

// What make_train_clip() takes for a level forward walk: planted feet within this of the floor
// fitted to them (m), a pace (Walker::pace) and a cadence (steps a minute) people walk at.
inline constexpr double kFloorTolerance = 0.03;
inline constexpr double kSlowestPace = 0.12;
inline constexpr double kFastestPace = 0.9;
inline constexpr double kFewestSteps = 50.0;
inline constexpr double kMostSteps = 180.0;

// Measures a clip for training. Throws std::invalid_argument (naming `name`) when evaluate()
// finds no complete cycle in it, when it is no level forward walk (its planted feet further than
// kFloorTolerance from the floor, its feet landing behind the body, its pace or cadence outside
// the ranges above), or when its step is outside the walker's range for its legs.
TrainClip make_train_clip(std::string name, eval::Motion motion, terrain::Terrain ground);

struct TrainProgress {
  std::string stage;  // "commands", "joints", "coupled", "polish"
  int iteration = 0;  // the fit's iteration or the polish's generation
  double cost = 0.0;  // the stage's own cost (Ceres' or the walk's)
  // Per clip, when known: the closed-loop RMSE of the best set (thigh, knee, ankle, deg).
  std::vector<std::array<double, 3>> rmse;
};

struct TrainOptions {
  FitOptions fit;  // the fits' weights and iterations (stage, progress, stop are set)
  // The closed-loop cost and the polish: its conditions (the clips', plus the grid's when
  // `grid`), recovery seeds and generations. Its rmse bounds are the clips' targets.
  TuneOptions polish;
  ClipTolerances tolerances;
  bool grid = false;  // also price the level contact bounds on the step/stature grid
  // Also price the contact bounds and step error at each clip's body walking these multiples of
  // its step length (a clip shows one step; these keep the set walking others).
  std::vector<double> steps_around;
  int recovery_starts = 0;  // random starts that must settle into the gait
  bool fits = true;         // run stages 1-3 (false: the polish alone)
  // Add the learning structure (learning_structure(): words the base's rules lack) first.
  bool structure = true;
  std::function<void(const TrainProgress&)> progress;
  std::function<bool()> stop;  // true: stop after the current iteration, keeping the best set
};

// The default options: 800 polish generations of 48 walks, then 100 on the rounded values (3
// significant digits), two threads, words and knots of angles free, the words' promises kept,
// curve bounds 3.7 deg, a clip's stance and cycle time held firmly, no random starts.
TrainOptions default_train_options();

// A walk's pace (gait::Walker::pace) and step (leg lengths): a point of the stride relation.
struct StridePoint {
  double pace = 0.0;
  double step = 0.0;
  double weight = 1.0;
};
// The clips' body, step and speed, their means: what a set trained on them walks by default (the
// manifest's "body", ControllerSet::body, body_step_length and body_speed).
struct ClipsBody {
  rig::Segments body{};
  double step = 0.0;   // m, TrainClip::step_length
  double speed = 0.0;  // m/s, the clips' reports'
  std::string names;   // "07_01, 07_02"
};
// Throws std::invalid_argument when there is no clip.
ClipsBody clips_body(std::span<const TrainClip> clips);

// The stride points of the clips: each one's pace and step.
std::vector<StridePoint> stride_points(std::span<const TrainClip> clips);
// `set` with its stride (ControllerSet::stride) fitted to `points`: every step word's value v
// becomes a + b v, least squares through the points (b = 1 where they are of one pace), so the
// relation keeps its shape and words and passes through people's steps. Throws
// std::invalid_argument when the set has no stride, there is no point, or the fit would make the
// step shrink as the pace grows.
gait::ControllerSet fit_stride(const gait::ControllerSet& set, std::span<const StridePoint> points);

// One clip's closed-loop figures: the set walked at the clip's legs and step against its mean
// cycle.
struct ClipScore {
  bool walked = false;  // false: the walk failed or had too few cycles (the rest is 0)
  double thigh = 0.0;   // RMSE, deg
  double knee = 0.0;
  double ankle = 0.0;
  double stance = 0.0;   // % of the cycle (the clip's: TrainClip::report.stance_percent)
  double cadence = 0.0;  // steps/min
  eval::GaitReport report;
};
ClipScore score_clip(const gait::ControllerSet& set, const TrainClip& clip, double duration = 10.0);

// Walks checked against bounds: how many, how many met them all, and a line for each other walk
// ("0.85 m at 1.50 m: foot slip ...").
struct WalksCheck {
  int walks = 0;
  int within = 0;
  std::vector<std::string> misses;
};

// The level-walk contact bounds (eval::missed_contact_bounds) on the acceptance grid: steps 0.50,
// 0.60, 0.70 and 0.85 m at statures 1.50, 1.75 and 2.00 m, 10 s each.
WalksCheck check_grid(const gait::ControllerSet& set);

// Stairs and ramps at this body and step, priced as the terrain tests price them
// (tests/gait/terrain_walk_test.cpp): eight 0.17 x 0.28 m stairs up and down (24 s, reaching the
// landing) and 10 deg ramps up and down (16 s, steps on the ramp within 5 % of the command), each
// within the terrain contact bounds (eval::missed_contact_bounds: every leg point slipping under
// 1 mm a frame and under 1 mm in the ground, swing clearance at least 10 mm, no NaN) and the
// continuity bound (eval::missed_continuity_bound: no joint faster than people's fastest between
// two frames), recorded at 120 frames a second.
WalksCheck check_terrain(const gait::ControllerSet& set, const rig::Segments& body, double step);

// Random start poses (eval::walk_from_random_start, seeds 1000 on) at this body and step: walks
// that stay sound, and that also take steps within 5 % of the command from their fourth step.
struct StartsCheck {
  int starts = 0;
  int sound = 0;
  int settled = 0;
};
StartsCheck check_starts(const gait::ControllerSet& set, const rig::Segments& body, double step,
                         int count);

struct StageRecord {
  std::string stage;
  double cost = 0.0;  // the closed-loop cost after the stage
  // Fits: the controllers (and the inertia, as one more) whose fitted values were kept;
  // "structure": the words added; the polish: 0.
  int kept = 0;
  double seconds = 0.0;
};

struct TrainResult {
  gait::ControllerSet set;        // the trained set, rounded
  std::vector<AddedWord> added;   // the structure added to the base (their peaks as trained)
  std::vector<ClipScore> before;  // the base set, clip by clip
  std::vector<ClipScore> after;   // the trained set
  std::vector<StageRecord> stages;
  double cost_before = 0.0;
  double cost_after = 0.0;
  bool stopped = false;  // stopped early (TrainOptions::stop): `set` is the best so far
  double seconds = 0.0;
};

// Trains `base` (every slot a partition controller) on the clips. The set's name, description
// and manifest are the base's; the caller names it. With options.structure the set has the words
// of learning_structure() too.
TrainResult train(const gait::ControllerSet& base, std::span<const TrainClip> clips,
                  const TrainOptions& options);

}  // namespace fuzzygait::learn

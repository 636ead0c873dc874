// Tuning a controller set against normative gait curves: the output velocities of every rule
// ("velocity is fast") are the parameters; a candidate is scored by walking it and measuring the
// walk (realism against the reference, contact quality, timing). The result keeps the set's
// rules and words, so the artist reads and edits it as before.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "fuzzygait/eval/evaluation.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/learn/range.hpp"
#include "fuzzygait/rig/rig.hpp"

namespace fuzzygait::learn {

// One walk the tuner prices. The target is either normative curves at a stature (the defaults)
// or a motion capture clip's mean cycle with the clip's body and timing (clip_condition()).
struct WalkCondition {
  double stature = 1.75;
  // The body's segment lengths (a clip's); none: from the stature.
  std::optional<rig::Segments> segments{};
  double step_length = 0.70;
  // Curves scored against this reference with this weight (none: contact and timing only).
  const eval::Normative* reference = nullptr;
  double realism_weight = 1.0;
  // The curve errors pay steeply above TuneOptions' thigh/knee/ankle_rmse_max (the main
  // condition, whose curves the acceptance bounds judge).
  bool enforce_bounds = false;
  // This walk's own ranges (a clip's timing and knee peak); where given they replace TuneOptions'
  // stance_min/max, cycle_time_min/max, knee_peak_min/max and knee_peak_percent_min/max.
  std::optional<Range> stance{};
  std::optional<Range> cycle_time{};
  std::optional<Range> knee_peak{};
  std::optional<Range> knee_peak_percent{};
  // The toes are priced for resting near neutral (weights.toe_off_neutral), as people's do; a
  // clip's toes are its own.
  bool toes_rest = true;
};

// The main condition: a 1.75 m adult's 0.70 m steps against `reference`, bounds enforced.
WalkCondition main_condition(const eval::Normative& reference);
// The main condition and the step/stature grid around it: the 1.75 m adult's 0.55 and 0.85 m
// steps against the slower and faster references (realism weight 0.3), and the rest of the
// acceptance grid (steps 0.50, 0.60, 0.70, 0.85 m for statures 1.50, 1.75, 2.00 m) for contact
// and timing only.
std::vector<WalkCondition> grid_conditions(const eval::Normative& reference,
                                           const eval::Normative& slower,
                                           const eval::Normative& faster);
// A clip's mean cycle (evaluate() of its motion) as a reference: thigh, knee and ankle curves
// (hip = thigh, pelvis tilt 0), named `name`.
eval::Normative clip_reference(const eval::GaitReport& clip, const std::string& name);
// How closely a walk must keep a clip's timing and knee peak in clip_condition(): its stance
// share within `stance` points, its cycle time within `cycle_time` of the clip's (a share), its
// peak swing knee flexion within `knee_peak` degrees and `knee_peak_percent` points of the cycle.
struct ClipTolerances {
  double stance = 1.0;
  double cycle_time = 0.02;
  double knee_peak = 3.0;
  double knee_peak_percent = 3.0;
};
// The walk of a clip: its body, the step length `step` (m), its mean cycle `reference`
// (clip_reference() of `clip`), its stance share, cycle time and knee peak within `tolerances`,
// bounds enforced.
WalkCondition clip_condition(const eval::Normative& reference, const eval::GaitReport& clip,
                             const rig::Segments& segments, double step,
                             const ClipTolerances& tolerances = {});
// Seeds of `count` random starts that must settle into the gait (TuneOptions::recovery_seeds).
std::vector<std::uint64_t> recovery_seeds(int count);

// What walk_cost() charges, term by term: every weight of the cost, and every threshold where a
// gentle charge begins (the bounds where the steep ones begin are TuneOptions'). A weight is cost
// per unit of what it prices, in the unit its comment names; 0 switches its term off. validate()
// refuses a field that is negative or not finite, and a word_unit, toe_clearance_wanted or
// failed_walk of 0.
struct CostWeights {
  // The set's words (word_penalty()).
  double words = 10.0;              // per unit of word penalty
  double words_over_bound = 100.0;  // per unit of word penalty above TuneOptions::word_penalty_max
  // Share of an output's range that is one unit of word penalty, and that a "stay" or "hold"
  // word may move for free.
  double word_unit = 0.02;
  // Random starts (TuneOptions::recovery_seeds).
  // Per start whose walk goes unsound (eval::RecoveryReport::sound) or cannot be walked.
  double unsound_start = 100.0;
  // Per step of a start, after the third up to the eighth, missing or more than 5 % off the
  // commanded length (eval::RecoveryReport::unsettled_steps).
  double unsettled_step = 5.0;
  // Every condition's walk.
  double failed_walk = 1000.0;  // per condition that cannot be walked, or costs NaN or infinity
  double step_error = 2.0;      // per % the steps miss the commanded length by
  double step_error_over_bound = 20.0;  // per % of step error above TuneOptions::step_error_max
  // For a toe with no mid-swing clearance at all; pro rata for one under toe_clearance_wanted.
  double toe_scuff = 200.0;
  double toe_clearance_wanted = 0.012;     // m of mid-swing toe clearance that costs nothing
  double cycle_time_sd = 100.0;            // per s of cycle time SD between cycles
  double step_length_sd = 100.0;           // per commanded step length of step length SD
  double stance_outside_range = 2.0;       // per % of stance share outside TuneOptions' range
  double pelvis_outside_range = 0.5;       // per mm of pelvis travel outside TuneOptions' range
  double cycle_time_outside_range = 50.0;  // per s of cycle time outside TuneOptions' range
  // Per unit of velocity jump ratio (the largest change of a joint's velocity at a phase switch,
  // in typical frame-to-frame changes) above velocity_jump_ratio_free.
  double velocity_jump = 10.0;
  double velocity_jump_ratio_free = 1.2;    // velocity jump ratio that costs nothing
  double slip = 2000.0;                     // per m a frame of foot slip above slip_free
  double slip_free = 0.0005;                // m a frame of foot slip that costs nothing
  double slip_over_bound = 20000.0;         // per m a frame of slip above TuneOptions::slip_max
  double penetration = 1000.0;              // per m a foot point goes below the ground
  double heel_bounce_over_bound = 20000.0;  // per m above TuneOptions::heel_bounce_max
  // Realism, on conditions with a reference, all times WalkCondition::realism_weight; the terms
  // over a bound on conditions with enforce_bounds only.
  double curve_rmse = 2.0;                // per deg of RMSE of the thigh, knee and ankle each
  double thigh_knee_uncorrelated = 10.0;  // per unit of 1 - r of the thigh's and knee's curve each
  double ankle_uncorrelated = 20.0;       // per unit of 1 - r of the ankle's curve
  double curve_rmse_over_bound = 10.0;    // per deg of a curve's RMSE above its TuneOptions bound
  // Per unit of acceleration ratio of the thigh and the knee each above
  // TuneOptions::acceleration_ratio_max.
  double acceleration_over_bound = 10.0;
  double knee_peak_outside_range = 1.0;  // per deg of peak knee flexion outside TuneOptions' range
  double knee_peak_timing_outside_range = 1.0;  // per % of cycle outside TuneOptions' range
  // Per deg of toe angle off neutral, summed over the mean cycle's samples while the foot is
  // flat (10-30 %) and before landing (86-100 %).
  double toe_off_neutral = 0.1;
  // Per squared step of SetParameters' scale that the set's values stray from TuneOptions::anchor
  // (the weak pull toward a base set, for values the walks say little about); 0 switches it off.
  double anchor = 0.0;
};

struct TuneOptions {
  std::vector<WalkCondition> conditions;
  std::vector<std::uint64_t> recovery_seeds;  // random starts that must settle into the gait
  double duration = 10.0;                     // s per walk
  // s each walk walks before it is recorded, from the walker's default start (StartPose).
  double warm_up = 3.0;
  // Adults walk about 100-120 steps a minute at these step lengths: cycles of 1.0-1.2 s.
  double cycle_time_min = 1.0;
  double cycle_time_max = 1.2;
  double minimum_inertia = 0.02;  // s
  // Ranges the walk should stay in: stance share (%), peak swing knee flexion (deg) and where in
  // the cycle it peaks (%), vertical travel of the pelvis over a cycle (mm). Styles move them.
  double stance_min = 58.0;
  double stance_max = 64.0;
  double knee_peak_min = 55.0;
  double knee_peak_max = 70.0;
  double knee_peak_percent_min = 69.0;
  double knee_peak_percent_max = 77.0;
  double pelvis_range_min = 0.0;
  double pelvis_range_max = 1e9;
  // Curve errors (deg RMSE) above which a condition with enforce_bounds (the main one) pays
  // steeply: a little inside the acceptance bounds, so rounding the values keeps them met.
  double thigh_rmse_max = 5.7;
  double knee_rmse_max = 7.7;
  double ankle_rmse_max = 5.7;
  // Likewise for every condition: foot slip (m a frame; bound 1 mm) and step error (%; bound
  // 3 %) pay steeply above these. And the set's word penalty (word_penalty) above this one,
  // a little under the 1 the shipped sets keep.
  double slip_max = 0.0009;
  double step_error_max = 2.5;
  double word_penalty_max = 0.9;
  // RMS angular acceleration of the thigh's and knee's mean cycles, as a multiple of the
  // reference's at the same cadence, above which a condition with enforce_bounds pays: how much
  // snappier than people the joints may move (their ease in and out). No limit by default.
  double acceleration_ratio_max = std::numeric_limits<double>::infinity();
  // Heel bounce (eval::GaitReport::max_heel_bounce, m) above which every condition pays
  // (weights.heel_bounce_over_bound): a heel that lifts after foot flat and drops back before
  // heel-off. No limit by default.
  double heel_bounce_max = std::numeric_limits<double>::infinity();
  CostWeights weights;  // what each term of walk_cost() charges
  // The set whose values weights.anchor pulls toward (it must outlive the options), or none.
  const gait::ControllerSet* anchor = nullptr;
  double fps = 120.0;
  int generations = 200;
  // Then this many generations on the values rounded to `digits` significant digits, the ones
  // written out for the artist.
  int polish_generations = 0;
  int digits = 3;
  // Also tune where the words of joint angles and of the sole hold (SetParameters' angle_words).
  bool angle_words = false;
  int threads = 2;
  std::uint64_t seed = 1;
  double sigma = 0.3;
  int population = 0;  // candidates a generation; 0: CMA-ES's default, 4 + 3 ln(parameters)
  std::function<void(int generation, double cost)> progress;
  // Asked after every generation; true ends the tuning there, with the best set found so far.
  std::function<bool()> stop;
  // Called after every generation with the best set so far (built only when this is set).
  std::function<void(int generation, const gait::ControllerSet& best)> best;
};

// The parameters of a set: every Constant output term of every controller, the inertia, and the
// interior knots of the partition controllers' inputs.
class SetParameters {
 public:
  // minimum_inertia (s) keeps joint velocities from jumping: tuning never goes below it.
  // Knots: of the progress inputs (delta, other_delta) only, when along its progress a joint
  // changes its mind; with `angle_words`, of every input, the words of joint angles and of the
  // sole too ("bent" at 30 degrees).
  explicit SetParameters(const gait::ControllerSet& base, double minimum_inertia = 0.02,
                         bool angle_words = false);
  std::size_t size() const { return scales_.size(); }
  // Scaled so that a change of 1 is a large change for every parameter.
  std::vector<double> values() const;
  gait::ControllerSet apply(const std::vector<double>& scaled) const;
  // The set with every value rounded to `significant` significant digits.
  gait::ControllerSet rounded(const std::vector<double>& scaled, int significant) const;
  // The set with these unscaled values (output velocities, then the inertia, then the knots).
  gait::ControllerSet with_values(const std::vector<double>& values) const;

 private:
  enum class Kind { Output, Inertia, Knot };
  struct Value {
    Kind kind;
    std::size_t slot;
    std::size_t input;  // Knot
    std::size_t index;  // the output term, or the knot's term
  };
  gait::ControllerSet base_;
  double minimum_inertia_;
  std::vector<Value> values_;
  std::vector<double> scales_;
  std::vector<double> start_;
};

// How far the set's values stray from what their words promise ("stay" near zero, "flex"
// positive, "fast" faster than the plain word...), in units of weights.word_unit of each
// output's range; 0 when every word is kept.
double word_penalty(const gait::ControllerSet& set, const CostWeights& weights = CostWeights{});

// Throws std::invalid_argument naming the first field of `options` out of its range (NaN, a
// reversed range, a CMA-ES step of zero, a negative weight, ...). walk_cost() and tune() call it.
void validate(const TuneOptions& options);

// The tuning objective, priced by options.weights: lower is better. `report` receives a one-line
// summary per condition; `failed_walks`, how many conditions could not be walked at all (each
// costs weights.failed_walk).
double walk_cost(const gait::ControllerSet& set, const TuneOptions& options,
                 std::string* report = nullptr, int* failed_walks = nullptr);

struct TuneResult {
  gait::ControllerSet set;  // the best set found (with polishing: its rounded values)
  double cost = 0.0;        // walk_cost() of `set`
  // `set` with its values rounded to TuneOptions::digits significant digits: the set to write
  // out for the artist (with polishing, `set` itself).
  gait::ControllerSet rounded;
  int evaluations = 0;  // walk_cost() calls
};

TuneResult tune(const gait::ControllerSet& start, const TuneOptions& options);

}  // namespace fuzzygait::learn

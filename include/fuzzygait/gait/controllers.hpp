// A controller set: one fuzzy controller per (leg phase, joint), loaded from FLL files and a
// small JSON manifest. Controllers read one or two metrics by name and output the joint's
// velocity; this is all the data that makes a walk (the default set, and the styles).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fuzzygait/fuzzy/engine.hpp"
#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/partition.hpp"
#include "fuzzygait/rig/rig.hpp"

namespace fuzzygait::gait {

enum class Joint : std::uint8_t { Hip, Knee, Ankle, Toe };
enum class LegPhase : std::uint8_t { Swing, Stance };

inline constexpr int kSlotCount = 8;
constexpr int slot(LegPhase phase, Joint joint) {
  return static_cast<int>(phase) * 4 + static_cast<int>(joint);
}
// "swing_hip", "swing_knee", ..., "stance_toe".
std::string_view slot_name(int slot);

// What a controller may read, by input-variable name. Angles in degrees.
enum class Metric : std::uint8_t {
  Delta,       // "delta": the leg's progress, -1 start, 0 thigh vertical, +1 arrived
  OtherDelta,  // "other_delta": the other leg's delta
  Hip,         // "hip": hip flexion
  Knee,        // "knee": knee flexion
  Ankle,       // "ankle": ankle dorsiflexion
  Toe,         // "toe": MTP extension
  Sole,        // "sole": angle of the sole to the ground surface under it, toes up +
  // "incline": the pitch of the ground the body is walking on, uphill +, degrees: from the
  // ground's pitches at the feet's footholds (Terrain::pitch: a ramp's slope, a stair's rise over
  // its tread). 0 on level ground, 10 on a 10 deg ramp, 31 up stairs of 0.17 x 0.28 m.
  Incline,
  // "stairs": 1 where that pitch is a stair's (a foothold on a tread), 0 on level ground and ramps.
  Stairs,
  // "pace": the walk's speed as a Froude-like number, v / sqrt(g * leg length) (people walk at
  // about 0.25-0.7; 0.4 is an adult's natural walk).
  Pace,
};
inline constexpr int kMetricCount = 10;

namespace detail {
// Controller i's workspace among ControllerSet::make_workspaces()'s. When it made none, every
// controller is on the fast path, which reads no workspace: any will do.
inline fuzzy::Workspace& workspace_at(std::vector<fuzzy::Workspace>& workspaces, std::size_t i) {
  static fuzzy::Workspace none;
  return workspaces.empty() ? none : workspaces[i];
}
}  // namespace detail

// The upper body's controllers (the manifest's "upper_body"): each answers from one leg's metrics
// (not a velocity: the upper body follows the legs). The shoulder (the upper arm's inclination
// forward of the vertical, deg) and the elbow (flexion, deg) read their own side's leg; each
// side's pelvis and thorax turn (forward +, deg) read the other side's leg, and the body turns by
// the left's minus the right's. The frontal plane reads each side's own leg: pelvis_obliquity
// (how far this side of the pelvis rises, deg; the pelvis rolls by the left's minus the right's)
// and pelvis_sway (how far the pelvis moves towards this side, percent of the leg's length; it
// moves by the left's minus the right's). trunk_lean reads each side's own leg's ground (incline,
// stairs): how far the chest leans forward, deg; it leans by the mean of the two sides'.
enum class UpperBody : std::uint8_t {
  Shoulder,
  Elbow,
  PelvisRotation,
  ThoraxRotation,
  PelvisObliquity,
  PelvisSway,
  TrunkLean
};
inline constexpr int kUpperBodyCount = 7;
// "shoulder", "elbow", "pelvis_rotation", "thorax_rotation", "pelvis_obliquity", "pelvis_sway",
// "trunk_lean".
std::string_view upper_body_name(UpperBody part);

// The kinds of ground a controller set may have words for (the manifest's "terrain").
enum class Ground : std::uint8_t { Slopes, Stairs };
inline constexpr int kGroundCount = 2;
std::string_view metric_name(Metric metric);
std::optional<Metric> metric_from_name(std::string_view name);

using MetricValues = std::array<double, kMetricCount>;

// One joint controller: a fuzzy engine with one or two metric inputs and one output. Engines of
// the partition shape (triangles, constants, weighted average) run on the fast path.
class Controller {
 public:
  // Throws std::invalid_argument naming `source` when the engine does not fit: inputs must be
  // metric names, one output, and the engine must compile.
  Controller(fuzzy::Engine engine, std::string source);

  // Inline only for the packed form, the walker's eight calls a time step; the other forms are
  // out of line (with the walker's back-end test made once a step, 1.3 % off a step).
  double evaluate(const MetricValues& metrics, fuzzy::Workspace& workspace) const {
    if (packed_) {
      return packed_->evaluate(metrics[static_cast<std::size_t>(inputs_[0])],
                               metrics[static_cast<std::size_t>(inputs_[1])]);
    }
    return evaluate_unpacked(metrics, workspace);
  }
  fuzzy::Workspace make_workspace() const;

  const fuzzy::Engine& engine() const { return engine_; }
  const std::string& source() const { return source_; }
  bool fast_path() const { return partition_.has_value(); }
  // The engine packed for the fast path (null when it is not a partition controller of at most
  // PackedPartition::kMaxKnots knots per input), reading metrics input(0) and input(1).
  const fuzzy::PackedPartition* packed() const { return packed_ ? &*packed_ : nullptr; }
  std::size_t input_count() const { return input_count_; }
  Metric input(std::size_t i) const { return inputs_[i]; }

 private:
  double evaluate_unpacked(const MetricValues& metrics, fuzzy::Workspace& workspace) const;

  fuzzy::Engine engine_;
  std::string source_;
  std::array<Metric, 2> inputs_{};
  std::size_t input_count_ = 0;
  std::optional<fuzzy::PartitionController<double>> partition_;
  std::optional<fuzzy::PackedPartition> packed_;  // partition_ in one block, when it fits
  std::optional<fuzzy::Evaluator> evaluator_;
};

struct ControllerSet {
  std::string name;
  std::string description;
  // Time constant (s) with which a joint's velocity follows its controller: the limbs' inertia.
  double inertia = 0.03;
  double pelvis_tilt = 0.19;  // radians, anterior +
  // The swing knee's velocities are those of a thigh sweeping this angle (radians, toe off to
  // landing); a longer sweep (a longer step) scales them up in proportion, so the knee folds
  // deeper on longer steps, as people's do. 0: no scaling.
  double swing_knee_reference_sweep = 0.0;
  // Shortest step, in leg lengths, that this set walks without losing its rhythm (measured over
  // statures 1.50-2.00 m; docs/walk.md, "Step lengths"). The walker refuses shorter steps.
  double shortest_step = 0.46;
  // The body, step and speed a trained set learnt its walk at (the manifest's "body": a motion
  // capture clip's segment lengths, step, heel to heel, and speed); walkers built with this set's
  // tools use them unless told otherwise. None for sets not trained on a body.
  std::optional<rig::Segments> body;
  std::optional<double> body_step_length;  // m
  std::optional<double> body_speed;        // m/s
  // The cadence (steps a minute) the controllers' velocities are written for: a walk of another
  // cadence plays them faster or slower (Walker: cadence = speed / step length).
  double cadence = 110.0;
  // How briskly the walk changes its speed, m/s^2 (people: about 0.5-1).
  double acceleration = 0.6;
  // Starting from standing (Walker::go()): the first step is this share of the commanded one
  // (people's is shorter) and swings for this long (s); the controllers start at this share of
  // their tempo and reach all of it over start_easing seconds, so the body speeds up from rest.
  double first_step = 0.8;
  double first_step_duration = 0.5;
  double start_tempo = 0.4;
  double start_easing = 1.0;
  // The first step and a stop's closing step lift the heel this high (leg lengths; Walker::stop()
  // and go()); the standing body settles over its feet critically damped at this rate (1/s:
  // within 5 % of rest after 4.7 / rate seconds).
  double placed_step_lift = 0.12;
  double settle_rate = 7.0;
  std::vector<Controller> controllers;  // indexed by slot()
  // How long a step people take at each pace (the manifest's "stride": an FLL file reading
  // "pace" and answering "step" in leg lengths, rising with the pace). What the walker makes of a
  // speed it is asked for, and the other way round.
  std::optional<Controller> stride;
  // The stride's step (leg lengths) at this pace, and the pace of this step (its inverse, clamped
  // to the stride's pace range). Both need a stride.
  double step_at_pace(double pace) const;
  // Why the stride relation cannot be walked by speed: its step does not rise with the pace over
  // the input's range, or leaves 0.1 to 2 leg lengths there (the loader refuses such a set).
  // Empty when it can, or when the set has none.
  std::string stride_problem() const;
  double pace_at_step(double step) const;
  // The paces the stride is written for (its input's range).
  double slowest_pace() const;
  double fastest_pace() const;
  // The upper body's controllers, by UpperBody; a part without one holds still (arms hanging,
  // pelvis and chest square to the path). They read delta, other_delta, hip, knee, ankle, toe,
  // incline, stairs and pace (body::PathFollower supplies those), not sole.
  std::array<std::optional<Controller>, kUpperBodyCount> upper_body;

  // How the controllers change with the ground (the manifest's "terrain": "slopes" for level
  // ground and ramps, "stairs"): words for the incline (such as down, level, up) peaking at given
  // degrees, a strong triangular partition, and for a slot the controller file of a word; a word a
  // slot names no file for uses the slot's own controller. A slot's command is the words'
  // commands weighted by their degrees (a fuzzy rule "if incline is up then the knee follows
  // stance_knee_up"). No words: the slots' controllers everywhere.
  struct GroundWords {
    std::vector<std::string> words;  // in order of their peaks
    std::vector<double> peaks;       // degrees, increasing
    // Words under which a swinging leg's delta runs to the knee's end position, the paper's
    // ascent metric: the thigh where the leg, knee bent, puts the heel on the target (up stairs);
    // under the others, where the straight leg's heel points at it.
    std::vector<bool> ascent;
    // How bent (radians) each word lands a swinging leg's knee: its delta runs to where the leg,
    // knee bent so, points its heel at the target (down stairs, the thigh reaches further
    // forward to carry the foot over the edge). 0: a straight leg, as on level ground.
    std::vector<double> landing_knee;
    // [slot][word]: index into terrain_controllers, or -1 for the slot's own controller.
    std::array<std::vector<int>, kSlotCount> of_slot;
    bool empty() const { return words.empty(); }
  };
  std::array<GroundWords, kGroundCount> ground;  // [Ground]
  std::vector<Controller> terrain_controllers;   // the terrain files
  bool has_terrain_words() const { return !ground[0].empty() || !ground[1].empty(); }

  const Controller& at(LegPhase phase, Joint joint) const {
    return controllers[static_cast<std::size_t>(slot(phase, joint))];
  }
  // The controller of `slot` for word `word` of `ground` (its own for a word without a file).
  const Controller& controller(int slot, Ground ground, std::size_t word) const;
  // Every controller: the slots' and the terrain's.
  std::size_t controller_count() const { return controllers.size() + terrain_controllers.size(); }
  // One workspace per controller, in controller_count() order (slots', then terrain's), for
  // evaluate(); none when every controller is on the fast path, which reads none (so the
  // characters of a crowd carry none).
  std::vector<fuzzy::Workspace> make_workspaces() const;
  // The command of `slot` for these metrics: its controller's, or on terrain (metrics incline and
  // stairs) the words' blend. `workspaces` as make_workspaces() made them.
  double evaluate(int slot, const MetricValues& metrics,
                  std::vector<fuzzy::Workspace>& workspaces) const;
  // The same with each controller's command from `controller(index)`, index in controller_count()
  // order: another evaluator of the same controllers (a reference implementation to compare with).
  double evaluate(int slot, const MetricValues& metrics,
                  const std::function<double(std::size_t controller)>& controller) const;
  // What the terrain words make of one ground (the metrics incline and stairs), worked out once:
  // the words that fire and how much, and what follows from them. Everything else a step asks of
  // the words reads it, so a walker works it out again only when a leg's ground changes (never
  // on level ground).
  struct GroundBlend {
    const GroundWords* words = nullptr;  // the ground's words; null where the set has none
    std::array<std::size_t, 2> word{};   // the words that fire, in order of their peaks,
    std::array<double, 2> degree{};      // and how much
    std::size_t fired = 0;
    double ascent = 0.0;                     // ascent_weight()
    double landing_knee = 0.0;               // landing_knee()
    std::array<bool, 2> own_at{true, true};  // own_controllers_at(), [LegPhase]
    // own_degree(): the degrees of the fired words without a file for `slot`, summed in order.
    double own_degree(int slot) const noexcept {
      if (!words) return 1.0;
      double sum = 0.0;
      for (std::size_t i = 0; i < fired; ++i) {
        if (words->of_slot[static_cast<std::size_t>(slot)][word[i]] < 0) sum += degree[i];
      }
      return sum;
    }
  };
  GroundBlend blend(const MetricValues& metrics) const;
  // evaluate() with the metrics' blend worked out before.
  double evaluate(int slot, const MetricValues& metrics, const GroundBlend& blend,
                  std::vector<fuzzy::Workspace>& workspaces) const;
  // Whether for these metrics every slot of `phase` commands with its own controller alone (no
  // terrain word with a file for one of them fires): then evaluate() is its controller's.
  bool own_controllers_at(LegPhase phase, const MetricValues& metrics) const;
  // The degree (0 to 1) to which `slot` commands with its own controller for these metrics: 1 on
  // level ground, less where terrain words with files of their own fire.
  double own_degree(int slot, const MetricValues& metrics) const;
  // How far the ascent metric holds (0 to 1), and the landing knee (radians), for these metrics.
  double ascent_weight(const MetricValues& metrics) const;
  double landing_knee(const MetricValues& metrics) const;

  // The manifest's numbers, read and written through this one table: key, range, default, and
  // how a set holds the value (in the manifest's unit).
  struct ManifestNumber {
    const char* key;
    double low;
    double high;
    double fallback;
    double (*get)(const ControllerSet& set);
    void (*set)(ControllerSet& set, double value);
  };
  static std::span<const ManifestNumber> manifest_numbers();

  // Reads DIR/manifest.json and the FLL files it names.
  static ControllerSet load(const std::filesystem::path& directory);
  // The same from texts: `files` maps file names in the manifest to FLL text.
  static ControllerSet parse(std::string_view manifest,
                             const std::map<std::string, std::string>& files,
                             const std::string& source);
  // The sets compiled into the library (the controllers/ folder at build time).
  static std::vector<std::string> builtin_names();
  static ControllerSet builtin(std::string_view name);
};

}  // namespace fuzzygait::gait

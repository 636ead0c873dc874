// Tuning a controller set's terrain words (the manifest's "terrain": a kind of ground's word, such
// as the stairs' "up", with its controller files and landing knee) by walking the ground they are
// for and measuring the walk with eval::evaluate_terrain against the bounds of published human
// data. The same CMA-ES as the level tuner; the result keeps the files' rules and words.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fuzzygait/eval/terrain_report.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/learn/range.hpp"

namespace fuzzygait::learn {

// What a walk on one kind of ground should show (degrees, percent, steps a minute), after
// docs/results.md's sources: Riener et al. 2002, Protopapadaki et al. 2007, McFadyen & Winter 1988
// for stairs. An unbounded range (-inf, inf) is not priced.
struct TerrainBounds {
  eval::Footing footing = eval::Footing::StairUp;
  Range stance_percent{62.0, 76.0};
  Range hip{50.0, 80.0};
  Range knee{50.0, 80.0};
  Range peak_swing_knee{80.0, 105.0};
  Range peak_swing_hip{55.0, 75.0};
  Range knee_at_toe_off{-1e9, 1e9};
  Range hip_range{-1e9, 1e9};
  Range toe_down_vs_level{10.0, 30.0};
  Range cadence{60.0, 85.0};
  Range mid_stance_sole{-1e9, 1e9};     // deg, the sole to the surface at mid-stance
  Range step_error_percent{-1e9, 1e9};  // the steps' length against the command
  // Against the same body's level walk (the level group's means): hip and knee flexion at contact,
  // the ankle at mid-stance and the most knee flexion in early stance, each shifted by this many
  // degrees per degree of the ramp's slope (ramps only; unbounded: not priced).
  Range hip_per_degree{-1e9, 1e9};
  Range knee_per_degree{-1e9, 1e9};
  Range mid_stance_ankle_per_degree{-1e9, 1e9};
  Range early_stance_knee_per_degree{-1e9, 1e9};
  int ramp_degrees = 0;  // the ramp's slope, for the per-degree shifts and the group's angle
};
// The bounds for stair ascent and descent.
TerrainBounds stair_ascent_bounds();
TerrainBounds stair_descent_bounds();
// Ramps of `degrees` (uphill +): the sole within 5 deg of the surface in mid-stance, steps within
// 5 % of the command; uphill hip and knee more flexed at contact (McIntosh et al. 2006: about
// 1-1.5 deg a degree for the hip) and the stance ankle dorsiflexed by about the slope; downhill
// hip less flexed at contact and more knee flexion in early stance.
TerrainBounds ramp_bounds(int degrees);

// The level walk a condition's per-degree bounds compare with.
struct LevelReference {
  double hip = 0.0;  // means of the level steps, degrees
  double knee = 0.0;
  double mid_stance_ankle = 0.0;
  double early_stance_knee = 0.0;
};

struct TerrainCondition {
  std::string terrain;  // a terrain spec (io::terrain_from_spec), e.g. "stairs:0.17:0.28:10"
  double stature = 1.75;
  double step_length = 0.70;
  double seconds = 16.0;  // walked from the default start
  TerrainBounds bounds;
  // Measured on flat ground by terrain_cost when missing (tune_terrain measures it once).
  std::optional<LevelReference> level;
};

// The level walk of `set` for a condition's body and step.
LevelReference level_reference(const gait::ControllerSet& set, const TerrainCondition& condition,
                               double fps);

// The step a condition walks: its own, or the set's shortest (1 % longer) where that is longer.
double condition_step(const gait::ControllerSet& set, const TerrainCondition& condition);

// The terrain words' broken promises (word_penalty() over the set's terrain controllers).
double terrain_word_penalty(const gait::ControllerSet& set);

// Every price of the cost, named, in its unit.
struct TerrainWeights {
  double missing_height = 2000.0;  // a metre of the terrain's rise or drop not reached
  double bound = 0.3;              // a unit (deg, %, steps/min) of a group mean out of its range
  double bound_range = 0.1;        // a unit of a group's min or max out of the range
  double contact = 2.0;            // a millimetre of slip a frame or penetration past 1 mm
  double clearance = 1.0;          // a millimetre of swing clearance short of 10 mm
  double edge_across = 2.0;        // a millimetre of a foot's sole across an edge at a strike
  double nan_walk = 1e5;           // a walk with a NaN, or that could not be walked
  double pop = 1.0;                // a millimetre of the pelvis's largest move a frame past 80 mm
  double words = 100.0;            // a unit of the terrain words' broken promises
  double stall = 1000.0;           // a metre the pelvis fell short, in any 2 s after the first,
                                   // of walking 30 steps a minute at the condition's step
};

// Which words to tune: a ground and a word of its incline_deg.
struct TerrainWord {
  gait::Ground ground = gait::Ground::Stairs;
  std::string word;
};

struct TerrainTuneOptions {
  std::vector<TerrainCondition> conditions;
  std::vector<TerrainWord> words;
  TerrainWeights weights;
  double fps = 60.0;
  int generations = 150;
  int digits = 3;  // the values written are rounded to this many significant digits
  int threads = 2;
  std::uint64_t seed = 1;
  double sigma = 0.2;
  std::function<void(int generation, double cost)> progress;
};

// Throws std::invalid_argument naming the first field out of its range, an unknown word or a
// bad terrain spec.
void validate(const TerrainTuneOptions& options, const gait::ControllerSet& set);

// The objective, lower is better: each condition walked and priced. `report` receives a summary
// per condition.
double terrain_cost(const gait::ControllerSet& set, const TerrainTuneOptions& options,
                    std::string* report = nullptr);

struct TerrainTuneResult {
  // The best found, its values rounded to `digits` significant digits (more where that loses much
  // of the cost found); the start when nothing better was found.
  gait::ControllerSet set;
  double cost = 0.0;        // terrain_cost of `set`
  double start_cost = 0.0;  // of the set tuning began from
  int evaluations = 0;
};

// Tunes the output values, the delta knots and the landing knee of the given words' terrain
// files. The words must have files of their own in `start`.
TerrainTuneResult tune_terrain(const gait::ControllerSet& start, const TerrainTuneOptions& options);

}  // namespace fuzzygait::learn

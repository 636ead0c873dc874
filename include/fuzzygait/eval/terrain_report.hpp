// How a walk meets its ground (docs/measuring.md, "On terrain"): for each step, what the foot
// lands on and how the leg meets it; per kind of ground, means and ranges; over the whole walk,
// slip and penetration of every point of the leg against the ground. Computed from a Motion and
// its Terrain only, so it measures a walker's walk, a walk CSV read back, or motion capture.
//
// A step is one foot's gait cycle: from its strike (the contact beginning, begins_strike()) to its
// next strike, its stance then its swing. Angles are in degrees with the rig's clinical signs
// (hip and knee flexion +, ankle dorsiflexion +); the foot's pitch is the sole's (heel to ball)
// angle to the horizontal, toes up +, so a foot "N deg more toe-down than on level ground" has a
// pitch N deg below the level steps'. Lengths are metres. A figure that cannot be had (the walk
// ends before the step's cycle does; no edge passed) is NaN.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::eval {

// What a foot lands on: a stair when a riser lies between it and the foothold before (of either
// foot) and the ground rose or fell between them; else a ramp when the surface under it is
// inclined by kRampThreshold or more (up or down the way the walk goes); else level ground.
enum class Footing : std::uint8_t { Level, RampUp, RampDown, StairUp, StairDown };
const char* name(Footing footing);  // "level", "ramp up", "ramp down", "stairs up", "stairs down"

inline constexpr double kRampThreshold = 1.0;  // degrees
// How far in x (m) a foot point counts as over an edge for its clearance.
inline constexpr double kEdgeWindow = 0.05;

// A convex corner of the ground that a swing foot passes: a stair's nosing (the top of a riser),
// or the crest of a ramp. Clearances in metres.
struct EdgeClearance {
  rig::Point corner;
  bool nosing = false;  // beside a riser; else a ramp's crest
  // The toe tip's and the heel's smallest height above the corner while within kEdgeWindow of it
  // in x over the ground beside it at its height (the tread's side of a nosing, both sides of a
  // crest), over the swing's frames as sampled (toe off to the frame before the strike); NaN if
  // never there.
  double tip = 0.0;
  double heel = 0.0;
  // The smallest distance from the corner to the foot's sole outline (heel to ball to toe tip)
  // over the swing, negative when the corner lies above the outline (inside the foot).
  double foot = 0.0;
};

struct TerrainStep {
  rig::Side side = rig::Side::Left;
  std::size_t frame = 0;  // the strike
  double time = 0.0;      // s
  // The foothold: the foot point (heel, ball or toe tip) nearest the ground at the strike.
  double x = 0.0;
  double height = 0.0;    // of the ground under it
  std::size_t run = 0;    // the Terrain::runs() index it stands on (on stairs, the tread)
  bool forefoot = false;  // the ball or toe tip, not the heel, nearest the ground at the strike
  Footing footing = Footing::Level;
  double surface = 0.0;      // the ground's angle under the foothold, uphill along the walk +
  double rise = 0.0;         // the foothold's height above the foothold before (either foot)
  double step_length = 0.0;  // |x| from the foothold before
  // At contact.
  double hip = 0.0;
  double knee = 0.0;
  double ankle = 0.0;
  double foot_pitch = 0.0;
  // Stance: to toe off (the first frame out of contact).
  double early_stance_knee = 0.0;  // the most knee flexion over the first half of stance
  double knee_at_toe_off = 0.0;
  // At 50 % of stance: the sole's angle to the surface under it (toes up +), and the ankle.
  double mid_stance_sole = 0.0;
  double mid_stance_ankle = 0.0;
  // The cycle: to the same foot's next strike.
  double cycle_time = 0.0;  // s
  double cadence = 0.0;     // steps a minute, 120 / cycle_time
  double stance_percent = 0.0;
  double peak_swing_knee = 0.0;  // the most knee flexion over the swing
  double peak_swing_hip = 0.0;   // the most hip flexion over the swing
  double hip_range = 0.0;        // max - min hip flexion over the cycle
  double pelvis_rise = 0.0;      // the pelvis's height at the next strike minus at this one
  double ground_rise = 0.0;      // the next foothold's height minus this one's
  // The edges the swing passes: those whose x lies between the heel's at toe off and the toe
  // tip's at the next strike, in order.
  std::vector<EdgeClearance> edges;
  // The smallest of edges' tip, heel and foot clearances (NaN without edges).
  double edge_tip = 0.0;
  double edge_heel = 0.0;
  double edge_foot = 0.0;
};

// Mean and range of one figure over a group's steps that have it (NaN when none does).
struct Stat {
  int count = 0;
  double mean = 0.0;
  double min = 0.0;
  double max = 0.0;
};

// The steps on one kind of ground. Each Stat is of the TerrainStep field of the same name.
struct TerrainGroup {
  Footing footing = Footing::Level;
  int degrees = 0;  // ramps: the surface angle rounded to a whole degree (its sign the footing's)
  int steps = 0;
  double forefoot_percent = 0.0;  // of the steps landing on the forefoot
  Stat hip, knee, ankle, foot_pitch;
  // Level steps' mean foot pitch minus this group's: how much more toe-down the foot lands than
  // on level ground (NaN when the walk has no level steps).
  double toe_down_vs_level = 0.0;
  Stat early_stance_knee, knee_at_toe_off, mid_stance_sole, mid_stance_ankle;
  Stat cycle_time, cadence, stance_percent, peak_swing_knee, peak_swing_hip, hip_range;
  Stat pelvis_rise, ground_rise, step_length, rise;
  Stat edge_tip, edge_heel, edge_foot;
};

// The worst of one leg point against the ground over the walk, both legs.
struct PointContact {
  double max_slip = 0.0;          // m a frame along the surface, while within 2 mm of it
  double slip_time = 0.0;         // s, where the largest slip was
  double max_penetration = 0.0;   // m, the deepest below the surface (distance to it)
  double penetration_time = 0.0;  // s, where the deepest was
};

inline constexpr std::array<const char*, 5> kContactPoints = {"knee", "ankle", "heel", "ball",
                                                              "tip"};

// People's fastest joint speed (deg/s), the continuity bound: no leg joint of a walk may turn
// faster between two frames (3.8 deg a frame at 120 fps). It is the steepest slope of any mean
// curve of Bovi et al. 2011's adults (data/normative/bovi2011_adult_*.csv at the cadences of
// data/parameters/bovi2011_adult_parameters.csv): the knee walking fast (task 'l', 141 steps a
// minute), 455 deg/s; on stairs their fastest is 289 deg/s. The data has no toe curves; the toes
// are held to the same bound.
inline constexpr double kFastestJointSpeed = 455.0;

// The fastest any leg joint (hip, knee, ankle or toes, either leg) turned between two frames.
struct JointJump {
  double speed = 0.0;    // deg/s: the change over the frame interval
  double degrees = 0.0;  // the change, deg
  double time = 0.0;     // s, of the later frame
  rig::Side side = rig::Side::Left;
  const char* joint = "hip";  // "hip", "knee", "ankle" or "toe"
};

struct TerrainReport {
  std::vector<TerrainStep> steps;        // in time order, both feet
  std::vector<TerrainGroup> groups;      // level, ramps up by angle, ramps down, stairs up, down
  std::array<PointContact, 5> points{};  // kContactPoints order
  int nan_frames = 0;                    // frames with a NaN or infinity anywhere
  JointJump fastest_joint;               // over consecutive finite frames
  // The smallest distance between the sole outline and the ground (its surface and its edges)
  // in the middle 60 % of each complete swing, negative inside the ground; NaN without a swing.
  double min_swing_clearance = 0.0;
  double min_swing_clearance_time = 0.0;  // s
  double min_edge_tip = 0.0;              // the smallest of the steps' edge clearances
  double min_edge_heel = 0.0;
  double min_edge_foot = 0.0;
  double cadence = 0.0;  // steps a minute, first strike to last
  // The ground's runs, the run of the last foothold, and whether it is the last run (the
  // landing at the top or bottom of stairs); none on ground of one run.
  std::size_t runs = 0;
  std::size_t last_run = 0;
  std::optional<bool> reached_end;
};

// Measures `motion` on `terrain`. Throws std::invalid_argument when the motion has fewer than two
// frames or no positive frame rate.
TerrainReport evaluate_terrain(const Motion& motion, const terrain::Terrain& terrain);

// The contact bounds on terrain (docs/measuring.md, "On terrain") that the walk misses, one
// phrase each with its figure and bound: slip under 1 mm a frame and penetration under 1 mm for
// every leg point, swing clearance over the ground and its edges at least 10 mm, no NaN. Empty
// when the walk meets them all.
std::vector<std::string> missed_contact_bounds(const TerrainReport& report);

// The continuity bound the walk misses, as a phrase with its figure, joint, time and bound
// ("left knee turned 31.2 deg in one frame at 4.117 s (3744 deg/s; people's fastest 455 deg/s,
// 3.8 deg a frame)"), or empty when no joint turned faster than kFastestJointSpeed.
std::string missed_continuity_bound(const TerrainReport& report, double fps);

// The report as tables people read (per kind of ground, each step, the leg points), and as JSON.
std::string to_text(const TerrainReport& report);
std::string to_json(const TerrainReport& report);

// The signed distance (m) from `p` to the ground: + above it, - below it (inside), the nearest
// point of the surface however steep (a riser's face too).
double ground_distance(const terrain::Terrain& terrain, rig::Point p);

}  // namespace fuzzygait::eval

// The paper's walking system: each frame the walker measures its metrics, asks the fuzzy
// controllers for joint velocities, integrates them in small time steps, and keeps planted feet
// where they are. This is the runtime API a game calls every frame.
//
// Who drives what:
//   swing leg        hip, knee, ankle and toe: their swing controllers.
//   stance leg       hip and knee: their stance controllers. Ankle: the stance controller while
//                    the heel rolls down (heel rocker) and after the heel lifts (push-off); while
//                    the foot is flat the ground holds the foot and the ankle follows the shank,
//                    until the controller dorsiflexes the ankle slower than the shank rolls over
//                    the foot: the heel lifts. Toe: its controller, except after heel-off when the
//                    toes stay flat on the ground (the MTP angle follows the foot).
//   pelvis           carried by the leg planted first: its foot anchors the chain, so a planted
//                    foot never slides, and the body moves on without a jerk at heel strike.
//   double support   the newly planted leg's hip and knee close the chain by two-link IK onto
//                    its heel (the only IK in the system) while its ankle lowers the forefoot;
//                    once that foot is flat (or, landing on the forefoot, at once), the trailing
//                    leg lifts off (toe off) and the new leg carries the pelvis.
//   pace             walked by step length, the controllers play as written; walked by speed, each
//                    step is the set's stride relation's at the speed reached, and every
//                    controller's velocity plays at the cadence speed / step against the cadence
//                    the set is written for. "pace" is an input the controllers may read.
//   joint velocity   follows the controller's command with the set's inertia time constant, so
//                    velocities never jump, even where a phase hands a joint to another controller.
//                    What a joint remembers as its speed is capped at about a sprinter's, so that
//                    the chain snapping onto a far foot (awkward starts) does not carry on.
//   crouched starts  a carrying leg whose knee reaches the ground folds no further, and the
//                    swinging leg then aims at least half a step ahead of the hip (only awkward
//                    starts crouch that deep); a swing lasting a second puts its foot down.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::gait {

// Contact configuration of a leg.
enum class Phase : std::uint8_t {
  Swing,  // foot in the air
  Heel,   // heel on the ground, forefoot not yet (heel rocker, after heel strike)
  Flat,   // whole foot on the ground (after foot flat)
  Ball,   // heel lifted, ball and toes on the ground (after heel off)
};
const char* name(Phase phase);

enum class Event : std::uint8_t { HeelStrike, ForefootStrike, FootFlat, HeelOff, ToeOff };
const char* name(Event event);

// What the walker as a whole is doing.
enum class Locomotion : std::uint8_t {
  Walking,
  // Asked to stop: the next foot to lift is the closing step, put down beside the planted foot
  // while the planted leg brakes the body over it.
  Stopping,
  // Both feet planted: the body settles over them and then stands still.
  Standing,
};
const char* name(Locomotion locomotion);

struct LegState {
  Phase phase = Phase::Swing;
  rig::LegAngles angles;     // radians
  rig::LegAngles velocity;   // radians per second
  rig::Point anchor;         // the planted contact point (heel in Heel/Flat, ball in Ball)
  double sweep_start = 0.0;  // thigh inclination where delta = -1 (radians)
  // Thigh inclination where delta = +1 (radians): in stance set at the strike from the step
  // length; in swing rewritten every step, where a straight leg's heel would point at the target.
  double sweep_end = 0.0;
  double target_x = 0.0;       // swing: where the heel should land
  double swing_start = 0.0;    // swing: when the foot left the ground (s)
  double strike_x = 0.0;       // stance: where the heel landed
  double strike_time = 0.0;    // stance: when the foot landed (s)
  double delta = 0.0;          // the leg's last progress metric
  double step_from_x = 0.0;    // where the heel stood before this leg's current or last step
  std::size_t target_run = 0;  // swing: the run of the ground (a tread) the foot aims at
};

// Everything that changes while walking: plain data, so many characters pack into arrays.
struct WalkerState {
  double time = 0.0;
  double speed = 0.0;  // m/s: the walk's commanded speed now, moving toward the target
  // Walking by speed: how much faster than speed / step the controllers play, so that the
  // cadence makes the speed. Its target is learnt at each strike of a steady walk from the time
  // the step took; the gain eases toward it.
  double tempo_gain = 1.0;
  double tempo_gain_target = 1.0;
  rig::Point pelvis;
  double pelvis_tilt = 0.0;
  std::array<LegState, 2> legs;
  int lead = 0;                // leg whose planted foot carries the pelvis; -1 while airborne
  double fall_velocity = 0.0;  // m/s, while airborne (only after awkward starts)
  std::uint32_t heel_strikes = 0;
  Locomotion locomotion = Locomotion::Walking;
  // The leg whose step is placed rather than swung by its controllers, while it is in the air:
  // stopping, the closing step; starting, the first step.
  int placed_leg = -1;
  bool placed_first = false;      // the placed step is a start's first step (else a closing step)
  bool go_when_standing = false;  // go() came while a closing step was in the air
  // Walking to stop at a spot (stop_at()): where the feet are to stand (m along the walk); NaN
  // for none.
  double stop_x = std::numeric_limits<double>::quiet_NaN();
  // Stopping: how far the pelvis had to go to stand over the planted foot when the closing step
  // lifted (m); the planted leg brakes in proportion to what is left of it.
  double brake_distance = 0.0;
  // The placed step: where its heel and the foot's pitch (rad) were when it lifted, and how long
  // it lasts (s).
  rig::Point placed_from;
  double placed_pitch = 0.0;
  double placed_duration = 0.0;
  // The pelvis's velocity (m/s), measured while stopping and standing: the body settles from it.
  rig::Point pelvis_velocity;
  // Starting from standing, the share of their tempo at which the controllers play, rising to 1
  // (the first steps accelerate the body from rest); 1 while walking.
  double start_tempo = 1.0;
};

struct StartPose {
  // Random joint angles within the joint limits (seeded, deterministic) instead of the default
  // mid-stride pose, each foot the lowest point of its leg; the lower foot is put on the ground.
  bool random = false;
  std::uint64_t seed = 0;
  // The default start walks this long (s) before time 0 on level ground, so that the character
  // starts in its own steady gait; 0 starts straight from the mid-stride pose.
  double warm_up = 3.0;
  // Standing still, the feet side by side under the pelvis at x = 0 (on stairs, on the tread
  // nearest; random and warm_up are then ignored): the walker stands until go().
  bool standing = false;
};

struct WalkerOptions {
  rig::Segments segments = rig::segments_from_stature(1.75);
  // The walk's pace: a step length (the controllers play at the set's own cadence) or, when
  // `speed` is above 0, a speed whose step follows the set's stride relation (people's step
  // lengthens with their speed); `step_length` is then ignored.
  double step_length = 0.70;       // metres, heel to heel
  double speed = 0.0;              // m/s
  double time_step = 1.0 / 240.0;  // seconds (0.00001 to 0.05); advance() subdivides longer frames
  // Contact events kept between clear_events() calls, the oldest dropped beyond (0 to 4096; 0
  // keeps none). Room for them is taken at construction, 32 bytes an event: a crowd whose game
  // reads and clears its characters' events every frame needs a few (a step makes at most four a
  // leg), the default keeps about 7 s of walking.
  std::size_t event_capacity = 64;
  rig::JointLimits limits;
  StartPose start;
};

struct EventRecord {
  double time;
  rig::Side side;
  Event event;
  rig::Point where;
};

namespace detail {
struct WalkerStages;       // the stages of a time step, shared with Crowd (internal)
struct ControllerBackend;  // another evaluator of the controllers, for comparisons (internal)
}  // namespace detail

class Walker {
 public:
  // The controller set and terrain must outlive the walker and stay unchanged while it walks (it
  // keeps a workspace made for each of the set's controllers). Throws std::invalid_argument naming
  // the field for a bad rig or joint limits, a time step outside 0.00001-0.05 s, an incomplete
  // set, a step length outside min_step_length() to max_step_length(), or a speed outside
  // min_speed() to max_speed() or with a set that has no stride relation; and naming the rise
  // and x of the first stair ahead of the feet taller than tallest_stair() (stair_too_tall()).
  Walker(const ControllerSet& controllers, const WalkerOptions& options,
         const terrain::Terrain& terrain);
  // A temporary set or terrain would be gone before the first step.
  Walker(ControllerSet&&, const WalkerOptions&, const terrain::Terrain&) = delete;
  Walker(const ControllerSet&, const WalkerOptions&, terrain::Terrain&&) = delete;

  // Per frame: none of these throws or allocates.

  // Advances by dt seconds in equal sub-steps no longer than the time step. Returns false and
  // changes nothing when dt is NaN, negative or longer than an hour (kLongestAdvance).
  bool advance(double dt) noexcept;
  // Commands a step length from the next foot placement on: `metres` clamped to
  // [min_step_length(), max_step_length()], played at the set's cadence (a walk by speed eases
  // back to it at the set's acceleration). Returns the step length now commanded (the old one,
  // unchanged, for NaN).
  double set_step_length(double metres) noexcept;
  // Commands a speed: `metres_per_second` clamped to [min_speed(), max_speed()], reached at the
  // set's acceleration, each step the stride relation's at the speed reached. Returns the speed
  // now commanded; NaN, changing nothing, for NaN or a set without a stride relation.
  double set_speed(double metres_per_second) noexcept;
  // Stops on the spot: the next foot to lift closes beside the planted one while the planted leg
  // brakes the body over it; the walker then stands, both feet planted, its body settling over
  // them (about a step and a half from a walk: standing() then). The pace commanded is kept for
  // go(). Nothing while standing or already stopping.
  void stop() noexcept;
  // Stops with the feet side by side at x (m along the walk, the heels' x): the steps still to
  // take lengthen or shorten evenly, within min_step_length() to max_step_length(), so that a
  // foot lands there and the other closes beside it. A spot nearer than the shortest step stops
  // as stop() does, or one shortest step on, whichever is nearer; a spot behind the planted foot
  // stops at once. NaN or an infinite x changes nothing. Nothing while standing or stopping.
  // stop() calls a spot off (and stops at once).
  void stop_at(double x) noexcept;
  // Walks on from standing: the foot further behind (the left, side by side) steps first, a short
  // step, the body accelerating from rest over the first steps at the pace commanded. Stopping,
  // the stop is called off; once the closing step is in the air, the walker walks on as soon as
  // it stands still. Nothing while walking.
  void go() noexcept;
  Locomotion locomotion() const noexcept { return state_.locomotion; }
  bool standing() const noexcept { return state_.locomotion == Locomotion::Standing; }
  // The step the next foot placement takes (m).
  double step_length() const noexcept;
  // The speed commanded (m/s): by step length, the step at the set's cadence.
  double speed() const noexcept { return speed_target_; }
  double min_step_length() const noexcept;
  double max_step_length() const noexcept;
  // The speeds walked by speed (m/s): the stride relation's pace range, within the steps from
  // min_step_length() to max_step_length(); NaN for a set without a stride relation.
  double min_speed() const noexcept;
  double max_speed() const noexcept;

  const WalkerState& state() const noexcept { return state_; }
  rig::Pose pose() const noexcept;
  rig::LegPoints points(rig::Side side) const noexcept;
  Phase phase(rig::Side side) const noexcept { return state_.legs[rig::index(side)].phase; }
  bool in_contact(rig::Side side) const noexcept { return phase(side) != Phase::Swing; }
  double time() const noexcept { return state_.time; }
  const rig::Segments& segments() const noexcept { return segments_; }
  const ControllerSet& controllers() const noexcept { return *controllers_; }
  // The ground a leg's controllers read at the last time step: its metrics "incline" (deg, uphill
  // +) and "stairs" (0 to 1), in that order; both 0 before the first step.
  std::array<double, 2> ground_metrics(rig::Side side) const noexcept {
    return blend_ground_[rig::index(side)];
  }

  // Contact events since the last clear_events(), at most WalkerOptions::event_capacity (the
  // oldest dropped).
  const std::vector<EventRecord>& events() const noexcept { return events_; }
  void clear_events() noexcept { events_.clear(); }
  static constexpr std::size_t kMostEvents = 4096;   // the largest event_capacity
  static constexpr double kLongestAdvance = 3600.0;  // s, the longest dt advance() takes

  // Shortest step these controllers walk for these legs (metres): the set's shortest_step leg
  // lengths (0.46 for the default set); shorter steps lose the gait's rhythm.
  static double min_step_length(const ControllerSet& controllers, const rig::Segments& segments);
  // Longest step the legs reach (metres): 1.2 leg lengths.
  static double max_step_length(const rig::Segments& segments);
  // Tallest stair, up or down, these legs take one stair a step (metres): 0.40 leg lengths
  // (Segments::leg_length()), as measured over statures and treads (docs/terrain.md).
  static double tallest_stair(const rig::Segments& segments);
  // A stair of the ground taller than tallest_stair(): where its risers begin (x, m), its rise
  // (m, + up, - down, the height between the runs either side) and the tallest these legs take.
  struct StairTooTall {
    double x = 0.0;
    double rise = 0.0;
    double tallest = 0.0;
  };
  // The first stair at or beyond from_x (the walk goes +x) that these legs cannot take, or
  // nothing: what the constructor refuses, for a game to ask before it builds a walker.
  static std::optional<StairTooTall> stair_too_tall(
      const terrain::Terrain& terrain, const rig::Segments& segments,
      double from_x = -std::numeric_limits<double>::infinity());
  // v / sqrt(g * leg length): the pace of a speed (m/s) for these legs (Metric::Pace).
  static double pace(double speed, const rig::Segments& segments);

 private:
  friend struct detail::WalkerStages;
  friend class Crowd;

  Walker(const ControllerSet& controllers, const WalkerOptions& options,
         const terrain::Terrain& terrain, const detail::ControllerBackend* backend);
  void start(const StartPose& start_pose);
  void start_standing();
  void warm_up(double seconds);
  void stand(double h);
  rig::Point standing_pelvis() const;
  rig::Point flat_ankle(const LegState& l) const;
  double braking_speed() const;
  bool place_step(int leg, double h);
  bool closing_step_in_air() const noexcept;
  void record(rig::Side side, Event event, rig::Point where);
  void strike(int leg, Phase phase, rig::Point contact);
  void lift_off(int leg);
  void lift_off(int leg, double step);
  double stride_step_at(double speed) const;
  double step_speed() const;
  double tempo();
  void hand_over(int leg);
  void place_pelvis(int leg);
  bool close_chain(int leg);
  void settle_foot(int leg, const rig::LegAngles& commanded);
  double stance_target() const;
  double sole_angle(const LegState& l) const;
  void keep_knee_up(int leg, double known_good);
  void clear_ground(int leg, double max_change, double margin, bool with_tip = true);

  const ControllerSet* controllers_;
  const terrain::Terrain* terrain_;
  const detail::ControllerBackend* backend_ = nullptr;  // null: the set's own engines
  rig::Segments segments_;
  rig::JointLimits limits_;
  double step_length_;  // the step commanded when walking by step length
  std::uint32_t event_capacity_;
  bool by_speed_ = false;
  bool end_points_valid_ = false;
  bool blends_valid_ = false;
  double speed_target_ = 0.0;  // m/s
  double speed_unit_ = 1.0;    // sqrt(g * leg length): the speed of pace 1
  // The cadence the controllers play at over the set's, cached for the speed it was computed at.
  double tempo_ = 1.0;
  double tempo_speed_ = -1.0;
  double tempo_gain_ = 0.0;
  double follow_tempo_ = 0.0;  // the tempo of follow_
  double time_step_;
  double follow_step_ = 0.0;  // the h of follow_
  double follow_ = 0.0;       // share of the way a joint's velocity goes to its command in h
  double heel_offset_ = 0.0;
  double reach_ = 0.0;  // hip to heel of the straight leg, neutral ankle
  WalkerState state_;
  // ControllerSet::make_workspaces(): none when the set's controllers are all on the fast path.
  std::vector<fuzzy::Workspace> workspaces_;
  // Each leg's segment orientations when their sines and cosines were last computed, and those:
  // a time step places a leg several times, mostly with unchanged angles.
  std::array<rig::LegOrientation, 2> trig_orientation_{};
  std::array<rig::LegTrig, 2> trig_{};
  // Each leg's points as the last time step left them: the next one starts from them.
  std::array<rig::LegPoints, 2> end_points_{};
  // Each leg's terrain-word blend, worked out again only when the leg's ground (its metrics
  // incline and stairs, bit for bit) changes.
  std::array<ControllerSet::GroundBlend, 2> blends_{};
  std::array<std::array<double, 2>, 2> blend_ground_{};
  std::vector<EventRecord> events_;
};

}  // namespace fuzzygait::gait

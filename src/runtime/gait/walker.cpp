#include "fuzzygait/gait/walker.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "fuzzygait/compiler.hpp"
#include "fuzzygait/fuzzy/term.hpp"
#include "runtime/common/format.hpp"
#include "runtime/common/splitmix64.hpp"
#include "runtime/gait/leg_metrics.hpp"
#include "runtime/gait/walker_stages.hpp"
#include "runtime/rig/trigonometry.hpp"
#include "runtime/simd/lanes.hpp"

namespace fuzzygait::gait {
namespace {

using detail::chain_opening;
using detail::ControllerBackend;
using detail::foot_of;
using detail::inclination;
using detail::shank_of;
using detail::StepData;
using detail::SubSteps;
using detail::thigh_of;
using detail::WalkerStages;
using fuzzygait::common::number_text;
using rig::LegAngles;
using rig::LegPoints;
using rig::Point;
using rig::detail::arcsin;
using rig::detail::arctan2;
using rig::detail::sin_cos;

constexpr double kGravity = 9.81;
// A swing foot lands once its leg's delta reaches this (the leg arrives in front of the body).
constexpr double kLandingDelta = 0.8;
// Walking by speed, the tempo is learnt from the steps after the first few (the start's steps are
// not the walk's), within these bounds of speed / step.
constexpr std::uint32_t kStrikesBeforeTempoLearning = 3;
constexpr double kLeastTempoGain = 0.8;
constexpr double kMostTempoGain = 1.25;
// The time (s) over which the tempo's gain eases toward its target, about a step: a tempo that
// changed at once would jerk every joint's command at the strike.
constexpr double kTempoGainEasing = 0.5;
// Mid-swing, the clearance reflex keeps a swinging foot this far above the ground (m); lifting it
// well clear is the swing controllers' job.
constexpr double kSwingClearance = 0.01;
// Longest double support lasts before the newly planted leg takes the weight, s (walks hand over
// in 0.1 to 0.2).
constexpr double kLongestDoubleSupport = 0.4;
// Longest a swing lasts before the foot is put down anyway, s (walks swing for 0.3 to 0.5).
constexpr double kLongestSwing = 1.0;
// Fastest the clearance reflex folds the knee, rad/s.
constexpr double kReflexSpeed = 10.0;
// rad: a knee this straight cannot lower its foot further.
constexpr double kStraightKnee = 0.1;
// m: a swing foot's toes this close behind an edge they are below lift the thigh, at most this
// fast (rad/s).
constexpr double kLiftReach = 0.05;
constexpr double kLiftSpeed = 3.0;
// Walker::kLongestAdvance, an hour, is longer than any frame, so that a nonsense dt (a timer gone
// wrong) is refused rather than a program frozen for days or a count of sub-steps overflowing:
// with the shortest time step it is 3.6e8 sub-steps, within an int.
// Longest step, in leg lengths: as far as these legs reach. (The shortest is the controller
// set's: ControllerSet::shortest_step.)
constexpr double kLongestStep = 1.2;
// Tallest stair, up or down, in leg lengths (thigh, shank and ankle height): the rise the walker
// takes one stair a step. Measured with the default set over rises of 0.05-0.25 m, treads of
// 0.20-0.40 m and statures of 0.6-2.0 m (docs/terrain.md, "Which stairs"): from 0.42-0.50 leg
// lengths up, descents stall on every tread (0.16 m at 0.60 m stature, 0.19 at 0.80, 0.22 at
// 1.00); climbs reach the top on most treads to 0.40 and beyond. Below it, the stalls left depend
// on the tread, not on the rise, and are the walker's (a stalled walk is reported, not refused).
constexpr double kTallestStair = 0.40;
constexpr double kShortestTimeStep = 1e-5;
// How far an edge may reach up to a landing foot's sole (m): a heel reaching over a tread shorter
// than the foot lies on its nosing.
constexpr double kEdgeUnderSole = 0.002;
// m: a step across a riser between runs that are not treads (a kerb) climbs or drops as a stair
// of that rise with a tread this long would.
constexpr double kKerbTread = 0.30;
// rad: how far a straight knee's chain may ask it to bend backwards and still be closed straight.
constexpr double kStraightKneeSlack = 0.002;
// How far a foot's heel and toes keep from a tread's edges (m).
constexpr double kFootholdMargin = 0.005;
// A swinging leg aims to land with its knee bent where its target lies more than this (m) within
// the straight leg's reach, fully at twice this: level steps end a few millimetres within it.
constexpr double kStraightLanding = 0.02;
// m: a toe tip this close to the ground rests on it.
constexpr double kToesResting = 0.0005;
constexpr double kLongestTimeStep = 0.05;
// Standing and starting (the set's start and stop numbers are in ControllerSet). People stand
// with the knee nearly straight (a few degrees of flexion); a foot that lands as the walk stops
// comes down flat no faster than a loading response lowers it (rad/s).
constexpr double kStandingKnee = rig::radians(4.0);
constexpr double kFootSettling = rig::radians(120.0);
// A stop's closing step lasts as long as the body takes to brake over the planted foot, within
// these (s; people's swing lasts 0.35 to 0.45 s).
constexpr double kShortestClosingStep = 0.35;
constexpr double kLongestClosingStep = 0.6;
// A placed step's knee stays bent this much in the air (rad): a closing step's from a tenth of the
// way, a first step's most mid-way; less towards the landing.
constexpr double kPlacedKnee = rig::radians(15.0);
// A start's first step lands on the heel with the sole this far from the ground's slope, the
// foot pointing this much further down mid-way (rad).
constexpr double kFirstStepHeelPitch = rig::radians(15.0);
constexpr double kFirstStepDip = rig::radians(25.0);
// On a stair's tread it lands on the forefoot, the sole this far from the tread, toes down (rad).
constexpr double kFirstStepBallPitch = rig::radians(10.0);
// Over a placed step's way the ground is taken to fall from a corner a metre a metre, easing in
// over this share of the step's time after the lift and out over as much before the landing.
constexpr double kEdgeEasing = 0.2;
// Within this (m) the feet stand side by side: the left steps first.
constexpr double kSideBySide = 0.01;

// Between `good` (passes `ok`) and `bad` (fails it), the value nearest `bad` that still passes,
// to 40 halvings.
template <class Ok>
double bisect(double good, double bad, Ok ok) {
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (good + bad);
    (ok(mid) ? good : bad) = mid;
  }
  return good;
}

// How far the ground's corners (a stair's nosing, the top of a kerb) rise through the segment from
// a to b: the largest height of a corner above the segment, -infinity when none lies under it.
FUZZYGAIT_ALWAYS_INLINE double corner_depth(const terrain::Terrain& terrain, Point a, Point b) {
  if (b.x < a.x) std::swap(a, b);
  double depth = -std::numeric_limits<double>::infinity();
  for (const Point& c : terrain.corners_between(a.x, b.x)) {
    const double y = a.y + (b.y - a.y) * (c.x - a.x) / (b.x - a.x);
    depth = std::max(depth, c.y - y);
  }
  return depth;
}

// The ground's height under a foot's heel, ball and toe tip, and the corners under its sole and
// toes.
struct FootGround {
  double heel;
  double ball;
  double tip;
  double sole_corners;  // corner_depth of heel-ball
  double toe_corners;   // and of ball-tip
};
FUZZYGAIT_ALWAYS_INLINE FootGround ground_under(const terrain::Terrain& terrain,
                                                const LegPoints& p) {
  return {terrain.height(p.heel.x), terrain.height(p.ball.x), terrain.height(p.tip.x),
          corner_depth(terrain, p.heel, p.ball), corner_depth(terrain, p.ball, p.tip)};
}

// How deep the foot is in the ground: its heel, ball or (with_tip) toe tip below the ground, or a
// corner of the ground through its sole or toes (negative when all is above).
double foot_depth(const LegPoints& p, const FootGround& ground, bool with_tip = true) {
  const double sole =
      std::max({ground.heel - p.heel.y, ground.ball - p.ball.y, ground.sole_corners});
  return with_tip ? std::max({sole, ground.tip - p.tip.y, ground.toe_corners}) : sole;
}

Point contact_point(const LegPoints& p, Phase phase) {
  return phase == Phase::Ball ? p.ball : p.heel;
}

// Two joints of a leg (hip and knee, or ankle and toe) as one lane pair (SSE2 on x86-64): each
// operation is the same IEEE operation on each joint, so the bits are the scalar code's, in fewer
// instructions.
using detail::JointPair;
struct Joints {
  JointPair hip_knee;
  JointPair ankle_toe;
};
Joints joints(const LegAngles& a) {
  return std::bit_cast<Joints>(a);
}
void store(LegAngles& a, const Joints& v) {
  a = std::bit_cast<LegAngles>(v);
}

}  // namespace

const char* name(Phase phase) {
  switch (phase) {
    case Phase::Swing:
      return "swing";
    case Phase::Heel:
      return "heel";
    case Phase::Flat:
      return "flat";
    case Phase::Ball:
      return "ball";
  }
  return "?";
}

const char* name(Locomotion locomotion) {
  switch (locomotion) {
    case Locomotion::Walking:
      return "walking";
    case Locomotion::Stopping:
      return "stopping";
    case Locomotion::Standing:
      return "standing";
  }
  return "?";
}

const char* name(Event event) {
  switch (event) {
    case Event::HeelStrike:
      return "heel strike";
    case Event::ForefootStrike:
      return "forefoot strike";
    case Event::FootFlat:
      return "foot flat";
    case Event::HeelOff:
      return "heel off";
    case Event::ToeOff:
      return "toe off";
  }
  return "?";
}

double Walker::min_step_length(const ControllerSet& controllers, const rig::Segments& s) {
  return controllers.shortest_step * s.leg_length();
}

double Walker::max_step_length(const rig::Segments& s) {
  return kLongestStep * s.leg_length();
}

double Walker::tallest_stair(const rig::Segments& s) {
  return kTallestStair * s.leg_length();
}

std::optional<Walker::StairTooTall> Walker::stair_too_tall(const terrain::Terrain& terrain,
                                                           const rig::Segments& s, double from_x) {
  const double tallest = tallest_stair(s);
  const std::vector<terrain::Terrain::Run>& runs = terrain.runs();
  for (std::size_t k = 0; k + 1 < runs.size(); ++k) {
    // The risers between two runs make one stair however many segments they are.
    const double foot = runs[k].end;
    if (foot < from_x) continue;
    const double rise = terrain.height(runs[k + 1].begin) - terrain.height(foot);
    if (std::abs(rise) > tallest) return StairTooTall{foot, rise, tallest};
  }
  return std::nullopt;
}

Walker::Walker(const ControllerSet& controllers, const WalkerOptions& options,
               const terrain::Terrain& terrain)
    : Walker(controllers, options, terrain, nullptr) {}

Walker::Walker(const ControllerSet& controllers, const WalkerOptions& options,
               const terrain::Terrain& terrain, const ControllerBackend* backend)
    : controllers_(&controllers),
      terrain_(&terrain),
      backend_(backend),
      segments_(options.segments),
      limits_(options.limits),
      step_length_(options.step_length),
      event_capacity_(static_cast<std::uint32_t>(std::min(options.event_capacity, kMostEvents))),
      time_step_(options.time_step) {
  rig::validate(segments_);
  rig::validate(limits_);
  if (controllers.controllers.size() != static_cast<std::size_t>(kSlotCount)) {
    throw std::invalid_argument("the controller set is incomplete");
  }
  if (!(time_step_ >= kShortestTimeStep && time_step_ <= kLongestTimeStep)) {
    throw std::invalid_argument("time step must be between 0.00001 and 0.05 s, got " +
                                number_text(time_step_));
  }
  if (options.event_capacity > kMostEvents) {
    throw std::invalid_argument("event capacity must be at most " + std::to_string(kMostEvents) +
                                " events, got " + std::to_string(options.event_capacity));
  }
  speed_unit_ = std::sqrt(kGravity * segments_.leg_length());
  by_speed_ = !(options.speed == 0.0);
  if (by_speed_) {
    if (!controllers.stride) {
      throw std::invalid_argument("the controller set '" + controllers.name +
                                  "' has no stride relation (the manifest's 'stride'): walk it by "
                                  "step length");
    }
    if (!(options.speed >= min_speed() && options.speed <= max_speed())) {
      throw std::invalid_argument("speed must be between " + number_text(min_speed(), 3) + " and " +
                                  number_text(max_speed(), 3) + " m/s (the paces '" +
                                  controllers_->name + "' walks with these legs), got " +
                                  number_text(options.speed) + " m/s");
    }
    speed_target_ = options.speed;
  } else if (!(options.step_length >= min_step_length() &&
               options.step_length <= max_step_length())) {
    throw std::invalid_argument(
        "step length must be between " + number_text(min_step_length(), 3) + " m (" +
        number_text(controllers_->shortest_step) + " leg lengths, the shortest '" +
        controllers_->name + "' walks) and " + number_text(max_step_length(), 3) + " m (" +
        number_text(kLongestStep) + " leg lengths, the reach of these legs), got " +
        number_text(options.step_length) + " m");
  } else {
    speed_target_ = step_speed();
  }
  workspaces_ = controllers.make_workspaces();
  events_.reserve(event_capacity_);
  heel_offset_ = detail::heel_offset(segments_);
  const LegPoints straight = rig::forward_kinematics(segments_, {0.0, 0.0}, 0.0, LegAngles{});
  reach_ = std::hypot(straight.heel.x - straight.hip.x, straight.heel.y - straight.hip.y);
  start(options.start);
  // The ground ahead of the feet must be ground these legs take: a frozen walk is no walk.
  const double behind = std::min(points(rig::Side::Left).heel.x, points(rig::Side::Right).heel.x);
  if (const std::optional<StairTooTall> stair = stair_too_tall(terrain, segments_, behind)) {
    throw std::invalid_argument(
        "the ground has a stair " + number_text(std::abs(stair->rise), 3) + " m " +
        (stair->rise > 0.0 ? "up" : "down") + " at x = " + number_text(stair->x, 3) +
        " m, taller than these legs take one stair a step: " + number_text(stair->tallest, 3) +
        " m (" + number_text(kTallestStair) + " leg lengths of " +
        number_text(segments_.leg_length(), 3) + " m)");
  }
}

double Walker::min_step_length() const noexcept {
  return controllers_->shortest_step * segments_.leg_length();
}

double Walker::max_step_length() const noexcept {
  return kLongestStep * segments_.leg_length();
}

double Walker::pace(double speed, const rig::Segments& s) {
  return speed / std::sqrt(kGravity * s.leg_length());
}

double Walker::set_step_length(double metres) noexcept {
  if (std::isnan(metres)) return step_length_;
  step_length_ = std::clamp(metres, min_step_length(), max_step_length());
  by_speed_ = false;
  speed_target_ = step_speed();
  return step_length_;
}

double Walker::set_speed(double metres_per_second) noexcept {
  if (std::isnan(metres_per_second) || !controllers_->stride) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  speed_target_ = std::clamp(metres_per_second, min_speed(), max_speed());
  by_speed_ = true;
  return speed_target_;
}

void Walker::stop() noexcept {
  // (The last call wins: a go() waiting for the walker to stand is called off.)
  state_.go_when_standing = false;
  state_.stop_x = std::numeric_limits<double>::quiet_NaN();
  if (state_.locomotion != Locomotion::Walking) return;
  // (A first step in the air lands as placed; the foot after it closes.)
  state_.locomotion = Locomotion::Stopping;
}

void Walker::stop_at(double x) noexcept {
  if (state_.locomotion != Locomotion::Walking || !std::isfinite(x)) return;
  state_.stop_x = x;
}

bool Walker::closing_step_in_air() const noexcept {
  return state_.placed_leg >= 0 && !state_.placed_first;
}

void Walker::go() noexcept {
  WalkerState& s = state_;
  if (s.locomotion == Locomotion::Walking) return;
  s.stop_x = std::numeric_limits<double>::quiet_NaN();
  if (s.locomotion == Locomotion::Stopping) {
    // Before the closing step lifts, the stop is called off; after, the walker walks on once it
    // stands still.
    if (!closing_step_in_air()) {
      s.locomotion = Locomotion::Walking;
    } else {
      s.go_when_standing = true;
    }
    return;
  }
  s.go_when_standing = false;
  const int stepping =
      points(rig::Side::Right).heel.x < points(rig::Side::Left).heel.x - kSideBySide ? 1 : 0;
  const int standing = 1 - stepping;
  LegState& stance = s.legs[static_cast<std::size_t>(standing)];
  s.locomotion = Locomotion::Walking;
  s.lead = standing;
  s.start_tempo = controllers_->start_tempo;
  s.heel_strikes = 0;
  s.pelvis_velocity = {};
  // The standing leg is at mid-stance (delta 0): its sweep ends where a stance of this step
  // ends and begins as far ahead of the thigh.
  stance.strike_time = s.time;
  stance.sweep_end = stance_target();
  stance.sweep_start = 2.0 * thigh_of(s.pelvis_tilt, stance.angles) - stance.sweep_end;
  for (LegState& l : s.legs)
    l.velocity = LegAngles{};
  LegState& step = s.legs[static_cast<std::size_t>(stepping)];
  const LegPoints from = points(static_cast<rig::Side>(stepping));
  lift_off(stepping, std::max(min_step_length(), controllers_->first_step * step_length()));
  s.placed_leg = stepping;
  s.placed_first = true;
  s.placed_from = from.heel;
  s.placed_pitch = foot_of(s.pelvis_tilt, step.angles);
  s.placed_duration = controllers_->first_step_duration;
}

double Walker::step_length() const noexcept {
  return by_speed_ ? stride_step_at(state_.speed) : step_length_;
}

double Walker::step_speed() const {
  return step_length_ * controllers_->cadence / 60.0;
}

double Walker::stride_step_at(double speed) const {
  return std::clamp(controllers_->step_at_pace(speed / speed_unit_) * segments_.leg_length(),
                    min_step_length(), max_step_length());
}

double Walker::min_speed() const noexcept {
  if (!controllers_->stride) return std::numeric_limits<double>::quiet_NaN();
  const double legs = segments_.leg_length();
  return std::max(controllers_->slowest_pace(),
                  controllers_->pace_at_step(min_step_length() / legs)) *
         speed_unit_;
}

double Walker::max_speed() const noexcept {
  if (!controllers_->stride) return std::numeric_limits<double>::quiet_NaN();
  const double legs = segments_.leg_length();
  return std::min(controllers_->fastest_pace(),
                  controllers_->pace_at_step(max_step_length() / legs)) *
         speed_unit_;
}

// The cadence the controllers play at over the set's: 1 walking by step length, speed / step
// over the set's cadence walking by speed.
// Starting from standing, times the start's share (start_tempo).
double Walker::tempo() {
  if (!by_speed_) return state_.start_tempo;
  if (!(state_.speed == tempo_speed_) || !(state_.tempo_gain == tempo_gain_)) {
    tempo_speed_ = state_.speed;
    tempo_gain_ = state_.tempo_gain;
    tempo_ = state_.speed / step_length() * 60.0 / controllers_->cadence * state_.tempo_gain;
  }
  return tempo_ * state_.start_tempo;
}

rig::Pose Walker::pose() const noexcept {
  rig::Pose p;
  p.pelvis = state_.pelvis;
  p.pelvis_tilt = state_.pelvis_tilt;
  p.legs = {state_.legs[0].angles, state_.legs[1].angles};
  return p;
}

LegPoints Walker::points(rig::Side side) const noexcept {
  return rig::forward_kinematics(segments_, state_.pelvis, state_.pelvis_tilt,
                                 state_.legs[rig::index(side)].angles);
}

namespace {
bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// The cached sines and cosines brought to orientation o: all four when the thigh, shank or foot
// turned; only the toes' when they alone did (the ground bent them up, about every other step),
// the bits their lane of the four would get.
void update_trig(rig::LegOrientation& cached, rig::LegTrig& trig, const rig::LegOrientation& o) {
  if (same_bits(o.thigh, cached.thigh) && same_bits(o.shank, cached.shank) &&
      same_bits(o.foot, cached.foot)) {
    if (same_bits(o.toes, cached.toes)) return;
    cached.toes = o.toes;
    const rig::detail::SinCos toes = sin_cos(o.toes);
    trig.toes_sin = toes.sin;
    trig.toes_cos = toes.cos;
    return;
  }
  cached = o;
  trig = rig::detail::leg_trig(o);
}
}  // namespace

// rig::forward_kinematics with the walker's tilt: the same points, with the segments' sines and
// cosines computed only when an orientation changed (bit for bit) since the leg was last placed.
// Inline, so that a caller computes only the points it reads.
inline LegPoints WalkerStages::leg_points(Walker& w, int leg, Point hip, const LegAngles& angles) {
  const rig::LegOrientation o = rig::orientation(w.state_.pelvis_tilt, angles);
  const auto k = static_cast<std::size_t>(leg);
  rig::LegOrientation& cached = w.trig_orientation_[k];
  // The test inline: in a crowd, which fills the caches for a step in one batch, most calls pass.
  if (!(same_bits(o.thigh, cached.thigh) && same_bits(o.shank, cached.shank) &&
        same_bits(o.foot, cached.foot) && same_bits(o.toes, cached.toes))) {
    update_trig(cached, w.trig_[k], o);
  }
  return rig::forward_kinematics(w.segments_, hip, w.trig_[k]);
}

void Walker::record(rig::Side side, Event event, Point where) {
  if (event_capacity_ == 0) return;
  if (events_.size() == event_capacity_) events_.erase(events_.begin());
  events_.push_back({state_.time, side, event, where});
}

double Walker::stance_target() const {
  return detail::stance_target(segments_, step_length());
}

void Walker::start(const StartPose& start_pose) {
  state_ = WalkerState{};
  end_points_valid_ = false;
  state_.pelvis_tilt = controllers_->pelvis_tilt;
  const double tilt = state_.pelvis_tilt;
  LegState& left = state_.legs[0];
  LegState& right = state_.legs[1];
  // The default start's thigh angles and speeds are those of a 0.70 m step of a 1.75 m adult,
  // scaled to this step for this leg (a short step of a long leg sweeps a small angle).
  const double reference = 0.70 / rig::segments_from_stature(1.75).leg_length();
  state_.speed = speed_target_;
  const double scale = std::clamp(step_length() / segments_.leg_length() / reference, 0.5, 1.5);
  if (start_pose.standing) {
    start_standing();
    return;
  }
  if (start_pose.random) {
    // Seeds hashed apart first, so nearby seeds do not walk the same sequence.
    std::uint64_t x = (start_pose.seed ^ 0x632BE59BD9B4E019ull) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 31)) * 0x94D049BB133111EBull;
    detail::SplitMix64 random(x);
    auto uniform = [&random](double low, double high) {
      return low + (high - low) * random.uniform();
    };
    // Any angles within the joint limits, as long as each foot is the lowest part of its leg
    // (the feet near the ground, not a kneeling start) and, should it be the foot put down, its
    // toes can lie on the ground within their limit.
    const double slope = terrain_->slope(0.0);
    for (int attempt = 0; attempt < 10000; ++attempt) {
      bool feet_lowest = true;
      for (LegState& leg : state_.legs) {
        leg.angles.hip = uniform(limits_.minimum.hip, limits_.maximum.hip);
        leg.angles.knee = uniform(limits_.minimum.knee, limits_.maximum.knee);
        leg.angles.ankle = uniform(limits_.minimum.ankle, limits_.maximum.ankle);
        leg.angles.toe = uniform(limits_.minimum.toe, limits_.maximum.toe);
        const LegPoints p = rig::forward_kinematics(segments_, {0.0, 0.0}, tilt, leg.angles);
        const double foot = std::min({p.heel.y, p.ball.y, p.tip.y});
        const bool toes_fit = slope - foot_of(tilt, leg.angles) <= limits_.maximum.toe;
        feet_lowest = feet_lowest && foot < p.knee.y - 0.15 && p.ankle.y < p.knee.y && toes_fit;
      }
      if (feet_lowest) break;
    }
  } else {
    // Mid stride: the right foot under the body with its heel just lifted (it starts on the
    // ball of the foot; flat only for the longest steps), the left leg just off the ground
    // behind it and already swinging forward (the velocities of a walk at this moment).
    right.angles = {rig::radians(8.0 * scale) + tilt, rig::radians(12.0), 0.0, 0.0};
    left.angles = {rig::radians(-14.0 * scale) + tilt, rig::radians(45.0), rig::radians(-12.0),
                   rig::radians(25.0)};
    // (played at the walk's tempo, as the controllers are)
    const double tempo = this->tempo();
    left.velocity = {rig::radians(150.0 * scale) * tempo, rig::radians(300.0) * tempo,
                     rig::radians(60.0) * tempo, 0.0};
    right.velocity = {rig::radians(-80.0 * scale) * tempo, 0.0, 0.0, 0.0};
  }
  // Put the lower foot on the ground with the pelvis above x = 0.
  state_.pelvis = {0.0, 0.0};
  std::array<double, 2> lowest{};
  for (int leg = 0; leg < 2; ++leg) {
    const LegPoints p = rig::forward_kinematics(segments_, state_.pelvis, tilt,
                                                state_.legs[static_cast<std::size_t>(leg)].angles);
    lowest[static_cast<std::size_t>(leg)] =
        std::min({p.heel.y - terrain_->height(p.heel.x), p.ball.y - terrain_->height(p.ball.x),
                  p.tip.y - terrain_->height(p.tip.x)});
  }
  // The default start stands on the right foot; a random start on the lower foot.
  const int down = start_pose.random ? (lowest[0] <= lowest[1] ? 0 : 1) : 1;
  state_.pelvis.y = -lowest[static_cast<std::size_t>(down)];
  LegState& planted = state_.legs[static_cast<std::size_t>(down)];
  LegPoints p = rig::forward_kinematics(segments_, state_.pelvis, tilt, planted.angles);
  // Toes resting on the ground keep the foot's sole on it.
  if (p.tip.y - terrain_->height(p.tip.x) < std::min(p.heel.y, p.ball.y) - 1e-9) {
    planted.angles.toe = terrain_->slope(p.ball.x) - foot_of(tilt, planted.angles);
    state_.pelvis.y = 0.0;
    p = rig::forward_kinematics(segments_, state_.pelvis, tilt, planted.angles);
    state_.pelvis.y =
        -std::min(p.heel.y - terrain_->height(p.heel.x), p.ball.y - terrain_->height(p.ball.x));
    p = rig::forward_kinematics(segments_, state_.pelvis, tilt, planted.angles);
  }
  const double heel_gap = p.heel.y - terrain_->height(p.heel.x);
  const double ball_gap = p.ball.y - terrain_->height(p.ball.x);
  const double flat_within = 0.002;  // m
  const Phase phase = std::abs(heel_gap - ball_gap) < flat_within ? Phase::Flat
                      : heel_gap < ball_gap                       ? Phase::Heel
                                                                  : Phase::Ball;
  if (phase == Phase::Flat) {
    // Level the sole on the ground.
    planted.angles.ankle = terrain_->slope(p.heel.x) - shank_of(tilt, planted.angles);
    state_.pelvis.y = 0.0;
    p = rig::forward_kinematics(segments_, state_.pelvis, tilt, planted.angles);
    state_.pelvis.y = terrain_->height(p.heel.x) - p.heel.y;
    p = rig::forward_kinematics(segments_, state_.pelvis, tilt, planted.angles);
  }
  state_.lead = -1;
  strike(down, phase,
         phase == Phase::Ball ? Point{p.ball.x, terrain_->height(p.ball.x)}
                              : Point{p.heel.x, terrain_->height(p.heel.x)});
  const int up = 1 - down;
  if (start_pose.random) {
    lift_off(up);
  } else {
    // As if the right heel had struck a step ago and the left toes had just left the ground.
    planted.sweep_start = rig::radians(24.0 * scale);
    planted.strike_x = p.heel.x;
    lift_off(up);
    LegState& swinging = state_.legs[static_cast<std::size_t>(up)];
    swinging.sweep_start = thigh_of(tilt, swinging.angles) + rig::radians(2.0 * scale);
    if (start_pose.warm_up > 0.0) warm_up(start_pose.warm_up);
  }
  events_.clear();
  state_.heel_strikes = 0;
}

// Both feet flat side by side, their ankles under the pelvis at x = 0, the legs as people stand.
void Walker::start_standing() {
  const rig::Segments& s = segments_;
  const rig::detail::SinCos ground = sin_cos(terrain_->slope(0.0));
  // The whole foot on one run: on stairs, the tread nearest.
  const double wanted = -(s.heel * ground.cos - s.ankle_height * ground.sin);
  const terrain::Terrain::Foothold foothold =
      terrain_->foothold(wanted, wanted, s.foot_length(), kFootholdMargin);
  const double heel_x = terrain_->point_on_run(foothold.heel_x, foothold.run);
  for (LegState& l : state_.legs) {
    l.phase = Phase::Flat;
    l.anchor = {heel_x, terrain_->height(heel_x)};
    l.strike_x = heel_x;
    l.step_from_x = heel_x;
    l.target_x = heel_x;
    l.target_run = foothold.run;
    l.angles = {state_.pelvis_tilt, kStandingKnee, 0.0, 0.0};
  }
  state_.pelvis = standing_pelvis();
  for (int leg = 0; leg < 2; ++leg)
    close_chain(leg);
  state_.lead = 1;
  state_.locomotion = Locomotion::Standing;
  events_.clear();
}

// Stopping with the closing step in the air: the fastest the pelvis may move on (m/s), slowing
// evenly from the walk's speed to rest over the planted foot, as a body braking at a constant
// rate does; infinity otherwise.
double Walker::braking_speed() const {
  const WalkerState& s = state_;
  if (s.locomotion != Locomotion::Stopping || !closing_step_in_air() || s.lead < 0 ||
      s.lead == s.placed_leg) {
    return std::numeric_limits<double>::infinity();
  }
  const double left = flat_ankle(s.legs[static_cast<std::size_t>(s.lead)]).x - s.pelvis.x;
  return s.speed * std::sqrt(std::clamp(left / s.brake_distance, 0.0, 1.0));
}

// A time step of a placed step (the leg `leg`, swinging): a stop's closing step or a start's first
// step. The foot is carried from where it lifted to its target over placed_duration along a
// minimum-jerk path, the heel lifted the set's placed_step_lift mid-way and kept clear of the
// ground, its sole turning to its landing pitch by four fifths of the way (level for a closing
// step, on the heel for a first step, on the forefoot for a first step onto a tread); hip and
// knee reach its ankle (two-link IK, the knee forward), the toes straighten. True once it is down.
bool Walker::place_step(int leg, double h) {
  WalkerState& s = state_;
  LegState& l = s.legs[static_cast<std::size_t>(leg)];
  const rig::Segments& g = segments_;
  auto minimum_jerk = [](double u) { return u * u * u * (10.0 + u * (-15.0 + 6.0 * u)); };
  const double u = std::clamp((s.time + h - l.swing_start) / s.placed_duration, 0.0, 1.0);
  const bool first = s.placed_first;
  // (A first step's heel rises a tenth of the way before the foot goes forward: its toes leave
  // the ground rather than skim it.)
  const double along = minimum_jerk(first ? std::max(0.0, (u - 0.1) / 0.9) : u);
  // A first step lands on its heel, the toes up, its foot pointing down mid-way as people's does.
  // The lift (of the set's placed_step_lift) comes down with no speed at the landing; a first
  // step's foot leaves the ground from rest, a closing step's heel is rising already (as fast as a
  // walk's at toe off; it peaks at 0.58 a third of the way).
  const double arc = std::sin(std::numbers::pi * u);
  const double lift = first ? arc * arc : arc * (1.0 - u);
  const double slope = terrain_->slope(l.target_x);
  // (On a stair's tread a first step lands on the forefoot, toes down, as the walk's steps there
  // do.)
  const bool ball_first = first && terrain_->on_tread(l.target_x);
  const bool heel_first = first && !ball_first;
  const double landing = heel_first   ? slope + kFirstStepHeelPitch
                         : ball_first ? slope - kFirstStepBallPitch
                                      : slope;
  const double pitch = s.placed_pitch +
                       (landing - s.placed_pitch) * minimum_jerk(std::min(1.0, u / 0.8)) -
                       (first ? kFirstStepDip * lift : 0.0);
  const double ground_y = terrain_->height(terrain_->point_on_run(l.target_x, l.target_run));
  const rig::detail::SinCos sole = sin_cos(pitch);
  const double sole_length = g.heel + g.ball;
  // (Landing on the forefoot, the heel comes down above the ground.)
  const double landing_heel_y =
      ground_y + (ball_first ? sole_length * std::sin(kFirstStepBallPitch) : 0.0);
  Point heel{s.placed_from.x + (l.target_x - s.placed_from.x) * along,
             s.placed_from.y + (landing_heel_y - s.placed_from.y) * along +
                 controllers_->placed_step_lift * g.leg_length() * lift};
  // Heel and ball above the ground until the landing (kSwingClearance mid-way); the toes bend up
  // where it holds them (finish_step()). Over a stair's edge the ground is taken as the corners'
  // cones (cleared_ground()), so the foot rises to an edge and comes down past it smoothly, from
  // the ground it lifts from to the ground it lands on.
  const double clearance = kSwingClearance * lift;
  const double ball_x = heel.x + sole_length * sole.cos;
  const double lowest = std::min(s.placed_from.x, l.target_x) - sole_length;
  const double highest = std::max(s.placed_from.x, l.target_x) + 2.0 * sole_length;
  const std::span<const Point> corners = terrain_->corners_between(lowest, highest);
  const double edges = minimum_jerk(std::min(1.0, std::min(u, 1.0 - u) / kEdgeEasing));
  auto cleared_ground = [&](double x) {
    const double ground = terrain_->height(x);
    double cone = ground;
    for (const Point& c : corners)
      cone = std::max(cone, c.y - std::abs(x - c.x));
    return ground + edges * (cone - ground);
  };
  heel.y = std::max({heel.y, cleared_ground(heel.x) + clearance,
                     cleared_ground(ball_x) - sole_length * sole.sin + clearance});
  Point ankle{heel.x + g.heel * sole.cos - g.ankle_height * sole.sin,
              heel.y + g.heel * sole.sin + g.ankle_height * sole.cos};
  const Point hip = s.pelvis;
  // The knee stays bent in the air: an ankle beyond the reach of a knee bent kPlacedKnee (less
  // and less towards the landing, and from none at a first step's start) is lifted within it, as
  // a foot left behind a moving body is.
  if (u < 1.0) {
    // (A closing step's bend comes in over its first tenth: a leg lifting straighter, as from a
    // stair, is not pulled up at once.)
    const rig::detail::SinCos bend =
        sin_cos(kPlacedKnee * (first ? arc : std::min(1.0, 10.0 * u) * (1.0 - u)));
    const double reach =
        std::sqrt(g.thigh * g.thigh + g.shank * g.shank + 2.0 * g.thigh * g.shank * bend.cos);
    const double dx = ankle.x - hip.x;
    if (std::hypot(dx, ankle.y - hip.y) > reach && std::abs(dx) < reach) {
      const double raise = hip.y - std::sqrt(reach * reach - dx * dx) - ankle.y;
      heel.y += raise;
      ankle.y += raise;
    }
  }
  const double towards = inclination(hip, ankle);
  const double distance = std::clamp(std::hypot(ankle.x - hip.x, ankle.y - hip.y),
                                     std::abs(g.thigh - g.shank) + 1e-9, g.thigh + g.shank - 1e-9);
  const double thigh = towards + chain_opening(g.thigh, g.shank, distance);
  const rig::detail::SinCos t = sin_cos(thigh);
  const Point knee{hip.x + g.thigh * t.sin, hip.y - g.thigh * t.cos};
  const Point reached{hip.x + distance * std::sin(towards), hip.y - distance * std::cos(towards)};
  const double shank = inclination(knee, reached);
  l.angles.hip = thigh + s.pelvis_tilt;
  l.angles.knee = std::max(0.0, thigh - shank);
  l.angles.ankle = pitch - (thigh - l.angles.knee);
  const double toe_step = kFootSettling * h;
  l.angles.toe = std::clamp(0.0, l.angles.toe - toe_step, l.angles.toe + toe_step);
  if (u < 1.0) return false;
  l.angles.toe = 0.0;
  const LegPoints p = WalkerStages::leg_points(*this, leg, s.pelvis, l.angles);
  if (ball_first) {
    strike(leg, Phase::Ball, {p.ball.x, ground_y});
  } else {
    strike(leg, heel_first ? Phase::Heel : Phase::Flat, {p.heel.x, ground_y});
  }
  return true;
}

// Where a planted foot's ankle is once the foot is flat.
Point Walker::flat_ankle(const LegState& l) const {
  const rig::Segments& s = segments_;
  const double sole = s.heel + s.ball;
  const rig::detail::SinCos ground = sin_cos(terrain_->slope(l.anchor.x));
  const Point heel = l.phase == Phase::Ball
                         ? Point{l.anchor.x - sole * ground.cos, l.anchor.y - sole * ground.sin}
                         : l.anchor;
  return {heel.x + s.heel * ground.cos - s.ankle_height * ground.sin,
          heel.y + s.heel * ground.sin + s.ankle_height * ground.cos};
}

// Where the pelvis stands over the planted feet: over their ankles (as they stand once flat),
// as high as leaves both knees kStandingKnee bent.
Point Walker::standing_pelvis() const {
  const rig::Segments& s = segments_;
  const std::array<Point, 2> ankle = {flat_ankle(state_.legs[0]), flat_ankle(state_.legs[1])};
  const double x = 0.5 * (ankle[0].x + ankle[1].x);
  const rig::detail::SinCos knee = sin_cos(kStandingKnee);
  const double reach =
      std::sqrt(s.thigh * s.thigh + s.shank * s.shank + 2.0 * s.thigh * s.shank * knee.cos);
  double y = std::numeric_limits<double>::infinity();
  for (const Point& a : ankle) {
    const double dx = std::min(std::abs(x - a.x), reach);
    y = std::min(y, a.y + std::sqrt(reach * reach - dx * dx));
  }
  return {x, y};
}

// A time step standing: the pelvis settles toward standing_pelvis() from the velocity it had, a
// foot not yet flat comes down, and both legs close their chains onto their feet (IK).
void Walker::stand(double h) {
  WalkerState& s = state_;
  const Point rest = standing_pelvis();
  const bool flat = s.legs[0].phase == Phase::Flat && s.legs[1].phase == Phase::Flat;
  if (flat && s.pelvis.x == rest.x && s.pelvis.y == rest.y) return;  // standing still
  // The critically damped settle solved exactly over h (stable at any rate and time step).
  const double w = controllers_->settle_rate;
  const double decay = std::exp(-w * h);
  auto settle = [&](double& position, double& velocity, double target) {
    const double off = position - target;
    const double carried = velocity + w * off;
    position = target + (off + carried * h) * decay;
    velocity = (velocity - w * carried * h) * decay;
  };
  settle(s.pelvis.x, s.pelvis_velocity.x, rest.x);
  settle(s.pelvis.y, s.pelvis_velocity.y, rest.y);
  // (Within 0.01 mm of rest at under 0.1 mm/s it is there: a step no one sees.)
  if (flat && std::hypot(rest.x - s.pelvis.x, rest.y - s.pelvis.y) < 1e-5 &&
      std::hypot(s.pelvis_velocity.x, s.pelvis_velocity.y) < 1e-4) {
    s.pelvis = rest;
    s.pelvis_velocity = {};
  }
  const double tilt = s.pelvis_tilt;
  const double sole_length = segments_.heel + segments_.ball;
  for (int leg = 0; leg < 2; ++leg) {
    LegState& l = s.legs[static_cast<std::size_t>(leg)];
    if (l.phase != Phase::Flat) {
      const double slope = sole_angle(l);
      const double foot = foot_of(tilt, l.angles);
      const double most = kFootSettling * h;
      if (std::abs(foot - slope) <= most) {
        if (l.phase == Phase::Ball) {
          const rig::detail::SinCos ground = sin_cos(slope);
          l.anchor = {l.anchor.x - sole_length * ground.cos, l.anchor.y - sole_length * ground.sin};
        }
        l.phase = Phase::Flat;
        record(static_cast<rig::Side>(leg), Event::FootFlat, l.anchor);
      } else {
        l.angles.ankle += foot > slope ? -most : most;
      }
    }
    if (!close_chain(leg)) {
      // Out of reach (a foot not yet flat, the body still moving away from it): the pelvis
      // lowers just as far as the leg reaches.
      const double high = s.pelvis.y;
      s.pelvis.y = bisect(high - segments_.leg_length(), high, [&](double y) {
        s.pelvis.y = y;
        return close_chain(leg);
      });
      s.pelvis_velocity.y = std::min(s.pelvis_velocity.y, 0.0);
      if (!close_chain(leg) || (leg == 1 && !close_chain(0))) {
        s.pelvis.y = high - segments_.leg_length();
        close_chain(0);
        close_chain(1);
      }
    }
  }
}

// Walks `seconds` on level ground at the start's height, then brings that walk back to x = 0:
// the character starts in its own steady gait rather than from a pose it never takes.
void Walker::warm_up(double seconds) {
  const terrain::Terrain* ground = terrain_;
  const terrain::Terrain level =
      terrain::Terrain::polyline({{-1e6, ground->height(0.0)}, {1e6, ground->height(0.0)}});
  terrain_ = &level;
  // Run indices name runs of the ground in use: the level ground has one.
  for (LegState& l : state_.legs)
    l.target_run = 0;
  for (double t = 0.0; t < seconds; t += time_step_)
    WalkerStages::step(*this, time_step_);
  terrain_ = ground;
  const double shift = state_.pelvis.x;
  state_.pelvis.x = 0.0;
  end_points_valid_ = false;
  for (LegState& l : state_.legs) {
    l.anchor.x -= shift;
    l.target_x -= shift;
    l.strike_x -= shift;
    l.step_from_x -= shift;
    l.swing_start -= state_.time;
    l.strike_time -= state_.time;
    l.target_run = ground->run_at(l.target_x);
  }
  state_.time = 0.0;
}

void Walker::strike(int leg, Phase phase, Point contact) {
  LegState& l = state_.legs[static_cast<std::size_t>(leg)];
  const double tilt = state_.pelvis_tilt;
  l.phase = phase;
  l.anchor = contact;
  l.strike_time = state_.time;
  l.strike_x = phase == Phase::Ball ? contact.x - segments_.heel - segments_.ball : contact.x;
  l.sweep_start = thigh_of(tilt, l.angles);
  l.sweep_end = stance_target();
  // (Only steady steps teach: not a placed one, nor those resized to reach a spot.)
  if (by_speed_ && state_.heel_strikes >= kStrikesBeforeTempoLearning &&
      state_.speed == speed_target_ && state_.locomotion == Locomotion::Walking &&
      state_.placed_leg < 0 && std::isnan(state_.stop_x)) {
    // A steady walk by speed: the step just ended took `took` where the speed asks for `wanted`;
    // play the controllers that much faster or slower, half-way (the square root) so that one
    // odd step does not swing the cadence.
    const double took = state_.time - state_.legs[static_cast<std::size_t>(1 - leg)].strike_time;
    const double wanted = step_length() / state_.speed;
    if (took > 0.0 && wanted > 0.0) {
      const double ratio = std::clamp(took / wanted, 0.8, 1.25);
      state_.tempo_gain_target =
          std::clamp(state_.tempo_gain_target * std::sqrt(ratio), kLeastTempoGain, kMostTempoGain);
    }
  }
  ++state_.heel_strikes;
  record(static_cast<rig::Side>(leg),
         phase == Phase::Ball ? Event::ForefootStrike : Event::HeelStrike, contact);
  if (state_.lead < 0) {
    state_.lead = leg;
    state_.fall_velocity = 0.0;
    place_pelvis(leg);
  }
}

// The planted leg that carries the pelvis lifts off; the other planted foot takes over.
void Walker::hand_over(int leg) {
  const int next = 1 - leg;
  const bool planted = state_.legs[static_cast<std::size_t>(next)].phase != Phase::Swing;
  state_.lead = planted ? next : -1;
  lift_off(leg);
  if (planted) place_pelvis(next);
}

void Walker::lift_off(int leg) {
  lift_off(leg, step_length());
}

void Walker::lift_off(int leg, double step) {
  LegState& l = state_.legs[static_cast<std::size_t>(leg)];
  const LegPoints p = WalkerStages::leg_points(*this, leg, state_.pelvis, l.angles);
  if (l.phase != Phase::Swing) record(static_cast<rig::Side>(leg), Event::ToeOff, p.tip);
  l.phase = Phase::Swing;
  l.swing_start = state_.time;
  l.sweep_start = thigh_of(state_.pelvis_tilt, l.angles);
  const int lead = state_.lead;
  const bool planted = lead >= 0 && lead != leg;
  const LegState* other = planted ? &state_.legs[static_cast<std::size_t>(lead)] : nullptr;
  const double from = other ? other->strike_x : p.heel.x;
  // A step of the commanded length along the ground, moved to where the whole foot stands on one
  // tread, at most a stair up or down from the tread the other foot stands on.
  l.step_from_x = l.strike_x;
  bool closing = state_.locomotion == Locomotion::Stopping;
  if (other && !std::isnan(state_.stop_x) && !closing) {
    // Walking to a spot: as many even steps as reach it, the last onto it (the foot after it
    // closes beside it); one nearer than the shortest step: closing now or a shortest step on,
    // whichever ends nearer.
    const double left = state_.stop_x - from;
    const double shortest = min_step_length();
    closing = left < shortest && left < shortest - left;
    const double steps = left < shortest ? 1.0 : std::max(1.0, std::round(left / step));
    step = std::clamp(left / steps, shortest, max_step_length());
    if (closing || steps == 1.0) {
      state_.locomotion = Locomotion::Stopping;
      state_.stop_x = std::numeric_limits<double>::quiet_NaN();
    }
  }
  if (closing && other) {
    // The closing step: heel beside the planted heel, on its run; the planted leg brakes the
    // body until it stands over that foot.
    l.target_x = other->strike_x;
    l.target_run = terrain_->run_at(other->anchor.x);
    state_.placed_leg = leg;
    state_.placed_first = false;
    state_.brake_distance = std::max(flat_ankle(*other).x - state_.pelvis.x, 1e-3);
    state_.placed_from = p.heel;
    state_.placed_pitch = foot_of(state_.pelvis_tilt, l.angles);
    state_.placed_duration = std::clamp(2.0 * state_.brake_distance / std::max(state_.speed, 0.1),
                                        kShortestClosingStep, kLongestClosingStep);
    return;
  }
  const terrain::Terrain::Foothold target =
      terrain_->foothold(other ? other->anchor.x : from, terrain_->ahead_along_ground(from, step),
                         segments_.foot_length(), kFootholdMargin, min_step_length());
  l.target_x = target.heel_x;
  l.target_run = target.run;
}

void Walker::place_pelvis(int leg) {
  WalkerStages::place_pelvis(*this, leg, WalkerStages::hip_at_origin(*this, leg));
}

FUZZYGAIT_ALWAYS_INLINE void WalkerStages::place_pelvis(Walker& w, int leg,
                                                        const LegPoints& at_origin) {
  const LegState& l = w.state_.legs[static_cast<std::size_t>(leg)];
  const Point c = contact_point(at_origin, l.phase);
  w.state_.pelvis = {l.anchor.x - c.x, l.anchor.y - c.y};
}

FUZZYGAIT_ALWAYS_INLINE LegPoints WalkerStages::hip_at_origin(Walker& w, int leg) {
  return leg_points(w, leg, {0.0, 0.0}, w.state_.legs[static_cast<std::size_t>(leg)].angles);
}

// The angle (radians, toes up +) at which a planted foot's sole rests on the ground: the slope at
// its anchor, tilted where the ground under the rest of the sole rises above that slope (the foot
// of a ramp, a kerb's edge): on the heel (Heel, Flat) it rests on the highest of the ground
// ahead; on the ball, on the highest behind.
double Walker::sole_angle(const LegState& l) const {
  const double slope = terrain_->slope(l.anchor.x);
  if (terrain_->level()) return slope;
  const double sole = segments_.heel + segments_.ball;
  const double reach = sole * std::cos(slope);
  if (l.phase == Phase::Ball) {
    const double heel_x = l.anchor.x - reach;
    double angle = std::min(slope, std::atan2(l.anchor.y - terrain_->height(heel_x), reach));
    for (const Point& c : terrain_->corners_between(heel_x, l.anchor.x))
      angle = std::min(angle, std::atan2(l.anchor.y - c.y, l.anchor.x - c.x));
    return angle;
  }
  const double ball_x = l.anchor.x + reach;
  double angle = std::max(slope, std::atan2(terrain_->height(ball_x) - l.anchor.y, reach));
  for (const Point& c : terrain_->corners_between(l.anchor.x, ball_x))
    angle = std::max(angle, std::atan2(c.y - l.anchor.y, c.x - l.anchor.x));
  return angle;
}

// Two-link IK of the newly planted leg (the one not carrying the pelvis): hip and knee put its
// contact point back on its anchor (the ankle itself while the foot is flat). Returns false when
// out of reach.
bool Walker::close_chain(int leg) {
  LegState& l = state_.legs[static_cast<std::size_t>(leg)];
  const rig::Segments& s = segments_;
  const double tilt = state_.pelvis_tilt;
  const double slope = sole_angle(l);
  Point target = l.anchor;
  double we = 0.0;
  double wn = -s.shank;
  if (l.phase == Phase::Flat) {
    // The ankle sits above the planted heel.
    const rig::detail::SinCos ground = sin_cos(slope);
    target = {l.anchor.x + s.heel * ground.cos - s.ankle_height * ground.sin,
              l.anchor.y + s.heel * ground.sin + s.ankle_height * ground.cos};
  } else {
    const double cf = l.phase == Phase::Ball ? s.ball : -s.heel;
    const double cu = -s.ankle_height;
    const rig::detail::SinCos ankle = sin_cos(l.angles.ankle);
    const double ca = ankle.cos;
    const double sa = ankle.sin;
    we = cf * ca - cu * sa;
    wn = cf * sa + cu * ca - s.shank;
  }
  const double lower = std::sqrt(we * we + wn * wn);
  const Point hip = state_.pelvis;
  const double dx = target.x - hip.x;
  const double dy = target.y - hip.y;
  const double distance = std::sqrt(dx * dx + dy * dy);
  if (distance > s.thigh + lower - 1e-9) return false;
  const double d = std::max(distance, std::abs(s.thigh - lower) + 1e-9);
  // Two chains reach the target, mirrored about the hip-target line; the knee bends forward in
  // both when the lower link leans forward of the shank (a near-straight knee on the ball). Keep
  // the one nearest the leg's thigh, so a foot that touches down does not jump to the other.
  const double current = thigh_of(tilt, l.angles);
  const double towards = inclination(hip, target);
  const double opening = chain_opening(s.thigh, lower, d);
  auto shank_of_chain = [&](double thigh) {
    const rig::detail::SinCos t = sin_cos(thigh);
    const Point knee{hip.x + s.thigh * t.sin, hip.y - s.thigh * t.cos};
    // The knee-to-contact vector is (we, wn) in the shank's frame, rotated by the shank's
    // inclination.
    double inclined = arctan2(target.y - knee.y, target.x - knee.x) - arctan2(wn, we);
    if (inclined > std::numbers::pi) {
      inclined -= 2.0 * std::numbers::pi;
    } else if (inclined < -std::numbers::pi) {
      inclined += 2.0 * std::numbers::pi;
    }
    return inclined;
  };
  double thigh = towards + opening;
  double shank_inclination = shank_of_chain(thigh);
  const double mirrored = towards - opening;
  bool kept_mirrored = false;
  if (std::abs(mirrored - current) < std::abs(thigh - current)) {
    // A foot that touched down a hair below the ground may ask a straight knee to bend a little
    // backwards: it stays straight (the contact moves by less than a millimetre).
    const double mirrored_shank = shank_of_chain(mirrored);
    if (mirrored - mirrored_shank >= -kStraightKneeSlack) {
      thigh = mirrored;
      shank_inclination = mirrored_shank;
      kept_mirrored = true;
    }
  }
  // The knee cannot bend backwards: a chain that needs it is out of reach.
  if (thigh - shank_inclination < -1e-9 && !kept_mirrored) return false;
  l.angles.hip = thigh + tilt;
  l.angles.knee = std::max(0.0, thigh - shank_inclination);
  if (l.phase == Phase::Flat) {
    l.angles.ankle = slope - (thigh - l.angles.knee);
  } else if (l.phase == Phase::Ball) {
    l.angles.toe = slope - foot_of(tilt, l.angles);
  }
  return true;
}

// The planted foot's phase rules for its ankle and toe (see the header), given the ankle angle
// the controller integrated to.
void Walker::settle_foot(int leg, const LegAngles& commanded) {
  LegState& l = state_.legs[static_cast<std::size_t>(leg)];
  const double tilt = state_.pelvis_tilt;
  const double slope = sole_angle(l);
  const double sole_length = segments_.heel + segments_.ball;
  switch (l.phase) {
    case Phase::Heel:
      if (foot_of(tilt, l.angles) <= slope) {
        l.angles.ankle = slope - shank_of(tilt, l.angles);
        l.phase = Phase::Flat;
        record(static_cast<rig::Side>(leg), Event::FootFlat, l.anchor);
      }
      break;
    case Phase::Flat: {
      const double flat = slope - shank_of(tilt, l.angles);
      // (Braking for a stop, the heel stays down.)
      const bool braking = state_.locomotion == Locomotion::Stopping && closing_step_in_air();
      if (commanded.ankle < flat && !braking) {
        // The controller lets the ankle dorsiflex slower than the shank rolls over the foot:
        // the heel lifts (the calf holds the shin back).
        l.phase = Phase::Ball;
        const rig::detail::SinCos ground = sin_cos(slope);
        l.anchor = {l.anchor.x + sole_length * ground.cos, l.anchor.y + sole_length * ground.sin};
        l.angles.ankle = commanded.ankle;
        record(static_cast<rig::Side>(leg), Event::HeelOff, l.anchor);
      } else {
        l.angles.ankle = flat;
      }
      break;
    }
    case Phase::Ball: {
      const rig::detail::SinCos along = sin_cos(slope);
      const double heel_x = l.anchor.x - sole_length * along.cos;
      // The heel comes back down where there is ground under it. Over a stair's edge it cannot:
      // the sole rests on the edge (slope is the angle to it), the heel beyond it no lower.
      if (foot_of(tilt, l.angles) >= slope) {
        l.angles.ankle = slope - shank_of(tilt, l.angles);
        if (terrain_->run_at(heel_x) == terrain_->run_at(l.anchor.x)) {
          l.phase = Phase::Flat;
          const rig::detail::SinCos ground = sin_cos(slope);
          l.anchor = {l.anchor.x - sole_length * ground.cos, l.anchor.y - sole_length * ground.sin};
          record(static_cast<rig::Side>(leg), Event::FootFlat, l.anchor);
        }
      }
      l.angles.toe = slope - foot_of(tilt, l.angles);
      break;
    }
    case Phase::Swing:
      break;
  }
}

// Height of the carrying leg's knee above the ground, its foot on its anchor, from the leg's points
// with its hip at the origin.
FUZZYGAIT_ALWAYS_INLINE double WalkerStages::knee_gap(const Walker& w, int leg,
                                                      const LegPoints& p) {
  const LegState& l = w.state_.legs[static_cast<std::size_t>(leg)];
  const Point c = contact_point(p, l.phase);
  const Point knee{l.anchor.x + (p.knee.x - c.x), l.anchor.y + (p.knee.y - c.y)};
  return knee.y - w.terrain_->height(knee.x);
}

// A carrying leg whose knee is below the ground folds no further (only after an awkward start):
// its knee flexion goes back towards `known_good` (or straight) just as far as needed, a flat foot
// staying flat.
// The other leg, if swinging, then steps ahead of the body to take the weight, even where its
// target was behind it (the kneeling leg's foot far behind the hip).
void Walker::keep_knee_up(int leg, double known_good) {
  LegState& l = state_.legs[static_cast<std::size_t>(leg)];
  const double slope = sole_angle(l);
  auto gap = [&](double knee) {
    l.angles.knee = knee;
    if (l.phase == Phase::Flat) l.angles.ankle = slope - shank_of(state_.pelvis_tilt, l.angles);
    return WalkerStages::knee_gap(*this, leg, WalkerStages::hip_at_origin(*this, leg));
  };
  const double bad = l.angles.knee;
  double good = known_good;
  // Where the ankle moved too, the previous flexion may no longer clear: a straighter knee does.
  if (gap(good) < 0.0) good = limits_.minimum.knee;
  if (gap(good) >= 0.0) good = bisect(good, bad, [&](double knee) { return gap(knee) >= 0.0; });
  gap(good);
  if (l.phase == Phase::Ball) l.angles.toe = slope - foot_of(state_.pelvis_tilt, l.angles);
  LegState& other = state_.legs[static_cast<std::size_t>(1 - leg)];
  if (other.phase == Phase::Swing) {
    other.target_x = std::max(other.target_x, state_.pelvis.x + 0.5 * step_length());
  }
}

void Walker::clear_ground(int leg, double max_change, double margin, bool with_tip) {
  LegState& l = state_.legs[static_cast<std::size_t>(leg)];
  const double tilt = state_.pelvis_tilt;
  // A knee that would touch the ground (a deep crouch after an awkward start) swings the thigh
  // forward first: folding the knee cannot lift it.
  auto knee_depth = [&](double hip) {
    rig::LegAngles a = l.angles;
    a.hip = hip;
    const LegPoints p = WalkerStages::leg_points(*this, leg, state_.pelvis, a);
    return terrain_->height(p.knee.x) - p.knee.y + kSwingClearance;
  };
  if (knee_depth(l.angles.hip) > 0.0) {
    double forward = std::min(limits_.maximum.hip, tilt + std::numbers::pi / 2.0);
    if (knee_depth(forward) <= 0.0) {
      forward = bisect(forward, l.angles.hip, [&](double hip) { return !(knee_depth(hip) > 0.0); });
    }
    l.angles.hip = std::max(l.angles.hip, forward);
  }
  const double high = std::min(limits_.maximum.knee, l.angles.knee + max_change);
  auto depth = [&](double knee) {
    rig::LegAngles a = l.angles;
    a.knee = knee;
    const LegPoints p = WalkerStages::leg_points(*this, leg, state_.pelvis, a);
    return foot_depth(p, ground_under(*terrain_, p), with_tip) + margin;
  };
  if (depth(high) > 0.0) {  // cannot clear in one step: fold as far as allowed
    l.angles.knee = high;
    return;
  }
  l.angles.knee = bisect(high, l.angles.knee, [&](double knee) { return !(depth(knee) > 0.0); });
}

FUZZYGAIT_ALWAYS_INLINE void WalkerStages::update_metrics(Walker& w, int leg, const LegPoints& p,
                                                          double ascent, double landing_knee,
                                                          MetricValues& m) {
  LegState& l = w.state_.legs[static_cast<std::size_t>(leg)];
  const double tilt = w.state_.pelvis_tilt;
  double end = l.sweep_end;
  if (l.phase == Phase::Swing) {
    // Arrived when the thigh is where a straight leg's heel would point at the foot target; under
    // the set's ascent words (up a stair), where the target lies well within the leg's reach, where
    // the leg with its knee bent puts the heel on it: the paper's end position of the knee.
    // (A heel reaching over a tread's edge aims at the tread's height, not at the ground below.)
    const Point target{l.target_x,
                       w.terrain_->height(w.terrain_->point_on_run(l.target_x, l.target_run))};
    const Point hip = p.hip;
    end = inclination(hip, target) + w.heel_offset_;
    if (landing_knee > 0.0) {
      // The thigh's angle to the hip-heel line of a leg landing with its knee bent so.
      const LegPoints bent =
          rig::forward_kinematics(w.segments_, {0.0, 0.0}, 0.0, LegAngles{0.0, landing_knee});
      end = inclination(hip, target) - inclination(bent.hip, bent.heel);
    }
    if (ascent > 0.0) {
      const double within = w.reach_ - std::hypot(target.x - hip.x, target.y - hip.y);
      const double bent = knee_end_thigh(w, leg, hip, target);
      const double weight = ascent * std::clamp(within / kStraightLanding - 1.0, 0.0, 1.0);
      if (weight > 0.0 && !std::isnan(bent)) end += weight * (bent - end);
    }
    l.sweep_end = end;
  }
  detail::leg_metrics(tilt, l.angles.hip, l.angles.knee, l.angles.ankle, l.angles.toe,
                      l.sweep_start, end, w.terrain_->slope(p.ankle.x), m);
  l.delta = m[static_cast<std::size_t>(Metric::Delta)];
}

// All eight controllers before any joint moves: they read only the metrics, and side by side
// (rather than between the two legs' integrations) they took 3 % less of a step.
void WalkerStages::command(Walker& w, StepData& d) {
  const ControllerBackend* backend = w.backend_;
  const ControllerSet& set = *w.controllers_;
  FUZZYGAIT_UNROLL(2)
  for (std::size_t leg = 0; leg < 2; ++leg) {
    const LegPhase phase =
        w.state_.legs[leg].phase == Phase::Swing ? LegPhase::Swing : LegPhase::Stance;
    const MetricValues& m = d.metrics[leg];
    FUZZYGAIT_UNROLL(4)
    for (std::size_t joint = 0; joint < 4; ++joint) {
      const auto s = static_cast<std::size_t>(slot(phase, static_cast<Joint>(joint)));
      d.commands[leg][joint] =
          backend ? set.evaluate(
                        static_cast<int>(s), m,
                        [&](std::size_t c) { return backend->evaluate(static_cast<int>(c), m); })
                  : set.controllers[s].evaluate(m, detail::workspace_at(w.workspaces_, s));
    }
  }
  if (!backend && set.has_terrain_words()) command_on_terrain(w, d);
}

void WalkerStages::command_on_terrain(Walker& w, StepData& d) {
  const ControllerSet& set = *w.controllers_;
  for (std::size_t leg = 0; leg < 2; ++leg) {
    const LegPhase phase =
        w.state_.legs[leg].phase == Phase::Swing ? LegPhase::Swing : LegPhase::Stance;
    const MetricValues& m = d.metrics[leg];
    const ControllerSet::GroundBlend& blend = w.blends_[leg];
    if (blend.own_at[static_cast<std::size_t>(phase)]) continue;
    for (std::size_t joint = 0; joint < 4; ++joint) {
      d.commands[leg][joint] =
          set.evaluate(slot(phase, static_cast<Joint>(joint)), m, blend, w.workspaces_);
    }
  }
}

Walker WalkerStages::make_walker(const ControllerSet& controllers, const WalkerOptions& options,
                                 const terrain::Terrain& terrain,
                                 const ControllerBackend* backend) {
  return Walker(controllers, options, terrain, backend);
}

Crowd WalkerStages::make_crowd(const ControllerSet& controllers, const terrain::Terrain& terrain,
                               std::span<const WalkerOptions> characters,
                               std::span<const ControllerBackend* const> backends,
                               const CrowdOptions& options) {
  return Crowd(controllers, terrain, characters, backends, options);
}

SubSteps detail::sub_steps(double dt, double time_step) noexcept {
  if (!(dt >= 0.0 && dt <= Walker::kLongestAdvance)) return {};
  const double steps = std::ceil(dt / time_step - 1e-9);
  const int n = std::max(1, static_cast<int>(steps));
  const double h = dt / n;
  return {h > 0.0 ? n : 0, h};
}

bool Walker::advance(double dt) noexcept {
  if (!(dt >= 0.0 && dt <= kLongestAdvance)) return false;
  const SubSteps s = detail::sub_steps(dt, time_step_);
  for (int i = 0; i < s.count; ++i)
    WalkerStages::step(*this, s.length);
  return true;
}

void WalkerStages::step(Walker& w, double h) {
  StepData d;
  measure(w, d);
  command(w, d);
  integrate(w, h, d);
  finish_step(w, h, d);
}

void WalkerStages::measure(Walker& w, StepData& d) {
  if (!w.end_points_valid_) {
    for (int leg = 0; leg < 2; ++leg) {
      w.end_points_[static_cast<std::size_t>(leg)] =
          leg_points(w, leg, w.state_.pelvis, w.state_.legs[static_cast<std::size_t>(leg)].angles);
    }
  }
  std::array<MetricValues, 2>& metrics = d.metrics;
  // Level ground: every foothold's pitch is 0, and no foot is on a tread.
  const std::array<LegGround, 2> ground =
      w.terrain_->level() ? std::array<LegGround, 2>{} : leg_ground(w);
  const ControllerSet& set = *w.controllers_;
  const double pace = w.state_.speed / w.speed_unit_;
  for (int leg = 0; leg < 2; ++leg) {
    const auto k = static_cast<std::size_t>(leg);
    metrics[k][static_cast<std::size_t>(Metric::Incline)] = ground[k].incline;
    metrics[k][static_cast<std::size_t>(Metric::Stairs)] = ground[k].stairs;
    metrics[k][static_cast<std::size_t>(Metric::Pace)] = pace;
    std::array<double, 2>& blended = w.blend_ground_[k];
    if (!w.blends_valid_ || !same_bits(ground[k].incline, blended[0]) ||
        !same_bits(ground[k].stairs, blended[1])) {
      w.blends_[k] = set.blend(metrics[k]);
      blended = {ground[k].incline, ground[k].stairs};
    }
    update_metrics(w, leg, w.end_points_[k], w.blends_[k].ascent, w.blends_[k].landing_knee,
                   metrics[k]);
  }
  w.blends_valid_ = true;
  const auto other_delta = static_cast<std::size_t>(Metric::OtherDelta);
  const auto delta = static_cast<std::size_t>(Metric::Delta);
  metrics[0][other_delta] = metrics[1][delta];
  metrics[1][other_delta] = metrics[0][delta];
}

// Each leg's incline (degrees, uphill +) from the ground's pitch (Terrain::pitch) at the feet's
// footholds, and whether it is a stair's. A swinging leg: the steeper of where it left and where
// it lands (it lifts the foot over the edges between). A planted leg: going up, its own
// foothold's (it lifts the body onto it); going down, the lower of its own and the other foot's
// next (it lowers the body to it). A step across a riser between runs that are not treads (a
// kerb, a landing's edge) climbs or drops as a stair of that rise and a kKerbTread tread would.
std::array<WalkerStages::LegGround, 2> WalkerStages::leg_ground(const Walker& w) {
  std::array<LegGround, 2> result{};
  const terrain::Terrain& ground = *w.terrain_;
  // The pitch of a leg's step from from_x to its foothold (x on run), and whether it crosses a
  // riser between runs that are not treads.
  struct StepPitch {
    double pitch;
    bool kerb;
  };
  // (`base_x`: the ground the step rises from, the other foot's where it stands.)
  auto step_pitch = [&ground](double from_x, double to_x, std::size_t run, double base_x) {
    const double a = ground.pitch(from_x);
    const double b = ground.pitch(to_x);
    const double steeper = std::abs(a) > std::abs(b) ? a : b;
    if (ground.run_at(from_x) == run || ground.on_tread(from_x) || ground.on_tread(to_x)) {
      return StepPitch{steeper, false};
    }
    const double kerb = arctan2(ground.height(to_x) - ground.height(base_x), kKerbTread);
    return std::abs(kerb) > std::abs(steeper) ? StepPitch{kerb, true} : StepPitch{steeper, false};
  };
  for (std::size_t k = 0; k < 2; ++k) {
    const LegState& l = w.state_.legs[k];
    const LegState& other = w.state_.legs[1 - k];
    // (A swinging foot's target by its run: a heel reaching over a short tread's edge has its x
    // over the ground below.)
    auto foothold = [&ground](const LegState& leg) {
      return leg.phase == Phase::Swing ? ground.point_on_run(leg.target_x, leg.target_run)
                                       : leg.anchor.x;
    };
    auto run_of = [&ground](const LegState& leg) {
      return leg.phase == Phase::Swing ? leg.target_run : ground.run_at(leg.anchor.x);
    };
    // A swinging foot steps up or down from the planted one; a planted foot stepped up or down
    // from where it stood before.
    const double base_x =
        l.phase == Phase::Swing && other.phase != Phase::Swing ? other.anchor.x : l.step_from_x;
    const StepPitch own = step_pitch(l.step_from_x, foothold(l), run_of(l), base_x);
    double pitch = own.pitch;
    bool stairs = own.kerb || ground.on_tread(l.step_from_x) || ground.on_tread(foothold(l));
    if (l.phase != Phase::Swing) {
      // Its own foothold's pitch, or the kerb it stepped onto.
      const double here = own.kerb ? own.pitch : ground.pitch(l.anchor.x);
      StepPitch next{ground.pitch(foothold(other)), false};
      if (other.phase == Phase::Swing) {
        const StepPitch step =
            step_pitch(other.step_from_x, foothold(other), run_of(other), l.anchor.x);
        if (step.kerb) next = step;
      }
      pitch = std::max(here, 0.0) + std::min({here, next.pitch, 0.0});
      stairs =
          own.kerb || next.kerb || ground.on_tread(l.anchor.x) || ground.on_tread(foothold(other));
    }
    result[k] = {rig::degrees(pitch), stairs ? 1.0 : 0.0};
  }
  return result;
}

// The paper's end position of the knee: the thigh's inclination when hip and knee put the heel on
// `target` with the knee bent forward (two-link IK, the ankle as it is); NaN out of reach.
double WalkerStages::knee_end_thigh(const Walker& w, int leg, Point hip, Point target) {
  const rig::Segments& s = w.segments_;
  const rig::detail::SinCos ankle =
      sin_cos(w.state_.legs[static_cast<std::size_t>(leg)].angles.ankle);
  const double we = -s.heel * ankle.cos + s.ankle_height * ankle.sin;
  const double wn = -s.heel * ankle.sin - s.ankle_height * ankle.cos - s.shank;
  const double lower = std::sqrt(we * we + wn * wn);
  const double distance = std::hypot(target.x - hip.x, target.y - hip.y);
  if (!(distance < s.thigh + lower) || !(distance > std::abs(s.thigh - lower))) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return inclination(hip, target) + chain_opening(s.thigh, lower, distance);
}

void WalkerStages::integrate(Walker& w, double h, StepData& d) {
  // advance() splits a frame into equal sub-steps, so h changes only with the frame's length.
  // The controllers play at the walk's tempo: their velocities times it, the limbs' inertia over
  // it; exp() is recomputed only when h or the tempo changes.
  const double tempo = w.tempo();
  if (!(h == w.follow_step_) || !(tempo == w.follow_tempo_)) {
    w.follow_step_ = h;
    w.follow_tempo_ = tempo;
    w.follow_ = detail::follow_share(h, w.controllers_->inertia / tempo);
  }
  if (w.state_.locomotion == Locomotion::Standing) {
    // Standing: no controller moves a joint (finish_step() stands the legs).
    for (std::size_t leg = 0; leg < 2; ++leg) {
      d.previous[leg] = w.state_.legs[leg].angles;
      d.commanded[leg] = w.state_.legs[leg].angles;
    }
    return;
  }
  const double follow = w.follow_;
  const Joints minimum = joints(w.limits_.minimum);
  const Joints maximum = joints(w.limits_.maximum);
  constexpr double per_degree = rig::radians(1.0);
  for (int leg = 0; leg < 2; ++leg) {
    LegState& l = w.state_.legs[static_cast<std::size_t>(leg)];
    d.previous[static_cast<std::size_t>(leg)] = l.angles;
    const std::array<double, 4>& c = d.commands[static_cast<std::size_t>(leg)];
    // A longer swing of the thigh swings the shank faster in proportion (see ControllerSet).
    // (Only the set's own swing knee controller's share: a terrain word's file says its own
    // velocities.)
    const double reference = w.controllers_->swing_knee_reference_sweep;
    double knee_scale = l.phase == Phase::Swing
                            ? detail::swing_knee_scale(l.sweep_start, l.sweep_end, reference)
                            : 1.0;
    if (l.phase == Phase::Swing && w.controllers_->has_terrain_words()) {
      const double own =
          w.blends_[static_cast<std::size_t>(leg)].own_degree(slot(LegPhase::Swing, Joint::Knee));
      if (own < 1.0) knee_scale = own * knee_scale + (1.0 - own);
    }
    // The hip's command is a share of the sweep per second, the others degrees per second, at
    // the set's cadence.
    const double per_degree_now = per_degree * tempo;
    Joints target{
        JointPair{c[0], c[1] * per_degree_now} *
            JointPair{detail::sweep_scale(l.sweep_start, l.sweep_end) * tempo, knee_scale},
        JointPair{c[2], c[3]} * per_degree_now};

    Joints velocity = joints(l.velocity);
    Joints angles = joints(l.angles);
    detail::follow_command(target.hip_knee, velocity.hip_knee, angles.hip_knee, follow, h,
                           minimum.hip_knee, maximum.hip_knee);
    detail::follow_command(target.ankle_toe, velocity.ankle_toe, angles.ankle_toe, follow, h,
                           minimum.ankle_toe, maximum.ankle_toe);
    store(l.velocity, velocity);
    store(l.angles, angles);
    d.commanded[static_cast<std::size_t>(leg)] = l.angles;
  }
  const int lead = w.state_.lead;
  if (lead >= 0) {
    const auto k = static_cast<std::size_t>(lead);
    LegState& carrying = w.state_.legs[k];
    // The body waits for a swinging foot that has fallen behind it, held back by a stair's edge
    // (its foothold on another run than the ground under it): past that foot's target, the
    // carrying leg holds still until the foot lands.
    const LegState& other = w.state_.legs[1 - k];
    if (other.phase == Phase::Swing && w.state_.pelvis.x > other.target_x &&
        w.terrain_->run_at(w.end_points_[1 - k].ball.x) != other.target_run) {
      carrying.angles = d.previous[k];
      carrying.velocity = LegAngles{};
      d.commanded[k] = carrying.angles;
    }
    // The carrying foot's rules: with them every joint angle is set for the chain that follows
    // (finish_step() places the legs from here).
    w.settle_foot(lead, d.commanded[k]);
  }
}

// The body carried by the leg planted first, the swinging leg's flight and landing, and the
// double support's hand-over.
void WalkerStages::carry(Walker& w, double h, const StepData& d,
                         std::array<std::optional<double>, 2>& placed_tip_ground) {
  const double tilt = w.state_.pelvis_tilt;
  const std::array<LegAngles, 2>& previous = d.previous;
  const std::array<LegAngles, 2>& commanded = d.commanded;
  if (w.state_.lead < 0) {
    // Airborne (only after an awkward start): fall until a foot touches.
    w.state_.fall_velocity += kGravity * h;
    w.state_.pelvis.y -= w.state_.fall_velocity * h;
  } else {
    // The leg planted first carries the pelvis, through double support too: the chain grows
    // from its foot, so a planted foot never slides and the body's motion stays continuous.
    const int lead = w.state_.lead;
    LegPoints at_origin = hip_at_origin(w, lead);
    if (knee_gap(w, lead, at_origin) < 0.0) {
      w.keep_knee_up(lead, previous[static_cast<std::size_t>(lead)].knee);
      at_origin = hip_at_origin(w, lead);
    }
    const Point before = w.state_.pelvis;
    const double braking_speed = w.braking_speed();
    place_pelvis(w, lead, at_origin);
    const double moved = w.state_.pelvis.x - before.x;
    if (moved > braking_speed * h) {
      // Braking for a stop: the carrying leg's joints move only as far as takes the pelvis
      // braking_speed on.
      const double share = braking_speed * h / moved;
      const Joints from = joints(previous[static_cast<std::size_t>(lead)]);
      LegAngles& angles = w.state_.legs[static_cast<std::size_t>(lead)].angles;
      const Joints to = joints(angles);
      const JointPair by{share, share};
      store(angles, {from.hip_knee + (to.hip_knee - from.hip_knee) * by,
                     from.ankle_toe + (to.ankle_toe - from.ankle_toe) * by});
      LegState& carrying = w.state_.legs[static_cast<std::size_t>(lead)];
      if (carrying.phase == Phase::Flat) {
        // (A foot flat already stays flat however little the leg moved.)
        carrying.angles.ankle = w.sole_angle(carrying) - shank_of(tilt, carrying.angles);
      }
      place_pelvis(w, lead, hip_at_origin(w, lead));
    }
    if (w.state_.locomotion == Locomotion::Stopping) {
      w.state_.pelvis_velocity = {(w.state_.pelvis.x - before.x) / h,
                                  (w.state_.pelvis.y - before.y) / h};
    }
  }
  for (int leg = 0; leg < 2; ++leg) {
    if (leg == w.state_.lead) continue;
    LegState& l = w.state_.legs[static_cast<std::size_t>(leg)];
    if (l.phase == Phase::Swing && leg == w.state_.placed_leg) {
      // A stop's closing step or a start's first step: placed until it is down.
      const bool closed = !w.state_.placed_first;
      if (!w.place_step(leg, h)) break;
      w.state_.placed_leg = -1;
      if (closed) {
        w.state_.locomotion = Locomotion::Standing;
        break;
      }
      // (The first step is down on its heel: the double support goes on as after any step.)
    } else if (l.phase == Phase::Swing) {
      // Swing foot: it lands once the leg arrives in front of the body; before that the knee
      // folds just enough to keep the foot off the ground (a clearance reflex), and only a foot
      // the reflex cannot lift touches down early.
      LegPoints p = leg_points(w, leg, w.state_.pelvis, l.angles);
      // A swing that drags on (a leg stuck in a deep crouch after an awkward start) gives up
      // and puts the foot down where it is.
      // It lands only over its foothold's tread, no edge under its sole: elsewhere the ground is
      // an obstacle it keeps clear of.
      FootGround ground = ground_under(*w.terrain_, p);
      const terrain::Terrain& t = *w.terrain_;
      const bool over_target =
          t.run_at(p.ball.x) == l.target_run && !(ground.sole_corners >= kEdgeUnderSole) &&
          (t.run_at(p.heel.x) == l.target_run || t.run_at(l.target_x) != l.target_run);
      // A foot held back by a rise it steps onto (a kerb, a stair's nosing), its heel behind the
      // edge and its sole reaching it below its top, lifts: the thigh flexes, no faster than
      // kLiftSpeed, as far as puts the sole kSwingClearance above the edge (folding the knee
      // alone draws the foot back, never over the edge).
      if (!over_target && l.target_run > t.run_at(p.heel.x)) {
        const double edge_x = t.runs()[l.target_run].begin;
        const double edge_y = t.height(edge_x) + kSwingClearance;
        auto below = [&](double hip) {
          rig::LegAngles a = l.angles;
          a.hip = hip;
          const LegPoints q = leg_points(w, leg, w.state_.pelvis, a);
          return q.heel.x < edge_x && q.tip.x > edge_x - kLiftReach &&
                 std::min({q.heel.y, q.ball.y, q.tip.y}) < edge_y;
        };
        if (below(l.angles.hip)) {
          const double high = std::min(l.angles.hip + kLiftSpeed * h, w.limits_.maximum.hip);
          l.angles.hip = below(high)
                             ? high
                             : bisect(high, l.angles.hip, [&](double hip) { return !below(hip); });
          p = leg_points(w, leg, w.state_.pelvis, l.angles);
          ground = ground_under(t, p);
        }
      }
      const bool arriving = (l.delta >= kLandingDelta && over_target) || w.state_.lead < 0 ||
                            w.state_.time - l.swing_start > kLongestSwing;
      const double knee_clearance = p.knee.y - w.terrain_->height(p.knee.x);
      // The clearance wanted grows from nothing at toe off and fades again before landing, so
      // the reflex never jerks the knee when the foot leaves or reaches the ground.
      const double margin = over_target
                                ? kSwingClearance * std::clamp((l.delta + 1.0) / 0.5, 0.0, 1.0) *
                                      std::clamp((kLandingDelta - l.delta) / 0.3, 0.0, 1.0)
                                : kSwingClearance;
      if ((!arriving && foot_depth(p, ground) > -margin) || knee_clearance < kSwingClearance) {
        w.clear_ground(leg, kReflexSpeed * h, margin);
        p = leg_points(w, leg, w.state_.pelvis, l.angles);
        ground = ground_under(*w.terrain_, p);
        // A foot the reflex could not keep off ground that is not its foothold (a stair's edge)
        // does not land there: the knee folds as far as it must.
        if (!over_target && !arriving && foot_depth(p, ground) >= 0.0) {
          w.clear_ground(leg, w.limits_.maximum.knee, 0.0);
          p = leg_points(w, leg, w.state_.pelvis, l.angles);
          ground = ground_under(*w.terrain_, p);
        }
      }
      // A foot stands only on a run: a heel or ball over a riser (the toes pushed against it)
      // lands on the run behind it, at its foot, never part way up the riser.
      auto footing = [&t](Point q) {
        if (t.level()) return Point{q.x, t.height(q.x)};
        const double x = t.point_on_run(q.x, t.run_at(q.x));
        return Point{x, t.height(x)};
      };
      Point heel_footing = footing(p.heel);
      Point ball_footing = footing(p.ball);
      double heel_depth = heel_footing.y - p.heel.y;
      double ball_depth = ball_footing.y - p.ball.y;
      // A swing that drags on over its foothold, the foot hanging above it from a straight leg
      // (the body held up a hair too high), reaches down with the toes.
      if (heel_depth < 0.0 && ball_depth < 0.0 && over_target &&
          w.state_.time - l.swing_start > kLongestSwing && l.angles.knee < kStraightKnee &&
          l.angles.ankle > w.limits_.minimum.ankle) {
        l.angles.ankle = std::max(l.angles.ankle - kReflexSpeed * h, w.limits_.minimum.ankle);
        p = leg_points(w, leg, w.state_.pelvis, l.angles);
        ground = ground_under(t, p);
        heel_footing = footing(p.heel);
        ball_footing = footing(p.ball);
        heel_depth = heel_footing.y - p.heel.y;
        ball_depth = ball_footing.y - p.ball.y;
      }
      // Arrived over its tread with the toes already resting on it (bent up by it: a toe landing
      // going up stairs), the foot has landed: the ball comes down onto the tread.
      const bool on_toes = l.delta >= kLandingDelta && over_target && t.on_tread(l.target_x) &&
                           p.tip.y - ground.tip < kToesResting;
      if (heel_depth < 0.0 && ball_depth < 0.0 && !on_toes) {
        if (w.state_.lead >= 0) {
          placed_tip_ground[static_cast<std::size_t>(leg)] = ground.tip;
          w.end_points_[static_cast<std::size_t>(leg)] = p;
        }
        continue;
      }
      if (heel_depth >= ball_depth && !on_toes) {
        w.strike(leg, Phase::Heel, heel_footing);
      } else {
        w.strike(leg, Phase::Ball, ball_footing);
      }
      if (w.state_.lead == leg) {
        w.settle_foot(leg, l.angles);
        w.place_pelvis(leg);
        continue;
      }
    }
    // The newly planted foot: hip and knee close the chain onto it (IK) while its ankle
    // follows its controller; once it is flat, the carrying leg lifts off and hands over.
    if (!w.close_chain(leg)) {
      w.hand_over(w.state_.lead);
      break;
    }
    const Phase closed_in = l.phase;
    w.settle_foot(leg, commanded[static_cast<std::size_t>(leg)]);
    // On the heel or the ball with no change of phase, the foot's rules changed nothing the
    // chain depends on (a ball's toes rest as the chain left them): it is still closed.
    bool reached = (l.phase == closed_in && l.phase != Phase::Flat) || w.close_chain(leg);
    if (reached && l.phase == Phase::Ball && foot_of(tilt, l.angles) >= w.sole_angle(l)) {
      // The chain closed with the heel back on the ground.
      w.settle_foot(leg, l.angles);
      reached = w.close_chain(leg);
    }
    // A heel that stays down while its forefoot does not come down (double support lasting on:
    // the body held by the other leg a stair below, the ground falling away down a ramp, the
    // body stopped on a kerb) takes the weight anyway.
    const bool lasting = w.state_.time - l.strike_time > kLongestDoubleSupport;
    if (!reached || l.phase == Phase::Flat || l.phase == Phase::Ball || lasting) {
      w.hand_over(w.state_.lead);
    }
    break;
  }
}

void WalkerStages::finish_step(Walker& w, double h, StepData& d) {
  const double tilt = w.state_.pelvis_tilt;
  const std::array<LegAngles, 2>& previous = d.previous;
  // A swinging leg placed below with the pelvis carried by the other leg: its points stand (its
  // heel and ball above the ground), and this is the ground's height under its toe tip.
  std::array<std::optional<double>, 2> placed_tip_ground;
  if (w.state_.locomotion == Locomotion::Standing) {
    w.stand(h);
  } else {
    carry(w, h, d, placed_tip_ground);
  }
  for (int leg = 0; leg < 2; ++leg) {
    LegState& l = w.state_.legs[static_cast<std::size_t>(leg)];
    const std::optional<double> tip_ground = placed_tip_ground[static_cast<std::size_t>(leg)];
    const bool stands = tip_ground.has_value();
    // Placed where the next step starts from (a standing swing foot is there already).
    LegPoints& p = w.end_points_[static_cast<std::size_t>(leg)];
    if (!stands) p = leg_points(w, leg, w.state_.pelvis, l.angles);
    // A foot that has just lifted off can sit a hair below the ground once the other foot takes
    // the pelvis: lift it at once. (Its toe tip is left to the toes, which bend up below.)
    // (A placed step keeps its foot where it is put: on the ground as it lands.)
    if (!stands && l.phase == Phase::Swing && w.state_.lead >= 0 && leg != w.state_.placed_leg &&
        foot_depth(p, ground_under(*w.terrain_, p), false) > 0.0) {
      w.clear_ground(leg, w.limits_.maximum.knee, 0.0, false);
      p = leg_points(w, leg, w.state_.pelvis, l.angles);
    }
    // Toes never dip below the ground: they bend up where the ground holds them.
    const double ground = stands ? *tip_ground : w.terrain_->height(p.tip.x);
    if (p.tip.y < ground) {
      const double rise = std::clamp((ground - p.ball.y) / w.segments_.toe, -1.0, 1.0);
      l.angles.toe = std::max(l.angles.toe, arcsin(rise) - foot_of(tilt, l.angles));
      p = leg_points(w, leg, w.state_.pelvis, l.angles);
    }
    // What a joint remembers as its speed is capped: a jump made in one step (the chain closing
    // onto a foot put down far from the body after an awkward start) must not carry on as a
    // velocity, swinging the leg through a turn in a few steps and the pelvis with it.
    const Joints fastest = joints(detail::kMaxJointSpeed);
    const Joints now = joints(l.angles);
    const Joints before = joints(previous[static_cast<std::size_t>(leg)]);
    store(l.velocity,
          {detail::remembered_speed(now.hip_knee, before.hip_knee, h, fastest.hip_knee),
           detail::remembered_speed(now.ankle_toe, before.ankle_toe, h, fastest.ankle_toe)});
  }
  w.end_points_valid_ = true;
  w.state_.time += h;
  // A go() that came while the closing step was in the air, once the body stands still.
  if (w.state_.go_when_standing && w.state_.locomotion == Locomotion::Standing &&
      w.state_.pelvis_velocity.x == 0.0 && w.state_.pelvis_velocity.y == 0.0) {
    w.go();
  }
  if (w.state_.start_tempo < 1.0) {
    w.state_.start_tempo =
        std::min(1.0, w.state_.start_tempo +
                          h * (1.0 - w.controllers_->start_tempo) / w.controllers_->start_easing);
  }
  // Walking by speed, the speed moves toward the commanded one at the set's acceleration; by step
  // length it is the step's at the set's cadence at once (the tempo is 1).
  if (w.by_speed_) {
    const double most = w.controllers_->acceleration * h;
    w.state_.speed += std::clamp(w.speed_target_ - w.state_.speed, -most, most);
    WalkerState& s = w.state_;
    if (!(s.tempo_gain == s.tempo_gain_target)) {
      const double gap = s.tempo_gain_target - s.tempo_gain;
      // (snapped to the target within a part in 10^5, so that exp() is not recomputed forever)
      s.tempo_gain = std::abs(gap) < 1e-5
                         ? s.tempo_gain_target
                         : s.tempo_gain + gap * std::min(1.0, h / kTempoGainEasing);
    }
  } else {
    w.state_.speed = w.speed_target_;
  }
}

}  // namespace fuzzygait::gait

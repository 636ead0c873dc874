// The walker's time step in stages, which Crowd runs for a block of characters at a time, and the
// controller back end that tests and fuzzygait-bench compare the controllers with. Internal to
// fuzzygait (not installed).
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <span>

#include "fuzzygait/gait/crowd.hpp"
#include "fuzzygait/gait/walker.hpp"

namespace fuzzygait::gait::detail {

// Another evaluator of a set's controllers, called instead of its engines, eight or more times a
// time step: given a controller (ControllerSet::controller_count() order: the slots' first, see
// slot(), then the terrain files') and the leg's metrics, it returns what that controller would.
// The terrain words are blended as without it. It should not allocate. The caller keeps it alive
// while walkers use it.
struct ControllerBackend {
  std::function<double(int controller, const MetricValues& metrics)> evaluate;
};

// What a time step hands from stage to stage.
struct StepData {
  std::array<MetricValues, 2> metrics;
  std::array<std::array<double, 4>, 2> commands;  // [leg][joint]: the controllers' outputs
  std::array<rig::LegAngles, 2> previous;         // joint angles before the step
  std::array<rig::LegAngles, 2> commanded;        // and as the controllers turned them
};

// advance(dt)'s SubSteps (crowd.hpp).
SubSteps sub_steps(double dt, double time_step) noexcept;

struct WalkerStages {
  // One time step: measure() the metrics, command() the controllers, integrate() the joint
  // velocities (and the carrying foot's rules), finish_step() the chain and the contacts.
  static void step(Walker& w, double h);
  static void measure(Walker& w, StepData& d);
  static void command(Walker& w, StepData& d);
  // The commands of the legs on terrain whose incline words the set has controllers for (their
  // blend), replacing what command() or a crowd's batch gave them.
  static void command_on_terrain(Walker& w, StepData& d);
  static void integrate(Walker& w, double h, StepData& d);
  static void finish_step(Walker& w, double h, StepData& d);
  static void carry(Walker& w, double h, const StepData& d,
                    std::array<std::optional<double>, 2>& placed_tip_ground);

  // The stages' inline helpers (walker.cpp, the only file that calls them).
  // rig::forward_kinematics of a leg with its cached sines and cosines.
  static rig::LegPoints leg_points(Walker& w, int leg, rig::Point hip,
                                   const rig::LegAngles& angles);
  // The leg's points with its hip at the origin.
  static rig::LegPoints hip_at_origin(Walker& w, int leg);
  // The pelvis put where the leg's contact point meets its anchor.
  static void place_pelvis(Walker& w, int leg, const rig::LegPoints& at_origin);
  // Height of a carrying leg's knee above the ground, from its points with the hip at the origin.
  static double knee_gap(const Walker& w, int leg, const rig::LegPoints& at_origin);
  // `ascent`: how far the set's ascent words hold (ControllerSet::ascent_weight).
  // `landing_knee`: the knee angle the leg lands with (ControllerSet::landing_knee).
  static void update_metrics(Walker& w, int leg, const rig::LegPoints& points, double ascent,
                             double landing_knee, MetricValues& m);
  static double knee_end_thigh(const Walker& w, int leg, rig::Point hip, rig::Point target);
  struct LegGround {
    double incline;  // degrees (Metric::Incline)
    double stairs;   // 1 or 0 (Metric::Stairs)
  };
  static std::array<LegGround, 2> leg_ground(const Walker& w);

  // A walker, or a crowd, whose controllers `backend` evaluates (one per character, null for
  // the set's own engines).
  static Walker make_walker(const ControllerSet& controllers, const WalkerOptions& options,
                            const terrain::Terrain& terrain, const ControllerBackend* backend);
  static Crowd make_crowd(const ControllerSet& controllers, const terrain::Terrain& terrain,
                          std::span<const WalkerOptions> characters,
                          std::span<const ControllerBackend* const> backends,
                          const CrowdOptions& options = {});
};

}  // namespace fuzzygait::gait::detail

// Walking a set with the studio's settings, measuring the walk, and the page's view of it.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "fuzzygait/body/humanoid.hpp"
#include "fuzzygait/eval/evaluation.hpp"
#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/path/path.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::studio::detail {

struct WalkSettings {
  double step = 0.70;
  double speed = 0.0;  // m/s: above 0, the walk is by speed and its step the set's stride's
  double stature = 1.75;
  int cycles = 10;
  std::string terrain = "flat";  // the spec
  std::string reference = "schwartz2008_free";
  // A path drawn on the ground (x, z metres as path::Path has them; empty: straight ahead) and
  // the radius its corners are rounded to; `route` is made of them by drawn_path().
  std::vector<path::GroundPoint> path;
  double corner_radius = 1.0;
  std::optional<path::Path> route;
};

// The path a walk follows for these points and corner radius: none for no points; else
// path::Path::polyline of them. Throws RequestError 422 naming "path" (the point, from 1: repeated,
// a corner too sharp for its legs, turning back) or the path too long (Limits::kLongestPath).
std::optional<path::Path> drawn_path(const std::vector<path::GroundPoint>& points,
                                     double corner_radius);

// The longest a walk along a path is walked (s) when it neither reaches the path's end nor
// stalls: over twice the longest path's time at the slowest steps.
inline constexpr double kLongestPathWalk = 120.0;

// Frames a second the walk is recorded at (as `fuzzygait walk` writes it), and sent to the page,
// which plays it interpolated: a quarter of the frames keeps an edit's answer small (about 60 KB
// for 10 cycles), which is most of the time an edit takes to show in a browser that draws in
// software; the chord of a point between two frames 1/30 s apart is within 1 % of its arc.
inline constexpr double kRecordFps = 120.0;
inline constexpr double kPageFps = 30.0;
// Frames a second the whole body is sent at: every other page frame, which halves the answer's
// largest part (the page interpolates it: the chord of a swinging hand or knee between two frames
// is within a centimetre of its arc).
inline constexpr double kBodyFps = 15.0;

struct Walked {
  eval::Motion motion;
  // Why the walk stopped short of its cycles (it stumbled or stalled): then `motion` is what it
  // walked in that time. Empty when it walked them all.
  std::string failure;
  std::optional<eval::GaitReport> report;  // none when not measured (`not_measured` says why)
  std::string not_measured;
  std::vector<std::string> missed;  // contact bounds missed, one phrase each
  nlohmann::json figures;           // the contact figures with their bounds
  // The whole body (body::PathFollower on the settings' path, or a straight one;
  // body::humanoid_from_stature) at kBodyFps, the set's upper body playing.
  std::vector<body::BodyPose> body;
  double walk_ms = 0.0;  // wall time of the walk, of posing the body and of measuring
  double body_ms = 0.0;
  double measure_ms = 0.0;
};

// Throws std::invalid_argument (the walker's or the rig's message) when the walker cannot be
// made: a step shorter than the set walks or longer than the legs reach.
void check_walkable(const gait::ControllerSet& set, const WalkSettings& settings,
                    const terrain::Terrain& ground);

// The walker walk() walks with (a step or a speed, legs of the stature).
gait::Walker make_walker(const gait::ControllerSet& set, const WalkSettings& settings,
                         const terrain::Terrain& ground);

// Walks the set: `settings.cycles` gait cycles straight ahead, or along `settings.route` until the
// walker's pelvis reaches its end (then `failure` says when it stalls, 5 cm in 3 s, or has not
// reached it in kLongestPathWalk).
Walked walk(const gait::ControllerSet& set, const WalkSettings& settings,
            const terrain::Terrain& ground, const eval::Normative& reference);

// The page's view: frames at kPageFps (time, pelvis, both legs' points, contacts), the body's
// joints at kBodyFps, the path (null when straight), the ground under the walk, the mean curves
// with their scores, the figures and the warnings.
nlohmann::json walk_json(const Walked& walked, const terrain::Terrain& ground,
                         const WalkSettings& settings);
nlohmann::json reference_json(const eval::Normative& reference);

}  // namespace fuzzygait::studio::detail

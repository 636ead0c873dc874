#include "walk_view.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "fuzzygait/body/follower.hpp"
#include "fuzzygait/eval/terrain_report.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/path/path.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "fuzzygait/studio/studio.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::studio::detail {
namespace {

using nlohmann::json;

// What the page needs and no more: a tenth of a millimetre, a hundredth of a degree.
double rounded(double value, double scale) {
  return std::isfinite(value) ? std::round(value * scale) / scale : 0.0;
}
double metres(double v) {
  return rounded(v, 1e4);
}
double degrees(double radians) {
  return rounded(rig::degrees(radians), 100.0);
}

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

gait::WalkerOptions walker_options(const WalkSettings& settings) {
  gait::WalkerOptions options;
  options.segments = rig::segments_from_stature(settings.stature);
  options.step_length = settings.step;
  options.speed = settings.speed;
  return options;
}

// Seconds a walk that stops short of its cycles is shown for: about as long as the cycles take.
double stalled_duration(int cycles) {
  return 1.2 * (cycles + 2);
}

// The body's joints in the walk's axes (x along the walk, y up, z to the character's left; the
// humanoid's Z, Y and X on the straight path): every joint of body::Humanoid by its VRM name, then
// the backs of the heels, three numbers each a frame in whole millimetres (the body is drawn, not
// measured), each sent as its change from the frame before (from 0 before the first): less than
// half the bytes of the positions written out, and a running sum gives each frame's exactly.
json body_json(const std::vector<body::BodyPose>& poses) {
  json joints = json::array();
  for (std::size_t j = 0; j < body::kJointCount; ++j)
    joints.push_back(body::name(static_cast<body::Joint>(j)));
  joints.push_back("leftHeel");
  joints.push_back("rightHeel");
  constexpr std::size_t kNumbers = (body::kJointCount + 2) * 3;
  std::vector<long long> changes;
  changes.reserve(poses.size() * kNumbers);
  std::array<long long, kNumbers> last{};
  for (const body::BodyPose& pose : poses) {
    std::size_t k = 0;
    auto put = [&](double metres) {
      const long long mm = std::isfinite(metres) ? std::llround(metres * 1e3) : 0;
      changes.push_back(mm - last[k]);
      last[k++] = mm;
    };
    auto put_point = [&](const body::Vec3& p) {
      put(p.z);
      put(p.y);
      put(p.x);
    };
    for (const body::Vec3& p : pose.position)
      put_point(p);
    for (const body::Vec3& p : pose.heel)
      put_point(p);
  }
  return {{"fps", kBodyFps},
          {"count", poses.size()},
          {"joints", joints},
          {"unit", "mm"},
          {"changes", changes}};
}

json curve_json(const eval::Curve& curve, bool with_sd) {
  json c = {{"mean", std::vector<double>(curve.mean.begin(), curve.mean.end())}};
  if (with_sd) c["sd"] = std::vector<double>(curve.sd.begin(), curve.sd.end());
  return c;
}

json score_json(const std::optional<eval::JointScore>& score) {
  if (!score) return nullptr;
  return {{"rmse", score->rmse}, {"pearson", score->pearson}, {"within_2sd", score->within_2sd}};
}

// A figure with its bound; `missed` when one of the bounds missed names it (each phrase of
// missed_contact_bounds begins with or holds the figure's name).
json figure(const char* name, double value, const char* unit, const char* bound,
            const std::vector<std::string>& missed, const char* phrase) {
  const bool miss = std::any_of(missed.begin(), missed.end(), [&](const std::string& m) {
    return m.find(phrase) != std::string::npos;
  });
  return {{"name", name},
          {"value", std::isfinite(value) ? json(value) : json(nullptr)},
          {"unit", unit},
          {"bound", bound},
          {"missed", miss}};
}

// The body at kBodyFps over a walk `frames` recorded frames long: the set walked again as it was
// recorded (the walker is deterministic, so its states are the recording's), followed on the
// settings' path or a straight one. On a straight path the follower's pose depends on the
// walker's state alone (a planted foot's frame is the path's), so posing only the frames sent is
// enough; on a drawn one a foot is locked where it was first seen planted, so the follower is
// updated at every recorded frame, as a game updates it every frame.
std::vector<body::BodyPose> pose_body(const gait::ControllerSet& set, const WalkSettings& settings,
                                      const terrain::Terrain& ground, std::size_t frames) {
  const body::Humanoid humanoid = body::humanoid_from_stature(settings.stature);
  gait::Walker walker(set, walker_options(settings), ground);
  const path::Path straight;
  const path::Path& route = settings.route ? *settings.route : straight;
  body::PathFollower follower(humanoid, route, walker);
  const auto stride = static_cast<std::size_t>(std::lround(kRecordFps / kBodyFps));
  const bool every_frame = settings.route.has_value();
  std::vector<body::BodyPose> poses;
  poses.reserve(frames / stride + 1);
  for (std::size_t i = 0; i < frames; ++i) {
    if (i > 0) walker.advance(1.0 / kRecordFps);
    if (i % stride == 0) {
      poses.push_back(follower.update(walker));
    } else if (every_frame) {
      follower.update(walker);
    }
  }
  return poses;
}

// The walker along `route` from its start, recorded at kRecordFps until its pelvis reaches the
// path's end; `failure` says why it stopped short (a stall: 5 cm in 3 s, as `fuzzygait walk
// --path`; or kLongestPathWalk gone by).
eval::Motion record_path(gait::Walker& walker, const path::Path& route, std::string& failure) {
  eval::Motion motion;
  motion.fps = kRecordFps;
  motion.segments = walker.segments();
  const auto three_seconds = static_cast<std::size_t>(3.0 * kRecordFps);
  const auto longest = static_cast<std::size_t>(kLongestPathWalk * kRecordFps);
  for (std::size_t i = 0;; ++i) {
    if (i > 0) walker.advance(1.0 / kRecordFps);
    motion.frames.push_back(eval::capture_frame(walker, static_cast<double>(i) / kRecordFps));
    const double x = motion.frames.back().pose.pelvis.x;
    if (x >= route.length()) break;
    const auto where = [&] {
      return common::number_text(x, 2) + " m along the path's " +
             common::number_text(route.length(), 2) + " m";
    };
    if (i >= three_seconds && x - motion.frames[i - three_seconds].pose.pelvis.x < 0.05) {
      failure = "the walker stalled " + where();
      break;
    }
    if (i >= longest) {
      failure = "the walker did not reach the path's end in " +
                common::number_text(kLongestPathWalk) + " s (" + where() + ")";
      break;
    }
  }
  return motion;
}

// Metres along a drawn path between the points of its view (the page draws the rounded corners
// from them: a chord of 0.1 m on the tightest arc, 0.5 m, lies within 2.5 mm of it).
constexpr double kPathSpacing = 0.1;

// The path as the page draws it: the points and radius as given, its length, and the rounded
// path every kPathSpacing (x, z, millimetres' precision) from its start to its end.
json path_json(const WalkSettings& settings) {
  if (!settings.route) return nullptr;
  const path::Path& route = *settings.route;
  json points = json::array();
  for (const path::GroundPoint& p : settings.path)
    points.push_back({p.x, p.z});
  const auto count = static_cast<std::size_t>(std::ceil(route.length() / kPathSpacing - 1e-9));
  std::vector<double> samples;
  samples.reserve(2 * (count + 1));
  for (std::size_t i = 0; i <= count; ++i) {
    const path::PathSample at =
        route.at(std::min(static_cast<double>(i) * kPathSpacing, route.length()));
    samples.push_back(rounded(at.point.x, 1e3));
    samples.push_back(rounded(at.point.z, 1e3));
  }
  return {{"points", points},
          {"corner_radius", settings.corner_radius},
          {"length", route.length()},
          {"spacing", kPathSpacing},
          {"samples", samples}};
}

}  // namespace

std::optional<path::Path> drawn_path(const std::vector<path::GroundPoint>& points,
                                     double corner_radius) {
  if (points.empty()) return std::nullopt;
  std::optional<path::Path> route;
  try {
    route = path::Path::polyline(points, corner_radius);
  } catch (const std::invalid_argument& e) {
    throw RequestError(422, "path", e.what());
  }
  if (route->length() > Limits::kLongestPath) {
    throw RequestError(422, "path",
                       "the path is " + common::number_text(route->length(), 3) +
                           " m long with its corners rounded; the studio walks paths of up to " +
                           common::number_text(Limits::kLongestPath) + " m");
  }
  return route;
}

gait::Walker make_walker(const gait::ControllerSet& set, const WalkSettings& settings,
                         const terrain::Terrain& ground) {
  return gait::Walker(set, walker_options(settings), ground);
}

void check_walkable(const gait::ControllerSet& set, const WalkSettings& settings,
                    const terrain::Terrain& ground) {
  gait::Walker walker(set, walker_options(settings), ground);
}

Walked walk(const gait::ControllerSet& set, const WalkSettings& settings,
            const terrain::Terrain& ground, const eval::Normative& reference) {
  Walked w;
  const auto start = std::chrono::steady_clock::now();
  const gait::WalkerOptions options = walker_options(settings);
  double step = settings.step;
  if (settings.route) {
    gait::Walker walker(set, options, ground);
    step = walker.step_length();
    w.motion = record_path(walker, *settings.route, w.failure);
  } else {
    gait::Walker walker(set, options, ground);
    step = walker.step_length();  // by speed, the stride's at the speed asked
    try {
      w.motion = eval::record_cycles(walker, settings.cycles, kRecordFps);
    } catch (const std::runtime_error& e) {
      w.failure = e.what();
    }
  }
  if (!w.failure.empty() && !settings.route) {
    gait::Walker walker(set, options, ground);
    w.motion = eval::record(walker, stalled_duration(settings.cycles), kRecordFps);
  }
  w.walk_ms = milliseconds_since(start);
  const auto posing = std::chrono::steady_clock::now();
  w.body = pose_body(set, settings, ground, w.motion.frames.size());
  w.body_ms = milliseconds_since(posing);

  const auto measuring = std::chrono::steady_clock::now();
  try {
    w.report = eval::evaluate(w.motion, ground, &reference, step);
  } catch (const std::invalid_argument& e) {
    w.not_measured = e.what();
  }
  if (ground.level()) {
    if (w.report) w.missed = eval::missed_contact_bounds(*w.report);
    const std::optional<eval::GaitReport>& r = w.report;
    w.figures =
        json::array({figure("foot slip", r ? r->max_slip * 1e3 : NAN, "mm a frame", "< 1", w.missed,
                            "foot slip"),
                     figure("penetration", r ? r->max_penetration * 1e3 : NAN, "mm", "< 1",
                            w.missed, "penetration"),
                     figure("toe clearance", r ? r->min_toe_clearance * 1e3 : NAN, "mm", ">= 5",
                            w.missed, "toe clearance"),
                     figure("step error", r && r->step_error_percent ? *r->step_error_percent : NAN,
                            "%", "<= 3", w.missed, "step error")});
  } else {
    // Off level ground every leg point counts, edges too (docs/measuring.md, "On terrain").
    const eval::TerrainReport t = eval::evaluate_terrain(w.motion, ground);
    w.missed = eval::missed_contact_bounds(t);
    double slip = 0.0;
    double penetration = 0.0;
    for (const eval::PointContact& p : t.points) {
      slip = std::max(slip, p.max_slip);
      penetration = std::max(penetration, p.max_penetration);
    }
    w.figures = json::array(
        {figure("slip", slip * 1e3, "mm a frame", "< 1", w.missed, "slip"),
         figure("penetration", penetration * 1e3, "mm", "< 1", w.missed, "penetration"),
         figure("swing clearance", t.min_swing_clearance * 1e3, "mm", ">= 10", w.missed,
                "swing clearance"),
         figure("step error",
                w.report && w.report->step_error_percent ? *w.report->step_error_percent : NAN, "%",
                "(level ground only)", {}, "")});
  }
  if (!w.failure.empty()) w.missed.insert(w.missed.begin(), w.failure);
  w.measure_ms = milliseconds_since(measuring);
  return w;
}

json walk_json(const Walked& walked, const terrain::Terrain& ground, const WalkSettings& settings) {
  const eval::Motion& m = walked.motion;
  const auto stride = static_cast<std::size_t>(std::lround(m.fps / kPageFps));
  std::vector<double> time;
  std::vector<double> pelvis;  // x, y, tilt (deg)
  std::vector<double> legs;    // left then right: hip, knee, ankle, heel, ball, tip as x, y
  std::vector<int> contact;    // left, right
  double low = m.frames.front().pose.pelvis.x;
  double high = low;
  for (std::size_t i = 0; i < m.frames.size(); i += stride) {
    const eval::Frame& f = m.frames[i];
    time.push_back(rounded(f.time, 1e4));
    pelvis.insert(pelvis.end(),
                  {metres(f.pose.pelvis.x), metres(f.pose.pelvis.y), degrees(f.pose.pelvis_tilt)});
    for (std::size_t s = 0; s < 2; ++s) {
      const rig::LegPoints& p = f.points[s];
      for (const rig::Point& q : {p.hip, p.knee, p.ankle, p.heel, p.ball, p.tip}) {
        legs.push_back(metres(q.x));
        legs.push_back(metres(q.y));
        low = std::min(low, q.x);
        high = std::max(high, q.x);
      }
      contact.push_back(f.contact[s] ? 1 : 0);
    }
  }
  json ground_points = json::array();
  for (const rig::Point& p : ground.profile(low - 2.0, high + 2.0))
    ground_points.push_back({metres(p.x), metres(p.y)});
  const rig::Segments& s = m.segments;
  json result = {
      {"frames",
       {{"fps", m.fps / static_cast<double>(stride)},
        {"count", time.size()},
        {"time", time},
        {"pelvis", pelvis},
        {"legs", legs},
        {"contact", contact}}},
      {"segments",
       {{"thigh", s.thigh},
        {"shank", s.shank},
        {"ankle_height", s.ankle_height},
        {"heel", s.heel},
        {"ball", s.ball},
        {"toe", s.toe}}},
      {"body", body_json(walked.body)},
      {"path", path_json(settings)},
      {"ground", ground_points},
      {"completed", walked.failure.empty()},
      {"warnings", walked.missed},
      {"figures", walked.figures},
      {"timing_ms",
       {{"walk", walked.walk_ms}, {"body", walked.body_ms}, {"measure", walked.measure_ms}}}};
  if (const std::optional<eval::GaitReport>& r = walked.report) {
    result["curves"] = {{"thigh", curve_json(r->thigh, false)},
                        {"knee", curve_json(r->knee, false)},
                        {"ankle", curve_json(r->ankle, false)},
                        {"toe", curve_json(r->toe, false)}};
    result["scores"] = {{"thigh", score_json(r->thigh_score)},
                        {"knee", score_json(r->knee_score)},
                        {"ankle", score_json(r->ankle_score)}};
    result["gait"] = {{"cycles", r->cycles},
                      {"cycle_time", r->cycle_time},
                      {"cadence", r->cadence},
                      {"speed", r->speed},
                      {"stance_percent", r->stance_percent},
                      {"step_length", r->step_length},
                      {"knee_peak", r->knee_peak},
                      {"knee_peak_percent", r->knee_peak_percent}};
  } else {
    result["not_measured"] = walked.not_measured;
  }
  return result;
}

json reference_json(const eval::Normative& reference) {
  return {{"name", reference.name},
          {"thigh", curve_json(reference.thigh, true)},
          {"knee", curve_json(reference.knee, true)},
          {"ankle", curve_json(reference.ankle, true)}};
}

}  // namespace fuzzygait::studio::detail

#include "fuzzygait/eval/terrain_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>

#include "fuzzygait/eval/evaluation.hpp"

namespace fuzzygait::eval {
namespace {

using rig::Point;
using terrain::Terrain;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kOnGround = 0.002;  // m: a point this close to the ground bears on it
// m: a foothold this much above or below the one before, across a riser, is a stair step (the
// lowest stair the terrain builds rises 0.05 m).
constexpr double kStairRise = 0.02;
// m: how far beyond the sole outline's ends a corner of the ground is looked at for clearance.
constexpr double kCornerReach = 0.3;

// The smaller of two figures, a NaN standing for "none yet".
void keep_lower(double& best, double value) {
  if (std::isnan(value)) return;
  if (std::isnan(best) || value < best) best = value;
}
void keep_higher(double& best, double value) {
  if (std::isnan(value)) return;
  if (std::isnan(best) || value > best) best = value;
}

double segment_distance(Point p, Point a, Point b) {
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  const double length2 = dx * dx + dy * dy;
  double t = length2 > 0.0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / length2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

// A convex corner of the ground: where it turns down by more than kRampThreshold.
struct Corner {
  Point at;
  bool nosing = false;  // beside a segment too steep to stand on
  // Where the ground stands at the corner's height: +1 after it in x (the tread above a riser
  // going up), -1 before it (a tread before a drop), 0 both (a crest).
  int ground_side = 0;
};

std::vector<Corner> convex_corners(const Terrain& terrain) {
  const std::vector<Point>& p = terrain.points();
  std::vector<Corner> corners;
  const double turn = rig::radians(kRampThreshold);
  for (std::size_t i = 1; i + 1 < p.size(); ++i) {
    const double before = std::atan2(p[i].y - p[i - 1].y, p[i].x - p[i - 1].x);
    const double after = std::atan2(p[i + 1].y - p[i].y, p[i + 1].x - p[i].x);
    if (after - before < -turn) {
      const bool steep_before = std::abs(before) > Terrain::kSteepestFoothold;
      const bool steep_after = std::abs(after) > Terrain::kSteepestFoothold;
      corners.push_back({p[i], steep_before || steep_after,
                         steep_before == steep_after ? 0 : (steep_before ? 1 : -1)});
    }
  }
  return corners;
}

// The corners with x in [x0, x1] (corners are in x order).
std::pair<std::size_t, std::size_t> corners_between(const std::vector<Corner>& corners, double x0,
                                                    double x1) {
  const auto by_x = [](const Corner& c, double x) { return c.at.x < x; };
  const auto first = std::lower_bound(corners.begin(), corners.end(), x0, by_x);
  const auto last = std::lower_bound(first, corners.end(), std::nextafter(x1, HUGE_VAL), by_x);
  return {static_cast<std::size_t>(first - corners.begin()),
          static_cast<std::size_t>(last - corners.begin())};
}

// The sole outline: heel, ball, toe tip.
std::array<Point, 3> outline(const rig::LegPoints& p) {
  return {p.heel, p.ball, p.tip};
}

// Signed distance from a corner to the sole outline: negative when the corner lies above the
// outline where the outline spans its x (on ground that is a height field, some of the foot is
// then inside the ground).
double outline_distance(const rig::LegPoints& foot, Point corner) {
  const std::array<Point, 3> o = outline(foot);
  double distance = std::numeric_limits<double>::infinity();
  bool above = false;
  for (std::size_t k = 0; k + 1 < o.size(); ++k) {
    const Point a = o[k];
    const Point b = o[k + 1];
    distance = std::min(distance, segment_distance(corner, a, b));
    const double low = std::min(a.x, b.x);
    const double high = std::max(a.x, b.x);
    if (high > low && corner.x >= low && corner.x <= high) {
      const double y = a.y + (b.y - a.y) * (corner.x - a.x) / (b.x - a.x);
      above = above || corner.y > y;
    }
  }
  return above ? -distance : distance;
}

// The smallest distance between the sole outline and the ground, its surface and its corners.
double foot_clearance(const Terrain& terrain, const std::vector<Corner>& corners,
                      const rig::LegPoints& foot) {
  double clearance = kNaN;
  double x0 = std::numeric_limits<double>::infinity();
  double x1 = -x0;
  for (const Point& p : outline(foot)) {
    keep_lower(clearance, ground_distance(terrain, p));
    x0 = std::min(x0, p.x);
    x1 = std::max(x1, p.x);
  }
  const auto [first, last] = corners_between(corners, x0 - kCornerReach, x1 + kCornerReach);
  for (std::size_t c = first; c < last; ++c)
    keep_lower(clearance, outline_distance(foot, corners[c].at));
  return clearance;
}

// The ground's angle (radians) and height at x, taken on run `run` (x clamped into it): the
// surface a foot standing on that run has under it, never a riser's face.
std::pair<double, double> run_surface(const Terrain& terrain, std::size_t run, double x) {
  const Terrain::Run& r = terrain.runs()[run];
  double at = std::clamp(x, r.begin, r.end);
  // A point at a run's end begins the riser after it: step back onto the run.
  if (at >= r.end && r.end > r.begin) at = r.end - std::min(1e-7, 0.5 * (r.end - r.begin));
  return {terrain.slope(at), terrain.height(at)};
}

bool finite_frame(const Frame& f) {
  const rig::Pose& p = f.pose;
  bool ok = std::isfinite(p.pelvis.x) && std::isfinite(p.pelvis.y) && std::isfinite(p.pelvis_tilt);
  for (const rig::LegAngles& a : p.legs)
    ok = ok && std::isfinite(a.hip) && std::isfinite(a.knee) && std::isfinite(a.ankle) &&
         std::isfinite(a.toe);
  for (const rig::LegPoints& l : f.points) {
    for (const Point& q : {l.hip, l.knee, l.ankle, l.heel, l.ball, l.tip})
      ok = ok && std::isfinite(q.x) && std::isfinite(q.y);
  }
  return ok;
}

// The sole's pitch (radians, toes up +) for a walk going the way `direction` (+1 or -1) says.
double sole_pitch(const rig::LegPoints& p, double direction) {
  return std::atan2(p.ball.y - p.heel.y, direction * (p.ball.x - p.heel.x));
}

// A foot point's smallest height above a corner over frames [begin, end] while within
// kEdgeWindow of it in x on the side where the ground stands at its height (before a riser's
// foot, or past a drop, a point lower than the corner is over lower ground). Frames as sampled:
// a line between two frames may cut a corner the point itself went round.
template <typename PointOf>
double clearance_over(const Motion& m, std::size_t begin, std::size_t end, const Corner& corner,
                      PointOf point_of) {
  double best = kNaN;
  for (std::size_t k = begin; k <= end; ++k) {
    const Point p = point_of(m.frames[k]);
    const double along = p.x - corner.at.x;
    const bool over_ground = corner.ground_side == 0 || along * corner.ground_side >= 0.0;
    if (std::abs(along) <= kEdgeWindow && over_ground) keep_lower(best, p.y - corner.at.y);
  }
  return best;
}

Stat stat_of(const std::vector<double>& values) {
  Stat s{0, kNaN, kNaN, kNaN};
  double sum = 0.0;
  for (double v : values) {
    if (std::isnan(v)) continue;
    ++s.count;
    sum += v;
    keep_lower(s.min, v);
    keep_higher(s.max, v);
  }
  if (s.count > 0) s.mean = sum / s.count;
  return s;
}

// The per-step figures that groups summarise, with their names in the text and the JSON.
struct Measure {
  const char* key;    // JSON, before its unit
  const char* label;  // text
  const char* unit;   // text
  const char* json_unit;
  double text_scale;  // text value = field * scale (metres shown as mm)
  double TerrainStep::*step;
  Stat TerrainGroup::*group;
};

constexpr Measure kMeasures[] = {
    {"hip_at_contact", "hip flexion at contact", "deg", "deg", 1.0, &TerrainStep::hip,
     &TerrainGroup::hip},
    {"knee_at_contact", "knee flexion at contact", "deg", "deg", 1.0, &TerrainStep::knee,
     &TerrainGroup::knee},
    {"ankle_at_contact", "ankle at contact", "deg", "deg", 1.0, &TerrainStep::ankle,
     &TerrainGroup::ankle},
    {"foot_pitch_at_contact", "foot pitch at contact", "deg", "deg", 1.0, &TerrainStep::foot_pitch,
     &TerrainGroup::foot_pitch},
    {"early_stance_knee", "knee peak, 1st half stance", "deg", "deg", 1.0,
     &TerrainStep::early_stance_knee, &TerrainGroup::early_stance_knee},
    {"knee_at_toe_off", "knee flexion at toe off", "deg", "deg", 1.0, &TerrainStep::knee_at_toe_off,
     &TerrainGroup::knee_at_toe_off},
    {"mid_stance_sole_to_surface", "sole to surface, mid-stance", "deg", "deg", 1.0,
     &TerrainStep::mid_stance_sole, &TerrainGroup::mid_stance_sole},
    {"mid_stance_ankle", "ankle at mid-stance", "deg", "deg", 1.0, &TerrainStep::mid_stance_ankle,
     &TerrainGroup::mid_stance_ankle},
    {"peak_swing_knee", "peak swing knee flexion", "deg", "deg", 1.0, &TerrainStep::peak_swing_knee,
     &TerrainGroup::peak_swing_knee},
    {"peak_swing_hip", "peak swing hip flexion", "deg", "deg", 1.0, &TerrainStep::peak_swing_hip,
     &TerrainGroup::peak_swing_hip},
    {"hip_range", "hip range over the cycle", "deg", "deg", 1.0, &TerrainStep::hip_range,
     &TerrainGroup::hip_range},
    {"stance", "stance", "% cycle", "percent", 1.0, &TerrainStep::stance_percent,
     &TerrainGroup::stance_percent},
    {"cycle_time", "cycle time", "s", "s", 1.0, &TerrainStep::cycle_time,
     &TerrainGroup::cycle_time},
    {"cadence", "cadence", "steps/min", "steps_per_min", 1.0, &TerrainStep::cadence,
     &TerrainGroup::cadence},
    {"step_length", "step length", "m", "m", 1.0, &TerrainStep::step_length,
     &TerrainGroup::step_length},
    {"rise", "rise from foothold before", "mm", "m", 1000.0, &TerrainStep::rise,
     &TerrainGroup::rise},
    {"pelvis_rise", "pelvis rise per stride", "mm", "m", 1000.0, &TerrainStep::pelvis_rise,
     &TerrainGroup::pelvis_rise},
    {"ground_rise", "ground rise per stride", "mm", "m", 1000.0, &TerrainStep::ground_rise,
     &TerrainGroup::ground_rise},
    {"edge_tip_clearance", "toe tip over edges, min", "mm", "m", 1000.0, &TerrainStep::edge_tip,
     &TerrainGroup::edge_tip},
    {"edge_heel_clearance", "heel over edges, min", "mm", "m", 1000.0, &TerrainStep::edge_heel,
     &TerrainGroup::edge_heel},
    {"edge_foot_clearance", "sole outline to edges, min", "mm", "m", 1000.0,
     &TerrainStep::edge_foot, &TerrainGroup::edge_foot},
};

std::string group_title(const TerrainGroup& g) {
  std::string title = name(g.footing);
  if (g.footing == Footing::RampUp || g.footing == Footing::RampDown) {
    title += " " + std::to_string(std::abs(g.degrees)) + " deg";
  }
  return title;
}

// The sort order of groups: kind of ground, then steepness.
std::pair<int, int> group_order(Footing footing, int degrees) {
  return {static_cast<int>(footing), std::abs(degrees)};
}

}  // namespace

const char* name(Footing footing) {
  switch (footing) {
    case Footing::Level:
      return "level";
    case Footing::RampUp:
      return "ramp up";
    case Footing::RampDown:
      return "ramp down";
    case Footing::StairUp:
      return "stairs up";
    case Footing::StairDown:
      return "stairs down";
  }
  return "?";
}

double ground_distance(const Terrain& terrain, Point p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return kNaN;
  const double gap = p.y - terrain.height(p.x);
  const double reach = std::abs(gap);
  if (reach == 0.0) return gap;
  // The nearest surface point lies within `reach` of p: only segments over [x - reach, x + reach]
  // can hold it. Beyond the ends the ground is level, as near as the end points or the gap.
  const std::vector<Point>& points = terrain.points();
  const auto by_x = [](double x, const Point& q) { return x < q.x; };
  auto low = std::upper_bound(points.begin(), points.end(), p.x - reach, by_x);
  if (low != points.begin()) --low;
  auto high = std::upper_bound(low, points.end(), p.x + reach, by_x);
  if (high == points.end()) --high;
  double nearest = reach;
  for (auto it = low; it < high; ++it)
    nearest = std::min(nearest, segment_distance(p, *it, *(it + 1)));
  return gap < 0.0 ? -nearest : nearest;
}

TerrainReport evaluate_terrain(const Motion& m, const Terrain& terrain) {
  const std::size_t n = m.frames.size();
  if (n < 2 || !(m.fps > 0.0) || !std::isfinite(m.fps)) {
    throw std::invalid_argument("terrain measures: the walk needs two frames and a frame rate > 0");
  }
  TerrainReport r;
  r.runs = terrain.runs().size();
  const std::vector<Corner> corners = convex_corners(terrain);
  const double direction =
      m.frames.back().pose.pelvis.x >= m.frames.front().pose.pelvis.x ? 1.0 : -1.0;
  std::vector<bool> finite(n);
  for (std::size_t i = 0; i < n; ++i) {
    finite[i] = finite_frame(m.frames[i]);
    r.nan_frames += finite[i] ? 0 : 1;
  }

  // The strikes of both feet in time order (left first at the same frame).
  std::array<std::vector<std::size_t>, 2> strikes = {heel_strikes(m, rig::Side::Left),
                                                     heel_strikes(m, rig::Side::Right)};
  std::vector<std::pair<std::size_t, std::size_t>> order;  // frame, side
  for (std::size_t s = 0; s < 2; ++s) {
    for (std::size_t f : strikes[s])
      if (finite[f]) order.emplace_back(f, s);
  }
  std::sort(order.begin(), order.end());

  // Footholds and what is measured at contact.
  for (const auto& [f, s] : order) {
    TerrainStep step;
    step.side = static_cast<rig::Side>(s);
    step.frame = f;
    step.time = m.frames[f].time;
    const rig::LegPoints& foot = m.frames[f].points[s];
    const rig::LegAngles& angles = m.frames[f].pose.legs[s];
    double nearest = std::numeric_limits<double>::infinity();
    const Point* contact = &foot.heel;
    for (const Point* q : {&foot.heel, &foot.ball, &foot.tip}) {
      const double d = std::abs(ground_distance(terrain, *q));
      if (d < nearest) {
        nearest = d;
        contact = q;
      }
    }
    step.x = contact->x;
    step.forefoot = contact != &foot.heel;
    step.run = terrain.run_at(step.x);
    const auto [angle, height] = run_surface(terrain, step.run, step.x);
    step.height = height;
    step.surface = direction * rig::degrees(angle);
    step.rise = kNaN;
    step.step_length = kNaN;
    bool crossed = false;
    if (!r.steps.empty()) {
      const TerrainStep& before = r.steps.back();
      step.rise = step.height - before.height;
      step.step_length = std::abs(step.x - before.x);
      crossed = step.run != before.run;
    }
    if (crossed && std::abs(step.rise) >= kStairRise) {
      step.footing = step.rise > 0.0 ? Footing::StairUp : Footing::StairDown;
    } else if (std::abs(step.surface) >= kRampThreshold) {
      step.footing = step.surface > 0.0 ? Footing::RampUp : Footing::RampDown;
    }
    step.hip = rig::degrees(angles.hip);
    step.knee = rig::degrees(angles.knee);
    step.ankle = rig::degrees(angles.ankle);
    step.foot_pitch = rig::degrees(sole_pitch(foot, direction));
    r.steps.push_back(step);
  }

  // Each step's cycle: stance to toe off, swing to the same foot's next strike.
  auto knee = [&](std::size_t i, std::size_t s) {
    return rig::degrees(m.frames[i].pose.legs[s].knee);
  };
  auto hip = [&](std::size_t i, std::size_t s) {
    return rig::degrees(m.frames[i].pose.legs[s].hip);
  };
  for (std::size_t k = 0; k < r.steps.size(); ++k) {
    TerrainStep& step = r.steps[k];
    const auto s = static_cast<std::size_t>(rig::index(step.side));
    const std::size_t f = step.frame;
    // The same foot's next step, if the walk holds it.
    std::size_t next = k + 1;
    while (next < r.steps.size() && r.steps[next].side != step.side)
      ++next;
    const bool has_next = next < r.steps.size();
    const std::size_t g = has_next ? r.steps[next].frame : n;
    std::size_t toe_off = f + 1;
    while (toe_off < g && m.frames[toe_off].contact[s])
      ++toe_off;
    const bool lifted = toe_off < std::min(g, n);
    for (double* field :
         {&step.early_stance_knee, &step.knee_at_toe_off, &step.mid_stance_sole,
          &step.mid_stance_ankle, &step.cycle_time, &step.cadence, &step.stance_percent,
          &step.peak_swing_knee, &step.peak_swing_hip, &step.hip_range, &step.pelvis_rise,
          &step.ground_rise, &step.edge_tip, &step.edge_heel, &step.edge_foot})
      *field = kNaN;
    if (lifted) {
      for (std::size_t i = f; i <= f + (toe_off - f) / 2; ++i)
        keep_higher(step.early_stance_knee, knee(i, s));
      step.knee_at_toe_off = knee(toe_off, s);
      const std::size_t mid =
          f + static_cast<std::size_t>(std::lround(0.5 * static_cast<double>(toe_off - f)));
      const rig::LegPoints& foot = m.frames[mid].points[s];
      const double sole_x = 0.5 * (foot.heel.x + foot.ball.x);
      const double surface = direction * run_surface(terrain, step.run, sole_x).first;
      step.mid_stance_sole = rig::degrees(sole_pitch(foot, direction) - surface);
      step.mid_stance_ankle = rig::degrees(m.frames[mid].pose.legs[s].ankle);
    }
    if (!has_next || !lifted) continue;
    step.cycle_time = static_cast<double>(g - f) / m.fps;
    step.cadence = 120.0 / step.cycle_time;
    step.stance_percent = 100.0 * static_cast<double>(toe_off - f) / static_cast<double>(g - f);
    double hip_low = kNaN;
    double hip_high = kNaN;
    for (std::size_t i = f; i <= g; ++i) {
      keep_lower(hip_low, hip(i, s));
      keep_higher(hip_high, hip(i, s));
      if (i >= toe_off) {
        keep_higher(step.peak_swing_knee, knee(i, s));
        keep_higher(step.peak_swing_hip, hip(i, s));
      }
    }
    step.hip_range = hip_high - hip_low;
    step.pelvis_rise = m.frames[g].pose.pelvis.y - m.frames[f].pose.pelvis.y;
    step.ground_rise = r.steps[next].height - step.height;
    // The edges between the heel at toe off and the toe tip at landing.
    const double from = m.frames[toe_off].points[s].heel.x;
    const double to = m.frames[g].points[s].tip.x;
    const auto [first, last] = corners_between(corners, std::min(from, to), std::max(from, to));
    for (std::size_t c = first; c < last; ++c) {
      EdgeClearance e;
      e.corner = corners[c].at;
      e.nosing = corners[c].nosing;
      // Over the swing's frames: toe off to the frame before the strike.
      e.tip = clearance_over(m, toe_off, g - 1, corners[c],
                             [s](const Frame& fr) { return fr.points[s].tip; });
      e.heel = clearance_over(m, toe_off, g - 1, corners[c],
                              [s](const Frame& fr) { return fr.points[s].heel; });
      e.foot = kNaN;
      for (std::size_t i = toe_off; i < g; ++i) {
        if (finite[i]) keep_lower(e.foot, outline_distance(m.frames[i].points[s], e.corner));
      }
      keep_lower(step.edge_tip, e.tip);
      keep_lower(step.edge_heel, e.heel);
      keep_lower(step.edge_foot, e.foot);
      step.edges.push_back(e);
    }
    if (direction < 0.0) std::reverse(step.edges.begin(), step.edges.end());
  }

  // Groups: each kind of ground, ramps by whole degrees.
  std::vector<std::pair<Footing, int>> keys;
  for (const TerrainStep& step : r.steps) {
    const bool ramp = step.footing == Footing::RampUp || step.footing == Footing::RampDown;
    const std::pair<Footing, int> key{step.footing,
                                      ramp ? static_cast<int>(std::lround(step.surface)) : 0};
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  }
  std::sort(keys.begin(), keys.end(), [](const auto& a, const auto& b) {
    return group_order(a.first, a.second) < group_order(b.first, b.second);
  });
  for (const auto& [footing, degrees] : keys) {
    TerrainGroup g;
    g.footing = footing;
    g.degrees = degrees;
    std::vector<const TerrainStep*> members;
    for (const TerrainStep& step : r.steps) {
      const bool ramp = step.footing == Footing::RampUp || step.footing == Footing::RampDown;
      const int d = ramp ? static_cast<int>(std::lround(step.surface)) : 0;
      if (step.footing == footing && d == degrees) members.push_back(&step);
    }
    g.steps = static_cast<int>(members.size());
    int forefoot = 0;
    for (const TerrainStep* step : members)
      forefoot += step->forefoot ? 1 : 0;
    g.forefoot_percent = 100.0 * forefoot / g.steps;
    for (const Measure& measure : kMeasures) {
      std::vector<double> values;
      for (const TerrainStep* step : members)
        values.push_back(step->*measure.step);
      g.*measure.group = stat_of(values);
    }
    r.groups.push_back(g);
  }
  double level_pitch = kNaN;
  for (const TerrainGroup& g : r.groups) {
    if (g.footing == Footing::Level) level_pitch = g.foot_pitch.mean;
  }
  for (TerrainGroup& g : r.groups)
    g.toe_down_vs_level = level_pitch - g.foot_pitch.mean;

  // Every leg point against the ground: slip along the surface while on it, and depth below it.
  for (std::size_t s = 0; s < 2; ++s) {
    for (std::size_t i = 0; i < n; ++i) {
      if (!finite[i]) continue;
      const rig::LegPoints& now = m.frames[i].points[s];
      const rig::LegPoints& before = m.frames[i > 0 ? i - 1 : 0].points[s];
      const Point current[] = {now.knee, now.ankle, now.heel, now.ball, now.tip};
      const Point previous[] = {before.knee, before.ankle, before.heel, before.ball, before.tip};
      for (std::size_t p = 0; p < kContactPoints.size(); ++p) {
        PointContact& c = r.points[p];
        const double d = ground_distance(terrain, current[p]);
        if (-d > c.max_penetration) {
          c.max_penetration = -d;
          c.penetration_time = m.frames[i].time;
        }
        if (i == 0 || !finite[i - 1] || d >= kOnGround) continue;
        if (ground_distance(terrain, previous[p]) >= kOnGround) continue;
        const double angle = run_surface(terrain, terrain.run_at(current[p].x), current[p].x).first;
        const double along = (current[p].x - previous[p].x) * std::cos(angle) +
                             (current[p].y - previous[p].y) * std::sin(angle);
        if (std::abs(along) > c.max_slip) {
          c.max_slip = std::abs(along);
          c.slip_time = m.frames[i].time;
        }
      }
    }
  }

  // The fastest turn of a leg joint between two finite frames.
  for (std::size_t i = 1; i < n; ++i) {
    if (!finite[i] || !finite[i - 1]) continue;
    const double interval = m.frames[i].time - m.frames[i - 1].time;
    if (!(interval > 0.0)) continue;
    for (std::size_t s = 0; s < 2; ++s) {
      const rig::LegAngles& now = m.frames[i].pose.legs[s];
      const rig::LegAngles& before = m.frames[i - 1].pose.legs[s];
      const std::pair<const char*, double> changes[] = {{"hip", now.hip - before.hip},
                                                        {"knee", now.knee - before.knee},
                                                        {"ankle", now.ankle - before.ankle},
                                                        {"toe", now.toe - before.toe}};
      for (const auto& [joint, change] : changes) {
        const double degrees = rig::degrees(std::abs(change));
        if (degrees / interval > r.fastest_joint.speed) {
          r.fastest_joint = {degrees / interval, degrees, m.frames[i].time,
                             static_cast<rig::Side>(s), joint};
        }
      }
    }
  }

  // Clearance in the middle 60 % of each complete swing, as evaluate()'s toe clearance.
  r.min_swing_clearance = kNaN;
  r.min_swing_clearance_time = kNaN;
  for (std::size_t s = 0; s < 2; ++s) {
    std::size_t i = 0;
    while (i < n) {
      if (m.frames[i].contact[s]) {
        ++i;
        continue;
      }
      std::size_t j = i;
      while (j < n && !m.frames[j].contact[s])
        ++j;
      if (i > 0 && j < n) {
        for (std::size_t k = i + (j - i) / 5; k < j - (j - i) / 5; ++k) {
          if (!finite[k]) continue;
          const double c = foot_clearance(terrain, corners, m.frames[k].points[s]);
          if (std::isnan(r.min_swing_clearance) || c < r.min_swing_clearance) {
            r.min_swing_clearance = c;
            r.min_swing_clearance_time = m.frames[k].time;
          }
        }
      }
      i = j;
    }
  }

  r.min_edge_tip = r.min_edge_heel = r.min_edge_foot = kNaN;
  for (const TerrainStep& step : r.steps) {
    keep_lower(r.min_edge_tip, step.edge_tip);
    keep_lower(r.min_edge_heel, step.edge_heel);
    keep_lower(r.min_edge_foot, step.edge_foot);
  }
  r.cadence = kNaN;
  if (r.steps.size() >= 2) {
    const double span = r.steps.back().time - r.steps.front().time;
    if (span > 0.0) r.cadence = 60.0 * static_cast<double>(r.steps.size() - 1) / span;
  }
  if (!r.steps.empty()) {
    r.last_run = r.steps.back().run;
    if (r.runs > 1) r.reached_end = r.last_run + 1 == r.runs;
  }
  return r;
}

std::vector<std::string> missed_contact_bounds(const TerrainReport& r) {
  std::vector<std::string> missed;
  char line[200];
  for (std::size_t p = 0; p < kContactPoints.size(); ++p) {
    if (r.points[p].max_slip >= 0.001) {
      std::snprintf(line, sizeof line, "%s slip %.2f mm a frame (bound 1 mm)", kContactPoints[p],
                    r.points[p].max_slip * 1e3);
      missed.emplace_back(line);
    }
    if (r.points[p].max_penetration >= 0.001) {
      std::snprintf(line, sizeof line, "%s penetration %.2f mm (bound 1 mm)", kContactPoints[p],
                    r.points[p].max_penetration * 1e3);
      missed.emplace_back(line);
    }
  }
  if (r.min_swing_clearance < 0.010) {
    std::snprintf(line, sizeof line, "swing clearance %.2f mm (bound 10 mm)",
                  r.min_swing_clearance * 1e3);
    missed.emplace_back(line);
  }
  if (r.nan_frames > 0) missed.push_back(std::to_string(r.nan_frames) + " frames with NaN");
  return missed;
}

std::string missed_continuity_bound(const TerrainReport& r, double fps) {
  const JointJump& j = r.fastest_joint;
  if (!(j.speed > kFastestJointSpeed)) return {};
  char line[240];
  std::snprintf(line, sizeof line,
                "%s %s turned %.1f deg in one frame at %.3f s (%.0f deg/s; people's fastest %.0f "
                "deg/s, %.1f deg a frame)",
                j.side == rig::Side::Left ? "left" : "right", j.joint, j.degrees, j.time, j.speed,
                kFastestJointSpeed, kFastestJointSpeed / fps);
  return line;
}

std::string to_text(const TerrainReport& r) {
  std::string out;
  char line[320];
  auto figure = [](double v, double scale, int decimals) {
    if (std::isnan(v)) return std::string("-");
    char b[48];
    std::snprintf(b, sizeof b, "%.*f", decimals, v * scale);
    return std::string(b);
  };
  auto decimals_for = [](const Measure& m) {
    return std::string(m.unit) == "m" || std::string(m.unit) == "s" ? 2 : 1;
  };

  out += "On terrain: " + std::to_string(r.steps.size()) + " steps";
  if (r.reached_end) {
    out += "; the last foothold is on run " + std::to_string(r.last_run) + " of " +
           std::to_string(r.runs - 1) + " (" +
           (*r.reached_end ? "the last run: the walk reached the end" : "not the last run") + ")";
  }
  out += "\n";
  if (!r.groups.empty()) {
    // Per kind of ground: mean (min..max).
    std::snprintf(line, sizeof line, "%-30s", "by ground");
    out += line;
    for (const TerrainGroup& g : r.groups) {
      std::snprintf(line, sizeof line, " %22s", group_title(g).c_str());
      out += line;
    }
    out += "\n";
    auto row = [&](const std::string& label, auto cell) {
      std::snprintf(line, sizeof line, "%-30s", label.c_str());
      out += line;
      for (const TerrainGroup& g : r.groups) {
        std::snprintf(line, sizeof line, " %22s", cell(g).c_str());
        out += line;
      }
      out += "\n";
    };
    row("steps", [](const TerrainGroup& g) { return std::to_string(g.steps); });
    row("landing on the forefoot (%)",
        [&](const TerrainGroup& g) { return figure(g.forefoot_percent, 1.0, 0); });
    for (const Measure& m : kMeasures) {
      const int decimals = decimals_for(m);
      row(std::string(m.label) + " (" + m.unit + ")", [&](const TerrainGroup& g) {
        const Stat& s = g.*m.group;
        if (s.count == 0) return std::string("-");
        return figure(s.mean, m.text_scale, decimals) + " (" +
               figure(s.min, m.text_scale, decimals) + ".." +
               figure(s.max, m.text_scale, decimals) + ")";
      });
      if (m.group == &TerrainGroup::foot_pitch) {
        row("  toe-down vs level (deg)",
            [&](const TerrainGroup& g) { return figure(g.toe_down_vs_level, 1.0, 1); });
      }
    }
  }

  out +=
      "steps (deg; mm; stance %): side time x run ground | at contact: landing hip knee pitch | "
      "sole mid-stance | stance, swing knee, swing hip | edges: tip heel foot | rise: "
      "pelvis ground\n";
  for (const TerrainStep& s : r.steps) {
    std::string ground = name(s.footing);
    if (s.footing == Footing::RampUp || s.footing == Footing::RampDown) {
      ground += " " + figure(std::abs(s.surface), 1.0, 1);
    }
    std::snprintf(
        line, sizeof line,
        "  %s %7.3f %7.3f %3zu %-14s | %-4s %6s %6s %6s | %6s | %5s %6s %6s | %6s %6s "
        "%6s | %6s %6s\n",
        s.side == rig::Side::Left ? "L" : "R", s.time, s.x, s.run, ground.c_str(),
        s.forefoot ? "fore" : "heel", figure(s.hip, 1.0, 1).c_str(), figure(s.knee, 1.0, 1).c_str(),
        figure(s.foot_pitch, 1.0, 1).c_str(), figure(s.mid_stance_sole, 1.0, 1).c_str(),
        figure(s.stance_percent, 1.0, 0).c_str(), figure(s.peak_swing_knee, 1.0, 1).c_str(),
        figure(s.peak_swing_hip, 1.0, 1).c_str(), figure(s.edge_tip, 1e3, 0).c_str(),
        figure(s.edge_heel, 1e3, 0).c_str(), figure(s.edge_foot, 1e3, 0).c_str(),
        figure(s.pelvis_rise, 1e3, 0).c_str(), figure(s.ground_rise, 1e3, 0).c_str());
    out += line;
  }

  out += "leg points against the ground    max slip (mm a frame)     max penetration (mm)\n";
  // A figure with where it was, when it shows as 0.01 or more.
  auto at = [&figure](double value, double time) {
    std::string text = figure(value, 1e3, 2);
    if (value >= 0.000005) text += " (" + figure(time, 1.0, 3) + " s)";
    return text;
  };
  for (std::size_t p = 0; p < kContactPoints.size(); ++p) {
    const PointContact& c = r.points[p];
    std::snprintf(line, sizeof line, "  %-20s %26s %26s\n", kContactPoints[p],
                  at(c.max_slip, c.slip_time).c_str(),
                  at(c.max_penetration, c.penetration_time).c_str());
    out += line;
  }
  auto note = [&](const char* label, const std::string& value) {
    std::snprintf(line, sizeof line, "%-34s %s\n", label, value.c_str());
    out += line;
  };
  note("frames with NaN", std::to_string(r.nan_frames));
  note("fastest joint between two frames",
       figure(r.fastest_joint.speed, 1.0, 0) + " deg/s (" +
           figure(r.fastest_joint.degrees, 1.0, 1) + " deg, " +
           (r.fastest_joint.side == rig::Side::Left ? "left " : "right ") + r.fastest_joint.joint +
           ", at " + figure(r.fastest_joint.time, 1.0, 3) + " s)");
  note("min swing clearance, mid-swing",
       figure(r.min_swing_clearance, 1e3, 2) + " mm" +
           (std::isnan(r.min_swing_clearance_time)
                ? ""
                : " (at " + figure(r.min_swing_clearance_time, 1.0, 3) + " s)"));
  note("min clearance over edges", "toe tip " + figure(r.min_edge_tip, 1e3, 1) + " mm, heel " +
                                       figure(r.min_edge_heel, 1e3, 1) + " mm, sole outline " +
                                       figure(r.min_edge_foot, 1e3, 1) + " mm");
  note("cadence, first strike to last", figure(r.cadence, 1.0, 1) + " steps/min");
  return out;
}

std::string to_json(const TerrainReport& r) {
  using Json = nlohmann::ordered_json;
  auto number = [](double v) { return std::isnan(v) ? Json(nullptr) : Json(v); };
  Json j;
  j["runs"] = r.runs;
  j["last_run"] = r.last_run;
  j["reached_end"] = r.reached_end ? Json(*r.reached_end) : Json(nullptr);
  j["cadence_steps_per_min"] = number(r.cadence);
  j["nan_frames"] = r.nan_frames;
  j["fastest_joint"] = {{"speed_deg_per_s", r.fastest_joint.speed},
                        {"change_deg", r.fastest_joint.degrees},
                        {"time_s", r.fastest_joint.time},
                        {"side", r.fastest_joint.side == rig::Side::Left ? "left" : "right"},
                        {"joint", r.fastest_joint.joint}};
  for (std::size_t p = 0; p < kContactPoints.size(); ++p) {
    j["points"][kContactPoints[p]] = {{"max_slip_m_per_frame", r.points[p].max_slip},
                                      {"max_penetration_m", r.points[p].max_penetration},
                                      {"penetration_time_s", r.points[p].penetration_time},
                                      {"slip_time_s", r.points[p].slip_time}};
  }
  j["min_swing_clearance_m"] = number(r.min_swing_clearance);
  j["min_swing_clearance_time_s"] = number(r.min_swing_clearance_time);
  j["min_edge_clearance_m"] = {{"tip", number(r.min_edge_tip)},
                               {"heel", number(r.min_edge_heel)},
                               {"foot", number(r.min_edge_foot)}};
  j["groups"] = Json::array();
  for (const TerrainGroup& g : r.groups) {
    Json group;
    group["ground"] = name(g.footing);
    group["degrees"] = g.degrees;
    group["steps"] = g.steps;
    group["forefoot_percent"] = g.forefoot_percent;
    group["toe_down_vs_level_deg"] = number(g.toe_down_vs_level);
    for (const Measure& m : kMeasures) {
      const Stat& s = g.*m.group;
      group[std::string(m.key) + "_" + m.json_unit] = {{"count", s.count},
                                                       {"mean", number(s.mean)},
                                                       {"min", number(s.min)},
                                                       {"max", number(s.max)}};
    }
    j["groups"].push_back(group);
  }
  j["steps"] = Json::array();
  for (const TerrainStep& s : r.steps) {
    Json step;
    step["side"] = s.side == rig::Side::Left ? "left" : "right";
    step["frame"] = s.frame;
    step["time_s"] = s.time;
    step["x_m"] = s.x;
    step["height_m"] = s.height;
    step["run"] = s.run;
    step["ground"] = name(s.footing);
    step["surface_deg"] = s.surface;
    step["landing"] = s.forefoot ? "forefoot" : "heel";
    for (const Measure& m : kMeasures)
      step[std::string(m.key) + "_" + m.json_unit] = number(s.*m.step);
    step["edges"] = Json::array();
    for (const EdgeClearance& e : s.edges) {
      step["edges"].push_back({{"x_m", e.corner.x},
                               {"y_m", e.corner.y},
                               {"kind", e.nosing ? "nosing" : "crest"},
                               {"tip_m", number(e.tip)},
                               {"heel_m", number(e.heel)},
                               {"foot_m", number(e.foot)}});
    }
    j["steps"].push_back(step);
  }
  return j.dump(2);
}

}  // namespace fuzzygait::eval

#include "fuzzygait/eval/evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace fuzzygait::eval {
namespace {

constexpr double kOnGround = 0.002;  // m: a foot point this close to the ground bears on it

// The joints in gait::Joint order, and one of a frame's leg angles in degrees.
constexpr const char* kJointNames[4] = {"hip", "knee", "ankle", "toe"};
double joint_degrees(const Frame& f, std::size_t side, std::size_t joint) {
  const rig::LegAngles& a = f.pose.legs[side];
  const double v[4] = {a.hip, a.knee, a.ankle, a.toe};
  return rig::degrees(v[joint]);
}

double mean_of(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v)
    s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

double sd_of(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  const double m = mean_of(v);
  double s = 0.0;
  for (double x : v)
    s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}

Curve mean_curve(const std::vector<double>& values,
                 const std::vector<std::pair<std::size_t, std::size_t>>& cycles) {
  Curve c;
  std::vector<std::array<double, kCycleSamples>> all;
  for (const auto& [a, b] : cycles)
    all.push_back(resample_cycle(values, a, b));
  for (int k = 0; k < kCycleSamples; ++k) {
    std::vector<double> at;
    for (const auto& r : all)
      at.push_back(r[static_cast<std::size_t>(k)]);
    c.mean[static_cast<std::size_t>(k)] = mean_of(at);
    c.sd[static_cast<std::size_t>(k)] = sd_of(at);
  }
  return c;
}

// `offset_free`: the curves compared after removing the difference of their means.
JointScore score(const Curve& ours, const Curve& reference, bool offset_free = false) {
  JointScore s;
  double ma = 0.0;
  double mb = 0.0;
  for (int k = 0; k < kCycleSamples; ++k) {
    ma += ours.mean[static_cast<std::size_t>(k)];
    mb += reference.mean[static_cast<std::size_t>(k)];
  }
  ma /= kCycleSamples;
  mb /= kCycleSamples;
  const double shift = offset_free ? ma - mb : 0.0;
  double squared = 0.0;
  int inside = 0;
  for (int k = 0; k < kCycleSamples; ++k) {
    const double a = ours.mean[static_cast<std::size_t>(k)];
    const double b = reference.mean[static_cast<std::size_t>(k)] + shift;
    squared += (a - b) * (a - b);
    if (std::abs(a - b) <= 2.0 * reference.sd[static_cast<std::size_t>(k)]) ++inside;
  }
  double sab = 0.0;
  double saa = 0.0;
  double sbb = 0.0;
  for (int k = 0; k < kCycleSamples; ++k) {
    const double a = ours.mean[static_cast<std::size_t>(k)] - ma;
    const double b = reference.mean[static_cast<std::size_t>(k)] - mb;
    sab += a * b;
    saa += a * a;
    sbb += b * b;
  }
  s.rmse = std::sqrt(squared / kCycleSamples);
  s.pearson = (saa > 0.0 && sbb > 0.0) ? sab / std::sqrt(saa * sbb) : 0.0;
  s.within_2sd = 100.0 * inside / kCycleSamples;
  return s;
}

std::array<const rig::Point*, 3> foot(const rig::LegPoints& p) {
  return {&p.heel, &p.ball, &p.tip};
}

}  // namespace

std::vector<std::size_t> heel_strikes(const Motion& m, rig::Side side) {
  std::vector<std::size_t> strikes;
  for (std::size_t i = 1; i < m.frames.size(); ++i) {
    if (begins_strike(m, i, side, strikes)) strikes.push_back(i);
  }
  return strikes;
}

CurvePeak swing_peak(const Curve& knee) {
  CurvePeak peak;
  for (int k = kCycleSamples / 2; k < kCycleSamples; ++k) {
    const double v = knee.mean[static_cast<std::size_t>(k)];
    if (v > peak.value) peak = {100.0 * k / (kCycleSamples - 1), v};
  }
  return peak;
}

std::array<double, kCycleSamples> resample_cycle(const std::vector<double>& values,
                                                 std::size_t begin, std::size_t end) {
  std::array<double, kCycleSamples> out{};
  const double span = static_cast<double>(end - begin);
  for (int k = 0; k < kCycleSamples; ++k) {
    const double at = static_cast<double>(begin) + span * k / (kCycleSamples - 1);
    const auto i = std::min(static_cast<std::size_t>(at), values.size() - 1);
    const std::size_t j = std::min(i + 1, values.size() - 1);
    const double t = at - static_cast<double>(i);
    out[static_cast<std::size_t>(k)] = values[i] + t * (values[j] - values[i]);
  }
  return out;
}

std::array<JointSmoothness, 4> joint_smoothness(const Motion& m, std::size_t first) {
  const std::size_t n = m.frames.size();
  if (!(m.fps > 0.0)) throw std::invalid_argument("joint smoothness: the frame rate must be > 0");
  if (first >= n || n - first < 4) {
    throw std::invalid_argument("joint smoothness: fewer than 4 frames to measure");
  }
  const double fps = m.fps;
  std::array<JointSmoothness, 4> out{};
  for (std::size_t j = 0; j < out.size(); ++j) {
    double acceleration_squares = 0.0;
    double jerk_squares = 0.0;
    std::size_t accelerations = 0;
    std::size_t jerks = 0;
    for (std::size_t side = 0; side < 2; ++side) {
      auto angle = [&](std::size_t i) { return joint_degrees(m.frames[i], side, j); };
      for (std::size_t i = first + 1; i + 1 < n; ++i) {
        const double acceleration = (angle(i + 1) - 2.0 * angle(i) + angle(i - 1)) * fps * fps;
        acceleration_squares += acceleration * acceleration;
        ++accelerations;
        if (i + 2 < n) {
          const double jerk =
              (angle(i + 2) - 3.0 * angle(i + 1) + 3.0 * angle(i) - angle(i - 1)) * fps * fps * fps;
          jerk_squares += jerk * jerk;
          out[j].max_jerk = std::max(out[j].max_jerk, std::abs(jerk));
          ++jerks;
        }
      }
    }
    out[j].rms_acceleration = std::sqrt(acceleration_squares / static_cast<double>(accelerations));
    out[j].rms_jerk = std::sqrt(jerk_squares / static_cast<double>(jerks));
  }
  return out;
}

double cycle_acceleration_rms(const Curve& c, double cycle_time) {
  constexpr int intervals = kCycleSamples - 1;
  const double dt = cycle_time / intervals;
  auto at = [&](int k) { return c.mean[static_cast<std::size_t>((k + intervals) % intervals)]; };
  double squares = 0.0;
  for (int k = 0; k < intervals; ++k) {
    const double acceleration = (at(k + 1) - 2.0 * at(k) + at(k - 1)) / (dt * dt);
    squares += acceleration * acceleration;
  }
  return std::sqrt(squares / intervals);
}

GaitReport evaluate(const Motion& m, const terrain::Terrain& terrain, const Normative* reference,
                    std::optional<double> commanded_step) {
  const std::size_t n = m.frames.size();
  if (n < 3 || !(m.fps > 0.0)) throw std::invalid_argument("the walk has fewer than 3 frames");
  const double dt = 1.0 / m.fps;
  GaitReport r;

  // Contact quality over the whole walk.
  for (int side = 0; side < 2; ++side) {
    const auto s = static_cast<std::size_t>(side);
    for (std::size_t i = 0; i < n; ++i) {
      const auto now = foot(m.frames[i].points[s]);
      for (std::size_t p = 0; p < 3; ++p) {
        const double gap = now[p]->y - terrain.height(now[p]->x);
        r.max_penetration = std::max(r.max_penetration, -gap);
        if (i == 0) continue;
        const auto before = foot(m.frames[i - 1].points[s]);
        const double gap_before = before[p]->y - terrain.height(before[p]->x);
        if (gap < kOnGround && gap_before < kOnGround) {
          r.max_slip = std::max(r.max_slip, std::abs(now[p]->x - before[p]->x));
        }
      }
    }
    r.min_toe_clearance = std::numeric_limits<double>::infinity();
  }
  for (int side = 0; side < 2; ++side) {
    const auto s = static_cast<std::size_t>(side);
    std::size_t i = 0;
    while (i < n) {
      if (m.frames[i].contact[s]) {
        ++i;
        continue;
      }
      std::size_t j = i;
      while (j < n && !m.frames[j].contact[s])
        ++j;
      if (i > 0 && j < n) {  // a complete swing
        for (std::size_t k = i + (j - i) / 5; k < j - (j - i) / 5; ++k) {
          for (const rig::Point* p : foot(m.frames[k].points[s])) {
            r.min_toe_clearance = std::min(r.min_toe_clearance, p->y - terrain.height(p->x));
          }
        }
      }
      i = j;
    }
  }

  // Heel bounces: within one contact, the heel's rise between two frames on the ground.
  for (int side = 0; side < 2; ++side) {
    const auto s = static_cast<std::size_t>(side);
    double rise = 0.0;
    bool heel_was_down = false;  // in this contact
    for (const Frame& f : m.frames) {
      if (!f.contact[s]) {
        heel_was_down = false;
        continue;
      }
      const rig::Point& heel = f.points[s].heel;
      const double gap = heel.y - terrain.height(heel.x);
      if (gap < kOnGround) {
        if (heel_was_down) r.max_heel_bounce = std::max(r.max_heel_bounce, rise);
        heel_was_down = true;
        rise = 0.0;
      } else {
        rise = std::max(rise, gap);
      }
    }
  }

  // Cycles of the left leg, heel strike to heel strike. A walker's first is its start from
  // standing, left out; a clip is in its stride throughout and may hold a single cycle.
  const std::vector<std::size_t> left = heel_strikes(m, rig::Side::Left);
  const std::vector<std::size_t> right = heel_strikes(m, rig::Side::Right);
  const std::size_t first_cycle = m.captured ? 0 : 1;
  const std::size_t fewest_cycles = m.captured ? 1 : 2;
  std::vector<std::pair<std::size_t, std::size_t>> cycles;
  for (std::size_t k = first_cycle; k + 1 < left.size(); ++k)
    cycles.emplace_back(left[k], left[k + 1]);
  r.cycles = static_cast<int>(cycles.size());
  if (cycles.size() < fewest_cycles) {
    throw std::invalid_argument(m.captured
                                    ? "no complete gait cycle to measure"
                                    : "fewer than two complete gait cycles to measure (found " +
                                          std::to_string(cycles.size()) + " after the first)");
  }
  std::vector<double> durations;
  std::vector<double> stance;
  for (const auto& [a, b] : cycles) {
    durations.push_back(static_cast<double>(b - a) * dt);
    std::size_t down = 0;
    for (std::size_t k = a; k < b; ++k)
      down += m.frames[k].contact[0] ? 1 : 0;
    stance.push_back(100.0 * static_cast<double>(down) / static_cast<double>(b - a));
  }
  r.cycle_time = mean_of(durations);
  r.cycle_time_sd = sd_of(durations);
  r.cadence = 120.0 / r.cycle_time;
  r.stance_percent = mean_of(stance);
  const std::size_t first = cycles.front().first;
  const std::size_t last = cycles.back().second;
  r.speed = (m.frames[last].pose.pelvis.x - m.frames[first].pose.pelvis.x) /
            (static_cast<double>(last - first) * dt);

  // Step lengths between successive heel strikes of alternating feet.
  std::vector<std::pair<std::size_t, int>> strikes;
  for (std::size_t i : left)
    strikes.emplace_back(i, 0);
  for (std::size_t i : right)
    strikes.emplace_back(i, 1);
  std::sort(strikes.begin(), strikes.end());
  std::vector<double> steps;
  for (std::size_t k = 1; k < strikes.size(); ++k) {
    const auto [i0, s0] = strikes[k - 1];
    const auto [i1, s1] = strikes[k];
    if (s0 == s1 || i0 < first) continue;
    steps.push_back(std::abs(m.frames[i1].points[static_cast<std::size_t>(s1)].heel.x -
                             m.frames[i0].points[static_cast<std::size_t>(s0)].heel.x));
  }
  r.step_length = mean_of(steps);
  r.step_length_sd = sd_of(steps);
  if (commanded_step && *commanded_step > 0.0) {
    r.step_error_percent = 100.0 * std::abs(r.step_length - *commanded_step) / *commanded_step;
  }

  // Mean curves of the left leg.
  std::vector<double> thigh(n), knee(n), ankle(n), toe(n), pelvis_y(n);
  for (std::size_t i = 0; i < n; ++i) {
    const rig::Pose& p = m.frames[i].pose;
    thigh[i] = rig::degrees(p.legs[0].hip - p.pelvis_tilt);
    knee[i] = rig::degrees(p.legs[0].knee);
    ankle[i] = rig::degrees(p.legs[0].ankle);
    toe[i] = rig::degrees(p.legs[0].toe);
    pelvis_y[i] = p.pelvis.y;
  }
  r.thigh = mean_curve(thigh, cycles);
  r.knee = mean_curve(knee, cycles);
  r.ankle = mean_curve(ankle, cycles);
  r.toe = mean_curve(toe, cycles);
  const Curve pelvis = mean_curve(pelvis_y, cycles);
  r.pelvis_vertical_range = *std::max_element(pelvis.mean.begin(), pelvis.mean.end()) -
                            *std::min_element(pelvis.mean.begin(), pelvis.mean.end());
  r.thigh_range = *std::max_element(r.thigh.mean.begin(), r.thigh.mean.end()) -
                  *std::min_element(r.thigh.mean.begin(), r.thigh.mean.end());
  {
    constexpr std::size_t kHalf = kCycleSamples / 2;
    r.thigh_overshoot =
        *std::max_element(r.thigh.mean.begin() + kHalf, r.thigh.mean.end()) - r.thigh.mean.back();
    r.knee_loading_peak = *std::max_element(r.knee.mean.begin(), r.knee.mean.begin() + 16);
    r.ankle_push_off = *std::min_element(r.ankle.mean.begin() + 20, r.ankle.mean.begin() + 41);
  }
  // Body travel: the pelvis's speed over kTravelWindow, against each cycle's mean.
  {
    const auto half =
        static_cast<std::size_t>(std::max(1.0, std::round(0.5 * kTravelWindow * m.fps)));
    const double span = 2.0 * static_cast<double>(half) * dt;
    r.pelvis_speed_ratio_min = std::numeric_limits<double>::infinity();
    r.pelvis_speed_ratio_max = -std::numeric_limits<double>::infinity();
    for (const auto& [a, b] : cycles) {
      const double mean_speed = (m.frames[b].pose.pelvis.x - m.frames[a].pose.pelvis.x) /
                                (static_cast<double>(b - a) * dt);
      for (std::size_t k = a; k < b; ++k) {
        if (k < half || k + half >= n) continue;
        const rig::Point& before = m.frames[k - half].pose.pelvis;
        const rig::Point& after = m.frames[k + half].pose.pelvis;
        const double ratio = (after.x - before.x) / span / mean_speed;
        r.pelvis_speed_ratio_min = std::min(r.pelvis_speed_ratio_min, ratio);
        r.pelvis_speed_ratio_max = std::max(r.pelvis_speed_ratio_max, ratio);
        r.pelvis_rise_speed = std::max(r.pelvis_rise_speed, (after.y - before.y) / span);
      }
    }
  }
  const CurvePeak knee_peak = swing_peak(r.knee);
  r.knee_peak = knee_peak.value;
  r.knee_peak_percent = knee_peak.percent;
  if (reference) {
    auto scored = [&](const Curve& walk, const Curve& people, bool offset_free = false) {
      JointScore s = score(walk, people, offset_free);
      s.acceleration_rms = cycle_acceleration_rms(walk, r.cycle_time);
      s.reference_acceleration_rms = cycle_acceleration_rms(people, r.cycle_time);
      return s;
    };
    r.thigh_score = scored(r.thigh, reference->thigh);
    r.knee_score = scored(r.knee, reference->knee);
    r.ankle_score = scored(r.ankle, reference->ankle, reference->ankle_offset_unknown);
  }

  // Smoothness: how much a joint's velocity changes from one frame to the next, at phase
  // switches against everywhere.
  std::vector<double> changes;
  for (int side = 0; side < 2; ++side) {
    const auto s = static_cast<std::size_t>(side);
    for (int j = 0; j < 4; ++j) {
      auto angle = [&](std::size_t i) {
        return joint_degrees(m.frames[i], s, static_cast<std::size_t>(j));
      };
      for (std::size_t i = 2; i < n; ++i) {
        const double v1 = (angle(i) - angle(i - 1)) / dt;
        const double v0 = (angle(i - 1) - angle(i - 2)) / dt;
        const double change = std::abs(v1 - v0);
        changes.push_back(change);
        const bool switched = m.frames[i - 1].contact[s] != m.frames[i - 2].contact[s] ||
                              m.frames[i].contact[s] != m.frames[i - 1].contact[s];
        if (switched && i >= first) r.max_velocity_jump = std::max(r.max_velocity_jump, change);
      }
    }
  }
  std::sort(changes.begin(), changes.end());
  r.typical_velocity_change =
      changes[static_cast<std::size_t>(0.99 * static_cast<double>(changes.size() - 1))];
  r.smoothness = joint_smoothness(m, first);
  return r;
}

std::vector<std::string> missed_contact_bounds(const GaitReport& r) {
  std::vector<std::string> missed;
  char line[160];
  auto check = [&](bool met, const char* format, double value) {
    if (met) return;
    std::snprintf(line, sizeof line, format, value);
    missed.emplace_back(line);
  };
  check(r.max_slip < 0.001, "foot slip %.2f mm a frame (bound 1 mm)", r.max_slip * 1000.0);
  check(r.max_penetration < 0.001, "penetration %.2f mm (bound 1 mm)", r.max_penetration * 1000.0);
  check(r.min_toe_clearance >= 0.005, "toe clearance %.2f mm (bound 5 mm)",
        r.min_toe_clearance * 1000.0);
  if (r.step_error_percent) {
    check(*r.step_error_percent <= 3.0, "step error %.2f %% (bound 3 %%)", *r.step_error_percent);
  }
  return missed;
}

std::string to_text(const GaitReport& r) {
  std::string out;
  char line[200];
  auto row = [&](const char* name, double value, const char* unit) {
    std::snprintf(line, sizeof line, "%-28s %10.3f %s\n", name, value, unit);
    out += line;
  };
  auto note = [&](const char* name, const char* text) {
    std::snprintf(line, sizeof line, "%-28s %s\n", name, text);
    out += line;
  };
  row("cycles measured", r.cycles, "");
  row("cycle time", r.cycle_time, "s");
  row("cycle time sd", r.cycle_time_sd, "s");
  row("cadence", r.cadence, "steps/min");
  row("speed", r.speed, "m/s");
  row("stance", r.stance_percent, "% of cycle");
  row("step length", r.step_length, "m");
  row("step length sd", r.step_length_sd, "m");
  if (r.step_error_percent) {
    row("step error", *r.step_error_percent, "% of command");
  } else {
    note("step error", "(no commanded step given)");
  }
  row("peak swing knee flexion", r.knee_peak, "deg");
  row("  at", r.knee_peak_percent, "% of cycle");
  row("thigh range", r.thigh_range, "deg");
  row("pelvis vertical range", r.pelvis_vertical_range * 1000.0, "mm");
  row("pelvis speed, lowest", r.pelvis_speed_ratio_min, "of the cycle's mean");
  row("pelvis speed, highest", r.pelvis_speed_ratio_max, "of the cycle's mean");
  row("pelvis rising, fastest", r.pelvis_rise_speed, "m/s");
  row("thigh overshoot", r.thigh_overshoot, "deg past contact");
  row("knee in loading response", r.knee_loading_peak, "deg");
  row("ankle at push off", r.ankle_push_off, "deg");
  row("max foot slip in contact", r.max_slip * 1000.0, "mm per frame");
  row("max penetration", r.max_penetration * 1000.0, "mm");
  row("min toe clearance, swing", r.min_toe_clearance * 1000.0, "mm");
  row("max heel bounce in stance", r.max_heel_bounce * 1000.0, "mm");
  row("max velocity jump at switch", r.max_velocity_jump, "deg/s per frame");
  row("velocity change, 99th pct", r.typical_velocity_change, "deg/s per frame");
  for (std::size_t j = 0; j < 4; ++j) {
    const JointSmoothness& s = r.smoothness[j];
    std::snprintf(line, sizeof line,
                  "%-6s acceleration RMS %8.0f deg/s^2   jerk RMS %9.0f, max %9.0f deg/s^3\n",
                  kJointNames[j], s.rms_acceleration, s.rms_jerk, s.max_jerk);
    out += line;
  }
  auto joint = [&](const char* name, const std::optional<JointScore>& s) {
    if (!s) return;
    std::snprintf(line, sizeof line,
                  "%-28s %10.3f deg   r %.3f   in 2 SD %.0f %%   acceleration RMS %.0f (people "
                  "%.0f) deg/s^2\n",
                  name, s->rmse, s->pearson, s->within_2sd, s->acceleration_rms,
                  s->reference_acceleration_rms);
    out += line;
  };
  joint("thigh RMSE", r.thigh_score);
  joint("knee RMSE", r.knee_score);
  joint("ankle RMSE", r.ankle_score);
  return out;
}

std::string to_json(const GaitReport& r) {
  nlohmann::ordered_json j;
  j["cycles"] = r.cycles;
  j["cycle_time_s"] = r.cycle_time;
  j["cycle_time_sd_s"] = r.cycle_time_sd;
  j["cadence_steps_per_min"] = r.cadence;
  j["speed_m_per_s"] = r.speed;
  j["stance_percent"] = r.stance_percent;
  j["step_length_m"] = r.step_length;
  j["step_length_sd_m"] = r.step_length_sd;
  j["step_error_percent"] = r.step_error_percent ? nlohmann::ordered_json(*r.step_error_percent)
                                                 : nlohmann::ordered_json(nullptr);
  j["knee_peak_deg"] = r.knee_peak;
  j["knee_peak_percent"] = r.knee_peak_percent;
  j["thigh_range_deg"] = r.thigh_range;
  j["pelvis_vertical_range_m"] = r.pelvis_vertical_range;
  j["pelvis_speed_ratio_min"] = r.pelvis_speed_ratio_min;
  j["pelvis_speed_ratio_max"] = r.pelvis_speed_ratio_max;
  j["pelvis_rise_speed_m_per_s"] = r.pelvis_rise_speed;
  j["thigh_overshoot_deg"] = r.thigh_overshoot;
  j["knee_loading_peak_deg"] = r.knee_loading_peak;
  j["ankle_push_off_deg"] = r.ankle_push_off;
  j["max_slip_m_per_frame"] = r.max_slip;
  j["max_penetration_m"] = r.max_penetration;
  j["min_toe_clearance_m"] = r.min_toe_clearance;
  j["max_heel_bounce_m"] = r.max_heel_bounce;
  j["max_velocity_jump_deg_per_s"] = r.max_velocity_jump;
  j["typical_velocity_change_deg_per_s"] = r.typical_velocity_change;
  for (std::size_t k = 0; k < 4; ++k) {
    const JointSmoothness& s = r.smoothness[k];
    j["smoothness"][kJointNames[k]] = {{"rms_acceleration_deg_per_s2", s.rms_acceleration},
                                       {"rms_jerk_deg_per_s3", s.rms_jerk},
                                       {"max_jerk_deg_per_s3", s.max_jerk}};
  }
  auto joint = [&](const char* name, const std::optional<JointScore>& s) {
    if (s)
      j[name] = {{"rmse_deg", s->rmse},
                 {"pearson_r", s->pearson},
                 {"within_2sd_percent", s->within_2sd},
                 {"acceleration_rms_deg_per_s2", s->acceleration_rms},
                 {"reference_acceleration_rms_deg_per_s2", s->reference_acceleration_rms}};
  };
  joint("thigh", r.thigh_score);
  joint("knee", r.knee_score);
  joint("ankle", r.ankle_score);
  auto curve = [](const Curve& c) {
    return nlohmann::json(std::vector<double>(c.mean.begin(), c.mean.end()));
  };
  j["mean_cycle"] = {{"thigh", curve(r.thigh)},
                     {"knee", curve(r.knee)},
                     {"ankle", curve(r.ankle)},
                     {"toe", curve(r.toe)}};
  return j.dump(2);
}

}  // namespace fuzzygait::eval

#include "fuzzygait/plot/walk_plots.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace fuzzygait::plot {
namespace {

using svg::Color;
using svg::Point;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::string_view kDegree = "\xC2\xB0";
constexpr std::string_view kPlusMinus = "\xC2\xB1";
constexpr std::string_view kDash = "\xE2\x80\x93";
constexpr std::string_view kLeftArrow = "\xE2\x86\x90";
constexpr std::string_view kRightArrow = "\xE2\x86\x92";

// Colours: the two legs apart at a glance (Okabe & Ito blue and vermillion), the body neutral.
const Color kLeftLeg = svg::palette_color(0);
const Color kRightLeg = svg::palette_color(1);
const Color kBody{64, 64, 64};
const Color kReference{120, 120, 120};
const Color kMuted{100, 100, 100};
const Color kGroundLine{110, 100, 88};
const Color kGroundFill{236, 231, 222};
const Color kGroundHatch{170, 160, 146};

constexpr double kOnGround = 0.003;  // m: a foot point this close to the ground bears on it

// Fixed decimals ("0.90", not "0.9"), for figures read side by side.
std::string fixed(double value, int decimals) {
  std::array<char, 64> buffer{};
  std::snprintf(buffer.data(), buffer.size(), "%.*f", decimals, value);
  std::string text(buffer.data());
  if (text.find_first_not_of("-0.") == std::string::npos && text[0] == '-') text.erase(0, 1);
  return text;
}

std::string degrees_text(double value) {
  return fixed(value, 1) + std::string(kDegree);
}

// ---------------------------------------------------------------------------------------------
// Gait curves.

std::array<double, eval::kCycleSamples> cycle_percent() {
  std::array<double, eval::kCycleSamples> x{};
  for (int k = 0; k < eval::kCycleSamples; ++k)
    x[static_cast<std::size_t>(k)] = 100.0 * k / (eval::kCycleSamples - 1);
  return x;
}

const eval::Curve& curve_of(const eval::GaitReport& report, GaitJoint joint) {
  switch (joint) {
    case GaitJoint::Thigh:
      return report.thigh;
    case GaitJoint::Knee:
      return report.knee;
    case GaitJoint::Ankle:
      return report.ankle;
    case GaitJoint::Toe:
      return report.toe;
  }
  return report.thigh;
}

const eval::Curve* reference_of(const eval::Normative* reference, GaitJoint joint) {
  if (!reference) return nullptr;
  switch (joint) {
    case GaitJoint::Thigh:
      return &reference->thigh;
    case GaitJoint::Knee:
      return &reference->knee;
    case GaitJoint::Ankle:
      return &reference->ankle;
    case GaitJoint::Toe:
      return nullptr;  // gait labs rarely report the MTP joint: no normative curve
  }
  return nullptr;
}

// The reference drawn for a joint beside `walk`: an ankle whose zero is the source's own
// (eval::Normative::ankle_offset_unknown) is moved onto the walk's mean, as it is scored (shape
// only); `moved` says so. None without a reference curve.
std::optional<eval::Curve> shown_reference(const eval::Normative* reference, GaitJoint joint,
                                           const eval::Curve& walk, bool& moved) {
  const eval::Curve* normative = reference_of(reference, joint);
  if (!normative) return std::nullopt;
  eval::Curve shown = *normative;
  if (joint == GaitJoint::Ankle && reference->ankle_offset_unknown) {
    double difference = 0.0;
    for (std::size_t k = 0; k < shown.mean.size(); ++k)
      difference += walk.mean[k] - shown.mean[k];
    difference /= static_cast<double>(shown.mean.size());
    for (double& v : shown.mean)
      v += difference;
    moved = true;
  }
  return shown;
}

constexpr const char* kMovedAnkleNote =
    " The reference's ankle zero is its own (Bovi et al. 2011): its curve is moved onto the walk's "
    "mean, and the ankle is scored by its shape.";

const std::optional<eval::JointScore>& score_of(const eval::GaitReport& report, GaitJoint joint) {
  static const std::optional<eval::JointScore> kNone;
  switch (joint) {
    case GaitJoint::Thigh:
      return report.thigh_score;
    case GaitJoint::Knee:
      return report.knee_score;
    case GaitJoint::Ankle:
      return report.ankle_score;
    case GaitJoint::Toe:
      return kNone;
  }
  return kNone;
}

std::string joint_title(GaitJoint joint) {
  switch (joint) {
    case GaitJoint::Thigh:
      return "Hip: thigh inclination (flexion " + std::string(kDash) + " pelvic tilt)";
    case GaitJoint::Knee:
      return "Knee flexion";
    case GaitJoint::Ankle:
      return "Ankle dorsiflexion";
    case GaitJoint::Toe:
      return "Toe (MTP) extension";
  }
  return {};
}

std::string joint_axis(GaitJoint joint) {
  switch (joint) {
    case GaitJoint::Thigh:
      return "forward (" + std::string(kDegree) + ")";
    case GaitJoint::Knee:
      return "flexion (" + std::string(kDegree) + ")";
    case GaitJoint::Ankle:
      return "dorsiflexion (" + std::string(kDegree) + ")";
    case GaitJoint::Toe:
      return "extension (" + std::string(kDegree) + ")";
  }
  return {};
}

// "schwartz2008_free" reads "Schwartz et al. 2008, free speed"; other names (paths) as given.
std::string reference_title(const eval::Normative& reference) {
  static constexpr std::string_view kSchwartz = "schwartz2008_";
  const std::string& name = reference.name;
  if (name.rfind(kSchwartz, 0) != 0) return name;
  std::string speed = name.substr(kSchwartz.size());
  if (speed.rfind("very", 0) == 0) speed.insert(4, " ");
  return "Schwartz et al. 2008, " + speed + " speed";
}

std::string score_text(const eval::JointScore& score) {
  return "RMSE " + degrees_text(score.rmse) + ", r " + fixed(score.pearson, 2);
}

struct ValueRange {
  double low = std::numeric_limits<double>::infinity();
  double high = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    low = std::min(low, v);
    high = std::max(high, v);
  }
  double span() const { return std::max(high - low, 1.0); }
};

void add_curve(ValueRange& range, const eval::Curve& curve, double sds) {
  for (std::size_t k = 0; k < curve.mean.size(); ++k) {
    range.add(curve.mean[k] - sds * curve.sd[k]);
    range.add(curve.mean[k] + sds * curve.sd[k]);
  }
}

void mean_band(svg::Panel& panel, const eval::Curve& curve, double sds, svg::FillStyle style,
               std::string label) {
  const auto x = cycle_percent();
  std::array<double, eval::kCycleSamples> lower{};
  std::array<double, eval::kCycleSamples> upper{};
  for (std::size_t k = 0; k < lower.size(); ++k) {
    lower[k] = curve.mean[k] - sds * curve.sd[k];
    upper[k] = curve.mean[k] + sds * curve.sd[k];
  }
  panel.band(x, lower, upper, style, std::move(label));
}

void reference_curve(svg::Panel& panel, const eval::Curve& reference) {
  mean_band(panel, reference, 2.0, {.color = kReference, .opacity = 0.2},
            "reference " + std::string(kPlusMinus) + " 2 SD");
  panel.line(cycle_percent(), reference.mean,
             {.color = kReference, .width = 1.6, .dash = svg::Dash::Dashed}, "reference mean");
}

// A cycle panel's frame: x over 0-100 %, y over the values with room above for captions.
void cycle_axes(svg::Panel& panel, GaitJoint joint, const ValueRange& range) {
  panel.title(joint_title(joint))
      .x_label("gait cycle (%)")
      .y_label(joint_axis(joint))
      .x_range(0.0, 100.0)
      .x_ticks({0, 20, 40, 60, 80, 100})
      .y_range(range.low - 0.06 * range.span(), range.high + 0.2 * range.span());
}

std::string cycles_text(const eval::GaitReport& report) {
  return std::to_string(report.cycles) + (report.cycles == 1 ? " cycle" : " cycles");
}

// ---------------------------------------------------------------------------------------------
// The walker's body: sampled poses, stick figures, ground.

rig::Point lerp(rig::Point a, rig::Point b, double t) {
  return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
}

struct Body {
  rig::Point pelvis;
  double pelvis_tilt = 0.0;
  std::array<rig::LegPoints, 2> legs;
  std::array<bool, 2> contact{};
};

Body body_at(const eval::Frame& frame) {
  return {frame.pose.pelvis, frame.pose.pelvis_tilt, frame.points, frame.contact};
}

// The body at any time inside the motion, points interpolated between frames.
Body body_at(const eval::Motion& motion, double time) {
  const double position = std::clamp((time - motion.frames.front().time) * motion.fps, 0.0,
                                     static_cast<double>(motion.frames.size() - 1));
  const auto i = static_cast<std::size_t>(position);
  const std::size_t j = std::min(i + 1, motion.frames.size() - 1);
  const double t = position - static_cast<double>(i);
  const eval::Frame& a = motion.frames[i];
  const eval::Frame& b = motion.frames[j];
  Body body = body_at(t < 0.5 ? a : b);
  body.pelvis = lerp(a.pose.pelvis, b.pose.pelvis, t);
  body.pelvis_tilt = a.pose.pelvis_tilt + t * (b.pose.pelvis_tilt - a.pose.pelvis_tilt);
  for (std::size_t side = 0; side < 2; ++side) {
    const rig::LegPoints& p = a.points[side];
    const rig::LegPoints& q = b.points[side];
    body.legs[side] = {lerp(p.hip, q.hip, t),   lerp(p.knee, q.knee, t), lerp(p.ankle, q.ankle, t),
                       lerp(p.heel, q.heel, t), lerp(p.ball, q.ball, t), lerp(p.tip, q.tip, t)};
  }
  return body;
}

// Heights as fractions of stature (Drillis & Contini, tabulated by Winter 2009, Fig. 4.1), the
// proportions rig::segments_from_stature uses for the legs.
constexpr double kHipHeight = 0.530;
constexpr double kShoulderHeight = 0.818;
constexpr double kChinHeight = 0.870;
constexpr double kHeadRadius = 0.065;
// The trunk stands upright at the anterior pelvic tilt adults walk with (about 11 degrees in
// Schwartz et al. 2008); a tilt beyond it leans the trunk forward.
constexpr double kUprightPelvisTilt = 11.0 * std::numbers::pi / 180.0;
constexpr int kHeadSides = 20;

struct StickFigure {
  std::array<std::vector<Point>, 2> legs;  // hip, knee, ankle, heel, ball, tip, ball, ankle
  std::vector<Point> trunk;                // hip joint, shoulder
  std::vector<Point> neck;                 // shoulder, chin
  std::vector<Point> head;                 // a closed ring
};

Point moved(rig::Point p, Point shift) {
  return {p.x + shift.x, p.y + shift.y};
}

StickFigure stick_figure(const Body& body, const rig::Segments& segments, Point shift) {
  StickFigure figure;
  for (std::size_t side = 0; side < 2; ++side) {
    const rig::LegPoints& p = body.legs[side];
    // Ankle, heel, ball and back closes the foot; the toes stick out from the ball.
    for (const rig::Point& q : {p.hip, p.knee, p.ankle, p.heel, p.ball, p.tip, p.ball, p.ankle})
      figure.legs[side].push_back(moved(q, shift));
  }
  const double stature = segments.leg_length() / kHipHeight;
  const double lean = body.pelvis_tilt - kUprightPelvisTilt;
  const Point up{std::sin(lean), std::cos(lean)};
  const Point hip = moved(body.pelvis, shift);
  const auto above = [&](double height) {
    const double d = (height - kHipHeight) * stature;
    return Point{hip.x + d * up.x, hip.y + d * up.y};
  };
  figure.trunk = {hip, above(kShoulderHeight)};
  figure.neck = {figure.trunk.back(), above(kChinHeight)};
  const Point centre = above(kChinHeight + kHeadRadius);
  const double radius = kHeadRadius * stature;
  for (int k = 0; k <= kHeadSides; ++k) {
    const double a = 2.0 * std::numbers::pi * k / kHeadSides;
    figure.head.push_back({centre.x + radius * std::sin(a), centre.y + radius * std::cos(a)});
  }
  return figure;
}

struct FigureStyle {
  double width = 2.6;
  double opacity = 1.0;
};

// Far leg first (the left: the walker goes right, so its right side faces the viewer), then the
// body, then the near leg.
void draw_figure(svg::Panel& panel, const StickFigure& figure, FigureStyle style) {
  panel.line(figure.legs[0], {.color = kLeftLeg, .width = style.width, .opacity = style.opacity});
  panel.line(figure.trunk, {.color = kBody, .width = 2.2 * style.width, .opacity = style.opacity});
  panel.line(figure.neck, {.color = kBody, .width = style.width, .opacity = style.opacity});
  panel.line(figure.head, {.color = kBody, .width = style.width, .opacity = style.opacity});
  panel.line(figure.legs[1], {.color = kRightLeg, .width = style.width, .opacity = style.opacity});
}

double ground_gap(const terrain::Terrain& terrain, rig::Point p) {
  return p.y - terrain.height(p.x);
}

// Dots on the ground under the foot points that bear on it, in the leg's colour.
void draw_contacts(svg::Panel& panel, const terrain::Terrain& terrain, const Body& body,
                   Point shift, double opacity = 1.0) {
  for (std::size_t side = 0; side < 2; ++side) {
    if (!body.contact[side]) continue;
    const rig::LegPoints& p = body.legs[side];
    std::vector<Point> dots;
    for (const rig::Point& q : {p.heel, p.ball, p.tip}) {
      if (ground_gap(terrain, q) < kOnGround) {
        dots.push_back(moved({q.x, terrain.height(q.x)}, shift));
      }
    }
    if (dots.empty()) continue;
    panel.line(dots, {.color = side == 0 ? kLeftLeg : kRightLeg,
                      .width = 0,
                      .marker = svg::Marker::Circle,
                      .marker_size = 6.5,
                      .opacity = opacity});
  }
}

double lowest_ground(const terrain::Terrain& terrain, double x0, double x1) {
  double lowest = std::numeric_limits<double>::infinity();
  for (const rig::Point& p : terrain.profile(x0, x1))
    lowest = std::min(lowest, p.y);
  return lowest;
}

// The lowest and highest ground between x0 and x1.
std::pair<double, double> ground_span(const terrain::Terrain& terrain, double x0, double x1) {
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (const rig::Point& p : terrain.profile(x0, x1)) {
    low = std::min(low, p.y);
    high = std::max(high, p.y);
  }
  return {low, high};
}

// The ground between x0 and x1, moved by shift, filled down to `floor` under its surface line,
// and optionally hatched every `hatch` metres (it shows the ground moving under a following
// view).
void draw_ground(svg::Panel& panel, const terrain::Terrain& terrain, double x0, double x1,
                 Point shift, double floor, double hatch = 0.0) {
  std::vector<Point> surface;
  for (const rig::Point& p : terrain.profile(x0, x1))
    surface.push_back(moved(p, shift));
  if (surface.size() < 2) return;
  std::vector<Point> fill = surface;
  fill.push_back({surface.back().x, floor});
  fill.push_back({surface.front().x, floor});
  panel.polygon(fill, {.color = kGroundFill, .opacity = 1.0});
  if (hatch > 0.0) {
    std::vector<Point> strokes;
    const double length = std::min(0.6 * (lowest_ground(terrain, x0, x1) + shift.y - floor), 0.06);
    for (double x = std::ceil(x0 / hatch) * hatch; x <= x1; x += hatch) {
      const double y = terrain.height(x) + shift.y;
      strokes.push_back({x + shift.x, y});
      strokes.push_back({x + shift.x - 0.7 * length, y - length});
      strokes.push_back({kNaN, kNaN});
    }
    panel.line(strokes, {.color = kGroundHatch, .width = 1.2});
  }
  panel.line(surface, {.color = kGroundLine, .width = 1.6});
}

void check_motion(const eval::Motion& motion) {
  if (motion.frames.size() < 2 || !(motion.fps > 0.0) || !std::isfinite(motion.fps)) {
    throw std::invalid_argument("the walk needs at least two frames and a positive frame rate");
  }
  rig::validate(motion.segments);
}

// The frames [begin, end] of left stride `index`; throws when the walk has no such stride.
std::pair<std::size_t, std::size_t> stride_frames(const eval::Motion& motion, int index,
                                                  int count) {
  const std::vector<std::size_t> strikes = eval::heel_strikes(motion, rig::Side::Left);
  const auto last = static_cast<std::size_t>(index + count);
  if (index < 0 || count < 1 || last >= strikes.size()) {
    const std::size_t strides = strikes.empty() ? 0 : strikes.size() - 1;
    throw std::invalid_argument(
        "the walk has " + std::to_string(strides) + " complete left strides; stride " +
        std::to_string(index) +
        (count > 1 ? " and the " + std::to_string(count - 1) + " after it need" : " needs") +
        " more (walk longer)");
  }
  return {strikes[static_cast<std::size_t>(index)], strikes[last]};
}

// The left leg's gait phase (Perry's names) at frame i of the stride [begin, end).
std::string gait_phase(const eval::Motion& motion, const terrain::Terrain& terrain,
                       std::size_t begin, std::size_t end, std::size_t i) {
  const auto& frames = motion.frames;
  if (i == begin) return "initial contact";
  std::size_t toe_off = begin;
  while (toe_off < end && frames[toe_off].contact[0])
    ++toe_off;
  if (i < toe_off) {
    if (frames[i].contact[1]) {
      // Double support: loading response before the right foot lifts, pre-swing after.
      bool right_lifted_before = false;
      for (std::size_t k = begin; k < i; ++k)
        right_lifted_before = right_lifted_before || !frames[k].contact[1];
      return right_lifted_before ? "pre-swing" : "loading response";
    }
    return ground_gap(terrain, frames[i].points[0].heel) < kOnGround ? "mid stance"
                                                                     : "terminal stance";
  }
  const double share = static_cast<double>(i - toe_off) /
                       static_cast<double>(std::max<std::size_t>(1, end - toe_off));
  if (share < 1.0 / 3.0) return "initial swing";
  if (share < 2.0 / 3.0) return "mid swing";
  return "terminal swing";
}

// Contact runs [first, last] of one foot inside frames [begin, end].
std::vector<std::pair<std::size_t, std::size_t>> contact_runs(const eval::Motion& motion,
                                                              std::size_t side, std::size_t begin,
                                                              std::size_t end) {
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  std::size_t i = begin;
  while (i <= end) {
    if (!motion.frames[i].contact[side]) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 <= end && motion.frames[j + 1].contact[side])
      ++j;
    runs.emplace_back(i, j);
    i = j + 1;
  }
  return runs;
}

// Footprints: where each foot lay flattest during each of its contacts, as a thick mark on the
// ground from heel to toe tip.
void draw_footprints(svg::Panel& panel, const eval::Motion& motion, const terrain::Terrain& terrain,
                     std::size_t begin, std::size_t end) {
  for (std::size_t side = 0; side < 2; ++side) {
    for (const auto& [first, last] : contact_runs(motion, side, begin, end)) {
      std::size_t flattest = first;
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t k = first; k <= last; ++k) {
        const rig::LegPoints& p = motion.frames[k].points[side];
        const double lift =
            std::abs(ground_gap(terrain, p.heel)) + std::abs(ground_gap(terrain, p.ball));
        if (lift < best) {
          best = lift;
          flattest = k;
        }
      }
      const rig::LegPoints& p = motion.frames[flattest].points[side];
      std::vector<Point> print;
      for (const double x : {p.heel.x, p.ball.x, p.tip.x})
        print.push_back({x, terrain.height(x)});
      panel.line(print, {.color = side == 0 ? kLeftLeg : kRightLeg, .width = 5, .opacity = 0.3});
    }
  }
}

struct Extent {
  double left = std::numeric_limits<double>::infinity();
  double right = -std::numeric_limits<double>::infinity();
  double bottom = std::numeric_limits<double>::infinity();
  double top = -std::numeric_limits<double>::infinity();
  void add(const std::vector<Point>& points) {
    for (const Point& p : points) {
      left = std::min(left, p.x);
      right = std::max(right, p.x);
      bottom = std::min(bottom, p.y);
      top = std::max(top, p.y);
    }
  }
  void add(const StickFigure& figure) {
    add(figure.legs[0]);
    add(figure.legs[1]);
    add(figure.trunk);
    add(figure.neck);
    add(figure.head);
  }
};

std::string percent_text(double percent) {
  return svg::format_number(percent, 0) + " %";
}

}  // namespace

// ---------------------------------------------------------------------------------------------

svg::Figure plot_gait_curves(const eval::GaitReport& report, const eval::Normative* reference,
                             const GaitCurvesOptions& options) {
  svg::Figure figure(options.title + ": step " + fixed(report.step_length, 2) + " m, cadence " +
                     fixed(report.cadence, 0) + " steps/min, speed " + fixed(report.speed, 2) +
                     " m/s, stance " + fixed(report.stance_percent, 0) + " %");
  std::string subtitle = "Left leg, mean of " + cycles_text(report) + " (" +
                         fixed(report.cycle_time, 2) + " s each) from heel strike to heel strike";
  if (options.cycle_sd)
    subtitle += ", light band " + std::string(kPlusMinus) + " 1 SD between cycles";
  subtitle += reference ? "; grey: " + reference_title(*reference) + ", mean " +
                              std::string(kPlusMinus) + " 2 SD."
                        : ".";
  figure.subtitle(subtitle).columns(2).panel_size(540, 320);

  const Color walk = svg::palette_color(0);
  const double toe_off = report.stance_percent;
  bool ankle_moved = false;
  for (const GaitJoint joint :
       {GaitJoint::Thigh, GaitJoint::Knee, GaitJoint::Ankle, GaitJoint::Toe}) {
    const eval::Curve& curve = curve_of(report, joint);
    const std::optional<eval::Curve> normative =
        shown_reference(reference, joint, curve, ankle_moved);
    ValueRange range;
    add_curve(range, curve, options.cycle_sd ? 1.0 : 0.0);
    if (normative) add_curve(range, *normative, 2.0);

    svg::Panel& panel = figure.add_panel();
    cycle_axes(panel, joint, range);
    if (normative) reference_curve(panel, *normative);
    if (options.cycle_sd) mean_band(panel, curve, 1.0, {.color = walk, .opacity = 0.18}, {});
    const std::optional<eval::JointScore>& score = score_of(report, joint);
    panel.line(cycle_percent(), curve.mean, {.color = walk, .width = 2.4},
               score ? "walk: " + score_text(*score) : "walk");

    // Stance and swing, parted at toe off; labels so that the legend keeps off them.
    panel.vertical_line(toe_off, {.color = kMuted, .width = 1.1, .dash = svg::Dash::Dotted});
    const double caption_y = range.high + 0.13 * range.span();
    panel.label(toe_off, caption_y, std::string(kLeftArrow) + " stance " + percent_text(toe_off),
                {.size = 10.5, .color = kMuted, .anchor = svg::Anchor::End, .dx = -5});
    panel.label(toe_off, caption_y, "swing " + std::string(kRightArrow),
                {.size = 10.5, .color = kMuted, .anchor = svg::Anchor::Start, .dx = 5});

    if (joint == GaitJoint::Knee) {
      const auto [at, peak] = eval::swing_peak(curve);
      const Point mark[] = {{at, peak}};
      panel.line(mark,
                 {.color = walk, .width = 0, .marker = svg::Marker::Circle, .marker_size = 7.5});
      std::string text =
          "peak " + fixed(peak, 0) + std::string(kDegree) + " at " + percent_text(at);
      if (normative) {
        const auto [ref_at, ref_peak] = eval::swing_peak(*normative);
        const Point ref_mark[] = {{ref_at, ref_peak}};
        panel.line(
            ref_mark,
            {.color = kReference, .width = 0, .marker = svg::Marker::Circle, .marker_size = 6.5});
        text += " (reference " + fixed(ref_peak, 0) + std::string(kDegree) + " at " +
                percent_text(ref_at) + ")";
      }
      panel.label(at, peak, text,
                  {.size = 10, .color = walk, .anchor = svg::Anchor::Middle, .dy = -13});
    }
  }
  std::string note =
      "The hip is drawn as the thigh's inclination to the vertical (hip flexion minus pelvic "
      "tilt), which is what is compared, so the pelvis convention does not matter.";
  if (reference) {
    note +=
        " RMSE and Pearson r compare the mean curves; the toe (ball of the foot) has no "
        "reference curve.";
  }
  if (ankle_moved) note += kMovedAnkleNote;
  figure.note(note);
  return figure;
}

svg::Figure plot_curve_comparison(std::span<const LabelledReport> walks,
                                  const eval::Normative* reference,
                                  const CurveComparisonOptions& options) {
  if (walks.empty()) throw std::invalid_argument("curve comparison: no walks to draw");
  if (options.joints.empty()) throw std::invalid_argument("curve comparison: no joints to draw");
  svg::Figure figure(options.title);
  std::string subtitle =
      "Left leg, each walk the mean of its cycles from heel strike to heel "
      "strike; ticks at the bottom mark each walk's toe off";
  subtitle += reference ? "; grey: " + reference_title(*reference) + ", mean " +
                              std::string(kPlusMinus) + " 2 SD."
                        : ".";
  // Beyond a few walks the legends would hide the curves: wide panels, legends beside them.
  const bool many = walks.size() > 3;
  figure.subtitle(subtitle);
  if (many) {
    figure.columns(1).panel_size(1100, 290);
  } else {
    figure.columns(options.joints.size() == 1 ? 1 : 2).panel_size(540, 320);
  }
  const auto colour = [&](std::size_t i) {
    if (!options.graded) return svg::palette_color(i);
    // Viridis without its pale yellow end, which is too light for lines on white.
    const double t =
        walks.size() == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(walks.size() - 1);
    return svg::viridis(0.85 * t);
  };
  bool ankle_moved = false;
  for (const GaitJoint joint : options.joints) {
    // (an ankle of unknown zero moved onto the first walk's mean)
    const std::optional<eval::Curve> normative =
        walks.empty()
            ? std::nullopt
            : shown_reference(reference, joint, curve_of(walks.front().report, joint), ankle_moved);
    ValueRange range;
    for (const LabelledReport& walk : walks)
      add_curve(range, curve_of(walk.report, joint), 0.0);
    if (normative) add_curve(range, *normative, 2.0);

    svg::Panel& panel = figure.add_panel();
    cycle_axes(panel, joint, range);
    if (many) panel.legend(svg::LegendPlace::Right);
    if (normative) reference_curve(panel, *normative);
    const double tick_low = range.low - 0.06 * range.span();
    const double tick_high = range.low - 0.01 * range.span();
    for (std::size_t i = 0; i < walks.size(); ++i) {
      const std::optional<eval::JointScore>& score = score_of(walks[i].report, joint);
      panel.line(cycle_percent(), curve_of(walks[i].report, joint).mean,
                 {.color = colour(i), .width = 2.2},
                 score ? walks[i].label + ": " + score_text(*score) : walks[i].label);
      const double toe_off = walks[i].report.stance_percent;
      const Point tick[] = {{toe_off, tick_low}, {toe_off, tick_high}};
      panel.line(tick, {.color = colour(i), .width = 2.5});
    }
  }
  figure.note(
      std::string("The hip is drawn as the thigh's inclination to the vertical (hip flexion minus "
                  "pelvic tilt), which is what is compared. RMSE and Pearson r compare each walk's "
                  "mean curve with the reference mean; the toe (ball of the foot) has no reference "
                  "curve.") +
      (ankle_moved ? kMovedAnkleNote : ""));
  return figure;
}

svg::Figure plot_filmstrip(const eval::Motion& motion, const terrain::Terrain& terrain,
                           const FilmstripOptions& options) {
  check_motion(motion);
  if (options.poses < 2 || options.poses > 40) {
    throw std::invalid_argument("filmstrip: poses must be between 2 and 40");
  }
  const auto [begin, end] = stride_frames(motion, options.stride, 1);
  const auto poses = static_cast<std::size_t>(options.poses);
  const double stride_time = static_cast<double>(end - begin) / motion.fps;
  std::vector<std::size_t> frames;
  std::vector<double> percents;
  for (std::size_t k = 0; k < poses; ++k) {
    const double share = static_cast<double>(k) / static_cast<double>(poses);
    frames.push_back(
        begin + static_cast<std::size_t>(std::lround(share * static_cast<double>(end - begin))));
    percents.push_back(100.0 * share);
  }
  const double stride_length =
      motion.frames[end].pose.pelvis.x - motion.frames[begin].pose.pelvis.x;

  svg::Figure figure("One stride, side view: " + fixed(stride_length, 2) + " m in " +
                     fixed(stride_time, 2) + " s");
  figure.subtitle("From left heel strike to the next (stride " + std::to_string(options.stride) +
                  " of the walk). Blue: left leg; orange: right leg, nearer the viewer. Dots: foot "
                  "points bearing on the ground.");
  figure.columns(3).panel_size(460, 330);

  // Side by side: each pose centred on its pelvis in a cell wide enough for every pose.
  const double depth = 0.08;
  double half_width = 0.0;
  std::vector<StickFigure> centred;
  for (const std::size_t i : frames) {
    const Body body = body_at(motion.frames[i]);
    centred.push_back(stick_figure(body, motion.segments, {-body.pelvis.x, 0.0}));
    Extent e;
    e.add(centred.back());
    half_width = std::max({half_width, -e.left, e.right});
  }
  half_width += 0.12;
  const double cell = 2.0 * half_width;
  svg::Panel& strip = figure.add_panel(3);
  strip
      .title(std::to_string(poses) + " poses, every " +
             svg::format_number(100.0 / static_cast<double>(poses), 1) +
             " % of the stride, each centred on its pelvis")
      .equal_aspect()
      .hide_axes()
      .legend(svg::LegendPlace::Hidden);
  // One floor under every cell, so that the strip reads as one band of ground.
  double ground_low = std::numeric_limits<double>::infinity();
  for (const std::size_t i : frames) {
    const double x = motion.frames[i].pose.pelvis.x;
    ground_low = std::min(ground_low, lowest_ground(terrain, x - half_width, x + half_width));
  }
  Extent strip_extent;
  for (std::size_t k = 0; k < poses; ++k) {
    const std::size_t i = frames[k];
    const Body body = body_at(motion.frames[i]);
    const Point shift{static_cast<double>(k) * cell - body.pelvis.x, 0.0};
    draw_ground(strip, terrain, body.pelvis.x - half_width + 0.04,
                body.pelvis.x + half_width - 0.04, shift, ground_low - depth);
    const StickFigure stick = stick_figure(body, motion.segments, shift);
    draw_figure(strip, stick, {});
    draw_contacts(strip, terrain, body, shift);
    strip_extent.add(stick);
  }
  const double caption_top = strip_extent.top + 0.12;
  const double caption_bottom = ground_low - depth - 0.1;
  for (std::size_t k = 0; k < poses; ++k) {
    const double x = static_cast<double>(k) * cell;
    strip.text(x, caption_top, percent_text(percents[k]), {.size = 11.5, .bold = true});
    strip.text(x, caption_bottom, gait_phase(motion, terrain, begin, end, frames[k]),
               {.size = 10, .color = kMuted});
  }
  strip.x_range(-half_width, (static_cast<double>(poses) - 1.0) * cell + half_width)
      .y_range(caption_bottom - 0.08, caption_top + 0.08);

  // Chronophotograph: the same poses where they were, older ones paler.
  svg::Panel& chrono = figure.add_panel();
  chrono.title("Chronophotograph (later poses darker)").equal_aspect().hide_axes();
  Extent chrono_extent;
  std::vector<StickFigure> placed;
  for (const std::size_t i : frames) {
    placed.push_back(stick_figure(body_at(motion.frames[i]), motion.segments, {}));
    chrono_extent.add(placed.back());
  }
  const double x0 = chrono_extent.left - 0.1;
  const double x1 = chrono_extent.right + 0.1;
  const double chrono_ground = lowest_ground(terrain, x0, x1);
  draw_ground(chrono, terrain, x0, x1, {}, chrono_ground - depth);
  draw_footprints(chrono, motion, terrain, begin, end);
  for (std::size_t k = 0; k < poses; ++k) {
    const double opacity = 0.2 + 0.8 * static_cast<double>(k) / static_cast<double>(poses - 1);
    draw_figure(chrono, placed[k], {.width = 1.8, .opacity = opacity});
  }
  chrono.x_range(x0, x1).y_range(chrono_ground - depth - 0.02, chrono_extent.top + 0.05);

  // Contact over the stride: a bar per foot while it bears on the ground.
  svg::Panel& contact = figure.add_panel();
  // (The stride's ends copied in: Clang 14 cannot capture structured bindings.)
  const auto percent_of = [first = begin, last = end](std::size_t i) {
    return 100.0 * static_cast<double>(i - first) / static_cast<double>(last - first);
  };
  contact.title("Feet on the ground (grey: both)")
      .x_label("stride (%)")
      .x_range(0, 100)
      .x_ticks({0, 20, 40, 60, 80, 100})
      .y_range(-0.1, 2.3)
      .y_ticks({})
      .legend(svg::LegendPlace::Hidden);
  // A frame's contact holds until the next frame: frame i covers [i, i + 1).
  for (std::size_t i = begin; i < end;) {
    if (!(motion.frames[i].contact[0] && motion.frames[i].contact[1])) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < end && motion.frames[j].contact[0] && motion.frames[j].contact[1])
      ++j;
    const Point both[] = {
        {percent_of(i), -0.1}, {percent_of(j), -0.1}, {percent_of(j), 2.3}, {percent_of(i), 2.3}};
    contact.polygon(both, {.color = Color{225, 225, 225}, .opacity = 1.0});
    i = j;
  }
  for (std::size_t side = 0; side < 2; ++side) {
    const double row = side == 0 ? 1.3 : 0.2;
    const Color color = side == 0 ? kLeftLeg : kRightLeg;
    double share = 0.0;
    for (const auto& [first, last] : contact_runs(motion, side, begin, end - 1)) {
      const double a = percent_of(first);
      const double b = percent_of(last + 1);
      share += b - a;
      const Point bar[] = {{a, row}, {b, row}, {b, row + 0.5}, {a, row + 0.5}};
      contact.polygon(bar, {.color = color, .opacity = 0.9});
    }
    contact.text(
        1.0, row + 0.72,
        (side == 0 ? "left foot: " : "right foot: ") + fixed(share, 0) + " % of the stride",
        {.size = 10.5, .color = color, .anchor = svg::Anchor::Start});
  }

  // Foot clearance over the stride: how high heel and toe tip pass over the ground.
  svg::Panel& clearance = figure.add_panel();
  clearance.title("Height of the feet over the ground")
      .x_label("stride (%)")
      .y_label("height (mm)")
      .x_range(0, 100)
      .x_ticks({0, 20, 40, 60, 80, 100});
  double highest = 10.0;  // mm
  double deepest = 0.0;
  for (std::size_t side = 0; side < 2; ++side) {
    std::vector<double> x;
    std::vector<double> heel;
    std::vector<double> tip;
    for (std::size_t i = begin; i <= end; ++i) {
      x.push_back(percent_of(i));
      heel.push_back(1000.0 * ground_gap(terrain, motion.frames[i].points[side].heel));
      tip.push_back(1000.0 * ground_gap(terrain, motion.frames[i].points[side].tip));
    }
    const Color color = side == 0 ? kLeftLeg : kRightLeg;
    const std::string name = side == 0 ? "left " : "right ";
    clearance.line(x, heel, {.color = color, .width = 1.6, .dash = svg::Dash::Dashed},
                   name + "heel");
    clearance.line(x, tip, {.color = color, .width = 1.8}, name + "toe tip");
    for (const std::vector<double>* heights : {&heel, &tip}) {
      for (const double h : *heights) {
        highest = std::max(highest, h);
        deepest = std::min(deepest, h);
      }
    }
  }
  // Headroom for the legend above the curves.
  const double span = highest - deepest;
  clearance.y_range(deepest - 0.05 * span, highest + 0.6 * span);
  clearance.horizontal_line(0.0, {.color = kGroundLine, .width = 1});
  // The lowest foot point in the middle of each swing, as the evaluation measures clearance.
  for (std::size_t side = 0; side < 2; ++side) {
    for (std::size_t i = begin; i <= end;) {
      if (motion.frames[i].contact[side]) {
        ++i;
        continue;
      }
      std::size_t j = i;
      while (j <= end && !motion.frames[j].contact[side])
        ++j;
      const bool whole_swing = i > begin && j <= end;
      const std::size_t margin = (j - i) / 5;
      std::optional<std::pair<std::size_t, double>> lowest;
      for (std::size_t k = i + margin; whole_swing && k < j - margin; ++k) {
        const rig::LegPoints& p = motion.frames[k].points[side];
        for (const rig::Point& q : {p.heel, p.ball, p.tip}) {
          const double gap = ground_gap(terrain, q);
          if (!lowest || gap < lowest->second) lowest = {{k, gap}};
        }
      }
      if (lowest) {
        const Point mark[] = {{percent_of(lowest->first), 1000.0 * lowest->second}};
        const Color color = side == 0 ? kLeftLeg : kRightLeg;
        clearance.line(
            mark, {.color = color, .width = 0, .marker = svg::Marker::Circle, .marker_size = 7});
        clearance.text(mark[0].x, mark[0].y, "min " + fixed(1000.0 * lowest->second, 0) + " mm",
                       {.size = 10, .color = color, .dy = -12});
      }
      i = j;
    }
  }
  return figure;
}

svg::Figure plot_walk_animation(const eval::Motion& motion, const terrain::Terrain& terrain,
                                const WalkAnimationOptions& options) {
  check_motion(motion);
  if (!(options.frame_rate >= 1.0 && options.frame_rate <= 240.0)) {
    throw std::invalid_argument("walk animation: frame rate must be between 1 and 240");
  }
  if (options.strides < 0) throw std::invalid_argument("walk animation: strides must be >= 0");
  if (!(options.view_width >= 0.0) || !std::isfinite(options.view_width)) {
    throw std::invalid_argument("walk animation: view width must be a finite length >= 0");
  }
  std::size_t begin = 0;
  std::size_t end = motion.frames.size() - 1;
  if (options.strides > 0) {
    std::tie(begin, end) = stride_frames(motion, options.first_stride, options.strides);
  }
  const double t0 = motion.frames[begin].time;
  const double t1 = motion.frames[end].time;
  const double period = t1 - t0;
  if (!(period > 0.0)) throw std::invalid_argument("walk animation: the walk has no duration");
  const auto count =
      static_cast<std::size_t>(std::max(2L, std::lround(period * options.frame_rate) + 1));

  // Key frames at even times: SMIL plays the values evenly over the period.
  std::vector<Body> bodies;
  Extent extent;
  for (std::size_t f = 0; f < count; ++f) {
    const double t = t0 + period * static_cast<double>(f) / static_cast<double>(count - 1);
    bodies.push_back(body_at(motion, t));
    extent.add(stick_figure(bodies.back(), motion.segments, {}));
  }
  const rig::Point start = motion.frames[begin].pose.pelvis;
  const rig::Point finish = motion.frames[end].pose.pelvis;
  const double travel = finish.x - start.x;
  const double speed = travel / period;
  const double leg = motion.segments.leg_length();
  const double stature = leg / kHipHeight;

  std::string what = options.strides > 0 ? std::to_string(options.strides) +
                                               (options.strides == 1 ? " stride" : " strides")
                                         : "The whole walk";
  svg::Figure figure(what + " at " + fixed(speed, 2) + " m/s, played at real speed (" +
                     fixed(period, 2) + " s loop)");
  figure.subtitle(
      "Open in a web browser to play (SVG animation, no script). Blue: left leg; orange: right "
      "leg, nearer the viewer." +
      std::string(options.follow ? " The view follows the walker at its mean speed." : ""));
  figure.columns(1);
  svg::Panel& panel = figure.add_panel();
  panel.equal_aspect().hide_axes();

  const double depth = 0.12;
  std::vector<Point> shifts;
  double hatch = 0.25;
  double x0 = extent.left - 0.3;
  double x1 = extent.right + 0.3;
  double bottom = extent.bottom;
  double top = extent.top;
  if (options.follow) {
    const double width = options.view_width > 0.0 ? options.view_width : 4.0 * leg;
    // Hatching that repeats exactly over the loop's travel, so the loop joins unseen.
    if (std::abs(travel) > 0.05) {
      hatch = std::abs(travel) / std::max(1.0, std::round(std::abs(travel) / 0.25));
    }
    for (std::size_t f = 0; f < count; ++f) {
      const double t = static_cast<double>(f) / static_cast<double>(count - 1);
      shifts.push_back({t * travel, t * (finish.y - start.y)});
    }
    x0 = std::min(start.x, finish.x) - width;
    x1 = std::max(start.x, finish.x) + width;
    bottom = start.y - leg - 0.15;
    top = start.y + (1.0 - kHipHeight) * stature + 0.12;
    // Off level ground, the ground in view at the start and at the end of the loop (seen from
    // the view as it has moved), within a few leg lengths: stairs behind a climber and ahead of a
    // descender show.
    const double rise = finish.y - start.y;
    const auto [low_start, high_start] =
        ground_span(terrain, start.x - width / 2, start.x + width / 2);
    const auto [low_end, high_end] =
        ground_span(terrain, finish.x - width / 2, finish.x + width / 2);
    bottom =
        std::max(std::min(bottom, std::min(low_start, low_end - rise) - 0.1), bottom - 2.0 * leg);
    top = std::min(std::max(top, std::max(high_start, high_end - rise) + 0.1), top + 2.0 * leg);
    panel.x_range(start.x - width / 2, start.x + width / 2);
  } else {
    panel.x_range(x0, x1);
  }
  const double ground_low = lowest_ground(terrain, x0, x1);
  if (!options.follow) bottom = std::min(bottom, ground_low) - depth;
  bottom = std::min(bottom, top - 0.5);
  top += 0.05;
  panel.y_range(bottom, top);
  // The whole path is long and low: a panel of its shape, so the walker is not lost in white.
  const double shown_width =
      options.follow ? (options.view_width > 0.0 ? options.view_width : 4.0 * leg) : x1 - x0;
  const double plot_width = 940.0;
  const double panel_height = std::clamp(plot_width * (top - bottom) / shown_width, 200.0, 470.0);
  figure.panel_size(960.0, panel_height + 40.0);

  // The fill reaches below the view wherever it travels (down, on a descent).
  double lowest_view = bottom;
  for (const Point& shift : shifts)
    lowest_view = std::min(lowest_view, bottom + shift.y);
  draw_ground(panel, terrain, x0, x1, {}, std::min(ground_low - depth, lowest_view - 0.1), hatch);
  std::array<std::vector<std::vector<Point>>, 2> legs;
  std::vector<std::vector<Point>> trunk;
  std::vector<std::vector<Point>> neck;
  std::vector<std::vector<Point>> head;
  for (const Body& body : bodies) {
    const StickFigure stick = stick_figure(body, motion.segments, {});
    legs[0].push_back(stick.legs[0]);
    legs[1].push_back(stick.legs[1]);
    trunk.push_back(stick.trunk);
    neck.push_back(stick.neck);
    head.push_back(stick.head);
  }
  // Thinner strokes when the walker is drawn small (the whole path in view).
  const double pixels_per_metre = std::min(plot_width / shown_width, panel_height / (top - bottom));
  const double line = 3.2 * std::clamp(pixels_per_metre / 150.0, 0.5, 1.0);
  panel.animated_line(legs[0], period, {.color = kLeftLeg, .width = line});
  panel.animated_line(trunk, period, {.color = kBody, .width = 2.2 * line});
  panel.animated_line(neck, period, {.color = kBody, .width = line});
  panel.animated_line(head, period, {.color = kBody, .width = line});
  panel.animated_line(legs[1], period, {.color = kRightLeg, .width = line});
  if (options.follow) panel.animated_view(shifts, period);
  return figure;
}

}  // namespace fuzzygait::plot

// Pictures of a walk: gait curves over the normative band with the report's scores, comparisons
// of several walks, the stick-figure filmstrip and the animation. The walk is made up here (a
// smooth periodic gait with known timing), so the tests do not move when the controllers are
// tuned. Set FUZZYGAIT_SVG_OUT to a folder to keep the figures.
#include "fuzzygait/plot/walk_plots.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <regex>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzzygait/io/normative.hpp"
#include "plot/xml_check.hpp"
#include "support/text.hpp"

namespace io = fuzzygait::io;
namespace gait = fuzzygait::gait;
namespace eval = fuzzygait::eval;
namespace plot = fuzzygait::plot;
namespace rig = fuzzygait::rig;
namespace svg = fuzzygait::plot::svg;
using fuzzygait::terrain::Terrain;
using fuzzygait::test::check_xml;
using fuzzygait::test::count;
using fuzzygait::test::keep;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

constexpr double kFps = 100.0;
constexpr double kCycle = 1.2;  // s: 120 frames, so heel strikes fall on frames
constexpr double kStance = 0.6;

double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

// A leg's angles at a share p of its cycle (0 = heel strike), roughly as people walk.
rig::LegAngles leg_angles(double p, double tilt) {
  const double t = 2.0 * std::numbers::pi * p;
  const double thigh = 5.0 + 20.0 * std::cos(t - 0.3);
  const double knee = 8.0 + 10.0 * std::exp(-std::pow((p - 0.15) / 0.08, 2)) +
                      52.0 * std::exp(-std::pow((p - 0.72) / 0.1, 2));
  const double ankle = 2.0 + 8.0 * std::sin(t) - 12.0 * std::exp(-std::pow((p - 0.62) / 0.06, 2));
  const double toe =
      p > 0.45 && p < 0.65 ? 25.0 * std::sin((p - 0.45) / 0.2 * std::numbers::pi) : 0.0;
  return {radians(thigh) + tilt, radians(std::max(0.0, knee)), radians(ankle), radians(toe)};
}

// seconds of a made-up walk on level ground at 1.2 m/s.
eval::Motion made_up_walk(double seconds) {
  eval::Motion motion;
  motion.fps = kFps;
  motion.segments = rig::segments_from_stature(1.75);
  const double tilt = radians(11.0);
  const auto frames = static_cast<int>(std::lround(seconds * kFps)) + 1;
  for (int i = 0; i < frames; ++i) {
    eval::Frame f;
    f.time = i / kFps;
    const double p = std::fmod(f.time / kCycle, 1.0);
    f.pose.pelvis = {1.2 * f.time, 0.90 + 0.02 * std::cos(4.0 * std::numbers::pi * p)};
    f.pose.pelvis_tilt = tilt;
    // The left heel strikes between frames (0.045 of a cycle in), so every stride is 120 frames.
    const double left = std::fmod(p + 0.955, 1.0);
    const double right = std::fmod(left + 0.5, 1.0);
    f.pose.legs[0] = leg_angles(left, tilt);
    f.pose.legs[1] = leg_angles(right, tilt);
    for (int side = 0; side < 2; ++side) {
      f.points[static_cast<std::size_t>(side)] = rig::forward_kinematics(
          motion.segments, f.pose.pelvis, tilt, f.pose.legs[static_cast<std::size_t>(side)]);
    }
    f.contact = {left < kStance, right < kStance};
    motion.frames.push_back(f);
  }
  return motion;
}

const eval::Motion& walk() {
  static const eval::Motion motion = made_up_walk(8.0);
  return motion;
}

const eval::Normative& reference() {
  static const eval::Normative normative = io::load_normative("schwartz2008_free");
  return normative;
}

eval::GaitReport report(const eval::Motion& motion = walk()) {
  return eval::evaluate(motion, Terrain::flat(), &reference(), 0.7);
}

std::size_t count_matches(const std::string& text, const std::string& pattern) {
  const std::regex re(pattern);
  return static_cast<std::size_t>(
      std::distance(std::sregex_iterator(text.begin(), text.end(), re), std::sregex_iterator()));
}

std::string one_decimal(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", value);
  return buffer;
}

std::string no_decimals(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.0f", value);
  return buffer;
}

std::string two_decimals(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f", value);
  return buffer;
}

// The walk's mean curves are the only polylines drawn this blue and this wide; the reference
// bands the only closed paths in the reference grey.
constexpr const char* kWalkCurve = R"(<polyline[^>]*stroke="#0072b2" stroke-width="2.4")";
constexpr const char* kReferenceBand = R"(Z" fill="#787878")";

}  // namespace

TEST(WalkPlots, GaitCurvesOverTheReferenceWithTheReportsScores) {
  const eval::GaitReport r = report();
  ASSERT_TRUE(r.thigh_score && r.knee_score && r.ankle_score);
  const svg::Figure figure = plot::plot_gait_curves(r, &reference());
  const std::string text = figure.svg();
  EXPECT_EQ(check_xml(text), "");
  EXPECT_EQ(figure.panel_count(), 4u);
  EXPECT_EQ(count_matches(text, kWalkCurve), 4u);  // thigh, knee, ankle, toe
  EXPECT_EQ(count(text, kReferenceBand), 3u);      // no reference for the toe
  for (const auto& score : {r.thigh_score, r.knee_score, r.ankle_score}) {
    EXPECT_THAT(text, HasSubstr(">walk: RMSE " + one_decimal(score->rmse) + "\xC2\xB0, r " +
                                two_decimals(score->pearson) + "</text>"));
  }
  EXPECT_THAT(text, HasSubstr(">walk</text>"));  // the toe, unscored
  EXPECT_THAT(text, HasSubstr("step " + two_decimals(r.step_length) + " m"));
  EXPECT_THAT(text, HasSubstr("Schwartz et al. 2008, free speed"));
  EXPECT_THAT(text, HasSubstr("stance " + no_decimals(r.stance_percent) + " %"));
  EXPECT_THAT(text, HasSubstr(">peak "));                                 // swing knee flexion
  EXPECT_EQ(text, plot::plot_gait_curves(report(), &reference()).svg());  // deterministic
  keep(figure, "walk_gait_curves.svg");
}

// A reference whose ankle zero is its own (Bovi et al. 2011) is drawn moved onto the walk's
// ankle mean, as it is scored, and the figure says so; the other joints are drawn as they are.
TEST(WalkPlots, AnAnkleOfUnknownZeroIsDrawnOnTheWalksMean) {
  const eval::Normative bovi = io::load_normative("bovi2011_adult_natural");
  ASSERT_TRUE(bovi.ankle_offset_unknown);
  const eval::GaitReport r = eval::evaluate(walk(), Terrain::flat(), &bovi);
  const std::string text = plot::plot_gait_curves(r, &bovi).svg();
  EXPECT_EQ(check_xml(text), "");
  EXPECT_THAT(text, HasSubstr("ankle zero is its own (Bovi et al. 2011)"));
  const eval::Normative schwartz = io::load_normative("schwartz2008_free");
  EXPECT_THAT(plot::plot_gait_curves(r, &schwartz).svg(), Not(HasSubstr("ankle zero")));
  const std::vector<plot::LabelledReport> walks = {{"walk", r}};
  const std::string ankle =
      plot::plot_curve_comparison(walks, &bovi, {.joints = {plot::GaitJoint::Ankle}}).svg();
  EXPECT_EQ(check_xml(ankle), "");
  EXPECT_THAT(ankle, HasSubstr("ankle zero is its own"));
}

TEST(WalkPlots, GaitCurvesWithoutReference) {
  eval::GaitReport r = eval::evaluate(walk(), Terrain::flat());
  const std::string text = plot::plot_gait_curves(r, nullptr, {.cycle_sd = false}).svg();
  EXPECT_EQ(check_xml(text), "");
  EXPECT_EQ(count_matches(text, kWalkCurve), 4u);
  EXPECT_EQ(count(text, kReferenceBand), 0u);
  EXPECT_EQ(count(text, ">walk</text>"), 4u);
  EXPECT_THAT(text, Not(HasSubstr("RMSE")));
}

TEST(WalkPlots, CurveComparisonLabelsEachWalk) {
  const std::vector<plot::LabelledReport> walks = {{"step 0.60 m", report()},
                                                   {"step 0.70 m", report(made_up_walk(6.0))}};
  const svg::Figure figure = plot::plot_curve_comparison(walks, &reference());
  const std::string text = figure.svg();
  EXPECT_EQ(check_xml(text), "");
  EXPECT_EQ(figure.panel_count(), 4u);
  EXPECT_EQ(count(text, kReferenceBand), 3u);
  for (const plot::LabelledReport& w : walks) {
    EXPECT_EQ(count(text, ">" + w.label + ": RMSE "), 3u);
    EXPECT_EQ(count(text, ">" + w.label + "</text>"), 1u);  // the toe
    EXPECT_THAT(text, HasSubstr(">" + w.label + ": RMSE " + one_decimal(w.report.knee_score->rmse) +
                                "\xC2\xB0"));
  }
  EXPECT_EQ(text, plot::plot_curve_comparison(walks, &reference()).svg());
  keep(figure, "walk_curve_comparison.svg");

  // A graded grid of many walks, hip and knee only.
  std::vector<plot::LabelledReport> grid;
  for (int i = 0; i < 5; ++i)
    grid.push_back({"walk " + std::to_string(i), walks[0].report});
  const svg::Figure graded = plot::plot_curve_comparison(
      grid, &reference(),
      {.joints = {plot::GaitJoint::Thigh, plot::GaitJoint::Knee}, .graded = true});
  const std::string graded_text = graded.svg();
  EXPECT_EQ(check_xml(graded_text), "");
  EXPECT_EQ(graded.panel_count(), 2u);
  EXPECT_THAT(graded_text, HasSubstr(svg::viridis(0.0).hex()));
  EXPECT_THAT(graded_text, Not(HasSubstr(svg::palette_color(1).hex())));
  keep(graded, "walk_curve_grid.svg");

  EXPECT_THROW(plot::plot_curve_comparison({}, &reference()), std::invalid_argument);
  EXPECT_THROW(plot::plot_curve_comparison(walks, &reference(), {.joints = {}}),
               std::invalid_argument);
}

TEST(WalkPlots, FilmstripShowsTheRightNumberOfPoses) {
  for (const int poses : {8, 10, 12}) {
    const svg::Figure figure = plot::plot_filmstrip(walk(), Terrain::flat(), {.poses = poses});
    const std::string text = figure.svg();
    EXPECT_EQ(check_xml(text), "") << poses;
    // One caption per pose in the strip, "0 %" first; the percent of the stride.
    EXPECT_EQ(count(text, " %</text>"), static_cast<std::size_t>(poses)) << poses;
    EXPECT_THAT(text, HasSubstr(">0 %</text>"));
    EXPECT_THAT(text, HasSubstr(">initial contact</text>"));
    // Both legs in their colours, and dots (markers) under planted feet.
    EXPECT_THAT(text, HasSubstr(svg::palette_color(0).hex()));
    EXPECT_THAT(text, HasSubstr(svg::palette_color(1).hex()));
    EXPECT_THAT(text, HasSubstr("<marker "));
    if (poses == 10) keep(figure, "walk_filmstrip.svg");
  }
  EXPECT_EQ(plot::plot_filmstrip(walk(), Terrain::flat()).svg(),
            plot::plot_filmstrip(walk(), Terrain::flat()).svg());
}

TEST(WalkPlots, FilmstripOnStairs) {
  std::vector<rig::Point> points = {{-5.0, 0.0}, {3.0, 0.0}};
  for (int k = 1; k <= 4; ++k) {
    points.push_back({3.0 + 0.3 * (k - 1) + 0.001, 0.05 * k});
    points.push_back({3.0 + 0.3 * k, 0.05 * k});
  }
  const Terrain stairs = Terrain::polyline(points);
  const std::string text = plot::plot_filmstrip(walk(), stairs, {.stride = 2}).svg();
  EXPECT_EQ(check_xml(text), "");
}

TEST(WalkPlots, FilmstripRejectsWhatTheWalkDoesNotHave) {
  EXPECT_THROW(plot::plot_filmstrip(walk(), Terrain::flat(), {.stride = 40}),
               std::invalid_argument);
  EXPECT_THROW(plot::plot_filmstrip(walk(), Terrain::flat(), {.poses = 1}), std::invalid_argument);
  EXPECT_THROW(plot::plot_filmstrip(walk(), Terrain::flat(), {.stride = -1}),
               std::invalid_argument);
  EXPECT_THROW(plot::plot_filmstrip(eval::Motion{}, Terrain::flat()), std::invalid_argument);
}

TEST(WalkPlots, AnimationPlaysStridesAtRealSpeed) {
  const svg::Figure figure = plot::plot_walk_animation(walk(), Terrain::flat());
  const std::string text = figure.svg();
  EXPECT_EQ(check_xml(text), "");
  // Two legs, trunk, neck and head move; the view follows.
  EXPECT_EQ(count(text, "<animate "), 5u);
  EXPECT_EQ(count(text, "<animateTransform "), 1u);
  // Two strides of 1.2 s: every animation lasts 2.4 s, looping, with the same key frames.
  EXPECT_EQ(count(text, "dur=\"2.4s\""), 6u);
  EXPECT_EQ(count(text, "repeatCount=\"indefinite\""), 6u);
  // Found by hand: std::regex recurses once per character and overflows the stack on these
  // long attributes.
  std::set<std::size_t> key_frames;
  const std::string attribute = "values=\"";
  for (std::size_t at = text.find(attribute); at != std::string::npos;
       at = text.find(attribute, at + 1)) {
    const std::size_t begin = at + attribute.size();
    key_frames.insert(count(text.substr(begin, text.find('"', begin) - begin), ";") + 1);
  }
  EXPECT_EQ(key_frames, std::set<std::size_t>{73u});  // 30 per second, both ends
  EXPECT_EQ(text, plot::plot_walk_animation(walk(), Terrain::flat()).svg());
  keep(figure, "walk_animation.svg");

  // The whole walk in view: no moving view, one loop of the whole duration.
  const std::string whole =
      plot::plot_walk_animation(walk(), Terrain::flat(), {.strides = 0, .follow = false}).svg();
  EXPECT_EQ(check_xml(whole), "");
  EXPECT_EQ(count(whole, "<animate "), 5u);
  EXPECT_EQ(count(whole, "<animateTransform "), 0u);
  EXPECT_EQ(count(whole, "dur=\"8s\""), 5u);

  EXPECT_THROW(plot::plot_walk_animation(walk(), Terrain::flat(), {.strides = 10}),
               std::invalid_argument);
  EXPECT_THROW(plot::plot_walk_animation(walk(), Terrain::flat(), {.frame_rate = 0}),
               std::invalid_argument);
}

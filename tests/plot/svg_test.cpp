// The SVG chart builder: well-formed and deterministic output, escaping, number formatting,
// ticks, contours, and the figures the gait code will draw (curves over a normative band, a
// stick-figure filmstrip, an animation). Set FUZZYGAIT_SVG_OUT to a folder to keep the figures.
#include "fuzzygait/plot/svg.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "plot/xml_check.hpp"
#include "support/text.hpp"

namespace svg = fuzzygait::plot::svg;
using fuzzygait::test::check_xml;
using fuzzygait::test::count;
using fuzzygait::test::keep;
using fuzzygait::test::read_text;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

// A made-up joint angle over the gait cycle (degrees), smooth and periodic.
double joint_angle(double percent, double mean, double a1, double phase1, double a2,
                   double phase2) {
  const double t = 2 * std::numbers::pi * percent / 100.0;
  return mean + a1 * std::cos(t - phase1) + a2 * std::cos(2 * t - phase2);
}

// Several panels of joint angles over the gait cycle, each over a normative band with the RMSE
// in the legend: the figure the gait evaluation draws.
svg::Figure gait_curves() {
  svg::Figure figure("Level walking, step 60 cm");
  figure.subtitle("Simulated joint angles against normative data (mean \xC2\xB1 2 SD)");
  figure.columns(3).panel_size(360, 260);
  struct Joint {
    const char* name;
    double mean, a1, p1, a2, p2;
  };
  const Joint joints[] = {
      {"hip", 12, 22, 0.3, 4, 1.0}, {"knee", 28, -22, 0.9, 12, 2.4}, {"ankle", 2, 8, 3.0, 6, 1.2}};
  std::vector<double> x;
  for (int i = 0; i <= 100; ++i)
    x.push_back(i);
  for (const Joint& j : joints) {
    std::vector<double> mean, lower, upper, simulated;
    for (const double p : x) {
      const double m = joint_angle(p, j.mean, j.a1, j.p1, j.a2, j.p2);
      mean.push_back(m);
      lower.push_back(m - 8);
      upper.push_back(m + 8);
      simulated.push_back(m + 3 * std::sin(p / 9.0));
    }
    svg::Panel& panel = figure.add_panel();
    panel.title(j.name)
        .x_label("gait cycle (%)")
        .y_label(std::string(j.name) + " flexion (\xC2\xB0)")
        .x_range(0, 100);
    panel.band(x, lower, upper, {.color = svg::Color{150, 150, 150}, .opacity = 0.3},
               "normative \xC2\xB1 2 SD");
    panel.line(x, mean,
               {.color = svg::Color{110, 110, 110}, .width = 1.2, .dash = svg::Dash::Dashed},
               "normative mean");
    panel.vertical_line(
        60, {.color = svg::Color{150, 150, 150}, .width = 1, .dash = svg::Dash::Dotted});
    panel.label(
        60, joint_angle(60, j.mean, j.a1, j.p1, j.a2, j.p2) + 20, "toe off",
        {.size = 10, .color = svg::Color{110, 110, 110}, .anchor = svg::Anchor::Start, .dx = 4});
    panel.line(x, simulated, {.color = svg::palette_color(0), .width = 2.2},
               "simulated (RMSE 2.1\xC2\xB0)");
    // A playhead that moves with the animation, across the band.
    const double bottom = *std::min_element(lower.begin(), lower.end()) - 5;
    const double top = *std::max_element(upper.begin(), upper.end()) + 5;
    std::vector<std::vector<svg::Point>> playhead;
    for (int f = 0; f < 20; ++f)
      playhead.push_back({{f * 5.0, bottom}, {f * 5.0, top}});
    panel.animated_line(playhead, 1.2,
                        {.color = svg::palette_color(1), .width = 1, .opacity = 0.6});
  }
  return figure;
}

// Hip, knee, ankle and toe of one leg at a point of the cycle, in metres.
std::vector<svg::Point> leg(double percent, double hip_x, double phase) {
  const double p = percent + phase;
  const double hip = joint_angle(p, 12, 22, 0.3, 4, 1.0) * std::numbers::pi / 180;
  const double knee = joint_angle(p, 28, -22, 0.9, 12, 2.4) * std::numbers::pi / 180;
  const svg::Point h{hip_x, 0.95};
  const svg::Point k{h.x + 0.45 * std::sin(hip), h.y - 0.45 * std::cos(hip)};
  const double shank = hip - knee;
  const svg::Point a{k.x + 0.45 * std::sin(shank), k.y - 0.45 * std::cos(shank)};
  const svg::Point toe{a.x + 0.18 * std::cos(shank), a.y + 0.18 * std::sin(shank)};
  return {h, k, a, toe};
}

// A side-view filmstrip of stick figures and the same leg animated.
svg::Figure stick_figures() {
  svg::Figure figure("Gait, side view");
  figure.columns(3).panel_size(330, 260);
  svg::Panel& strip = figure.add_panel(2);
  strip.title("filmstrip, every 10 % of the cycle").equal_aspect().hide_axes();
  const svg::Point ground[] = {{-0.3, 0.0}, {5.6, 0.0}};
  strip.line(ground, {.color = svg::Color{120, 120, 120}, .width = 1});
  for (int i = 0; i < 10; ++i) {
    const double x = 0.55 * i;
    strip.line(leg(i * 10.0, x, 50), {.color = svg::Color{170, 170, 170}, .width = 2.5});
    strip.line(leg(i * 10.0, x, 0), {.color = svg::palette_color(0), .width = 2.5});
    const svg::Point trunk[] = {{x, 0.95}, {x, 1.5}};
    strip.line(trunk, {.color = svg::Color{60, 60, 60}, .width = 3});
    strip.text(x, -0.1, std::to_string(i * 10) + " %", {.size = 9.5});
  }
  svg::Panel& animation = figure.add_panel();
  animation.title("animated (open in a browser)").equal_aspect().hide_axes();
  std::vector<std::vector<svg::Point>> right, left;
  for (int f = 0; f < 20; ++f) {
    right.push_back(leg(f * 5.0, 0, 0));
    left.push_back(leg(f * 5.0, 0, 50));
  }
  animation.line(ground, {.color = svg::Color{120, 120, 120}, .width = 1});
  animation.animated_line(
      left, 1.2, {.color = svg::Color{170, 170, 170}, .width = 3, .marker = svg::Marker::Circle},
      "left leg");
  animation.animated_line(
      right, 1.2, {.color = svg::palette_color(0), .width = 3, .marker = svg::Marker::Circle},
      "right leg");
  animation.x_range(-0.8, 0.8).y_range(-0.1, 1.6).legend(svg::LegendPlace::TopRight);
  return figure;
}

svg::Grid cone(std::size_t n) {
  svg::Grid grid{-1, 1, -1, 1, n, n, std::vector<double>(n * n)};
  for (std::size_t r = 0; r < n; ++r) {
    for (std::size_t c = 0; c < n; ++c)
      grid.values[r * n + c] = std::hypot(grid.x(c), grid.y(r));
  }
  return grid;
}

}  // namespace

TEST(Svg, EscapesMarkupAndReplacesInvalidText) {
  EXPECT_EQ(svg::escape_xml("a < b & \"c\" > 'd'"),
            "a &lt; b &amp; &quot;c&quot; &gt; &apos;d&apos;");
  EXPECT_EQ(svg::escape_xml("caf\xC3\xA9 \xC2\xB1 2 SD"),
            "caf\xC3\xA9 \xC2\xB1 2 SD");  // UTF-8 kept
  EXPECT_EQ(svg::escape_xml("bad \xFF byte"), "bad \xEF\xBF\xBD byte");
  EXPECT_EQ(svg::escape_xml("cut \xE2\x88"), "cut \xEF\xBF\xBD\xEF\xBF\xBD");
  EXPECT_EQ(svg::escape_xml(std::string("nul\0bell\a", 9)),
            "nul\xEF\xBF\xBD"
            "bell\xEF\xBF\xBD");
  EXPECT_EQ(svg::escape_xml("overlong \xC0\xAF"), "overlong \xEF\xBF\xBD\xEF\xBF\xBD");
  EXPECT_EQ(svg::escape_xml("tab\tline\n"), "tab\tline\n");
}

TEST(Svg, WritesNumbersCompactly) {
  EXPECT_EQ(svg::format_number(12.5), "12.5");
  EXPECT_EQ(svg::format_number(3.0), "3");
  EXPECT_EQ(svg::format_number(-0.25), "-0.25");
  EXPECT_EQ(svg::format_number(-0.001), "0");  // never "-0"
  EXPECT_EQ(svg::format_number(1.0 / 3.0), "0.33");
  EXPECT_EQ(svg::format_number(1.0 / 3.0, 4), "0.3333");
  EXPECT_EQ(svg::format_number(100.0), "100");
  EXPECT_EQ(svg::format_number(2.675, 0), "3");
}

TEST(Svg, NiceTicksAreRoundNumbersInsideTheRange) {
  EXPECT_THAT(svg::nice_ticks(0, 100, 6), ::testing::ElementsAre(0, 20, 40, 60, 80, 100));
  EXPECT_THAT(svg::nice_ticks(-1, 1, 5), ::testing::ElementsAre(-1, -0.5, 0, 0.5, 1));
  EXPECT_THAT(svg::nice_ticks(0, 1, 5), ::testing::ElementsAre(0, 0.25, 0.5, 0.75, 1));
  EXPECT_THAT(svg::nice_ticks(-7.3, 63.1, 5), ::testing::ElementsAre(0, 20, 40, 60));
  for (const double t : svg::nice_ticks(0.1, 0.7, 7)) {
    EXPECT_GE(t, 0.1);
    EXPECT_LE(t, 0.7);
  }
  EXPECT_TRUE(svg::nice_ticks(1, 1, 5).empty());
  EXPECT_TRUE(svg::nice_ticks(0, std::nan(""), 5).empty());
}

TEST(Svg, PaletteAndColourMap) {
  EXPECT_EQ(svg::palette_color(0).hex(), "#0072b2");
  EXPECT_EQ(svg::palette_color(7), svg::palette_color(0));  // cycles
  EXPECT_EQ(svg::viridis(0).hex(), "#440154");
  EXPECT_EQ(svg::viridis(1).hex(), "#fde725");
  EXPECT_EQ(svg::viridis(-3), svg::viridis(0));
  EXPECT_EQ(svg::viridis(std::nan("")), svg::viridis(0));
}

TEST(Svg, TextWidthGrowsWithTextAndSize) {
  EXPECT_EQ(svg::text_width("", 11), 0.0);
  EXPECT_GT(svg::text_width("WWW", 11), svg::text_width("iii", 11));
  EXPECT_DOUBLE_EQ(svg::text_width("abc", 22), 2 * svg::text_width("abc", 11));
}

TEST(Svg, EmptyFigureIsAValidDocument) {
  const std::string text = svg::Figure().svg();
  EXPECT_EQ(check_xml(text), "");
  EXPECT_THAT(text, HasSubstr("<svg xmlns=\"http://www.w3.org/2000/svg\""));
}

TEST(Svg, TextInEveryPlaceIsEscaped) {
  svg::Figure figure("title <&> \"quoted\"");
  figure.subtitle("sub & title").note("note <b>");
  svg::Panel& panel = figure.add_panel();
  const double x[] = {0, 1};
  panel.title("a < b").x_label("x & y").y_label("'y'");
  panel.line(x, x, {}, "legend <entry>");
  panel.text(0.5, 0.5, "text & more");
  panel.label(0.5, 0.5, "label \xFF");
  const std::string text = figure.svg();
  EXPECT_EQ(check_xml(text), "");
  EXPECT_THAT(text, HasSubstr("title &lt;&amp;&gt; &quot;quoted&quot;"));
  EXPECT_THAT(text, HasSubstr("legend &lt;entry&gt;"));
  EXPECT_THAT(text, HasSubstr("label \xEF\xBF\xBD"));
  EXPECT_THAT(text, Not(HasSubstr("<b>")));
}

TEST(Svg, GaitCurvesFigure) {
  const svg::Figure figure = gait_curves();
  const std::string text = figure.svg();
  EXPECT_EQ(check_xml(text), "");
  EXPECT_EQ(count(text, ">simulated (RMSE 2.1\xC2\xB0)</text>"), 3u);
  EXPECT_EQ(count(text, "<animate "), 3u);
  EXPECT_EQ(count(text, "<clipPath "), 3u);
  EXPECT_EQ(text, gait_curves().svg());  // deterministic
  keep(figure, "gait_curves.svg");
}

TEST(Svg, StickFiguresAndAnimation) {
  const svg::Figure figure = stick_figures();
  const std::string text = figure.svg();
  EXPECT_EQ(check_xml(text), "");
  EXPECT_EQ(count(text, "attributeName=\"points\""), 2u);
  EXPECT_EQ(count(text, "repeatCount=\"indefinite\""), 2u);
  EXPECT_EQ(count(text, "dur=\"1.2s\""), 2u);
  EXPECT_THAT(text, HasSubstr("marker-mid="));
  EXPECT_EQ(text, stick_figures().svg());
  keep(figure, "stick_figures.svg");
}

TEST(Svg, EqualAspectKeepsUnitsEqual) {
  svg::Figure figure;
  figure.panel_size(400, 200);
  svg::Panel& panel = figure.add_panel();
  const svg::Point square[] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
  panel.line(square, {.color = svg::Color{0, 0, 0}}).equal_aspect().hide_axes();
  const std::string text = figure.svg();
  // The square's polyline: its width and height in pixels must match.
  const std::size_t at = text.find("points=\"");
  ASSERT_NE(at, std::string::npos);
  std::istringstream points(text.substr(at + 8, text.find('"', at + 8) - at - 8));
  std::vector<double> xs, ys;
  std::string pair;
  while (points >> pair) {
    const std::size_t comma = pair.find(',');
    xs.push_back(std::stod(pair.substr(0, comma)));
    ys.push_back(std::stod(pair.substr(comma + 1)));
  }
  ASSERT_EQ(xs.size(), 5u);
  EXPECT_NEAR(std::abs(xs[1] - xs[0]), std::abs(ys[2] - ys[1]), 0.02);
}

TEST(Svg, HeatMapWithColourBarAndContours) {
  svg::Figure figure("cone");
  svg::Panel& panel = figure.add_panel();
  svg::Grid grid = cone(41);
  grid.values[0] = std::nan("");  // a cell without a value
  const double levels[] = {0.5};
  panel.heat_map(grid, "distance").contours(grid, levels).x_label("x").y_label("y");
  const std::string text = figure.svg();
  EXPECT_EQ(check_xml(text), "");
  EXPECT_THAT(text, HasSubstr("xlink:href=\"data:image/png;base64,iVBORw0KGgo"));
  EXPECT_THAT(text, HasSubstr("<linearGradient "));
  EXPECT_THAT(text, HasSubstr(">distance</text>"));
  keep(figure, "cone.svg");
}

TEST(Svg, ContoursOfAConeAreClosedLoops) {
  // Marching squares on z = |(x, y)|: the 0.5 level is one closed loop.
  svg::Figure figure;
  svg::Panel& panel = figure.add_panel();
  const double levels[] = {0.5};
  panel.x_range(-1, 1).y_range(-1, 1).contours(cone(41), levels, {.color = svg::Color{1, 2, 3}});
  const std::string text = figure.svg();
  const std::size_t stroke = text.find("stroke=\"#010203\"");
  ASSERT_NE(stroke, std::string::npos);
  const std::size_t d = text.rfind(" d=\"", stroke) + 4;
  const std::string path = text.substr(d, text.find('"', d) - d);
  EXPECT_EQ(count(path, "M"), 1u);
  const std::string first = path.substr(1, path.find('L') - 1);
  EXPECT_EQ(path.substr(path.size() - first.size()), first);  // ends where it starts
}

TEST(Svg, BandsBreakAtMissingValues) {
  svg::Figure figure;
  svg::Panel& panel = figure.add_panel();
  const double x[] = {0, 1, 2, 3, 4};
  const double lower[] = {0, 0, std::nan(""), 0, 0};
  const double upper[] = {1, 1, 1, 1, 1};
  panel.band(x, lower, upper);
  const std::string text = figure.svg();
  EXPECT_EQ(check_xml(text), "");
  EXPECT_EQ(count(text, "Z"), 2u);  // two polygons
}

TEST(Svg, RejectsInconsistentInput) {
  svg::Figure figure;
  svg::Panel& panel = figure.add_panel();
  const double two[] = {0, 1};
  const double three[] = {0, 1, 2};
  EXPECT_THROW(panel.line(two, three), std::invalid_argument);
  EXPECT_THROW(panel.band(two, two, three), std::invalid_argument);
  EXPECT_THROW(panel.x_range(1, 1), std::invalid_argument);
  EXPECT_THROW(panel.heat_map(svg::Grid{0, 1, 0, 1, 2, 2, {1, 2, 3}}), std::invalid_argument);
  const std::vector<std::vector<svg::Point>> uneven = {{{0, 0}}, {{0, 0}, {1, 1}}};
  EXPECT_THROW(panel.animated_line(uneven, 1.0), std::invalid_argument);
  EXPECT_THROW(panel.animated_line(uneven, 0.0), std::invalid_argument);
  EXPECT_THROW(figure.columns(0), std::invalid_argument);
  EXPECT_THROW(figure.add_panel(0), std::invalid_argument);
}

TEST(Svg, LabelsDoNotOverlap) {
  svg::Figure figure;
  svg::Panel& panel = figure.add_panel();
  panel.x_range(0, 1).y_range(0, 1);
  for (int i = 0; i < 8; ++i)
    panel.label(0.5, 0.5, "label " + std::to_string(i));
  const std::string text = figure.svg();
  // Placed labels are written with their left edge at x and their middle 0.35 em above y.
  const std::regex element(R"re(<text x="([-0-9.]+)" y="([-0-9.]+)"[^>]*>(label \d)</text>)re");
  struct Box {
    double left, top, right, bottom;
  };
  std::vector<Box> boxes;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), element);
       it != std::sregex_iterator(); ++it) {
    const double x = std::stod((*it)[1]);
    const double middle = std::stod((*it)[2]) - 0.35 * 11;
    const double width = svg::text_width((*it)[3].str(), 11);
    boxes.push_back({x, middle - 0.6 * 11, x + width, middle + 0.6 * 11});
  }
  ASSERT_EQ(boxes.size(), 8u);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      const bool overlap =
          boxes[i].left < boxes[j].right - 0.01 && boxes[j].left < boxes[i].right - 0.01 &&
          boxes[i].top < boxes[j].bottom - 0.01 && boxes[j].top < boxes[i].bottom - 0.01;
      EXPECT_FALSE(overlap) << "labels " << i << " and " << j;
    }
  }
}

TEST(Svg, SavesToAFile) {
  const std::filesystem::path path = std::filesystem::path(::testing::TempDir()) / "svg_test.svg";
  const svg::Figure figure = gait_curves();
  figure.save(path);
  EXPECT_EQ(read_text(path), figure.svg());
  EXPECT_THROW(figure.save("/nonexistent-folder/x.svg"), std::runtime_error);
}

// A view that travels with a drawing: the contents move under a fixed clip, in step with the
// animated lines, and static viewers get the first frame's view.
TEST(Svg, AnimatedViewMovesTheContentsUnderTheClip) {
  svg::Figure figure;
  figure.columns(1).panel_size(400, 200);
  svg::Panel& panel = figure.add_panel();
  panel.hide_axes().x_range(0, 4).y_range(0, 2);
  const svg::Point ground[] = {{0, 0.5}, {10, 0.5}};
  panel.line(ground);
  std::vector<std::vector<svg::Point>> walker;
  std::vector<svg::Point> shifts;
  for (int f = 0; f < 5; ++f) {
    walker.push_back({{1.0 + f, 0.5}, {1.0 + f, 1.5}});
    shifts.push_back({1.0 * f, 0.0});
  }
  panel.animated_line(walker, 2.0).animated_view(shifts, 2.0);
  const std::string text = figure.svg();
  EXPECT_EQ(check_xml(text), "");
  EXPECT_EQ(count(text, "<animateTransform "), 1u);
  EXPECT_EQ(count(text, "dur=\"2s\""), 2u);
  // One data unit is (400 - 10 - 14) / 4 = 94 pixels: the view moves left by that much per
  // frame, as fast as the walker, who so stays in the middle; it starts unmoved.
  EXPECT_THAT(text, HasSubstr("values=\"0,0;-94,0;-188,0;-282,0;-376,0\""));
  EXPECT_THAT(text, HasSubstr("transform=\"translate(0,0)\""));
  // The moving group sits inside the clipped one.
  EXPECT_LT(text.find("clip-path="), text.find("<animateTransform "));
  EXPECT_EQ(text, figure.svg());
  const svg::Point bad[] = {{0, std::nan("")}};
  EXPECT_THROW(panel.animated_view(bad, 1.0), std::invalid_argument);
  EXPECT_THROW(panel.animated_view(shifts, 0.0), std::invalid_argument);
  EXPECT_THROW(panel.animated_view({}, 1.0), std::invalid_argument);
}

// Plot areas line up down a column on both sides, even when one panel's legend sits beside it.
TEST(Svg, PlotAreasLineUpDownAColumn) {
  svg::Figure figure;
  figure.columns(1);
  const double x[] = {0, 1};
  figure.add_panel().line(x, x, {}, "a long legend entry").legend(svg::LegendPlace::Right);
  figure.add_panel().line(x, x);
  const std::string text = figure.svg();
  const std::regex clip(
      "<clipPath id=\"p\\dc\"><rect x=\"([0-9.]+)\" y=\"[0-9.]+\" "
      "width=\"([0-9.]+)\"");
  std::vector<std::string> boxes;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), clip); it != std::sregex_iterator();
       ++it) {
    boxes.push_back((*it)[1].str() + " " + (*it)[2].str());
  }
  ASSERT_EQ(boxes.size(), 2u);
  EXPECT_EQ(boxes[0], boxes[1]);
}

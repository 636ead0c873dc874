// A small SVG chart builder, written by hand (no dependency). A Figure is a grid of Panels; a
// Panel has axes with round-numbered ticks and draws lines, filled bands, polygons, markers, text,
// heat maps with a colour bar, contour lines and animated lines, all in data coordinates.
// Output is deterministic (the same calls give the same bytes), compact, and well-formed XML
// whatever the text (escaped, invalid UTF-8 replaced). Animation is SMIL: no JavaScript.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fuzzygait::plot::svg {

struct Color {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
  std::string hex() const;  // "#rrggbb"
  bool operator==(const Color&) const = default;
};

// The i-th colour of Okabe & Ito's palette, told apart by colour-blind readers; cycles after 7.
Color palette_color(std::size_t index);
// The viridis colour map (perceptually uniform, colour-blind safe) at t in [0, 1].
Color viridis(double t);

struct Point {
  double x = 0.0;
  double y = 0.0;
};

enum class Dash : std::uint8_t { Solid, Dashed, Dotted };
enum class Marker : std::uint8_t { None, Circle, Square };

struct LineStyle {
  std::optional<Color> color = std::nullopt;  // unset: the panel's next palette colour
  double width = 1.75;                        // pixels; 0 draws the markers only
  Dash dash = Dash::Solid;
  Marker marker = Marker::None;  // drawn at every point
  double marker_size = 6.0;      // pixels across
  double opacity = 1.0;
};

struct FillStyle {
  std::optional<Color> color = std::nullopt;  // unset: the panel's next palette colour
  double opacity = 0.25;
  std::optional<Color> outline = std::nullopt;  // unset: no edge
};

enum class Anchor : std::uint8_t { Start, Middle, End };

// Text is centred vertically on its point, then moved by (dx, dy) pixels (dy > 0 is down).
struct TextStyle {
  double size = 11.0;                         // pixels
  std::optional<Color> color = std::nullopt;  // unset: near black
  Anchor anchor = Anchor::Middle;
  bool bold = false;
  double dx = 0.0;
  double dy = 0.0;
};

// z(x, y) sampled on a regular grid: values[row * columns + column] at
// x = x_min + column * (x_max - x_min) / (columns - 1), and y likewise with rows. NaN: no value.
struct Grid {
  double x_min = 0.0;
  double x_max = 1.0;
  double y_min = 0.0;
  double y_max = 1.0;
  std::size_t columns = 0;
  std::size_t rows = 0;
  std::vector<double> values;

  double x(std::size_t column) const;  // x of a column
  double y(std::size_t row) const;     // y of a row
  double at(std::size_t column, std::size_t row) const { return values[row * columns + column]; }
};

// Where a panel's legend goes: Best picks the inside corner that hides the least data.
enum class LegendPlace : std::uint8_t {
  Best,
  TopLeft,
  TopRight,
  BottomLeft,
  BottomRight,
  Right,
  Hidden
};

namespace detail {
struct PanelData;
}

// One chart of a Figure. Items draw in the order they are added; items with a label get a
// legend entry. Every call returns the panel, so calls chain.
class Panel {
 public:
  ~Panel();
  Panel(const Panel&) = delete;
  Panel& operator=(const Panel&) = delete;

  Panel& title(std::string text);              // heading above the plot area
  Panel& x_label(std::string text);            // caption of the horizontal axis
  Panel& y_label(std::string text);            // caption of the vertical axis
  Panel& x_range(double min, double max);      // fixed axis range (default: fits the data)
  Panel& y_range(double min, double max);      // fixed axis range (default: fits the data, padded)
  Panel& x_ticks(std::vector<double> values);  // ticks at these values (default: round numbers)
  Panel& y_ticks(std::vector<double> values);  // ticks at these values (default: round numbers)
  Panel& equal_aspect();             // one data unit is as long on both axes (stick figures, maps)
  Panel& hide_axes();                // no axes, ticks or grid lines (drawings, text)
  Panel& legend(LegendPlace place);  // default Best

  // A polyline through (x[i], y[i]); non-finite values break it.
  Panel& line(std::span<const double> x, std::span<const double> y, LineStyle style = {},
              std::string label = {});
  // A polyline through the points; non-finite points break it.
  Panel& line(std::span<const Point> points, LineStyle style = {}, std::string label = {});
  // The area between lower[i] and upper[i] over x[i] (e.g. mean +/- 2 SD); NaN breaks it.
  Panel& band(std::span<const double> x, std::span<const double> lower,
              std::span<const double> upper, FillStyle style = {}, std::string label = {});
  // A closed filled polygon.
  Panel& polygon(std::span<const Point> points, FillStyle style = {}, std::string label = {});
  // A line across the whole plot area at x (vertical) or y (horizontal).
  Panel& vertical_line(double x, LineStyle style = {}, std::string label = {});
  Panel& horizontal_line(double y, LineStyle style = {}, std::string label = {});
  // Text at (x, y), exactly there.
  Panel& text(double x, double y, std::string text, TextStyle style = {});
  // Text near (x, y), moved to the nearest free spot so that labels never overlap each other
  // (and keep off the lines when a spot nearby allows).
  Panel& label(double x, double y, std::string text, TextStyle style = {});
  // The grid as a smoothly shaded image in viridis colours, with a colour bar captioned
  // value_label; NaN cells stay grey.
  Panel& heat_map(const Grid& grid, std::string value_label = {});
  // Contour lines of the grid at the levels (default: round numbers inside its value range),
  // thin translucent dark grey unless styled; the levels are also marked on the colour bar.
  Panel& contours(const Grid& grid, std::span<const double> levels = {},
                  LineStyle style = {.color = Color{34, 34, 34}, .width = 0.8, .opacity = 0.6});
  // A polyline that plays the frames in a loop, evenly over period_seconds (SMIL <animate>).
  // Every frame must have the same number of points; static viewers show the first frame.
  Panel& animated_line(std::span<const std::vector<Point>> frames, double period_seconds,
                       LineStyle style = {}, std::string label = {});
  // Moves the view over the panel's contents in a loop, evenly over period_seconds (SMIL
  // <animateTransform>), so a drawing can follow something that travels: at frame f the plot area
  // shows the axis ranges moved by shifts[f] (data units). Play it with animated lines of as
  // many frames and the same period and they keep step. Axes, texts and the legend stay put,
  // so use it on drawings (hide_axes()) with fixed x_range and y_range; static viewers show
  // the view of frame 0.
  Panel& animated_view(std::span<const Point> shifts, double period_seconds);

 private:
  friend class Figure;
  Panel();
  Color take_color(const std::optional<Color>& wanted);
  std::unique_ptr<detail::PanelData> data_;
};

// A titled grid of panels, written as one SVG document.
class Figure {
 public:
  explicit Figure(std::string title = {});

  Figure& subtitle(std::string text);               // a line under the title (wrapped when long)
  Figure& columns(int count);                       // grid cells per row (default 2)
  Figure& panel_size(double width, double height);  // pixels per grid cell (default 520 x 300)
  Figure& note(std::string text);  // a paragraph under the panels (wrapped when long)
  // A new panel at the next free place, left to right then top to bottom, column_span cells wide.
  Panel& add_panel(int column_span = 1);

  std::size_t panel_count() const { return panels_.size(); }

  std::string svg() const;                             // the whole SVG document
  void save(const std::filesystem::path& path) const;  // writes svg(); throws std::runtime_error

 private:
  std::string title_;
  std::vector<std::string> subtitles_;
  std::vector<std::string> notes_;
  int columns_ = 2;
  double cell_width_ = 520.0;
  double cell_height_ = 300.0;
  std::vector<std::unique_ptr<Panel>> panels_;
  std::vector<int> spans_;
};

// Several figures one above the other in a single SVG document (each keeps its own layout and
// animations).
std::string stack_figures(const std::vector<const Figure*>& figures);

// Text made safe for XML content and attributes: & < > " ' escaped, invalid UTF-8 and control
// characters replaced by U+FFFD.
std::string escape_xml(std::string_view text);
// value with at most `decimals` decimals and no trailing zeros: "12.5", "-0.25", "3"; never "-0".
std::string format_number(double value, int decimals = 2);
// Round-numbered ticks (steps of 1, 2, 2.5 or 5 times a power of ten) inside [min, max], about
// target_count of them.
std::vector<double> nice_ticks(double min, double max, int target_count = 6);
// The width in pixels text is expected to take in the figures' sans-serif font.
double text_width(std::string_view text, double font_size);

}  // namespace fuzzygait::plot::svg

#include "fuzzygait/plot/svg.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>
#include <variant>

#include "fuzzygait/io/files.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::plot::svg {

// ---------------------------------------------------------------------------------------------
// Panel contents, kept out of the header.
namespace detail {

struct LineItem {
  std::vector<std::vector<Point>> runs;  // finite pieces
  LineStyle style;
  Color color;
};
struct FillItem {
  std::vector<std::vector<Point>> polygons;
  FillStyle style;
  Color color;
};
struct RuleItem {
  bool vertical;
  double value;
  LineStyle style;
  Color color;
};
struct TextItem {
  Point at;
  std::string text;
  TextStyle style;
  bool avoid_overlap;
};
struct HeatItem {
  Grid grid;
  std::string value_label;
  double z_min;
  double z_max;
};
struct ContourItem {
  std::vector<double> levels;
  std::vector<std::vector<Point>> lines;
  LineStyle style;
  Color color;
};
struct AnimatedItem {
  std::vector<std::vector<Point>> frames;
  double period;
  LineStyle style;
  Color color;
};
using Item =
    std::variant<LineItem, FillItem, RuleItem, TextItem, HeatItem, ContourItem, AnimatedItem>;

struct LegendEntry {
  bool filled;
  LineStyle line;
  FillStyle fill;
  Color color;
  std::string text;
};

struct PanelData {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::optional<std::pair<double, double>> x_range;
  std::optional<std::pair<double, double>> y_range;
  std::optional<std::vector<double>> x_ticks;
  std::optional<std::vector<double>> y_ticks;
  bool equal_aspect = false;
  bool axes = true;
  LegendPlace legend = LegendPlace::Best;
  std::vector<Item> items;
  std::vector<LegendEntry> legend_entries;
  std::size_t colors_used = 0;
  std::vector<Point> view_shifts;  // animated_view(): empty when the view stays put
  double view_period = 0.0;
};

}  // namespace detail

namespace {

using detail::PanelData;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::string_view kFont = "DejaVu Sans,Helvetica,Arial,sans-serif";
const Color kInk{34, 34, 34};
const Color kMutedInk{85, 85, 85};
const Color kAxis{102, 102, 102};
const Color kGridLine{232, 232, 232};
const Color kNoValue{210, 210, 210};
constexpr double kTickLength = 4.0;
constexpr double kXTickSpacing = 70.0;  // pixels per tick, roughly
constexpr double kYTickSpacing = 45.0;
constexpr double kTickFont = 10.5;
constexpr double kAxisFont = 11.5;
constexpr double kTitleFont = 13.0;
constexpr double kLegendFont = 11.0;

// ---------------------------------------------------------------------------------------------
// Text: UTF-8, widths, wrapping.

// Decodes one code point at text[i], advancing i; nullopt (and one byte consumed) when invalid.
std::optional<char32_t> next_code_point(std::string_view text, std::size_t& i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = 0;
  char32_t c = 0;
  if (lead < 0x80) {
    ++i;
    return lead;
  } else if ((lead & 0xE0) == 0xC0) {
    length = 2;
    c = lead & 0x1Fu;
  } else if ((lead & 0xF0) == 0xE0) {
    length = 3;
    c = lead & 0x0Fu;
  } else if ((lead & 0xF8) == 0xF0) {
    length = 4;
    c = lead & 0x07u;
  } else {
    ++i;
    return std::nullopt;
  }
  if (i + length > text.size()) {
    ++i;
    return std::nullopt;
  }
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) {
      ++i;
      return std::nullopt;
    }
    c = (c << 6) | (byte(i + k) & 0x3Fu);
  }
  static constexpr std::array<char32_t, 5> kSmallest = {0, 0, 0x80, 0x800, 0x10000};
  if (c < kSmallest[length] || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) {
    ++i;
    return std::nullopt;
  }
  i += length;
  return c;
}

bool allowed_in_xml(char32_t c) {
  return c == 0x9 || c == 0xA || c == 0xD || (c >= 0x20 && c <= 0xD7FF) ||
         (c >= 0xE000 && c <= 0xFFFD) || (c >= 0x10000 && c <= 0x10FFFF);
}

void append_utf8(std::string& out, char32_t c) {
  if (c < 0x80) {
    out += static_cast<char>(c);
  } else if (c < 0x800) {
    out += static_cast<char>(0xC0 | (c >> 6));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    out += static_cast<char>(0xE0 | (c >> 12));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (c >> 18));
    out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  }
}

// Advance widths of DejaVu Sans (the widest of the fonts named in kFont), in em, for ASCII
// 32..126: estimates on the wide side keep labels apart in narrower fonts too.
constexpr std::array<double, 95> kAsciiWidths = {
    0.318, 0.401, 0.460, 0.838, 0.636, 0.950, 0.780, 0.275, 0.390, 0.390, 0.500, 0.838,
    0.318, 0.361, 0.318, 0.337, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636,
    0.636, 0.636, 0.337, 0.337, 0.838, 0.838, 0.838, 0.531, 1.000, 0.684, 0.686, 0.698,
    0.770, 0.632, 0.575, 0.775, 0.752, 0.295, 0.295, 0.656, 0.557, 0.863, 0.748, 0.787,
    0.603, 0.787, 0.695, 0.635, 0.611, 0.732, 0.684, 0.989, 0.685, 0.611, 0.685, 0.390,
    0.337, 0.390, 0.838, 0.500, 0.500, 0.613, 0.635, 0.550, 0.635, 0.615, 0.352, 0.635,
    0.634, 0.278, 0.278, 0.579, 0.278, 0.974, 0.634, 0.612, 0.635, 0.635, 0.411, 0.521,
    0.392, 0.634, 0.592, 0.818, 0.592, 0.592, 0.525, 0.636, 0.337, 0.636, 0.838};

double code_point_width(char32_t c) {
  if (c >= 32 && c <= 126) return kAsciiWidths[c - 32];
  switch (c) {
    case 0x00B7:  // middle dot
      return 0.318;
    case 0x00B0:  // degree
      return 0.500;
    case 0x2026:  // ellipsis
      return 1.000;
    case 0x2212:  // minus
    case 0x00B1:  // plus-minus
    case 0x00D7:  // times
      return 0.838;
    default:
      return c < 32 ? 0.0 : 0.72;
  }
}

// Cuts text to max_width, ending in an ellipsis when something was cut.
std::string fit_text(std::string_view text, double size, double max_width) {
  if (text_width(text, size) <= max_width) return std::string(text);
  const double budget = max_width - code_point_width(0x2026) * size;
  double width = 0.0;
  std::size_t i = 0;
  std::size_t keep = 0;
  while (i < text.size()) {
    width += code_point_width(next_code_point(text, i).value_or(0xFFFD)) * size;
    if (width > budget) break;
    keep = i;
  }
  return std::string(text.substr(0, keep)) + "\xE2\x80\xA6";
}

// Breaks text into lines no wider than max_width, at spaces when possible.
std::vector<std::string> wrap_text(std::string_view text, double size, double max_width) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t i = 0;
  while (i <= text.size()) {
    std::size_t end = text.find(' ', i);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view word = text.substr(i, end - i);
    const std::string candidate = line.empty() ? std::string(word) : line + " " + std::string(word);
    if (!line.empty() && text_width(candidate, size) > max_width) {
      lines.push_back(line);
      line = std::string(word);
    } else {
      line = candidate;
    }
    i = end + 1;
  }
  if (!line.empty() || lines.empty()) lines.push_back(line);
  for (std::string& l : lines)
    l = fit_text(l, size, max_width);
  return lines;
}

// ---------------------------------------------------------------------------------------------
// XML elements.

// Numbers in pixel space: two decimals are a hundredth of a pixel; wild values are clamped so a
// point far off the chart cannot write hundreds of digits.
std::string px(double value) {
  return format_number(std::clamp(value, -1e6, 1e6), 2);
}

class Tag {
 public:
  explicit Tag(std::string_view name) : text_("<" + std::string(name)) {}
  Tag& set(std::string_view key, std::string_view value) {
    text_ += ' ';
    text_ += key;
    text_ += "=\"";
    text_ += escape_xml(value);
    text_ += '"';
    return *this;
  }
  Tag& set(std::string_view key, const char* value) { return set(key, std::string_view(value)); }
  Tag& set(std::string_view key, const std::string& value) {
    return set(key, std::string_view(value));
  }
  Tag& set(std::string_view key, double value) { return set(key, px(value)); }
  std::string empty() const { return text_ + "/>\n"; }
  std::string open() const { return text_ + ">"; }

 private:
  std::string text_;
};

std::string dash_array(Dash dash, double width) {
  const double w = std::max(width, 1.0);
  switch (dash) {
    case Dash::Solid:
      return {};
    case Dash::Dashed:
      return px(4.0 * w) + " " + px(2.5 * w);
    case Dash::Dotted:
      return px(0.01) + " " + px(2.2 * w);
  }
  return {};
}

void set_stroke(Tag& tag, const LineStyle& style, Color color) {
  if (style.width <= 0.0) {
    tag.set("stroke", "none");
    return;
  }
  tag.set("stroke", color.hex())
      .set("stroke-width", style.width)
      .set("stroke-linejoin", "round")
      .set("stroke-linecap", "round");  // round caps also make the dots of Dash::Dotted
  if (style.opacity < 1.0) tag.set("stroke-opacity", format_number(style.opacity, 3));
  const std::string dashes = dash_array(style.dash, style.width);
  if (!dashes.empty()) tag.set("stroke-dasharray", dashes);
}

std::string text_element(double x, double y, std::string_view text, const TextStyle& style,
                         bool halo) {
  Tag tag("text");
  tag.set("x", x + style.dx).set("y", y + style.dy + 0.35 * style.size);
  if (style.size != 11.0) tag.set("font-size", style.size);
  if (style.anchor == Anchor::Middle) tag.set("text-anchor", "middle");
  if (style.anchor == Anchor::End) tag.set("text-anchor", "end");
  if (style.bold) tag.set("font-weight", "bold");
  tag.set("fill", style.color.value_or(kInk).hex());
  if (halo) {
    tag.set("stroke", "#ffffff")
        .set("stroke-width", 3.0)
        .set("stroke-linejoin", "round")
        .set("paint-order", "stroke");
  }
  return tag.open() + escape_xml(text) + "</text>\n";
}

// ---------------------------------------------------------------------------------------------
// Geometry helpers.

struct Box {
  double left = 0.0;
  double top = 0.0;
  double width = 0.0;
  double height = 0.0;
  double right() const { return left + width; }
  double bottom() const { return top + height; }
  bool overlaps(const Box& other) const {
    return left < other.right() && other.left < right() && top < other.bottom() &&
           other.top < bottom();
  }
  bool contains(Point p) const {
    return p.x >= left && p.x <= right() && p.y >= top && p.y <= bottom();
  }
};

bool finite(Point p) {
  return std::isfinite(p.x) && std::isfinite(p.y);
}

// Splits a sequence of points into its finite runs.
std::vector<std::vector<Point>> finite_runs(std::span<const Point> points) {
  std::vector<std::vector<Point>> runs;
  std::vector<Point> run;
  for (const Point& p : points) {
    if (finite(p)) {
      run.push_back(p);
    } else if (!run.empty()) {
      runs.push_back(std::move(run));
      run.clear();
    }
  }
  if (!run.empty()) runs.push_back(std::move(run));
  return runs;
}

// Douglas-Peucker: drops points closer than tolerance to the line through their neighbours,
// so dense samples of straight pieces cost nothing in the file.
std::vector<Point> simplify(const std::vector<Point>& points, double tolerance) {
  if (points.size() < 3) return points;
  std::vector<bool> keep(points.size(), false);
  keep.front() = keep.back() = true;
  std::vector<std::pair<std::size_t, std::size_t>> stack{{0, points.size() - 1}};
  while (!stack.empty()) {
    const auto [first, last] = stack.back();
    stack.pop_back();
    const Point a = points[first];
    const Point b = points[last];
    const double dx = b.x - a.x;
    const double dy = b.y - a.y;
    const double length = std::hypot(dx, dy);
    double worst = -1.0;
    std::size_t worst_index = first;
    for (std::size_t i = first + 1; i < last; ++i) {
      const Point p = points[i];
      const double distance = length > 0.0 ? std::abs(dy * (p.x - a.x) - dx * (p.y - a.y)) / length
                                           : std::hypot(p.x - a.x, p.y - a.y);
      if (distance > worst) {
        worst = distance;
        worst_index = i;
      }
    }
    if (worst > tolerance) {
      keep[worst_index] = true;
      stack.emplace_back(first, worst_index);
      stack.emplace_back(worst_index, last);
    }
  }
  std::vector<Point> out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (keep[i]) out.push_back(points[i]);
  }
  return out;
}

std::string point_list(const std::vector<Point>& points) {
  std::string text;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i) text += ' ';
    text += px(points[i].x) + "," + px(points[i].y);
  }
  return text;
}

std::string path_data(const std::vector<std::vector<Point>>& runs, bool close) {
  std::string d;
  for (const std::vector<Point>& run : runs) {
    for (std::size_t i = 0; i < run.size(); ++i) {
      d += i == 0 ? "M" : (i == 1 ? "L" : " ");
      d += px(run[i].x) + "," + px(run[i].y);
    }
    if (close && !run.empty()) d += "Z";
  }
  return d;
}

// ---------------------------------------------------------------------------------------------
// PNG (stored, uncompressed deflate) for heat maps: smaller than thousands of rectangles, and
// viewers smooth it between the samples.

std::uint32_t crc32(std::string_view bytes) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k)
        c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xFFFFFFFFu;
  for (const char b : bytes)
    c = table[(c ^ static_cast<unsigned char>(b)) & 0xFFu] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

void append_be32(std::string& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) {
    out += static_cast<char>((value >> shift) & 0xFFu);
  }
}

void append_chunk(std::string& png, std::string_view type, std::string_view data) {
  append_be32(png, static_cast<std::uint32_t>(data.size()));
  const std::string body = std::string(type) + std::string(data);
  png += body;
  append_be32(png, crc32(body));
}

std::string encode_png(std::size_t width, std::size_t height,
                       const std::vector<std::uint8_t>& rgba) {
  std::string raw;
  raw.reserve(height * (width * 4 + 1));
  for (std::size_t row = 0; row < height; ++row) {
    raw += '\0';  // filter: none
    raw.append(reinterpret_cast<const char*>(rgba.data() + row * width * 4), width * 4);
  }
  std::string zlib = "\x78\x01";
  std::uint32_t a = 1;
  std::uint32_t b = 0;
  for (const char c : raw) {
    a = (a + static_cast<unsigned char>(c)) % 65521u;
    b = (b + a) % 65521u;
  }
  std::size_t offset = 0;
  do {
    const std::size_t length = std::min<std::size_t>(65535, raw.size() - offset);
    const bool last = offset + length == raw.size();
    zlib += static_cast<char>(last ? 1 : 0);
    zlib += static_cast<char>(length & 0xFFu);
    zlib += static_cast<char>(length >> 8);
    zlib += static_cast<char>(~length & 0xFFu);
    zlib += static_cast<char>((~length >> 8) & 0xFFu);
    zlib.append(raw, offset, length);
    offset += length;
  } while (offset < raw.size());
  append_be32(zlib, (b << 16) | a);

  std::string header;
  append_be32(header, static_cast<std::uint32_t>(width));
  append_be32(header, static_cast<std::uint32_t>(height));
  header +=
      std::string("\x08\x06\x00\x00\x00", 5);  // 8 bits, RGBA, deflate, no filter, no interlace
  std::string png = "\x89PNG\r\n\x1a\n";
  append_chunk(png, "IHDR", header);
  append_chunk(png, "IDAT", zlib);
  append_chunk(png, "IEND", {});
  return png;
}

std::string base64(std::string_view bytes) {
  static constexpr std::string_view kDigits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t n = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
    if (i + 1 < bytes.size())
      n |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) n |= static_cast<unsigned char>(bytes[i + 2]);
    out += kDigits[(n >> 18) & 63u];
    out += kDigits[(n >> 12) & 63u];
    out += i + 1 < bytes.size() ? kDigits[(n >> 6) & 63u] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63u] : '=';
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Contours: marching squares, crossings joined into polylines through the grid edges they share.

std::vector<std::vector<Point>> contour_lines(const Grid& grid, double level) {
  const std::size_t columns = grid.columns;
  const std::size_t rows = grid.rows;
  // Edge ids: 2 * node + 0 for the edge to the right of the node, + 1 for the edge above it.
  const auto right_edge = [&](std::size_t c, std::size_t r) { return 2 * (r * columns + c); };
  const auto up_edge = [&](std::size_t c, std::size_t r) { return 2 * (r * columns + c) + 1; };
  const auto crossing = [&](std::size_t c0, std::size_t r0, std::size_t c1, std::size_t r1) {
    const double v0 = grid.at(c0, r0);
    const double v1 = grid.at(c1, r1);
    const double t = (level - v0) / (v1 - v0);
    return Point{grid.x(c0) + t * (grid.x(c1) - grid.x(c0)),
                 grid.y(r0) + t * (grid.y(r1) - grid.y(r0))};
  };
  std::map<std::size_t, Point> points;
  std::map<std::size_t, std::vector<std::size_t>> links;
  const auto connect = [&](std::size_t a, std::size_t b) {
    links[a].push_back(b);
    links[b].push_back(a);
  };
  for (std::size_t r = 0; r + 1 < rows; ++r) {
    for (std::size_t c = 0; c + 1 < columns; ++c) {
      const double v00 = grid.at(c, r);
      const double v10 = grid.at(c + 1, r);
      const double v11 = grid.at(c + 1, r + 1);
      const double v01 = grid.at(c, r + 1);
      if (!std::isfinite(v00) || !std::isfinite(v10) || !std::isfinite(v11) ||
          !std::isfinite(v01)) {
        continue;
      }
      const bool a00 = v00 > level;
      const bool a10 = v10 > level;
      const bool a11 = v11 > level;
      const bool a01 = v01 > level;
      const std::size_t bottom = right_edge(c, r);
      const std::size_t top = right_edge(c, r + 1);
      const std::size_t left = up_edge(c, r);
      const std::size_t right = up_edge(c + 1, r);
      std::vector<std::size_t> crossed;
      if (a00 != a10) {
        crossed.push_back(bottom);
        points.emplace(bottom, crossing(c, r, c + 1, r));
      }
      if (a10 != a11) {
        crossed.push_back(right);
        points.emplace(right, crossing(c + 1, r, c + 1, r + 1));
      }
      if (a01 != a11) {
        crossed.push_back(top);
        points.emplace(top, crossing(c, r + 1, c + 1, r + 1));
      }
      if (a00 != a01) {
        crossed.push_back(left);
        points.emplace(left, crossing(c, r, c, r + 1));
      }
      if (crossed.size() == 2) {
        connect(crossed[0], crossed[1]);
      } else if (crossed.size() == 4) {
        // Saddle: the cell centre decides which corners the lines cut off.
        const bool centre_above = (v00 + v10 + v11 + v01) / 4.0 > level;
        if (a00 == centre_above) {  // cut off the corners (1,0) and (0,1)
          connect(bottom, right);
          connect(left, top);
        } else {  // cut off the corners (0,0) and (1,1)
          connect(left, bottom);
          connect(right, top);
        }
      }
    }
  }
  std::vector<std::vector<Point>> lines;
  std::map<std::size_t, bool> used;
  const auto walk = [&](std::size_t start) {
    std::vector<Point> line{points.at(start)};
    used[start] = true;
    std::size_t current = start;
    for (;;) {
      std::optional<std::size_t> next;
      for (const std::size_t n : links.at(current)) {
        if (!used[n]) {
          next = n;
          break;
        }
      }
      if (!next) {
        // Close loops: the start is a neighbour of the last point.
        const std::vector<std::size_t>& around = links.at(current);
        if (line.size() > 2 && std::find(around.begin(), around.end(), start) != around.end()) {
          line.push_back(points.at(start));
        }
        break;
      }
      used[*next] = true;
      line.push_back(points.at(*next));
      current = *next;
    }
    lines.push_back(std::move(line));
  };
  for (const auto& [edge, neighbours] : links) {  // open lines start at their ends
    if (neighbours.size() == 1 && !used[edge]) walk(edge);
  }
  for (const auto& [edge, neighbours] : links) {  // then the loops
    if (!used[edge]) walk(edge);
  }
  return lines;
}

std::pair<double, double> value_range(const Grid& grid) {
  double lo = kInf;
  double hi = -kInf;
  for (const double v : grid.values) {
    if (std::isfinite(v)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  return {lo, hi};
}

void check_grid(const Grid& grid) {
  if (grid.columns < 2 || grid.rows < 2 || grid.values.size() != grid.columns * grid.rows ||
      !(grid.x_max > grid.x_min) || !(grid.y_max > grid.y_min)) {
    throw std::invalid_argument(
        "svg grid: needs at least 2 x 2 samples, columns * rows values and a positive extent");
  }
}

// ---------------------------------------------------------------------------------------------
// Axes.

struct Axis {
  double min = 0.0;
  double max = 1.0;
  std::vector<double> ticks;
  int decimals = 0;
  double to_pixel(double v, double start, double length, bool flip) const {
    const double t = (v - min) / (max - min);
    return flip ? start + length - t * length : start + t * length;
  }
};

int decimals_for(const std::vector<double>& values) {
  for (int d = 0; d < 10; ++d) {
    const double scale = std::pow(10.0, d);
    bool exact = true;
    for (const double v : values) {
      const double scaled = v * scale;
      if (std::abs(scaled - std::round(scaled)) > 1e-6 * std::max(1.0, std::abs(scaled))) {
        exact = false;
        break;
      }
    }
    if (exact) return d;
  }
  return 10;
}

// Every tick of an axis with the same decimals ("0.0 0.5 1.0"), and a real minus sign.
std::string tick_text(double value, int decimals) {
  std::array<char, 400> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                    std::chars_format::fixed, decimals);
  std::string text(buffer.data(), result.ptr);
  if (text[0] == '-' && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
  if (!text.empty() && text[0] == '-') text.replace(0, 1, "\xE2\x88\x92");
  return text;
}

struct Bounds {
  double x_min = kInf;
  double x_max = -kInf;
  double y_min = kInf;
  double y_max = -kInf;
  void add_x(double x) {
    if (!std::isfinite(x)) return;
    x_min = std::min(x_min, x);
    x_max = std::max(x_max, x);
  }
  void add_y(double y) {
    if (!std::isfinite(y)) return;
    y_min = std::min(y_min, y);
    y_max = std::max(y_max, y);
  }
  void add(Point p) {
    if (!finite(p)) return;
    add_x(p.x);
    add_y(p.y);
  }
};

Bounds data_bounds(const PanelData& panel) {
  Bounds bounds;
  for (const detail::Item& item : panel.items) {
    if (const auto* line = std::get_if<detail::LineItem>(&item)) {
      for (const auto& run : line->runs) {
        for (const Point& p : run)
          bounds.add(p);
      }
    } else if (const auto* fill = std::get_if<detail::FillItem>(&item)) {
      for (const auto& polygon : fill->polygons) {
        for (const Point& p : polygon)
          bounds.add(p);
      }
    } else if (const auto* rule = std::get_if<detail::RuleItem>(&item)) {
      if (rule->vertical) {
        bounds.add_x(rule->value);
      } else {
        bounds.add_y(rule->value);
      }
    } else if (const auto* heat = std::get_if<detail::HeatItem>(&item)) {
      bounds.add({heat->grid.x_min, heat->grid.y_min});
      bounds.add({heat->grid.x_max, heat->grid.y_max});
    } else if (const auto* animated = std::get_if<detail::AnimatedItem>(&item)) {
      for (const auto& frame : animated->frames) {
        for (const Point& p : frame)
          bounds.add(p);
      }
    }
  }
  return bounds;
}

bool has_heat_map(const PanelData& panel) {
  return std::any_of(panel.items.begin(), panel.items.end(), [](const detail::Item& item) {
    return std::holds_alternative<detail::HeatItem>(item);
  });
}

bool has_markers(const PanelData& panel) {
  return std::any_of(panel.items.begin(), panel.items.end(), [](const detail::Item& item) {
    const auto* line = std::get_if<detail::LineItem>(&item);
    return line && line->style.marker != Marker::None;
  });
}

// A finite, non-empty range from the data, padded by `pad` of its span on each side.
std::pair<double, double> resolve_range(double lo, double hi, double pad) {
  if (!(lo <= hi)) return {0.0, 1.0};
  if (hi - lo <= 1e-12 * std::max(1.0, std::abs(lo))) {
    const double half = lo == 0.0 ? 0.5 : 0.1 * std::abs(lo);
    return {lo - half, hi + half};
  }
  const double extra = pad * (hi - lo);
  return {lo - extra, hi + extra};
}

Axis make_axis(std::pair<double, double> range, const std::optional<std::vector<double>>& fixed,
               double length, double spacing) {
  Axis axis;
  axis.min = range.first;
  axis.max = range.second;
  if (fixed) {
    for (const double t : *fixed) {
      if (t >= axis.min - 1e-9 * (axis.max - axis.min) &&
          t <= axis.max + 1e-9 * (axis.max - axis.min)) {
        axis.ticks.push_back(t);
      }
    }
  } else {
    const int target = std::max(2, static_cast<int>(length / spacing));
    axis.ticks = nice_ticks(axis.min, axis.max, target);
  }
  axis.decimals = decimals_for(axis.ticks);
  return axis;
}

double widest_tick(const Axis& axis) {
  double widest = 0.0;
  for (const double t : axis.ticks) {
    widest = std::max(widest, text_width(tick_text(t, axis.decimals), kTickFont));
  }
  return widest;
}

// ---------------------------------------------------------------------------------------------
// Panel layout and drawing.

struct Margins {
  double left = 0.0;
  double top = 0.0;
  double right = 0.0;
  double bottom = 0.0;
};

constexpr double kColorBarGap = 12.0;
constexpr double kColorBarWidth = 12.0;

struct LegendLayout {
  double width = 0.0;
  double height = 0.0;
};

constexpr double kLegendRow = 17.0;
constexpr double kLegendSwatch = 24.0;
constexpr double kLegendPad = 7.0;

LegendLayout legend_size(const PanelData& panel, double max_text) {
  LegendLayout size;
  if (panel.legend_entries.empty() || panel.legend == LegendPlace::Hidden) return size;
  double widest = 0.0;
  for (const detail::LegendEntry& e : panel.legend_entries) {
    widest = std::max(widest, text_width(fit_text(e.text, kLegendFont, max_text), kLegendFont));
  }
  size.width = 2 * kLegendPad + kLegendSwatch + 6.0 + widest;
  size.height = 2 * kLegendPad + kLegendRow * static_cast<double>(panel.legend_entries.size()) - 4;
  return size;
}

const detail::HeatItem* first_heat_map(const PanelData& panel) {
  for (const detail::Item& item : panel.items) {
    if (const auto* heat = std::get_if<detail::HeatItem>(&item)) return heat;
  }
  return nullptr;
}

// Everything needed to draw a panel in its cell, decided before drawing.
struct PanelLayout {
  Box cell;
  Margins margins;
  Box plot;
  Axis x;
  Axis y;
  Axis color;  // colour bar scale, when there is a heat map
};

double vertical_margin_top(const PanelData& panel) {
  return panel.title.empty() ? 10.0 : 30.0;
}

double vertical_margin_bottom(const PanelData& panel) {
  if (!panel.axes) return 10.0;
  return 8.0 + kTickLength + kTickFont + 4.0 + (panel.x_label.empty() ? 0.0 : kAxisFont + 8.0);
}

std::pair<double, double> y_data_range(const PanelData& panel, const Bounds& bounds) {
  if (panel.y_range) return *panel.y_range;
  const double pad = has_heat_map(panel) ? 0.0 : 0.05;
  return resolve_range(bounds.y_min, bounds.y_max, pad);
}

std::pair<double, double> x_data_range(const PanelData& panel, const Bounds& bounds) {
  if (panel.x_range) return *panel.x_range;
  const double pad = panel.equal_aspect || has_markers(panel) ? 0.04 : 0.0;
  return resolve_range(bounds.x_min, bounds.x_max, pad);
}

double left_margin(const PanelData& panel, const Axis& y) {
  if (!panel.axes) return 10.0;
  return 10.0 + (panel.y_label.empty() ? 0.0 : kAxisFont + 8.0) + widest_tick(y) + kTickLength +
         4.0;
}

double right_margin(const PanelData& panel, double plot_height, Axis* color_axis) {
  double right = 14.0;
  if (const detail::HeatItem* heat = first_heat_map(panel)) {
    *color_axis =
        make_axis(resolve_range(heat->z_min, heat->z_max, 0.0), std::nullopt, plot_height, 45.0);
    right += kColorBarGap + kColorBarWidth + kTickLength + 4.0 + widest_tick(*color_axis) +
             (heat->value_label.empty() ? 0.0 : kAxisFont + 8.0);
  }
  if (panel.legend == LegendPlace::Right) {
    right += legend_size(panel, 220.0).width + 10.0;
  }
  return right;
}

// Widens one axis so that a data unit has the same length on both.
void make_equal_aspect(PanelLayout& layout, const PanelData& panel) {
  const double x_scale = layout.plot.width / (layout.x.max - layout.x.min);
  const double y_scale = layout.plot.height / (layout.y.max - layout.y.min);
  if (x_scale > y_scale) {
    const double span = layout.plot.width / y_scale;
    const double centre = 0.5 * (layout.x.min + layout.x.max);
    layout.x = make_axis({centre - span / 2, centre + span / 2}, panel.x_ticks, layout.plot.width,
                         kXTickSpacing);
  } else {
    const double span = layout.plot.height / x_scale;
    const double centre = 0.5 * (layout.y.min + layout.y.max);
    layout.y = make_axis({centre - span / 2, centre + span / 2}, panel.y_ticks, layout.plot.height,
                         kYTickSpacing);
  }
}

class PanelPainter {
 public:
  PanelPainter(const PanelData& panel, const PanelLayout& layout, std::size_t id)
      : panel_(panel), layout_(layout), prefix_("p" + std::to_string(id)) {}

  std::string paint() {
    out_ += "<g>\n";
    out_ += Tag("clipPath").set("id", prefix_ + "c").open();
    out_ += Tag("rect")
                .set("x", layout_.plot.left)
                .set("y", layout_.plot.top)
                .set("width", layout_.plot.width)
                .set("height", layout_.plot.height)
                .empty();
    out_ += "</clipPath>\n";
    if (panel_.axes) grid_lines();
    out_ += Tag("g").set("clip-path", "url(#" + prefix_ + "c)").open() + "\n";
    if (!panel_.view_shifts.empty()) open_moving_view();
    for (const detail::Item& item : panel_.items) {
      std::visit([this](const auto& i) { draw(i); }, item);
    }
    if (!panel_.view_shifts.empty()) out_ += "</g>\n";
    out_ += "</g>\n";
    if (panel_.axes) axes();
    titles();
    place_texts();
    if (const detail::HeatItem* heat = first_heat_map(panel_)) color_bar(*heat);
    legend();
    out_ += "</g>\n";
    return std::move(out_);
  }

 private:
  Point to_pixel(Point p) const {
    return {layout_.x.to_pixel(p.x, layout_.plot.left, layout_.plot.width, false),
            layout_.y.to_pixel(p.y, layout_.plot.top, layout_.plot.height, true)};
  }
  std::vector<Point> to_pixels(const std::vector<Point>& points) const {
    std::vector<Point> out;
    out.reserve(points.size());
    for (const Point& p : points)
      out.push_back(to_pixel(p));
    return out;
  }

  // An unfilled 1 px path: grid lines, axes, the colour bar's frame.
  void stroke_path(const std::string& d, Color color) {
    out_ += Tag("path")
                .set("d", d)
                .set("fill", "none")
                .set("stroke", color.hex())
                .set("stroke-width", 1.0)
                .empty();
  }

  // A caption turned to read bottom to top, centred on the plot area's height at `x`: the y
  // axis label, the colour bar's label.
  void vertical_caption(double x, std::string_view text) {
    const Box& plot = layout_.plot;
    const double y = plot.top + plot.height / 2;
    Tag tag("text");
    tag.set("transform", "translate(" + px(x) + "," + px(y) + ") rotate(-90)")
        .set("y", 0.35 * kAxisFont)
        .set("font-size", kAxisFont)
        .set("text-anchor", "middle")
        .set("fill", kInk.hex());
    out_ += tag.open() + escape_xml(fit_text(text, kAxisFont, plot.height)) + "</text>\n";
  }

  // A group inside the clip whose translation plays the view's shifts: the clip stays on the
  // plot area while the contents move under it.
  void open_moving_view() {
    const double x_scale = layout_.plot.width / (layout_.x.max - layout_.x.min);
    const double y_scale = layout_.plot.height / (layout_.y.max - layout_.y.min);
    const auto translation = [&](Point shift) {
      return px(-shift.x * x_scale) + "," + px(shift.y * y_scale);
    };
    std::string values;
    for (std::size_t f = 0; f < panel_.view_shifts.size(); ++f) {
      if (f) values += ';';
      values += translation(panel_.view_shifts[f]);
    }
    out_ += Tag("g")
                .set("transform", "translate(" + translation(panel_.view_shifts.front()) + ")")
                .open() +
            "\n";
    out_ += Tag("animateTransform")
                .set("attributeName", "transform")
                .set("type", "translate")
                .set("dur", format_number(panel_.view_period, 3) + "s")
                .set("repeatCount", "indefinite")
                .set("values", values)
                .empty();
  }

  void grid_lines() {
    std::string d;
    for (const double t : layout_.x.ticks) {
      const double x = to_pixel({t, layout_.y.min}).x;
      d += "M" + px(x) + "," + px(layout_.plot.top) + "V" + px(layout_.plot.bottom());
    }
    for (const double t : layout_.y.ticks) {
      const double y = to_pixel({layout_.x.min, t}).y;
      d += "M" + px(layout_.plot.left) + "," + px(y) + "H" + px(layout_.plot.right());
    }
    if (d.empty()) return;
    stroke_path(d, kGridLine);
  }

  void axes() {
    const Box& plot = layout_.plot;
    std::string d =
        "M" + px(plot.left) + "," + px(plot.top) + "V" + px(plot.bottom()) + "H" + px(plot.right());
    for (const double t : layout_.x.ticks) {
      d += "M" + px(to_pixel({t, 0}).x) + "," + px(plot.bottom()) + "v" + px(kTickLength);
    }
    for (const double t : layout_.y.ticks) {
      d += "M" + px(plot.left) + "," + px(to_pixel({0, t}).y) + "h" + px(-kTickLength);
    }
    stroke_path(d, kAxis);
    const TextStyle tick_style{.size = kTickFont, .color = kMutedInk};
    for (const double t : layout_.x.ticks) {
      out_ += text_element(to_pixel({t, 0}).x, plot.bottom() + kTickLength + 4 + kTickFont / 2,
                           tick_text(t, layout_.x.decimals), tick_style, false);
    }
    TextStyle y_style = tick_style;
    y_style.anchor = Anchor::End;
    for (const double t : layout_.y.ticks) {
      out_ += text_element(plot.left - kTickLength - 3, to_pixel({0, t}).y,
                           tick_text(t, layout_.y.decimals), y_style, false);
    }
  }

  void titles() {
    const Box& plot = layout_.plot;
    const double centre = plot.left + plot.width / 2;
    if (!panel_.title.empty()) {
      const std::string title = fit_text(panel_.title, kTitleFont, layout_.cell.width - 16);
      // Centred on the plot area unless that would push it out of the cell.
      const double half = text_width(title, kTitleFont) / 2;
      const double x =
          std::clamp(centre, layout_.cell.left + 8 + half, layout_.cell.right() - 8 - half);
      out_ += text_element(x, layout_.cell.top + 16, title,
                           {.size = kTitleFont, .color = kInk, .bold = true}, false);
    }
    if (!panel_.axes) return;
    if (!panel_.x_label.empty()) {
      out_ +=
          text_element(centre, plot.bottom() + kTickLength + 4 + kTickFont + 6 + kAxisFont / 2,
                       fit_text(panel_.x_label, kAxisFont, plot.width), {.size = kAxisFont}, false);
    }
    if (!panel_.y_label.empty()) {
      vertical_caption(layout_.cell.left + 10 + kAxisFont / 2, panel_.y_label);
    }
  }

  // Texts, then labels placed one by one where they overlap no earlier label.
  void place_texts() {
    const Box& plot = layout_.plot;
    for (const detail::Item& item : panel_.items) {
      const auto* text = std::get_if<detail::TextItem>(&item);
      if (!text) continue;
      const Point at = to_pixel(text->at);
      if (!finite(at)) continue;
      if (!text->avoid_overlap) {
        out_ += text_element(at.x, at.y, text->text, text->style, true);
        continue;
      }
      const double width = text_width(text->text, text->style.size);
      const double height = text->style.size * 1.2;
      Box box{at.x + text->style.dx, at.y + text->style.dy - height / 2, width, height};
      if (box.top < plot.top || box.bottom() > plot.bottom()) {  // no room: the other side
        box.top = at.y - text->style.dy - height / 2;
      }
      if (text->style.anchor == Anchor::Middle) box.left -= width / 2;
      if (text->style.anchor == Anchor::End) box.left -= width;
      box.left =
          std::clamp(box.left, plot.left + 2, std::max(plot.left + 2, plot.right() - 2 - width));
      box.top =
          std::clamp(box.top, plot.top + 1, std::max(plot.top + 1, plot.bottom() - 1 - height));
      // The nearest free spot, trying whole rows up and down and half widths sideways.
      struct Candidate {
        double distance;
        Box box;
      };
      std::vector<Candidate> candidates;
      const double row = height + 1.0;
      const double column = width / 2 + 3.0;
      for (int r = -5; r <= 5; ++r) {
        for (int c = -4; c <= 4; ++c) {
          Box candidate = box;
          candidate.top += r * row;
          candidate.left += c * column;
          if (candidate.top < plot.top || candidate.bottom() > plot.bottom() ||
              candidate.left < plot.left || candidate.right() > plot.right()) {
            continue;
          }
          candidates.push_back({std::hypot(r * row, c * column), candidate});
        }
      }
      std::stable_sort(
          candidates.begin(), candidates.end(),
          [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
      // Never on another label; off the lines too when that costs under three rows of travel.
      Box chosen = box;
      double best = kInf;
      for (const Candidate& candidate : candidates) {
        if (candidate.distance >= best) break;
        if (std::any_of(labels_.begin(), labels_.end(),
                        [&](const Box& b) { return b.overlaps(candidate.box); })) {
          continue;
        }
        const double score = candidate.distance + (crosses(candidate.box) ? 3 * row : 0.0);
        if (score < best) {
          best = score;
          chosen = candidate.box;
        }
      }
      labels_.push_back(chosen);
      TextStyle style = text->style;
      style.anchor = Anchor::Start;
      style.dx = 0;
      style.dy = 0;
      out_ += text_element(chosen.left, chosen.top + height / 2, text->text, style, true);
    }
  }

  // Whether any drawn line passes through the box.
  bool crosses(const Box& box) const {
    const auto segment_hits = [&](Point a, Point b) {
      // Liang-Barsky: clip the segment to the box; it hits when something is left.
      double t0 = 0.0;
      double t1 = 1.0;
      const double dx = b.x - a.x;
      const double dy = b.y - a.y;
      const double p[] = {-dx, dx, -dy, dy};
      const double q[] = {a.x - box.left, box.right() - a.x, a.y - box.top, box.bottom() - a.y};
      for (int k = 0; k < 4; ++k) {
        if (p[k] == 0.0) {
          if (q[k] < 0.0) return false;
        } else {
          const double t = q[k] / p[k];
          if (p[k] < 0.0) {
            t0 = std::max(t0, t);
          } else {
            t1 = std::min(t1, t);
          }
        }
      }
      return t0 <= t1;
    };
    for (const std::vector<Point>& line : strokes_) {
      for (std::size_t i = 0; i + 1 < line.size(); ++i) {
        if (segment_hits(line[i], line[i + 1])) return true;
      }
    }
    return false;
  }

  void draw(const detail::LineItem& line) {
    std::vector<std::vector<Point>> runs;
    for (const auto& run : line.runs) {
      std::vector<Point> pixels = to_pixels(run);
      runs.push_back(line.style.marker == Marker::None ? simplify(pixels, 0.1) : pixels);
    }
    if (runs.empty()) return;
    obstacles_.insert(obstacles_.end(), runs.begin(), runs.end());
    if (line.style.width > 0) strokes_.insert(strokes_.end(), runs.begin(), runs.end());
    Tag tag = runs.size() == 1 ? Tag("polyline") : Tag("path");
    if (runs.size() == 1) {
      tag.set("points", point_list(runs.front()));
    } else {
      tag.set("d", path_data(runs, false));
    }
    tag.set("fill", "none");
    set_stroke(tag, line.style, line.color);
    set_markers(tag, line.style, line.color);
    out_ += tag.empty();
  }

  void draw(const detail::FillItem& fill) {
    std::vector<std::vector<Point>> polygons;
    for (const auto& polygon : fill.polygons)
      polygons.push_back(simplify(to_pixels(polygon), 0.1));
    if (polygons.empty()) return;
    obstacles_.insert(obstacles_.end(), polygons.begin(), polygons.end());
    Tag tag("path");
    tag.set("d", path_data(polygons, true)).set("fill", fill.color.hex());
    if (fill.style.opacity < 1.0) tag.set("fill-opacity", format_number(fill.style.opacity, 3));
    if (fill.style.outline) {
      tag.set("stroke", fill.style.outline->hex()).set("stroke-width", 1.0);
    }
    out_ += tag.empty();
  }

  void draw(const detail::RuleItem& rule) {
    const Box& plot = layout_.plot;
    std::string d;
    if (rule.vertical) {
      const double x = to_pixel({rule.value, 0}).x;
      if (!std::isfinite(x)) return;
      d = "M" + px(x) + "," + px(plot.top) + "V" + px(plot.bottom());
      strokes_.push_back({{x, plot.top}, {x, plot.bottom()}});
    } else {
      const double y = to_pixel({0, rule.value}).y;
      if (!std::isfinite(y)) return;
      d = "M" + px(plot.left) + "," + px(y) + "H" + px(plot.right());
      strokes_.push_back({{plot.left, y}, {plot.right(), y}});
    }
    Tag tag("path");
    tag.set("d", d).set("fill", "none");
    set_stroke(tag, rule.style, rule.color);
    out_ += tag.empty();
  }

  void draw(const detail::TextItem&) {}  // drawn above everything, in place_texts()

  void draw(const detail::HeatItem& heat) {
    const Grid& grid = heat.grid;
    const double z_span = heat.z_max > heat.z_min ? heat.z_max - heat.z_min : 1.0;
    std::vector<std::uint8_t> rgba(grid.columns * grid.rows * 4, 0);
    for (std::size_t r = 0; r < grid.rows; ++r) {
      for (std::size_t c = 0; c < grid.columns; ++c) {
        const double v = grid.at(c, r);
        const std::size_t k = 4 * ((grid.rows - 1 - r) * grid.columns + c);  // PNG rows go down
        const Color color = std::isfinite(v) ? viridis((v - heat.z_min) / z_span) : kNoValue;
        rgba[k] = color.r;
        rgba[k + 1] = color.g;
        rgba[k + 2] = color.b;
        rgba[k + 3] = 255;
      }
    }
    // Pixel centres sit on the samples, so the image reaches half a cell past the grid; the
    // plot area clips it. Cells without a value are grey (opaque: smoothing toward transparent
    // pixels would fade into the background).
    const double half_x = 0.5 * (grid.x_max - grid.x_min) / static_cast<double>(grid.columns - 1);
    const double half_y = 0.5 * (grid.y_max - grid.y_min) / static_cast<double>(grid.rows - 1);
    const Point low = to_pixel({grid.x_min - half_x, grid.y_min - half_y});
    const Point high = to_pixel({grid.x_max + half_x, grid.y_max + half_y});
    out_ += Tag("image")
                .set("x", low.x)
                .set("y", high.y)
                .set("width", high.x - low.x)
                .set("height", low.y - high.y)
                .set("preserveAspectRatio", "none")
                .set("xlink:href",
                     "data:image/png;base64," + base64(encode_png(grid.columns, grid.rows, rgba)))
                .empty();
  }

  void draw(const detail::ContourItem& contour) {
    std::vector<std::vector<Point>> lines;
    for (const auto& line : contour.lines)
      lines.push_back(simplify(to_pixels(line), 0.1));
    if (lines.empty()) return;
    const std::string d = path_data(lines, false);
    if (contour.style.width > 0) {  // a pale halo keeps dark lines visible on dark colours
      out_ += Tag("path")
                  .set("d", d)
                  .set("fill", "none")
                  .set("stroke", "#ffffff")
                  .set("stroke-opacity", "0.25")
                  .set("stroke-width", contour.style.width + 1.0)
                  .set("stroke-linejoin", "round")
                  .empty();
    }
    Tag tag("path");
    tag.set("d", d).set("fill", "none");
    set_stroke(tag, contour.style, contour.color);
    out_ += tag.empty();
  }

  void draw(const detail::AnimatedItem& animated) {
    std::string values;
    for (std::size_t f = 0; f < animated.frames.size(); ++f) {
      if (f) values += ';';
      values += point_list(to_pixels(animated.frames[f]));
    }
    obstacles_.push_back(to_pixels(animated.frames.front()));
    strokes_.push_back(obstacles_.back());
    Tag tag("polyline");
    tag.set("points", point_list(to_pixels(animated.frames.front()))).set("fill", "none");
    set_stroke(tag, animated.style, animated.color);
    set_markers(tag, animated.style, animated.color);
    out_ += tag.open() + "\n";
    out_ += Tag("animate")
                .set("attributeName", "points")
                .set("dur", format_number(animated.period, 3) + "s")
                .set("repeatCount", "indefinite")
                .set("values", values)
                .empty();
    out_ += "</polyline>\n";
  }

  // Vertex markers through SVG <marker>, so they follow animated points too.
  void set_markers(Tag& tag, const LineStyle& style, Color color) {
    if (style.marker == Marker::None) return;
    const std::string id = prefix_ + "m" + std::to_string(markers_++);
    const double size = style.marker_size;
    std::string shape;
    if (style.marker == Marker::Circle) {
      shape = Tag("circle")
                  .set("cx", size / 2)
                  .set("cy", size / 2)
                  .set("r", size / 2)
                  .set("fill", color.hex())
                  .empty();
    } else {
      shape = Tag("rect").set("width", size).set("height", size).set("fill", color.hex()).empty();
    }
    out_ += Tag("marker")
                .set("id", id)
                .set("markerUnits", "userSpaceOnUse")
                .set("markerWidth", size)
                .set("markerHeight", size)
                .set("refX", size / 2)
                .set("refY", size / 2)
                .set("overflow", "visible")
                .open() +
            shape + "</marker>\n";
    const std::string url = "url(#" + id + ")";
    tag.set("marker-start", url).set("marker-mid", url).set("marker-end", url);
  }

  void color_bar(const detail::HeatItem& heat) {
    const Box& plot = layout_.plot;
    const Axis& scale = layout_.color;
    const double left = plot.right() + kColorBarGap;
    const std::string gradient = prefix_ + "g";
    out_ += Tag("linearGradient")
                .set("id", gradient)
                .set("x1", 0.0)
                .set("y1", 1.0)
                .set("x2", 0.0)
                .set("y2", 0.0)
                .open() +
            "\n";
    for (int i = 0; i <= 10; ++i) {
      const double t = i / 10.0;
      out_ += Tag("stop")
                  .set("offset", format_number(t, 2))
                  .set("stop-color", viridis(t).hex())
                  .empty();
    }
    out_ += "</linearGradient>\n";
    out_ += Tag("rect")
                .set("x", left)
                .set("y", plot.top)
                .set("width", kColorBarWidth)
                .set("height", plot.height)
                .set("fill", "url(#" + gradient + ")")
                .empty();
    const auto bar_y = [&](double v) { return scale.to_pixel(v, plot.top, plot.height, true); };
    // Contour levels as thin lines across the bar.
    std::string levels;
    for (const detail::Item& item : panel_.items) {
      if (const auto* contour = std::get_if<detail::ContourItem>(&item)) {
        for (const double level : contour->levels) {
          if (level <= scale.min || level >= scale.max) continue;
          levels += "M" + px(left) + "," + px(bar_y(level)) + "h" + px(kColorBarWidth);
        }
      }
    }
    if (!levels.empty()) {
      out_ += Tag("path")
                  .set("d", levels)
                  .set("stroke", "#ffffff")
                  .set("stroke-opacity", "0.8")
                  .set("stroke-width", 1.0)
                  .empty();
    }
    std::string d = "M" + px(left) + "," + px(plot.top) + "h" + px(kColorBarWidth) + "v" +
                    px(plot.height) + "h" + px(-kColorBarWidth) + "Z";
    for (const double t : scale.ticks) {
      d += "M" + px(left + kColorBarWidth) + "," + px(bar_y(t)) + "h" + px(kTickLength);
    }
    stroke_path(d, kAxis);
    TextStyle style{.size = kTickFont, .color = kMutedInk, .anchor = Anchor::Start};
    const double label_x = left + kColorBarWidth + kTickLength + 3;
    for (const double t : scale.ticks) {
      out_ += text_element(label_x, bar_y(t), tick_text(t, scale.decimals), style, false);
    }
    if (!heat.value_label.empty()) {
      vertical_caption(label_x + widest_tick(scale) + 6 + kAxisFont / 2, heat.value_label);
    }
  }

  // How much a legend box at `box` would hide: line vertices and labels under it.
  double coverage(const Box& box) const {
    double score = 0.0;
    for (const std::vector<Point>& run : obstacles_) {
      for (std::size_t i = 0; i < run.size(); ++i) {
        if (box.contains(run[i])) score += 1.0;
        if (i + 1 < run.size()) {  // long straight segments have few vertices: sample them
          const Point mid{(run[i].x + run[i + 1].x) / 2, (run[i].y + run[i + 1].y) / 2};
          if (box.contains(mid)) score += 1.0;
        }
      }
    }
    for (const Box& label : labels_) {
      if (label.overlaps(box)) score += 10.0;
    }
    return score;
  }

  void legend() {
    if (panel_.legend_entries.empty() || panel_.legend == LegendPlace::Hidden) return;
    const Box& plot = layout_.plot;
    const LegendLayout size = legend_size(
        panel_, panel_.legend == LegendPlace::Right ? 220.0 : std::max(40.0, plot.width - 60.0));
    const double inset = 8.0;
    const auto corner = [&](LegendPlace place) {
      const bool left = place == LegendPlace::TopLeft || place == LegendPlace::BottomLeft;
      const bool top = place == LegendPlace::TopLeft || place == LegendPlace::TopRight;
      return Box{left ? plot.left + inset : plot.right() - inset - size.width,
                 top ? plot.top + inset : plot.bottom() - inset - size.height, size.width,
                 size.height};
    };
    Box box;
    if (panel_.legend == LegendPlace::Right) {
      double right = plot.right() + 12.0;
      if (first_heat_map(panel_)) right = layout_.cell.right() - 14.0 - size.width;
      box = Box{right, plot.top, size.width, size.height};
    } else if (panel_.legend == LegendPlace::Best) {
      double best = kInf;
      for (const LegendPlace place : {LegendPlace::TopRight, LegendPlace::TopLeft,
                                      LegendPlace::BottomRight, LegendPlace::BottomLeft}) {
        const double score = coverage(corner(place));
        if (score < best) {
          best = score;
          box = corner(place);
        }
      }
    } else {
      box = corner(panel_.legend);
    }
    out_ += Tag("rect")
                .set("x", box.left)
                .set("y", box.top)
                .set("width", box.width)
                .set("height", box.height)
                .set("rx", 3.0)
                .set("fill", "#ffffff")
                .set("fill-opacity", "0.9")
                .set("stroke", "#cccccc")
                .set("stroke-width", 1.0)
                .empty();
    double y = box.top + kLegendPad + kLegendRow / 2 - 2;
    const double swatch_left = box.left + kLegendPad;
    for (const detail::LegendEntry& e : panel_.legend_entries) {
      if (e.filled) {
        Tag tag("rect");
        tag.set("x", swatch_left)
            .set("y", y - 5)
            .set("width", kLegendSwatch)
            .set("height", 10.0)
            .set("fill", e.color.hex());
        if (e.fill.opacity < 1.0) tag.set("fill-opacity", format_number(e.fill.opacity, 3));
        if (e.fill.outline) tag.set("stroke", e.fill.outline->hex()).set("stroke-width", 1.0);
        out_ += tag.empty();
      } else {
        Tag tag("path");
        tag.set("d", "M" + px(swatch_left) + "," + px(y) + "h" + px(kLegendSwatch))
            .set("fill", "none");
        set_stroke(tag, e.line, e.color);
        if (e.line.marker != Marker::None) {
          // One marker in the middle of the swatch.
          const double s = e.line.marker_size;
          out_ += tag.empty();
          Tag mark(e.line.marker == Marker::Circle ? "circle" : "rect");
          if (e.line.marker == Marker::Circle) {
            mark.set("cx", swatch_left + kLegendSwatch / 2).set("cy", y).set("r", s / 2);
          } else {
            mark.set("x", swatch_left + kLegendSwatch / 2 - s / 2)
                .set("y", y - s / 2)
                .set("width", s)
                .set("height", s);
          }
          out_ += mark.set("fill", e.color.hex()).empty();
        } else {
          out_ += tag.empty();
        }
      }
      out_ += text_element(
          swatch_left + kLegendSwatch + 6, y,
          fit_text(e.text, kLegendFont, box.width - 2 * kLegendPad - kLegendSwatch - 6 + 0.5),
          {.size = kLegendFont, .anchor = Anchor::Start}, false);
      y += kLegendRow;
    }
  }

  const PanelData& panel_;
  const PanelLayout& layout_;
  std::string prefix_;
  std::string out_;
  std::vector<Box> labels_;
  std::vector<std::vector<Point>> obstacles_;  // pixel polylines, for the legend's placement
  std::vector<std::vector<Point>> strokes_;    // pixel lines that labels keep off
  int markers_ = 0;
};

}  // namespace

// ---------------------------------------------------------------------------------------------
// Public free functions.

std::string Color::hex() const {
  static constexpr std::string_view kHex = "0123456789abcdef";
  std::string text = "#";
  for (const std::uint8_t channel : {r, g, b}) {
    text += kHex[channel >> 4];
    text += kHex[channel & 15];
  }
  return text;
}

Color palette_color(std::size_t index) {
  // Okabe & Ito (2008) without yellow, which is too light for lines on white.
  static constexpr std::array<Color, 7> kPalette = {{{0, 114, 178},
                                                     {213, 94, 0},
                                                     {0, 158, 115},
                                                     {204, 121, 167},
                                                     {230, 159, 0},
                                                     {86, 180, 233},
                                                     {0, 0, 0}}};
  return kPalette[index % kPalette.size()];
}

Color viridis(double t) {
  static constexpr std::array<Color, 11> kStops = {{{68, 1, 84},
                                                    {72, 36, 117},
                                                    {65, 68, 135},
                                                    {53, 95, 141},
                                                    {42, 120, 142},
                                                    {33, 145, 140},
                                                    {34, 168, 132},
                                                    {68, 191, 112},
                                                    {122, 209, 81},
                                                    {189, 223, 38},
                                                    {253, 231, 37}}};
  if (!(t > 0.0)) return kStops.front();
  if (t >= 1.0) return kStops.back();
  const double position = t * static_cast<double>(kStops.size() - 1);
  const auto index = static_cast<std::size_t>(position);
  const double f = position - static_cast<double>(index);
  const Color& a = kStops[index];
  const Color& b = kStops[index + 1];
  const auto mix = [f](std::uint8_t from, std::uint8_t to) {
    return static_cast<std::uint8_t>(std::lround(from + f * (to - from)));
  };
  return {mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b)};
}

std::string escape_xml(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    const std::optional<char32_t> c = next_code_point(text, i);
    if (!c || !allowed_in_xml(*c)) {
      out += "\xEF\xBF\xBD";  // U+FFFD
      continue;
    }
    switch (*c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        append_utf8(out, *c);
    }
  }
  return out;
}

std::string format_number(double value, int decimals) {
  return common::number_text(value, decimals);
}

std::vector<double> nice_ticks(double min, double max, int target_count) {
  if (!std::isfinite(min) || !std::isfinite(max) || !(max > min)) return {};
  const double raw = (max - min) / std::max(1, target_count - 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double normalised = raw / magnitude;
  double step = 10.0;
  if (normalised < 1.5) {
    step = 1.0;
  } else if (normalised < 2.25) {
    step = 2.0;
  } else if (normalised < 3.5) {
    step = 2.5;
  } else if (normalised < 7.5) {
    step = 5.0;
  }
  step *= magnitude;
  const double slack = 1e-9 * (max - min);
  const auto first = static_cast<long long>(std::ceil((min - slack) / step));
  const auto last = static_cast<long long>(std::floor((max + slack) / step));
  std::vector<double> ticks;
  // k * step carries binary rounding (7 * 0.1 > 0.7); snap to the step's decimals.
  const double scale = std::pow(10.0, std::max(0.0, 1.0 - std::floor(std::log10(step))));
  for (long long k = first; k <= last && ticks.size() < 1000; ++k) {
    double t = static_cast<double>(k) * step;
    if (scale > 1.0) t = std::round(t * scale) / scale;
    if (std::abs(t) < 1e-12 * step) t = 0.0;
    ticks.push_back(t);
  }
  return ticks;
}

double text_width(std::string_view text, double font_size) {
  double em = 0.0;
  std::size_t i = 0;
  while (i < text.size())
    em += code_point_width(next_code_point(text, i).value_or(0xFFFD));
  return em * font_size;
}

double Grid::x(std::size_t column) const {
  if (columns < 2) return x_min;
  return x_min + static_cast<double>(column) * (x_max - x_min) / static_cast<double>(columns - 1);
}

double Grid::y(std::size_t row) const {
  if (rows < 2) return y_min;
  return y_min + static_cast<double>(row) * (y_max - y_min) / static_cast<double>(rows - 1);
}

// ---------------------------------------------------------------------------------------------
// Panel.

Panel::Panel() : data_(std::make_unique<detail::PanelData>()) {}
Panel::~Panel() = default;

Color Panel::take_color(const std::optional<Color>& wanted) {
  if (wanted) return *wanted;
  return palette_color(data_->colors_used++);
}

Panel& Panel::title(std::string text) {
  data_->title = std::move(text);
  return *this;
}
Panel& Panel::x_label(std::string text) {
  data_->x_label = std::move(text);
  return *this;
}
Panel& Panel::y_label(std::string text) {
  data_->y_label = std::move(text);
  return *this;
}

namespace {
void check_range(double min, double max) {
  if (!std::isfinite(min) || !std::isfinite(max) || !(max > min)) {
    throw std::invalid_argument("svg axis range: needs finite min < max, got " +
                                format_number(min, 6) + " .. " + format_number(max, 6));
  }
}
}  // namespace

Panel& Panel::x_range(double min, double max) {
  check_range(min, max);
  data_->x_range = {min, max};
  return *this;
}
Panel& Panel::y_range(double min, double max) {
  check_range(min, max);
  data_->y_range = {min, max};
  return *this;
}
Panel& Panel::x_ticks(std::vector<double> values) {
  data_->x_ticks = std::move(values);
  return *this;
}
Panel& Panel::y_ticks(std::vector<double> values) {
  data_->y_ticks = std::move(values);
  return *this;
}
Panel& Panel::equal_aspect() {
  data_->equal_aspect = true;
  return *this;
}
Panel& Panel::hide_axes() {
  data_->axes = false;
  return *this;
}
Panel& Panel::legend(LegendPlace place) {
  data_->legend = place;
  return *this;
}

Panel& Panel::line(std::span<const double> x, std::span<const double> y, LineStyle style,
                   std::string label) {
  if (x.size() != y.size()) {
    throw std::invalid_argument("svg line: " + std::to_string(x.size()) + " x values but " +
                                std::to_string(y.size()) + " y values");
  }
  std::vector<Point> points(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    points[i] = {x[i], y[i]};
  return line(points, style, std::move(label));
}

Panel& Panel::line(std::span<const Point> points, LineStyle style, std::string label) {
  const Color color = take_color(style.color);
  if (!label.empty()) data_->legend_entries.push_back({false, style, {}, color, std::move(label)});
  data_->items.emplace_back(detail::LineItem{finite_runs(points), style, color});
  return *this;
}

Panel& Panel::band(std::span<const double> x, std::span<const double> lower,
                   std::span<const double> upper, FillStyle style, std::string label) {
  if (x.size() != lower.size() || x.size() != upper.size()) {
    throw std::invalid_argument("svg band: x, lower and upper need the same number of values");
  }
  std::vector<std::vector<Point>> polygons;
  std::size_t i = 0;
  while (i < x.size()) {
    const auto usable = [&](std::size_t k) {
      return std::isfinite(x[k]) && std::isfinite(lower[k]) && std::isfinite(upper[k]);
    };
    if (!usable(i)) {
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end < x.size() && usable(end))
      ++end;
    std::vector<Point> polygon;
    for (std::size_t k = i; k < end; ++k)
      polygon.push_back({x[k], upper[k]});
    for (std::size_t k = end; k-- > i;)
      polygon.push_back({x[k], lower[k]});
    polygons.push_back(std::move(polygon));
    i = end;
  }
  const Color color = take_color(style.color);
  if (!label.empty()) data_->legend_entries.push_back({true, {}, style, color, std::move(label)});
  data_->items.emplace_back(detail::FillItem{std::move(polygons), style, color});
  return *this;
}

Panel& Panel::polygon(std::span<const Point> points, FillStyle style, std::string label) {
  std::vector<Point> polygon;
  for (const Point& p : points) {
    if (finite(p)) polygon.push_back(p);
  }
  const Color color = take_color(style.color);
  if (!label.empty()) data_->legend_entries.push_back({true, {}, style, color, std::move(label)});
  std::vector<std::vector<Point>> polygons;
  if (polygon.size() >= 2) polygons.push_back(std::move(polygon));
  data_->items.emplace_back(detail::FillItem{std::move(polygons), style, color});
  return *this;
}

Panel& Panel::vertical_line(double x, LineStyle style, std::string label) {
  const Color color = take_color(style.color);
  if (!label.empty()) data_->legend_entries.push_back({false, style, {}, color, std::move(label)});
  data_->items.emplace_back(detail::RuleItem{true, x, style, color});
  return *this;
}

Panel& Panel::horizontal_line(double y, LineStyle style, std::string label) {
  const Color color = take_color(style.color);
  if (!label.empty()) data_->legend_entries.push_back({false, style, {}, color, std::move(label)});
  data_->items.emplace_back(detail::RuleItem{false, y, style, color});
  return *this;
}

Panel& Panel::text(double x, double y, std::string text, TextStyle style) {
  data_->items.emplace_back(detail::TextItem{{x, y}, std::move(text), style, false});
  return *this;
}

Panel& Panel::label(double x, double y, std::string text, TextStyle style) {
  data_->items.emplace_back(detail::TextItem{{x, y}, std::move(text), style, true});
  return *this;
}

Panel& Panel::heat_map(const Grid& grid, std::string value_label) {
  check_grid(grid);
  const auto [lo, hi] = value_range(grid);
  data_->items.emplace_back(detail::HeatItem{grid, std::move(value_label), lo, hi});
  return *this;
}

Panel& Panel::contours(const Grid& grid, std::span<const double> levels, LineStyle style) {
  check_grid(grid);
  std::vector<double> chosen(levels.begin(), levels.end());
  if (chosen.empty()) {
    const auto [lo, hi] = value_range(grid);
    for (const double t : nice_ticks(lo, hi, 8)) {
      if (t > lo && t < hi) chosen.push_back(t);
    }
  }
  std::vector<std::vector<Point>> lines;
  for (const double level : chosen) {
    for (auto& l : contour_lines(grid, level))
      lines.push_back(std::move(l));
  }
  const Color color = take_color(style.color);
  data_->items.emplace_back(detail::ContourItem{std::move(chosen), std::move(lines), style, color});
  return *this;
}

Panel& Panel::animated_line(std::span<const std::vector<Point>> frames, double period_seconds,
                            LineStyle style, std::string label) {
  if (frames.empty() || !(period_seconds > 0.0) || !std::isfinite(period_seconds)) {
    throw std::invalid_argument("svg animated line: needs frames and a positive period");
  }
  for (const std::vector<Point>& frame : frames) {
    if (frame.size() != frames.front().size()) {
      throw std::invalid_argument("svg animated line: every frame needs the same number of points");
    }
    if (!std::all_of(frame.begin(), frame.end(), finite)) {
      throw std::invalid_argument("svg animated line: points must be finite");
    }
  }
  const Color color = take_color(style.color);
  if (!label.empty()) data_->legend_entries.push_back({false, style, {}, color, std::move(label)});
  data_->items.emplace_back(detail::AnimatedItem{
      std::vector<std::vector<Point>>(frames.begin(), frames.end()), period_seconds, style, color});
  return *this;
}

Panel& Panel::animated_view(std::span<const Point> shifts, double period_seconds) {
  if (shifts.empty() || !(period_seconds > 0.0) || !std::isfinite(period_seconds)) {
    throw std::invalid_argument("svg animated view: needs shifts and a positive period");
  }
  if (!std::all_of(shifts.begin(), shifts.end(), finite)) {
    throw std::invalid_argument("svg animated view: shifts must be finite");
  }
  data_->view_shifts.assign(shifts.begin(), shifts.end());
  data_->view_period = period_seconds;
  return *this;
}

// ---------------------------------------------------------------------------------------------
// Figure.

Figure::Figure(std::string title) : title_(std::move(title)) {}

Figure& Figure::subtitle(std::string text) {
  subtitles_.push_back(std::move(text));
  return *this;
}

Figure& Figure::columns(int count) {
  if (count < 1) throw std::invalid_argument("svg figure: needs at least one column");
  columns_ = count;
  return *this;
}

Figure& Figure::panel_size(double width, double height) {
  if (!(width >= 100.0) || !(height >= 80.0)) {
    throw std::invalid_argument("svg figure: panels need at least 100 x 80 pixels");
  }
  cell_width_ = width;
  cell_height_ = height;
  return *this;
}

Figure& Figure::note(std::string text) {
  notes_.push_back(std::move(text));
  return *this;
}

Panel& Figure::add_panel(int column_span) {
  if (column_span < 1) throw std::invalid_argument("svg figure: column span must be at least 1");
  panels_.push_back(std::unique_ptr<Panel>(new Panel()));
  spans_.push_back(column_span);
  return *panels_.back();
}

std::string Figure::svg() const {
  constexpr double kOuter = 10.0;
  const double width = 2 * kOuter + columns_ * cell_width_;
  const double text_room = width - 2 * kOuter - 12;

  // Header lines.
  std::vector<std::string> subtitle_lines;
  for (const std::string& s : subtitles_) {
    for (std::string& line : wrap_text(s, 12.0, text_room))
      subtitle_lines.push_back(line);
  }
  double header = title_.empty() ? 6.0 : 36.0;
  header += 17.0 * static_cast<double>(subtitle_lines.size());
  if (!subtitle_lines.empty() || !title_.empty()) header += 6.0;

  // Cells: left to right, wrapping rows; a span never exceeds the row.
  struct Place {
    int row;
    int column;
    int span;
  };
  std::vector<Place> places;
  int row = 0;
  int column = 0;
  for (const int wanted : spans_) {
    const int span = std::min(wanted, columns_);
    if (column + span > columns_) {
      ++row;
      column = 0;
    }
    places.push_back({row, column, span});
    column += span;
  }
  const int rows = places.empty() ? 0 : places.back().row + 1;

  // Layouts: vertical margins shared along a row, left margins down a column and right margins
  // down the column a panel ends in, so that the plot areas line up.
  std::vector<PanelLayout> layouts(panels_.size());
  std::vector<Bounds> bounds(panels_.size());
  std::vector<double> row_top(static_cast<std::size_t>(rows), 0.0);
  std::vector<double> row_bottom(static_cast<std::size_t>(rows), 0.0);
  for (std::size_t i = 0; i < panels_.size(); ++i) {
    const PanelData& panel = *panels_[i]->data_;
    const auto r = static_cast<std::size_t>(places[i].row);
    row_top[r] = std::max(row_top[r], vertical_margin_top(panel));
    row_bottom[r] = std::max(row_bottom[r], vertical_margin_bottom(panel));
    bounds[i] = data_bounds(panel);
  }
  std::vector<double> column_left(static_cast<std::size_t>(columns_), 0.0);
  for (std::size_t i = 0; i < panels_.size(); ++i) {
    const PanelData& panel = *panels_[i]->data_;
    PanelLayout& layout = layouts[i];
    const auto r = static_cast<std::size_t>(places[i].row);
    layout.cell = {kOuter + places[i].column * cell_width_, header + places[i].row * cell_height_,
                   places[i].span * cell_width_, cell_height_};
    layout.margins.top = row_top[r];
    layout.margins.bottom = row_bottom[r];
    const double plot_height = cell_height_ - row_top[r] - row_bottom[r];
    layout.y = make_axis(y_data_range(panel, bounds[i]), panel.y_ticks, plot_height, kYTickSpacing);
    const auto c = static_cast<std::size_t>(places[i].column);
    column_left[c] = std::max(column_left[c], left_margin(panel, layout.y));
  }
  std::vector<double> column_right(static_cast<std::size_t>(columns_), 0.0);
  for (std::size_t i = 0; i < panels_.size(); ++i) {
    const PanelData& panel = *panels_[i]->data_;
    PanelLayout& layout = layouts[i];
    const double plot_height = cell_height_ - layout.margins.top - layout.margins.bottom;
    const auto c = static_cast<std::size_t>(places[i].column + places[i].span - 1);
    column_right[c] = std::max(column_right[c], right_margin(panel, plot_height, &layout.color));
  }
  for (std::size_t i = 0; i < panels_.size(); ++i) {
    const PanelData& panel = *panels_[i]->data_;
    PanelLayout& layout = layouts[i];
    layout.margins.left = column_left[static_cast<std::size_t>(places[i].column)];
    const double plot_height = cell_height_ - layout.margins.top - layout.margins.bottom;
    layout.margins.right =
        column_right[static_cast<std::size_t>(places[i].column + places[i].span - 1)];
    layout.plot = {layout.cell.left + layout.margins.left, layout.cell.top + layout.margins.top,
                   std::max(10.0, layout.cell.width - layout.margins.left - layout.margins.right),
                   std::max(10.0, plot_height)};
    layout.x =
        make_axis(x_data_range(panel, bounds[i]), panel.x_ticks, layout.plot.width, kXTickSpacing);
    if (panel.equal_aspect) make_equal_aspect(layout, panel);
  }

  // Footer.
  std::vector<std::string> note_lines;
  for (const std::string& n : notes_) {
    for (std::string& line : wrap_text(n, 11.0, text_room))
      note_lines.push_back(line);
  }
  const double body_bottom = header + rows * cell_height_;
  const double height =
      body_bottom +
      (note_lines.empty() ? 8.0 : 10.0 + 15.0 * static_cast<double>(note_lines.size()));

  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += Tag("svg")
             .set("xmlns", "http://www.w3.org/2000/svg")
             .set("xmlns:xlink", "http://www.w3.org/1999/xlink")
             .set("width", width)
             .set("height", height)
             .set("viewBox", "0 0 " + px(width) + " " + px(height))
             .set("font-family", kFont)
             .set("font-size", 11.0)
             .open() +
         "\n";
  if (!title_.empty()) out += "<title>" + escape_xml(title_) + "</title>\n";
  out += Tag("rect").set("width", width).set("height", height).set("fill", "#ffffff").empty();
  double y = 6.0;
  if (!title_.empty()) {
    out += text_element(kOuter + 6, 22, fit_text(title_, 17.0, text_room),
                        {.size = 17.0, .anchor = Anchor::Start, .bold = true}, false);
    y = 36.0;
  }
  for (const std::string& line : subtitle_lines) {
    out += text_element(kOuter + 6, y + 8, line,
                        {.size = 12.0, .color = kMutedInk, .anchor = Anchor::Start}, false);
    y += 17.0;
  }
  for (std::size_t i = 0; i < panels_.size(); ++i) {
    out += PanelPainter(*panels_[i]->data_, layouts[i], i).paint();
  }
  y = body_bottom + 10.0;
  for (const std::string& line : note_lines) {
    out += text_element(kOuter + 6, y + 6, line,
                        {.size = 11.0, .color = kMutedInk, .anchor = Anchor::Start}, false);
    y += 15.0;
  }
  out += "</svg>\n";
  return out;
}

void Figure::save(const std::filesystem::path& path) const {
  io::write_file(path, svg());
}

std::string stack_figures(const std::vector<const Figure*>& figures) {
  double width = 0.0;
  double height = 0.0;
  std::string body;
  for (const Figure* const& figure : figures) {
    std::string text = figure->svg();
    // Our own documents: an XML declaration, then <svg ... width="W" height="H" ...>.
    const std::size_t root = text.find("<svg ");
    const auto attribute = [&text, root](const std::string& name) {
      const std::size_t at = text.find(" " + name + "=\"", root);
      return std::stod(text.substr(at + name.size() + 3));
    };
    const double w = attribute("width");
    const double h = attribute("height");
    text = text.substr(root);
    // Element ids (clip paths, gradients) are unique per figure only: prefix them.
    const std::string prefix = "f" + std::to_string(&figure - figures.data()) + "-";
    for (const auto& [from, to] : {std::pair<std::string, std::string>{"id=\"", "id=\"" + prefix},
                                   {"url(#", "url(#" + prefix},
                                   {"href=\"#", "href=\"#" + prefix}}) {
      for (std::size_t at = text.find(from); at != std::string::npos;
           at = text.find(from, at + to.size())) {
        text.replace(at, from.size(), to);
      }
    }
    text.insert(5, "x=\"0\" y=\"" + format_number(height) + "\" ");
    body += text;
    width = std::max(width, w);
    height += h;
  }
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" "
         "xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"" +
         format_number(width) + "\" height=\"" + format_number(height) + "\" viewBox=\"0 0 " +
         format_number(width) + " " + format_number(height) + "\">\n" + body + "</svg>\n";
}

}  // namespace fuzzygait::plot::svg

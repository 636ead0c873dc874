#include "fuzzygait/io/walk_csv.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "csv.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/fuzzy/term.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::io {
namespace {

constexpr const char* kPointNames[] = {"hip", "knee", "ankle", "heel", "ball", "tip"};
constexpr const char* kSidePrefix[] = {"l", "r"};
// Optional, after the others: 1 on every row of captured motion (eval::Motion::captured).
constexpr const char* kCapturedColumn = "captured";

std::vector<std::string> header() {
  std::vector<std::string> h = {"time", "pelvis_x", "pelvis_y", "pelvis_tilt"};
  for (const char* s : kSidePrefix) {
    for (const char* j : {"hip", "knee", "ankle", "toe"})
      h.push_back(std::string(s) + "_" + j);
  }
  h.push_back("l_contact");
  h.push_back("r_contact");
  for (const char* s : kSidePrefix) {
    for (const char* p : kPointNames) {
      h.push_back(std::string(s) + "_" + p + "_x");
      h.push_back(std::string(s) + "_" + p + "_y");
    }
  }
  return h;
}

std::array<rig::Point*, 6> point_fields(rig::LegPoints& p) {
  return {&p.hip, &p.knee, &p.ankle, &p.heel, &p.ball, &p.tip};
}

void append(std::string& line, double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  if (!line.empty()) line += ',';
  line += buffer;
}

// Why the value of the header()'s column k cannot be, or nullptr: a wrong unit (radians where
// degrees belong) or a broken file, which would measure as nonsense.
const char* out_of_range(std::size_t k, double value) {
  constexpr std::size_t kFirstAngle = 3;     // pelvis_tilt, then the joints
  constexpr std::size_t kFirstContact = 12;  // l_contact, r_contact
  if (k >= kFirstAngle && k < kFirstContact) {
    return std::abs(value) > 360.0 ? "is beyond a turn (angles are in degrees)" : nullptr;
  }
  if (k == kFirstContact || k == kFirstContact + 1) {
    return value == 0.0 || value == 1.0 ? nullptr : "is neither 0 nor 1";
  }
  if (k > 0) {  // positions
    return std::abs(value) > terrain::Terrain::kMaxCoordinate
               ? "lies more than 1000 km from the origin (positions are in metres)"
               : nullptr;
  }
  return nullptr;
}

}  // namespace

void write_walk_csv(std::ostream& out, const eval::Motion& motion) {
  std::string line;
  for (const std::string& h : header())
    line += (line.empty() ? "" : ",") + h;
  if (motion.captured) line += std::string(",") + kCapturedColumn;
  out << line << "\n";
  for (const eval::Frame& f : motion.frames) {
    line.clear();
    append(line, f.time, 6);
    append(line, f.pose.pelvis.x, 6);
    append(line, f.pose.pelvis.y, 6);
    append(line, rig::degrees(f.pose.pelvis_tilt), 4);
    for (const rig::LegAngles& a : f.pose.legs) {
      for (double v : {a.hip, a.knee, a.ankle, a.toe})
        append(line, rig::degrees(v), 4);
    }
    line += f.contact[0] ? ",1" : ",0";
    line += f.contact[1] ? ",1" : ",0";
    for (rig::LegPoints p : f.points) {
      for (const rig::Point* q : point_fields(p)) {
        append(line, q->x, 6);
        append(line, q->y, 6);
      }
    }
    if (motion.captured) line += ",1";
    out << line << "\n";
  }
}

eval::Motion read_walk_csv(std::istream& in, std::string_view source) {
  const std::string where(source);
  std::string line;
  if (!std::getline(in, line)) throw fuzzy::ParseError(where, 1, "the file is empty");
  const std::vector<std::string> columns = detail::split_csv_line(line);
  const std::vector<std::size_t> wanted = detail::required_columns(columns, header(), where);
  // Where the optional `captured` column is; columns.size() when there is none.
  const auto captured_column = static_cast<std::size_t>(
      std::find(columns.begin(), columns.end(), kCapturedColumn) - columns.begin());
  eval::Motion motion;
  std::vector<int> frame_lines;  // the line each frame was read from
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> cells = detail::split_csv_line(line);
    std::vector<double> v;
    v.reserve(wanted.size());
    for (std::size_t k = 0; k < wanted.size(); ++k) {
      const std::size_t c = wanted[k];
      const std::optional<double> value =
          c < cells.size() ? fuzzy::parse_scalar(cells[c]) : std::nullopt;
      if (!value || !std::isfinite(*value)) {
        throw fuzzy::ParseError(where, number,
                                "column '" + columns[c] + "': '" +
                                    (c < cells.size() ? cells[c] : std::string()) +
                                    "' is not a finite number");
      }
      if (const char* wrong = out_of_range(k, *value)) {
        throw fuzzy::ParseError(where, number,
                                "column '" + columns[c] + "': " + cells[c] + " " + wrong);
      }
      v.push_back(*value);
    }
    eval::Frame f;
    std::size_t k = 0;
    f.time = v[k++];
    f.pose.pelvis = {v[k], v[k + 1]};
    k += 2;
    f.pose.pelvis_tilt = rig::radians(v[k++]);
    for (rig::LegAngles& a : f.pose.legs) {
      for (double* field : {&a.hip, &a.knee, &a.ankle, &a.toe})
        *field = rig::radians(v[k++]);
    }
    f.contact = {v[k] == 1.0, v[k + 1] == 1.0};
    k += 2;
    for (rig::LegPoints& p : f.points) {
      for (rig::Point* q : point_fields(p)) {
        q->x = v[k++];
        q->y = v[k++];
      }
    }
    if (captured_column < columns.size()) {
      const std::size_t c = captured_column;
      const std::string cell = c < cells.size() ? cells[c] : std::string();
      if (cell != "0" && cell != "1") {
        throw fuzzy::ParseError(
            where, number,
            std::string("column '") + kCapturedColumn + "': '" + cell + "' is neither 0 nor 1");
      }
      if (!motion.frames.empty() && (cell == "1") != motion.captured) {
        throw fuzzy::ParseError(where, number,
                                std::string("column '") + kCapturedColumn + "': " + cell +
                                    " differs from the rows before (the whole motion is "
                                    "captured or not)");
      }
      motion.captured = cell == "1";
    }
    if (!motion.frames.empty() && !(f.time > motion.frames.back().time)) {
      throw fuzzy::ParseError(
          where, number,
          "column 'time': " + cells[wanted[0]] + " does not come after the row before it");
    }
    motion.frames.push_back(f);
    frame_lines.push_back(number);
  }
  if (motion.frames.size() < 2) throw fuzzy::ParseError(where, number, "fewer than two frames");
  // The CSV holds no segment lengths: measure them on the first frame's left leg.
  const rig::LegPoints& p = motion.frames.front().points[0];
  auto distance = [](rig::Point a, rig::Point b) { return std::hypot(b.x - a.x, b.y - a.y); };
  rig::Segments& s = motion.segments;
  s.thigh = distance(p.hip, p.knee);
  s.shank = distance(p.knee, p.ankle);
  s.toe = distance(p.ball, p.tip);
  const double sole = distance(p.heel, p.ball);
  if (sole > 0.0) {
    // The ankle over the sole line: its height, and where its foot falls between heel and ball.
    const double ux = (p.ball.x - p.heel.x) / sole;
    const double uy = (p.ball.y - p.heel.y) / sole;
    const double along = (p.ankle.x - p.heel.x) * ux + (p.ankle.y - p.heel.y) * uy;
    s.heel = along;
    s.ball = sole - along;
    s.ankle_height = std::abs((p.ankle.x - p.heel.x) * uy - (p.ankle.y - p.heel.y) * ux);
  }
  try {
    rig::validate(s);
  } catch (const std::invalid_argument& e) {
    throw fuzzy::ParseError(
        where, 2, std::string("the leg's points do not make a plausible rig: ") + e.what());
  }
  // Evaluation takes the frames as evenly spaced: a dropped or doubled frame would shift every
  // timing figure after it. Each gap is held to the median gap; times are written to the
  // microsecond, so that much rounding passes.
  std::vector<double> gaps;
  for (std::size_t i = 1; i < motion.frames.size(); ++i)
    gaps.push_back(motion.frames[i].time - motion.frames[i - 1].time);
  std::vector<double> sorted = gaps;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                   sorted.end());
  const double median = sorted[sorted.size() / 2];
  for (std::size_t i = 0; i < gaps.size(); ++i) {
    if (std::abs(gaps[i] - median) > 0.01 * median + 2e-6) {
      throw fuzzy::ParseError(where, frame_lines[i + 1],
                              "column 'time': frames are not evenly spaced (" +
                                  common::number_text(gaps[i]) + " s after the row before, " +
                                  common::number_text(median) + " s between most)");
    }
  }
  const double span = motion.frames.back().time - motion.frames.front().time;
  motion.fps = static_cast<double>(motion.frames.size() - 1) / span;
  return motion;
}

void write_terrain_csv(std::ostream& out, const terrain::Terrain& terrain, double x0, double x1) {
  out << "x,y\n";
  for (const rig::Point& p : terrain.profile(x0, x1)) {
    std::string line;
    append(line, p.x, 6);
    append(line, p.y, 6);
    out << line << "\n";
  }
}

terrain::Terrain read_terrain_csv(std::istream& in, std::string_view source) {
  const std::string where(source);
  std::string line;
  if (!std::getline(in, line) ||
      detail::split_csv_line(line) != std::vector<std::string>{"x", "y"}) {
    throw fuzzy::ParseError(where, 1, "expected the header 'x,y'");
  }
  std::vector<rig::Point> points;
  std::vector<int> point_lines;  // the line each point was read from
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> cells = detail::split_csv_line(line);
    if (cells.size() != 2) throw fuzzy::ParseError(where, number, "expected two values 'x,y'");
    double xy[2] = {0.0, 0.0};
    for (std::size_t c = 0; c < 2; ++c) {
      const std::string column = std::string("column '") + (c == 0 ? "x" : "y") + "': ";
      const std::optional<double> value = fuzzy::parse_scalar(cells[c]);
      if (!value)
        throw fuzzy::ParseError(where, number, column + "'" + cells[c] + "' is not a number");
      if (!std::isfinite(*value)) {
        throw fuzzy::ParseError(where, number, column + cells[c] + " is not a finite number");
      }
      if (std::abs(*value) > terrain::Terrain::kMaxCoordinate) {
        throw fuzzy::ParseError(
            where, number, column + cells[c] + " lies more than 1000 km from the origin (metres)");
      }
      xy[c] = *value;
    }
    if (!points.empty() && !(xy[0] > points.back().x)) {
      throw fuzzy::ParseError(where, number,
                              "column 'x': " + cells[0] +
                                  " does not come after the x before it (x must increase along "
                                  "the profile)");
    }
    points.push_back({xy[0], xy[1]});
    point_lines.push_back(number);
  }
  if (points.size() < 2) {
    throw fuzzy::ParseError(where, number, "the profile needs at least two points");
  }
  // What is left (a wall taller than a leg climbs) is named by the line of its point.
  if (const auto fault = terrain::Terrain::find_fault(points)) {
    throw fuzzy::ParseError(where, point_lines[fault->point], fault->reason);
  }
  return terrain::Terrain::polyline(std::move(points));
}

}  // namespace fuzzygait::io

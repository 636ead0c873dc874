// The walk CSV and terrain CSV: the exact column names the file contract asks for, values that
// come back as written, and errors that name the file, the line and the column.
#include "fuzzygait/io/walk_csv.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "support/walks.hpp"

namespace fuzzygait {
namespace {

using ::testing::HasSubstr;

eval::Motion short_walk(const terrain::Terrain& ground) {
  gait::Walker walker = test::make_walker(ground);
  return eval::record(walker, 1.0, 60.0);
}

std::string csv_of(const eval::Motion& m) {
  std::ostringstream out;
  io::write_walk_csv(out, m);
  return out.str();
}

// The message of the ParseError that `read` throws on `text`, or "" if it reads.
template <class Read>
std::string parse_error(const std::string& text, Read read) {
  std::istringstream in(text);
  try {
    read(in);
  } catch (const fuzzy::ParseError& e) {
    return e.what();
  }
  return "";
}

std::string read_error(const std::string& text) {
  return parse_error(text, [](std::istream& in) { io::read_walk_csv(in, "walk.csv"); });
}

TEST(WalkCsv, HeaderHasTheContractsColumnsInOrder) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  const std::string csv = csv_of(short_walk(ground));
  std::string expected =
      "time,pelvis_x,pelvis_y,pelvis_tilt,l_hip,l_knee,l_ankle,l_toe,r_hip,r_knee,r_ankle,r_toe,"
      "l_contact,r_contact";
  for (const char* side : {"l", "r"}) {
    for (const char* point : {"hip", "knee", "ankle", "heel", "ball", "tip"}) {
      expected += std::string(",") + side + "_" + point + "_x," + side + "_" + point + "_y";
    }
  }
  EXPECT_EQ(csv.substr(0, csv.find('\n')), expected);
}

TEST(WalkCsv, ReadsBackWhatItWrote) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  const eval::Motion m = short_walk(ground);
  std::istringstream in(csv_of(m));
  const eval::Motion back = io::read_walk_csv(in, "walk.csv");
  ASSERT_EQ(back.frames.size(), m.frames.size());
  EXPECT_NEAR(back.fps, 60.0, 1e-3);
  // Angles are written to 1e-4 degrees, positions and time to 1e-6 (m, s).
  for (std::size_t i = 0; i < m.frames.size(); ++i) {
    const eval::Frame& a = m.frames[i];
    const eval::Frame& b = back.frames[i];
    EXPECT_NEAR(a.time, b.time, 5e-7);
    EXPECT_NEAR(a.pose.pelvis.x, b.pose.pelvis.x, 5e-7);
    EXPECT_NEAR(a.pose.pelvis.y, b.pose.pelvis.y, 5e-7);
    EXPECT_NEAR(rig::degrees(a.pose.pelvis_tilt), rig::degrees(b.pose.pelvis_tilt), 5e-5);
    for (std::size_t s = 0; s < 2; ++s) {
      const rig::LegAngles& p = a.pose.legs[s];
      const rig::LegAngles& q = b.pose.legs[s];
      EXPECT_NEAR(rig::degrees(p.hip), rig::degrees(q.hip), 5e-5);
      EXPECT_NEAR(rig::degrees(p.knee), rig::degrees(q.knee), 5e-5);
      EXPECT_NEAR(rig::degrees(p.ankle), rig::degrees(q.ankle), 5e-5);
      EXPECT_NEAR(rig::degrees(p.toe), rig::degrees(q.toe), 5e-5);
      EXPECT_EQ(a.contact[s], b.contact[s]);
      EXPECT_NEAR(a.points[s].tip.x, b.points[s].tip.x, 5e-7);
      EXPECT_NEAR(a.points[s].heel.y, b.points[s].heel.y, 5e-7);
    }
  }
  // The segment lengths, measured on the points, are the walker's to the CSV's precision.
  const rig::Segments s = rig::segments_from_stature(1.75);
  EXPECT_NEAR(back.segments.thigh, s.thigh, 1e-5);
  EXPECT_NEAR(back.segments.shank, s.shank, 1e-5);
  EXPECT_NEAR(back.segments.ankle_height, s.ankle_height, 1e-5);
  EXPECT_NEAR(back.segments.heel, s.heel, 1e-5);
  EXPECT_NEAR(back.segments.ball, s.ball, 1e-5);
  EXPECT_NEAR(back.segments.toe, s.toe, 1e-5);
  // Written again, the same bytes.
  EXPECT_EQ(csv_of(back), csv_of(m));
}

TEST(WalkCsv, ExtraColumnsAndTheirOrderDoNotMatter) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  const std::string csv = csv_of(short_walk(ground));
  // A spreadsheet added a column in front: every value moves one cell to the right.
  std::string shifted;
  std::istringstream lines(csv);
  std::string line;
  bool header = true;
  while (std::getline(lines, line)) {
    shifted += (header ? "note," : "x,") + line + "\n";
    header = false;
  }
  std::istringstream a(csv);
  std::istringstream b(shifted);
  EXPECT_EQ(csv_of(io::read_walk_csv(a, "a")), csv_of(io::read_walk_csv(b, "b")));
}

TEST(WalkCsv, ErrorsNameTheFileLineAndColumn) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  const std::string csv = csv_of(short_walk(ground));
  const std::size_t header_end = csv.find('\n');
  const std::string header = csv.substr(0, header_end);

  EXPECT_THAT(read_error(""), HasSubstr("walk.csv:1"));
  EXPECT_THAT(read_error(""), HasSubstr("empty"));

  std::string missing = csv;
  missing.replace(missing.find("r_knee,"), 7, "r_kne,");
  EXPECT_THAT(read_error(missing), HasSubstr("walk.csv:1"));
  EXPECT_THAT(read_error(missing), HasSubstr("missing column 'r_knee'"));

  // The third data row (line 4) with a word where l_knee's number should be.
  std::vector<std::string> rows;
  std::istringstream lines(csv);
  std::string line;
  while (std::getline(lines, line))
    rows.push_back(line);
  std::string broken;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    std::string row = rows[i];
    if (i == 3) {
      std::size_t at = 0;
      for (int comma = 0; comma < 5; ++comma)
        at = row.find(',', at) + 1;  // l_knee is the sixth column
      row.replace(at, row.find(',', at) - at, "bent");
    }
    broken += row + "\n";
  }
  EXPECT_THAT(read_error(broken), HasSubstr("walk.csv:4"));
  EXPECT_THAT(read_error(broken), HasSubstr("column 'l_knee': 'bent' is not a finite number"));

  std::string nan = broken;
  nan.replace(nan.find("bent"), 4, "nan");
  EXPECT_THAT(read_error(nan), HasSubstr("'nan' is not a finite number"));
  // Numbers in the wrong unit or no state at all: each named by line and column.
  std::string turns = broken;
  turns.replace(turns.find("bent"), 4, "-400");
  EXPECT_THAT(
      read_error(turns),
      HasSubstr("walk.csv:4: column 'l_knee': -400 is beyond a turn (angles are in degrees)"));
  turns.replace(turns.find("-400"), 4, "-360");
  EXPECT_EQ(read_error(turns), "");
  std::string contact = rows[0] + "\n";
  for (std::size_t i = 1; i < rows.size(); ++i) {
    std::string row = rows[i];
    if (i == 2) {
      std::vector<std::string> cells;
      std::istringstream split(row);
      for (std::string cell; std::getline(split, cell, ',');)
        cells.push_back(cell);
      cells[13] = "0.5";  // r_contact
      cells[37] = "1e7";  // r_tip_y
      row.clear();
      for (const std::string& cell : cells)
        row += (row.empty() ? "" : ",") + cell;
    }
    contact += row + "\n";
  }
  EXPECT_THAT(read_error(contact),
              HasSubstr("walk.csv:3: column 'r_contact': 0.5 is neither 0 nor 1"));
  contact.replace(contact.find(",0.5,"), 5, ",1,");
  EXPECT_THAT(
      read_error(contact),
      HasSubstr("walk.csv:3: column 'r_tip_y': 1e7 lies more than 1000 km from the origin"));

  EXPECT_THAT(read_error(header + "\n" + rows[1] + "\n"), HasSubstr("fewer than two frames"));
  // Two rows of the same time, rows out of order, a dropped frame: each named by its line.
  EXPECT_THAT(read_error(header + "\n" + rows[1] + "\n" + rows[1] + "\n"),
              HasSubstr("walk.csv:3: column 'time': 0.000000 does not come after the row before"));
  std::string swapped = header + "\n";
  std::string dropped = header + "\n";
  for (std::size_t i = 1; i < rows.size(); ++i) {
    swapped += rows[i == 5 ? 6 : i == 6 ? 5 : i] + "\n";
    if (i != 20) dropped += rows[i] + "\n";
  }
  EXPECT_THAT(read_error(swapped), HasSubstr("walk.csv:7: column 'time'"));
  EXPECT_THAT(read_error(dropped), HasSubstr("walk.csv:21: column 'time': frames are not evenly"));
  // A row cut short names the first column it lacks.
  EXPECT_THAT(read_error(header + "\n" + rows[1] + "\n" + rows[2].substr(0, 20) + "\n"),
              HasSubstr("walk.csv:3"));
}

TEST(TerrainCsv, RoundTripAndErrors) {
  const terrain::Terrain stairs =
      terrain::Terrain::polyline({{0.0, 0.0}, {1.0, 0.0}, {1.001, 0.17}, {1.3, 0.17}});
  std::ostringstream out;
  io::write_terrain_csv(out, stairs, -1.0, 2.0);
  EXPECT_EQ(out.str(),
            "x,y\n-1.000000,0.000000\n0.000000,0.000000\n1.000000,0.000000\n"
            "1.001000,0.170000\n1.300000,0.170000\n2.000000,0.170000\n");
  std::istringstream in(out.str());
  const terrain::Terrain back = io::read_terrain_csv(in, "t.csv");
  for (double x : {-0.5, 0.5, 1.0005, 1.2, 1.9})
    EXPECT_NEAR(back.height(x), stairs.height(x), 1e-9) << x;

  auto error = [](const std::string& text) {
    return parse_error(text, [](std::istream& s) { io::read_terrain_csv(s, "t.csv"); });
  };
  EXPECT_THAT(error("a,b\n0,0\n1,0\n"), HasSubstr("t.csv:1"));
  EXPECT_THAT(error("x,y\n0,0\n1\n"), HasSubstr("t.csv:3"));
  EXPECT_THAT(error("x,y\n0,0\n1,up\n2,0\n"), HasSubstr("t.csv:3"));
  // A point that is not finite, or x going back, is named by its own line.
  EXPECT_THAT(error("x,y\n0,0\n1,inf\n2,0\n3,0\n"), HasSubstr("t.csv:3"));
  EXPECT_THAT(error("x,y\n0,0\n1,0\n0.5,0\n3,0\n"), HasSubstr("t.csv:4"));
  EXPECT_THAT(error("x,y\n0,0\n"), HasSubstr("at least two points"));
  // Heights of 1e300 would make every contact figure nonsense: the ground ends at 1000 km.
  EXPECT_THAT(error("x,y\n0,0\n1,1e300\n"),
              HasSubstr("t.csv:3: column 'y': 1e300 lies more than 1000 km from the origin"));
  // Each bad value names its column; a wall, the line of its top.
  EXPECT_THAT(error("x,y\n0,0\nabc,1\n"), HasSubstr("t.csv:3: column 'x': 'abc' is not a number"));
  EXPECT_THAT(error("x,y\n0,0\n1,nan\n"), HasSubstr("t.csv:3: column 'y': nan is not a finite"));
  EXPECT_THAT(error("x,y\n0,0\n1,0\n1,0.2\n"),
              HasSubstr("t.csv:4: column 'x': 1 does not come after the x before it"));
  EXPECT_THAT(error("x,y\n0,0\n1,0\n1.001,0.4\n2,0.4\n3,0.4\n"),
              HasSubstr("t.csv:4: a wall 0.4 m high at x = 1.001 is taller than a leg climbs"));
  EXPECT_THROW(terrain::Terrain::polyline({{0.0, 0.0}, {2e6, 0.0}}), std::invalid_argument);
  EXPECT_NO_THROW(terrain::Terrain::polyline({{-1e6, -1e6}, {1e6, 1e6}}));
}

}  // namespace
}  // namespace fuzzygait

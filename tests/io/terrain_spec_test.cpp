// The --terrain SPEC: each form gives the ground the library's constructors give, and each
// mistake an error naming the option and the part at fault.
#include "fuzzygait/io/terrain_spec.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace fuzzygait::io {
namespace {

using terrain::Terrain;
using ::testing::HasSubstr;
using ::testing::StartsWith;

std::uint64_t bits(double x) {
  return std::bit_cast<std::uint64_t>(x);
}

// The same ground to the bit: the same points.
void expect_same_ground(const Terrain& a, const Terrain& b, const std::string& what) {
  ASSERT_EQ(a.points().size(), b.points().size()) << what;
  for (std::size_t i = 0; i < a.points().size(); ++i) {
    EXPECT_EQ(bits(a.points()[i].x), bits(b.points()[i].x)) << what << " point " << i;
    EXPECT_EQ(bits(a.points()[i].y), bits(b.points()[i].y)) << what << " point " << i;
  }
}

std::string spec_error(const std::string& spec, const std::string& option = "--terrain") {
  try {
    terrain_from_spec(spec, option);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

std::filesystem::path profile_file(const std::string& name, const std::string& text) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "fuzzygait_terrain_spec";
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / name;
  std::ofstream(path) << text;
  return path;
}

TEST(TerrainSpec, EachFormGivesTheLibrarysGround) {
  using Piece = Terrain::Piece;
  expect_same_ground(terrain_from_spec("flat"), Terrain::sequence({}), "flat");
  EXPECT_EQ(bits(terrain_from_spec("flat").height(12.0)), bits(0.0));
  EXPECT_EQ(bits(terrain_from_spec("flat:3").height(12.0)), bits(0.0));
  expect_same_ground(terrain_from_spec("slope:8"), Terrain::ramp(8.0), "slope:8");
  expect_same_ground(terrain_from_spec("ramp:8"), Terrain::ramp(8.0), "ramp:8");
  expect_same_ground(terrain_from_spec("slope:-12.5"), Terrain::ramp(-12.5), "slope:-12.5");
  expect_same_ground(terrain_from_spec("stairs:0.17:0.28:10"), Terrain::stairs(0.17, 0.28, 10),
                     "stairs");
  expect_same_ground(terrain_from_spec("stairs:-0.17:0.28:10"), Terrain::stairs(-0.17, 0.28, 10),
                     "stairs down");
  const Piece chain[] = {Terrain::ramp_piece(8.0), Terrain::stairs_piece(0.17, 0.28, 6),
                         Terrain::flat_piece()};
  expect_same_ground(terrain_from_spec("slope:8+stairs:0.17:0.28:6+flat"), Terrain::sequence(chain),
                     "chain");
  const Piece lengths[] = {Terrain::flat_piece(2.5), Terrain::ramp_piece(-10.0, 1.5),
                           Terrain::flat_piece(0.5), Terrain::stairs_piece(0.15, 0.3, 3)};
  expect_same_ground(terrain_from_spec("flat:2.5+slope:-10:1.5+flat:0.5+stairs:0.15:0.3:3"),
                     Terrain::sequence(lengths), "lengths");
  // The heights a reader expects: a 10 deg slope from x = 1, stairs from x = 1.
  EXPECT_NEAR(terrain_from_spec("slope:10").height(3.0),
              2.0 * std::tan(10.0 * std::numbers::pi / 180.0), 1e-12);
  EXPECT_NEAR(terrain_from_spec("stairs:0.17:0.28:10").height(1.0 + 0.28 * 9 + 0.1), 1.7, 1e-9);
  EXPECT_NEAR(terrain_from_spec("stairs:0.17:0.28:10+stairs:-0.17:0.28:10").height(30.0), 0.0,
              1e-9);
}

TEST(TerrainSpec, AProfileAloneLiesWhereItsFilePutsItAndInAChainFollowsOn) {
  const std::filesystem::path kerb =
      profile_file("kerb.csv", "x,y\n-2,0.1\n2,0.1\n2.001,0.25\n4,0.25\n");
  const Terrain alone = terrain_from_spec("profile:" + kerb.string());
  expect_same_ground(
      alone, Terrain::polyline({{-2.0, 0.1}, {2.0, 0.1}, {2.001, 0.25}, {4.0, 0.25}}), "alone");
  const Terrain chained = terrain_from_spec("slope:5:2+profile:" + kerb.string() + "+flat");
  const double top = 2.0 * std::tan(5.0 * std::numbers::pi / 180.0);
  EXPECT_NEAR(chained.height(3.0), top, 1e-12);  // the ramp ends at x = 3
  // The kerb's first point moved there: its riser at 3 + 4 m.
  EXPECT_NEAR(chained.height(6.9), top, 1e-12);
  EXPECT_NEAR(chained.height(7.1), top + 0.15, 1e-9);
  EXPECT_NEAR(chained.height(50.0), top + 0.15, 1e-9);
}

TEST(TerrainSpec, ErrorsNameTheOptionThePartAndTheField) {
  EXPECT_EQ(spec_error("stairs:0.3:0.28:6"),
            "--terrain: 'stairs:0.3:0.28:6': rise must be between 0.05 and 0.25 m (-0.25 to "
            "-0.05 going down), got 0.3");
  EXPECT_EQ(spec_error("slope:8+stairs:0.17:0.5:6"),
            "--terrain: 'stairs:0.17:0.5:6': tread must be between 0.2 and 0.4 m, got 0.5");
  EXPECT_EQ(spec_error("stairs:0.17:0.28:0"),
            "--terrain: 'stairs:0.17:0.28:0': count must be between 1 and 200 steps, got 0");
  EXPECT_EQ(spec_error("slope:30"),
            "--terrain: 'slope:30': angle must be between -25 and 25 deg, got 30");
  EXPECT_EQ(spec_error("flat+slope:-26"),
            "--terrain: 'slope:-26': angle must be between -25 and 25 deg, got -26");
  EXPECT_THAT(spec_error("slope:8:0+flat"),
              StartsWith("--terrain: 'slope:8:0': length must be between 0.01 and 10000 m"));
  EXPECT_THAT(spec_error("flat:-1+slope:3"), StartsWith("--terrain: 'flat:-1': length must be"));
  // Unknown kinds, missing and extra fields.
  EXPECT_THAT(spec_error("stair:0.17:0.28:6"),
              StartsWith("--terrain: 'stair:0.17:0.28:6': unknown kind 'stair' (flat, "));
  EXPECT_THAT(spec_error("hill"), StartsWith("--terrain: 'hill': unknown kind 'hill'"));
  EXPECT_EQ(spec_error("stairs:0.17:0.28"),
            "--terrain: 'stairs:0.17:0.28': missing COUNT (stairs:RISE:TREAD:COUNT)");
  EXPECT_EQ(spec_error("stairs"), "--terrain: 'stairs': missing RISE (stairs:RISE:TREAD:COUNT)");
  EXPECT_EQ(spec_error("slope"), "--terrain: 'slope': missing DEG (slope:DEG[:LENGTH])");
  EXPECT_EQ(spec_error("slope:8:4:2"),
            "--terrain: 'slope:8:4:2': an extra field '2' (slope:DEG[:LENGTH])");
  EXPECT_EQ(spec_error("flat:1:2"), "--terrain: 'flat:1:2': an extra field '2' (flat[:LENGTH])");
  EXPECT_EQ(spec_error("stairs:0.17:0.28:6:1"),
            "--terrain: 'stairs:0.17:0.28:6:1': an extra field '1' (stairs:RISE:TREAD:COUNT)");
  // Numbers that are not.
  EXPECT_EQ(spec_error("slope:abc"), "--terrain: 'slope:abc': angle 'abc' is not a number");
  EXPECT_EQ(spec_error("slope:"), "--terrain: 'slope:': angle '' is not a number");
  EXPECT_EQ(spec_error("slope:nan"), "--terrain: 'slope:nan': angle 'nan' is not a finite number");
  EXPECT_EQ(spec_error("stairs:inf:0.28:6"),
            "--terrain: 'stairs:inf:0.28:6': rise 'inf' is not a finite number");
  EXPECT_EQ(spec_error("stairs:0.17:0.28:6.5"),
            "--terrain: 'stairs:0.17:0.28:6.5': count '6.5' is not a whole number");
  EXPECT_EQ(spec_error("stairs:0.17:0.28x:6"),
            "--terrain: 'stairs:0.17:0.28x:6': tread '0.28x' is not a number");
  EXPECT_EQ(spec_error("slope: 8"), "--terrain: 'slope: 8': angle ' 8' is not a number");
  // Empty specs and parts.
  EXPECT_THAT(spec_error(""), StartsWith("--terrain: empty"));
  EXPECT_EQ(spec_error("slope:8++flat"), "--terrain: 'slope:8++flat': part 2 is empty");
  EXPECT_EQ(spec_error("slope:8+"), "--terrain: 'slope:8+': part 2 is empty");
  // The option is the caller's.
  EXPECT_THAT(spec_error("slope:99", "--ground"), StartsWith("--ground: 'slope:99': angle"));
}

TEST(TerrainSpec, BadProfilesNameTheFileLineAndField) {
  EXPECT_EQ(spec_error("profile:"), "--terrain: 'profile:': missing FILE (profile:FILE)");
  EXPECT_EQ(spec_error("profile"), "--terrain: 'profile': missing FILE (profile:FILE)");
  const std::string absent = (std::filesystem::path(::testing::TempDir()) / "no_such.csv").string();
  EXPECT_EQ(spec_error("profile:" + absent),
            "--terrain: 'profile:" + absent + "': " + absent + ": cannot open the file");
  const std::string folder = std::filesystem::path(::testing::TempDir()).string();
  EXPECT_THAT(spec_error("profile:" + folder), HasSubstr("is a directory, not a file"));
  const std::string back = profile_file("back.csv", "x,y\n0,0\n1,0\n0.5,0.1\n").string();
  EXPECT_EQ(spec_error("flat+profile:" + back),
            "--terrain: 'profile:" + back + "': " + back +
                ":4: column 'x': 0.5 does not come after the x before it (x must increase along "
                "the profile)");
  const std::string nan = profile_file("nan.csv", "x,y\n0,0\n1,nan\n").string();
  EXPECT_EQ(spec_error("profile:" + nan), "--terrain: 'profile:" + nan + "': " + nan +
                                              ":3: column 'y': nan is not a finite number");
  const std::string word = profile_file("word.csv", "x,y\n0,0\nabc,1\n").string();
  EXPECT_THAT(spec_error("profile:" + word),
              HasSubstr(word + ":3: column 'x': 'abc' is not a number"));
  const std::string header = profile_file("header.csv", "0,0\n1,0\n").string();
  EXPECT_THAT(spec_error("profile:" + header), HasSubstr(header + ":1: expected the header 'x,y'"));
  const std::string wall = profile_file("wall.csv", "x,y\n0,0\n1,0\n1.001,0.5\n2,0.5\n").string();
  EXPECT_THAT(spec_error("profile:" + wall),
              HasSubstr(wall + ":4: a wall 0.5 m high at x = 1.001 is taller than a leg climbs"));
  // Pieces that meet in a wall: the profile ends in a riser, the stairs begin with one.
  const std::string riser = profile_file("riser.csv", "x,y\n0,0\n0.5,0\n0.501,0.2\n").string();
  EXPECT_THAT(spec_error("profile:" + riser + "+stairs:0.17:0.28:3"),
              StartsWith("--terrain: 'profile:" + riser +
                         "+stairs:0.17:0.28:3': terrain piece 2 (stairs): a wall 0.37 m high"));
}

}  // namespace
}  // namespace fuzzygait::io

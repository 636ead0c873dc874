#include "fuzzygait/terrain/terrain.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace fuzzygait::terrain {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;
using ::testing::ThrowsMessage;

std::uint64_t bits(double x) {
  return std::bit_cast<std::uint64_t>(x);
}

using Piece = Terrain::Piece;

double tan_degrees(double degrees) {
  return std::tan(degrees * std::numbers::pi / 180.0);
}

// The message a call throws as std::invalid_argument, or "" when it does not throw.
template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

// The walker's kerb: level, a slope up, level, a step down, level.
Terrain kerb() {
  return Terrain::polyline({{-10.0, 0.0}, {2.0, 0.0}, {4.0, 0.5}, {5.0, 0.5}, {5.001, 0.3}});
}

TEST(Terrain, HeightsInterpolateBetweenPointsAndStayLevelBeyondTheEnds) {
  const Terrain t = kerb();
  EXPECT_DOUBLE_EQ(t.height(-20.0), 0.0);
  EXPECT_DOUBLE_EQ(t.height(0.0), 0.0);
  EXPECT_DOUBLE_EQ(t.height(3.0), 0.25);
  EXPECT_DOUBLE_EQ(t.height(3.5), 0.375);
  EXPECT_DOUBLE_EQ(t.height(4.5), 0.5);
  EXPECT_NEAR(t.height(5.0005), 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(t.height(9.0), 0.3);
  // At a point itself, its own height.
  EXPECT_DOUBLE_EQ(t.height(2.0), 0.0);
  EXPECT_DOUBLE_EQ(t.height(4.0), 0.5);
}

TEST(Terrain, SlopesAreEachSegmentsAngleAndLevelBeyondTheEnds) {
  const Terrain t = kerb();
  EXPECT_DOUBLE_EQ(t.slope(-20.0), 0.0);
  EXPECT_DOUBLE_EQ(t.slope(0.0), 0.0);
  EXPECT_DOUBLE_EQ(t.slope(3.0), std::atan2(0.5, 2.0));
  EXPECT_DOUBLE_EQ(t.slope(4.5), 0.0);
  EXPECT_NEAR(t.slope(5.0005), std::atan2(-0.2, 0.001), 1e-12);
  EXPECT_DOUBLE_EQ(t.slope(9.0), 0.0);
}

// Level ground answers without searching its segments (the walker asks several times a time
// step): the same bits as a search would give, a NaN x still NaN.
TEST(Terrain, LevelGroundGivesTheSearchsBits) {
  const double y = 0.1;
  const Terrain level = Terrain::polyline({{-5.0, y}, {-1.0, y}, {0.5, y}, {7.0, y}});
  // The same ground with one far point a hair higher answers by searching its segments.
  const Terrain searched = Terrain::polyline(
      {{-5.0, y}, {-1.0, y}, {0.5, y}, {7.0, y}, {1000.0, std::nextafter(y, 1.0)}});
  for (double x : {-100.0, -5.0, -4.999, -1.0, 0.0, 0.25, 0.5, 6.999, 7.0, 9.0}) {
    EXPECT_EQ(bits(level.height(x)), bits(y)) << x;
    EXPECT_EQ(bits(searched.height(x)), bits(y)) << x;
    EXPECT_EQ(bits(level.slope(x)), bits(0.0)) << x;  // +0, not -0
    // (Past x = 7 the searched ground rises by its hair.)
    if (x < 7.0) {
      EXPECT_EQ(bits(level.slope(x)), bits(searched.slope(x))) << x;
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(std::isnan(level.height(nan)));
  EXPECT_EQ(bits(level.slope(nan)), bits(0.0));
  EXPECT_EQ(bits(level.height(inf)), bits(y));
  EXPECT_EQ(bits(level.height(-inf)), bits(y));
  EXPECT_EQ(bits(level.slope(-inf)), bits(0.0));
  // Ends at the same height with a bump between them is not level.
  const Terrain bump = Terrain::polyline({{-1.0, 0.0}, {0.0, 0.2}, {1.0, 0.0}});
  EXPECT_DOUBLE_EQ(bump.height(0.0), 0.2);
  EXPECT_DOUBLE_EQ(bump.height(0.5), 0.1);
  EXPECT_DOUBLE_EQ(bump.slope(0.5), std::atan2(-0.2, 1.0));
  EXPECT_TRUE(std::isnan(Terrain::flat().height(nan)));
  EXPECT_EQ(bits(Terrain::flat().height(123.0)), bits(0.0));
  // Zeros of both signs are not the same bits: such ground is searched, each segment giving its
  // own zero.
  const Terrain signed_zeros = Terrain::polyline({{-1.0, -0.0}, {0.0, 0.0}, {1.0, -0.0}});
  EXPECT_EQ(bits(signed_zeros.height(-0.5)), bits(-0.0));
  EXPECT_EQ(bits(signed_zeros.height(0.5)), bits(0.0));
}

TEST(Terrain, ManySegmentsAreFound) {
  // Stairs of 200 steps, 0.3 m deep and 0.17 m high, risers 1 mm wide.
  std::vector<Point> points{{-1.0, 0.0}};
  for (int i = 0; i < 200; ++i) {
    points.push_back({0.3 * i, 0.17 * i});
    points.push_back({0.3 * i + 0.001, 0.17 * (i + 1)});
  }
  const Terrain stairs = Terrain::polyline(points);
  for (int i = 0; i < 199; ++i) {
    EXPECT_NEAR(stairs.height(0.3 * i + 0.15), 0.17 * (i + 1), 1e-12) << i;
    EXPECT_NEAR(stairs.slope(0.3 * i + 0.15), 0.0, 1e-12) << i;
    EXPECT_GT(stairs.slope(0.3 * i + 0.0005), 1.5) << i;  // a riser, nearly vertical
  }
}

TEST(Terrain, ProfileKeepsTheCornersBetweenItsEnds) {
  const std::vector<Point> p = kerb().profile(1.0, 4.5);
  ASSERT_EQ(p.size(), 4u);
  EXPECT_DOUBLE_EQ(p[0].x, 1.0);
  EXPECT_DOUBLE_EQ(p[1].x, 2.0);
  EXPECT_DOUBLE_EQ(p[2].y, 0.5);
  EXPECT_DOUBLE_EQ(p[3].x, 4.5);
}

TEST(Terrain, BadPolylinesGetClearErrors) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(
      [] {
        Terrain::polyline({{0.0, 0.0}});
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("at least two points")));
  EXPECT_THAT(
      [&] {
        Terrain::polyline({{0.0, 0.0}, {1.0, nan}});
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("terrain point 1 is not finite")));
  EXPECT_THAT(
      [] {
        Terrain::polyline({{0.0, 0.0}, {2e6, 0.0}});
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("1000 km")));
  EXPECT_THAT(
      [] {
        Terrain::polyline({{0.0, 0.0}, {1.0, 0.0}, {1.0, 0.2}});
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("terrain point 2: x must increase")));
}

TEST(Terrain, ARampRisesAtItsAngleFromItsStartForEver) {
  const Terrain up = Terrain::ramp(10.0);
  EXPECT_EQ(bits(up.height(-3.0)), bits(0.0));
  EXPECT_EQ(bits(up.height(1.0)), bits(0.0));
  EXPECT_NEAR(up.height(3.0), 2.0 * tan_degrees(10.0), 1e-12);
  EXPECT_NEAR(up.height(1001.0), 1000.0 * tan_degrees(10.0), 1e-9);
  EXPECT_NEAR(up.slope(2.0), 10.0 * std::numbers::pi / 180.0, 1e-12);
  EXPECT_EQ(bits(up.slope(0.5)), bits(0.0));
  // Downhill, and from another start.
  const Terrain down = Terrain::ramp(-20.0, 2.5);
  EXPECT_EQ(bits(down.height(2.5)), bits(0.0));
  EXPECT_NEAR(down.height(4.5), -2.0 * tan_degrees(20.0), 1e-12);
  EXPECT_NEAR(down.slope(4.0), -20.0 * std::numbers::pi / 180.0, 1e-12);
  // A ramp is one run with the level ground before it.
  ASSERT_EQ(up.runs().size(), 1u);
  EXPECT_EQ(up.run_at(0.0), 0u);
  EXPECT_EQ(up.run_at(50.0), 0u);
  // A ramp of 0 degrees is level ground.
  EXPECT_EQ(bits(Terrain::ramp(0.0).height(7.0)), bits(0.0));
}

TEST(Terrain, AnyStartAndAngleGivesARampToTheEndOfTheGround) {
  // The last ramp ends where the ground does (1000 km); rounding must not put it past.
  for (double start : {-999.9, -3.3, 0.1, 1.1, 7.77, 123.456, 999.99}) {
    for (double degrees : {-25.0, -13.7, -0.1, 0.3, 8.0, 19.9, 25.0}) {
      const std::string error = error_of([&] { Terrain::ramp(degrees, start); });
      EXPECT_EQ(error, "") << start << " " << degrees;
    }
  }
  const Piece ramps[] = {Terrain::ramp_piece(25.0, 1e4), Terrain::ramp_piece(25.0)};
  EXPECT_EQ(error_of([&] { Terrain::sequence(ramps, 0.7); }), "");
}

// Stairs 0.17 x 0.28 m, 10 steps from x = 1: risers 1 mm wide at 1 + 0.28 k.
TEST(Terrain, StairsHaveATreadEveryTreadDepthAndEndInALanding) {
  const Terrain t = Terrain::stairs(0.17, 0.28, 10);
  EXPECT_EQ(bits(t.height(0.999)), bits(0.0));
  EXPECT_EQ(bits(t.height(1.0)), bits(0.0));  // the foot of the first riser
  for (int k = 0; k < 10; ++k) {
    const double riser = 1.0 + 0.28 * k;
    // Just before the riser, the tread below; just after its top, the tread above.
    EXPECT_NEAR(t.height(riser - 0.0005), 0.17 * k, 1e-9) << k;
    EXPECT_NEAR(t.height(riser + Terrain::kRiserWidth + 0.0005), 0.17 * (k + 1), 1e-9) << k;
    EXPECT_NEAR(t.height(riser + 0.14), 0.17 * (k + 1), 1e-9) << k;
    EXPECT_NEAR(t.slope(riser + 0.14), 0.0, 1e-12) << k;
    // The riser itself: nearly vertical, 1 mm wide.
    EXPECT_NEAR(t.height(riser + 0.0005), 0.17 * k + 0.085, 1e-9) << k;
    EXPECT_GT(t.slope(riser + 0.0005), Terrain::kSteepestFoothold) << k;
  }
  // The top landing goes on for ever.
  EXPECT_NEAR(t.height(1.0 + 0.28 * 9 + 0.01), 1.7, 1e-9);
  EXPECT_NEAR(t.height(50.0), 1.7, 1e-9);
  EXPECT_NEAR(t.slope(50.0), 0.0, 1e-12);
}

TEST(Terrain, TheRunsOfStairsAreTheGroundBeforeTheTreadsAndTheLanding) {
  const Terrain t = Terrain::stairs(0.17, 0.28, 10);
  const std::vector<Terrain::Run>& runs = t.runs();
  ASSERT_EQ(runs.size(), 11u);  // the ground before, 9 treads, the landing
  EXPECT_EQ(runs.front().begin, -Terrain::kMaxCoordinate);
  EXPECT_NEAR(runs.front().end, 1.0, 1e-12);
  for (std::size_t k = 1; k < 10; ++k) {
    EXPECT_NEAR(runs[k].begin, 1.0 + 0.28 * static_cast<double>(k - 1) + 0.001, 1e-9) << k;
    EXPECT_NEAR(runs[k].end, 1.0 + 0.28 * static_cast<double>(k), 1e-9) << k;
    EXPECT_NEAR(runs[k].end - runs[k].begin, 0.28 - Terrain::kRiserWidth, 1e-9) << k;
  }
  EXPECT_NEAR(runs.back().begin, 1.0 + 0.28 * 9 + 0.001, 1e-9);
  EXPECT_EQ(runs.back().end, Terrain::kMaxCoordinate);
  // run_at: a tread's own run; on a riser, the run behind it; before the ground, the first.
  EXPECT_EQ(t.run_at(-2e6), 0u);
  EXPECT_EQ(t.run_at(0.5), 0u);
  EXPECT_EQ(t.run_at(1.0005), 0u);
  EXPECT_EQ(t.run_at(1.14), 1u);
  EXPECT_EQ(t.run_at(1.0 + 0.28 * 4 + 0.0005), 4u);
  EXPECT_EQ(t.run_at(1.0 + 0.28 * 4 + 0.1), 5u);
  EXPECT_EQ(t.run_at(20.0), 10u);
  EXPECT_EQ(t.run_at(2e6), 10u);
}

TEST(Terrain, StairsWithANegativeRiseGoDown) {
  const Terrain t = Terrain::stairs(-0.17, 0.28, 10);
  EXPECT_EQ(bits(t.height(0.9)), bits(0.0));
  for (int k = 0; k < 10; ++k) {
    EXPECT_NEAR(t.height(1.0 + 0.28 * k + 0.14), -0.17 * (k + 1), 1e-9) << k;
    EXPECT_LT(t.slope(1.0 + 0.28 * k + 0.0005), -Terrain::kSteepestFoothold) << k;
  }
  EXPECT_NEAR(t.height(40.0), -1.7, 1e-9);
  EXPECT_EQ(t.runs().size(), 11u);
  EXPECT_EQ(t.run_at(1.0 + 0.28 * 3 + 0.1), 4u);
}

TEST(Terrain, ASequenceJoinsARampStairsAndLevelGround) {
  // Ramp 8 deg (4 m), stairs 0.17 x 0.28 x 6 with a 1 m landing, level ground.
  const Piece pieces[] = {Terrain::ramp_piece(8.0), Terrain::stairs_piece(0.17, 0.28, 6),
                          Terrain::flat_piece()};
  const Terrain t = Terrain::sequence(pieces);
  const double top = 4.0 * tan_degrees(8.0);
  EXPECT_EQ(bits(t.height(0.5)), bits(0.0));
  EXPECT_NEAR(t.height(3.0), 2.0 * tan_degrees(8.0), 1e-12);
  EXPECT_NEAR(t.height(5.0), top, 1e-12);  // the ramp's top is the foot of the first riser
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(t.height(5.0 + 0.28 * k + 0.14), top + 0.17 * (k + 1), 1e-9) << k;
  }
  EXPECT_NEAR(t.height(5.0 + 0.28 * 5 + 0.5), top + 1.02, 1e-9);  // the landing
  EXPECT_NEAR(t.height(100.0), top + 1.02, 1e-9);                 // level ground for ever
  // Runs: the level ground and the ramp, five treads, the landing and the level ground after it.
  ASSERT_EQ(t.runs().size(), 7u);
  EXPECT_NEAR(t.runs()[0].end, 5.0, 1e-12);
  EXPECT_EQ(t.run_at(3.0), 0u);
  EXPECT_EQ(t.run_at(5.0 + 0.28 * 5 + 0.5), 6u);
  EXPECT_EQ(t.run_at(100.0), 6u);
}

TEST(Terrain, SequencePiecesFollowOneAnotherFromTheStart) {
  // Level 2 m, stairs down 3, a ramp up 10 deg for 1.5 m, stairs up 2, then the level landing.
  const Piece pieces[] = {Terrain::flat_piece(2.0), Terrain::stairs_piece(-0.15, 0.30, 3),
                          Terrain::ramp_piece(10.0, 1.5), Terrain::stairs_piece(0.2, 0.25, 2)};
  const Terrain t = Terrain::sequence(pieces, 0.5);
  EXPECT_EQ(bits(t.height(2.4)), bits(0.0));
  EXPECT_NEAR(t.height(2.5 + 0.15), -0.15, 1e-9);  // the first riser at 0.5 + 2
  // The stairs end at 2.5 + 2 * 0.30 + 0.001, then a 1 m landing at -0.45.
  const double landing = 2.5 + 0.6 + 0.001;
  EXPECT_NEAR(t.height(landing + 0.5), -0.45, 1e-9);
  const double ramp = landing + 1.0;
  EXPECT_NEAR(t.height(ramp + 1.0), -0.45 + tan_degrees(10.0), 1e-9);
  const double stairs = ramp + 1.5;
  EXPECT_NEAR(t.height(stairs + 0.1), -0.45 + 1.5 * tan_degrees(10.0) + 0.2, 1e-9);
  EXPECT_NEAR(t.height(stairs + 10.0), -0.45 + 1.5 * tan_degrees(10.0) + 0.4, 1e-9);
  // A profile piece is moved so its first point is where the piece begins.
  const Piece kerb_after_flat[] = {
      Terrain::flat_piece(1.0),
      Terrain::profile_piece({{10.0, 5.0}, {10.5, 5.0}, {10.501, 5.12}, {11.0, 5.12}})};
  const Terrain k = Terrain::sequence(kerb_after_flat, 1.0);
  EXPECT_EQ(bits(k.height(2.4)), bits(0.0));
  EXPECT_NEAR(k.height(2.6), 0.12, 1e-9);
  EXPECT_NEAR(k.height(9.0), 0.12, 1e-9);  // level after the profile at its end height
  EXPECT_EQ(k.runs().size(), 2u);
}

TEST(Terrain, EveryRangeErrorNamesThePieceAndTheField) {
  auto error = [](std::vector<Piece> pieces, double start = 1.0) {
    return error_of([&] { Terrain::sequence(pieces, start); });
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Piece level = Terrain::flat_piece();
  EXPECT_THAT(error({Terrain::ramp_piece(26.0)}),
              StartsWith("terrain piece 1 (ramp): angle must be between -25 and 25 deg, got 26"));
  EXPECT_THAT(error({level, Terrain::ramp_piece(-25.5)}),
              StartsWith("terrain piece 2 (ramp): angle must be between -25 and 25 deg"));
  EXPECT_THAT(error({Terrain::ramp_piece(nan)}), HasSubstr("angle must be between"));
  EXPECT_THAT(error({Terrain::ramp_piece(5.0, 0.0)}),
              StartsWith("terrain piece 1 (ramp): length must be between 0.01 and 10000 m, got 0"));
  EXPECT_THAT(error({Terrain::ramp_piece(5.0, nan)}), HasSubstr("(ramp): length"));
  EXPECT_THAT(error({Terrain::flat_piece(-1.0)}),
              StartsWith("terrain piece 1 (flat): length must be between"));
  EXPECT_THAT(error({Terrain::flat_piece(std::numeric_limits<double>::infinity())}),
              HasSubstr("(flat): length"));
  for (double rise : {0.3, -0.3, 0.04, -0.04, 0.0, nan}) {
    EXPECT_THAT(error({level, level, Terrain::stairs_piece(rise, 0.28, 6)}),
                StartsWith("terrain piece 3 (stairs): rise must be between 0.05 and 0.25 m "
                           "(-0.25 to -0.05 going down)"))
        << rise;
  }
  for (double tread : {0.19, 0.41, nan}) {
    EXPECT_THAT(error({Terrain::stairs_piece(0.17, tread, 6)}),
                StartsWith("terrain piece 1 (stairs): tread must be between 0.2 and 0.4 m"))
        << tread;
  }
  for (int count : {0, -3, 201}) {
    EXPECT_THAT(error({Terrain::stairs_piece(0.17, 0.28, count)}),
                StartsWith("terrain piece 1 (stairs): count must be between 1 and 200 steps, got " +
                           std::to_string(count)))
        << count;
  }
  EXPECT_THAT(error({Terrain::profile_piece({{0.0, 0.0}})}),
              StartsWith("terrain piece 1 (profile): a profile needs at least two points"));
  EXPECT_THAT(error({level, Terrain::profile_piece({{0.0, 0.0}, {1.0, 0.0}, {0.5, 0.1}})}),
              StartsWith("terrain piece 2 (profile): point 2: x must increase along the profile"));
  EXPECT_THAT(error({Terrain::profile_piece({{0.0, 0.0}, {1.0, nan}})}),
              StartsWith("terrain piece 1 (profile): point 1 is not finite"));
  EXPECT_THAT(error({Terrain::profile_piece({{0.0, 0.0}, {1.0, 2e6}})}),
              StartsWith("terrain piece 1 (profile): point 1 lies more than 1000 km"));
  // A profile within 1000 km that the sequence moves past it.
  EXPECT_THAT(error({Terrain::profile_piece({{0.0, 0.0}, {9.9e5, 0.0}}),
                     Terrain::profile_piece({{0.0, 0.0}, {1e5, 0.0}})}),
              StartsWith("terrain piece 2 (profile): point 1 lies more than 1000 km"));
  EXPECT_THAT(error({level}, nan),
              StartsWith("terrain: the start must be between -1000 and 1000 m"));
  EXPECT_THAT(error({level}, 2000.0), HasSubstr("got 2000"));
  Piece odd = level;
  odd.kind = static_cast<Piece::Kind>(9);
  EXPECT_THAT(error({level, odd}), StartsWith("terrain piece 2 (unknown kind): not a kind"));
}

TEST(Terrain, AWallTallerThanALegClimbsIsRefused) {
  // One riser of 0.31 m; 0.30 m is the tallest taken.
  EXPECT_THAT(error_of([] {
                Terrain::polyline({{0.0, 0.0}, {1.0, 0.0}, {1.001, 0.31}, {2.0, 0.31}});
              }),
              HasSubstr("terrain point 2: a wall 0.31 m high at x = 1.001 is taller than a leg "
                        "climbs in a step (0.3 m)"));
  EXPECT_EQ(error_of([] {
              Terrain::polyline({{0.0, 0.0}, {1.0, 0.0}, {1.001, 0.30}, {2.0, 0.3}});
            }),
            "");
  // Down too, and a wall of two steep segments counts whole.
  EXPECT_THAT(error_of([] {
                Terrain::polyline({{0.0, 0.5}, {1.0, 0.5}, {1.001, 0.0}});
              }),
              HasSubstr("a wall 0.5 m high"));
  EXPECT_THAT(error_of([] {
                Terrain::polyline({{0.0, 0.0}, {1.0, 0.0}, {1.001, 0.2}, {1.002, 0.4}});
              }),
              HasSubstr("terrain point 3: a wall 0.4 m high"));
  // A steep bank (70 deg) is a wall; a 59 deg one is ground.
  EXPECT_THAT(error_of([] {
                Terrain::polyline({{0.0, 0.0}, {0.2, 0.55}});
              }),
              HasSubstr("a wall 0.55 m high"));
  EXPECT_EQ(error_of([] { Terrain::polyline({{0.0, 0.0}, {1.0, 1.6}}); }), "");
  // In a sequence, the wall is named by the piece that holds its top.
  const Piece pieces[] = {Terrain::profile_piece({{0.0, 0.0}, {0.5, 0.0}, {0.501, 0.2}}),
                          Terrain::stairs_piece(0.17, 0.28, 3)};
  EXPECT_THAT(error_of([&] { Terrain::sequence(pieces); }),
              StartsWith("terrain piece 2 (stairs): a wall 0.37 m high at x = 1.502"));
  const Piece tall[] = {Terrain::flat_piece(),
                        Terrain::profile_piece({{0.0, 0.0}, {0.5, 0.0}, {0.501, 0.45}})};
  EXPECT_THAT(error_of([&] { Terrain::sequence(tall); }),
              StartsWith("terrain piece 2 (profile): point 2: a wall 0.45 m high"));
}

TEST(Terrain, FindFaultNamesThePointPolylineRefuses) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(Terrain::find_fault(kerb().points()).has_value());
  const std::vector<Point> bad{{0.0, 0.0}, {1.0, 0.0}, {2.0, nan}};
  const auto fault = Terrain::find_fault(bad);
  ASSERT_TRUE(fault.has_value());
  EXPECT_EQ(fault->point, 2u);
  EXPECT_EQ(fault->reason, "is not finite");
  EXPECT_TRUE(fault->about_point);
  const std::vector<Point> back{{0.0, 0.0}, {1.0, 0.0}, {1.0, 0.1}};
  EXPECT_EQ(Terrain::find_fault(back)->point, 2u);
  EXPECT_FALSE(Terrain::find_fault(back)->about_point);
}

TEST(Terrain, TheSameSequenceGivesTheSameGroundToTheBit) {
  const Piece pieces[] = {Terrain::ramp_piece(-7.5, 2.2), Terrain::stairs_piece(-0.16, 0.3, 8),
                          Terrain::ramp_piece(12.0)};
  const Terrain a = Terrain::sequence(pieces, 0.9);
  const Terrain b = Terrain::sequence(pieces, 0.9);
  ASSERT_EQ(a.points().size(), b.points().size());
  for (std::size_t i = 0; i < a.points().size(); ++i) {
    EXPECT_EQ(bits(a.points()[i].x), bits(b.points()[i].x));
    EXPECT_EQ(bits(a.points()[i].y), bits(b.points()[i].y));
  }
}

}  // namespace
}  // namespace fuzzygait::terrain

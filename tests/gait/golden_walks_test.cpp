// Walks held to recorded bits: a hash of every frame's state and events for walks across the
// built-in sets, statures, steps, awkward starts, slopes and a kerb, and a crowd. The hashes were
// recorded by the build that introduced this test (GCC 12, x86-64); any build of the same sources
// (another compiler, the scalar lane body, a machine without AVX2) must walk the same bits. A
// change that alters walks on purpose records new hashes and says why in CHANGES.md.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "fuzzygait/gait/crowd.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "support/walks.hpp"

using namespace fuzzygait;

namespace {

// FNV-1a over 64-bit words.
struct Hash {
  std::uint64_t value = 0xcbf29ce484222325ull;
  void add(std::uint64_t word) {
    for (int b = 0; b < 8; ++b) {
      value ^= (word >> (8 * b)) & 0xffu;
      value *= 0x100000001b3ull;
    }
  }
  void add(double x) { add(std::bit_cast<std::uint64_t>(x)); }
};

void add_walker(Hash& h, const gait::Walker& w) {
  const gait::WalkerState& s = w.state();
  h.add(s.time);
  h.add(s.pelvis.x);
  h.add(s.pelvis.y);
  h.add(s.pelvis_tilt);
  h.add(static_cast<std::uint64_t>(s.lead + 1));
  h.add(s.fall_velocity);
  h.add(static_cast<std::uint64_t>(s.heel_strikes));
  for (const gait::LegState& l : s.legs) {
    h.add(static_cast<std::uint64_t>(l.phase));
    for (const rig::LegAngles& a : {l.angles, l.velocity}) {
      h.add(a.hip);
      h.add(a.knee);
      h.add(a.ankle);
      h.add(a.toe);
    }
    for (double x : {l.anchor.x, l.anchor.y, l.sweep_start, l.sweep_end, l.target_x, l.swing_start,
                     l.strike_x, l.delta})
      h.add(x);
  }
  for (const gait::EventRecord& e : w.events()) {
    h.add(e.time);
    h.add(static_cast<std::uint64_t>(e.side));
    h.add(static_cast<std::uint64_t>(e.event));
    h.add(e.where.x);
    h.add(e.where.y);
  }
}

struct GoldenWalk {
  std::string name;
  std::string set;
  double stature;
  double step;        // metres; 0: halfway between the set's shortest and 0.70 m steps at 1.75 m
  int ground;         // 0 flat, 1 a 5 deg ramp, 2 a 0.15 m kerb up then down
  std::int64_t seed;  // -1: the default start
  std::uint64_t hash;
};

terrain::Terrain ground_of(int kind) {
  if (kind == 1) return terrain::Terrain::polyline({{-1e3, 0.0}, {2.0, 0.0}, {50.0, 4.2}});
  if (kind == 2) {
    return terrain::Terrain::polyline(
        {{-1e3, 0.0}, {2.0, 0.0}, {2.001, 0.15}, {4.0, 0.15}, {4.001, 0.0}, {1e3, 0.0}});
  }
  return terrain::Terrain::flat();
}

std::uint64_t walk_hash(const GoldenWalk& g) {
  const gait::ControllerSet set = gait::ControllerSet::builtin(g.set);
  const terrain::Terrain ground = ground_of(g.ground);
  gait::WalkerOptions o;
  o.segments = rig::segments_from_stature(g.stature);
  o.step_length = g.step;
  if (g.seed >= 0) {
    o.start.random = true;
    o.start.seed = static_cast<std::uint64_t>(g.seed);
  }
  gait::Walker w(set, o, ground);
  Hash h;
  for (int frame = 0; frame < 600; ++frame) {  // 10 s at 60 frames a second
    w.advance(frame % 50 == 7 ? 0.05 : 1.0 / 60.0);
    add_walker(h, w);
    if (frame % 60 == 59) w.clear_events();
  }
  return h.value;
}

const std::vector<GoldenWalk>& golden_walks() {
  static const std::vector<GoldenWalk> walks = {
      {"default 1.75 m 0.70 m", "default", 1.75, 0.70, 0, -1, 0x11ffd8998951a582},
      {"default 1.50 m 0.50 m", "default", 1.50, 0.50, 0, -1, 0x5383d3494553847b},
      {"default 2.00 m 0.85 m", "default", 2.00, 0.85, 0, -1, 0x6e5d087be1d3d696},
      {"default shortest step", "default", 1.75, 0.43, 0, -1, 0x7681fed986a215b8},
      {"energetic 1.75 m 0.70 m", "energetic", 1.75, 0.70, 0, -1, 0xb5c2dc39feb9d2eb},
      {"heavy 1.60 m 0.65 m", "heavy", 1.60, 0.65, 0, -1, 0xff0d53815d05b09},
      {"cautious 1.90 m 0.80 m", "cautious", 1.90, 0.80, 0, -1, 0xe673d6e3d8c40ab},
      {"default on a 5 deg ramp", "default", 1.75, 0.70, 1, -1, 0x97210f9fad06852f},
      {"default over a kerb", "default", 1.75, 0.70, 2, -1, 0x99b042cc08e4ac0a},
      {"heavy over a kerb", "heavy", 1.75, 0.70, 2, -1, 0x6b3f8bf2e0c32829},
      {"default random start 3", "default", 1.75, 0.70, 0, 3, 0xc635c4210f392e73},
      {"default random start 17", "default", 1.60, 0.60, 0, 17, 0xdf3b0449fb009a77},
      {"energetic random start 5", "energetic", 1.75, 0.70, 0, 5, 0x230a1eec0d4ddba5},
      {"cautious random start 9 on a ramp", "cautious", 1.75, 0.75, 1, 9, 0x1b4cd80bb5455909},
  };
  return walks;
}

TEST(GoldenWalks, EveryWalkHasTheRecordedBits) {
  for (const GoldenWalk& g : golden_walks()) {
    const std::uint64_t hash = walk_hash(g);
    EXPECT_EQ(hash, g.hash) << g.name << ": 0x" << std::hex << hash;
  }
}

// Characters of statures 1.50-2.00 m, steps across each one's range, phases spread by their
// warm-ups, every sixth from a random awkward pose.
std::vector<gait::WalkerOptions> crowd_characters(const gait::ControllerSet& set,
                                                  std::size_t count) {
  std::vector<gait::WalkerOptions> characters(count);
  for (std::size_t i = 0; i < characters.size(); ++i) {
    gait::WalkerOptions& o = characters[i];
    const double a = static_cast<double>(i % 7) / 6.0;
    const double b = static_cast<double>(i % 5) / 4.0;
    o.segments = rig::segments_from_stature(1.5 + 0.5 * a);
    const double shortest = gait::Walker::min_step_length(set, o.segments);
    const double longest = gait::Walker::max_step_length(o.segments);
    o.step_length = shortest + (longest - shortest) * (0.1 + 0.8 * b);
    o.start.warm_up = 3.0 + 0.1 * static_cast<double>(i % 11);
    if (i % 6 == 1) {
      o.start.random = true;
      o.start.seed = i;
    }
  }
  return characters;
}

std::uint64_t crowd_hash(std::size_t count, int frames, std::size_t threads) {
  const gait::ControllerSet& set = test::default_set();
  const terrain::Terrain ground = ground_of(2);
  gait::CrowdOptions options;
  options.threads = threads;
  gait::Crowd crowd(set, ground, crowd_characters(set, count), options);
  Hash h;
  for (int frame = 0; frame < frames; ++frame) {
    crowd.advance(1.0 / 60.0);
    for (std::size_t i = 0; i < crowd.size(); ++i)
      add_walker(h, crowd[i]);
    crowd.clear_events();
  }
  return h.value;
}

TEST(GoldenWalks, ACrowdHasTheRecordedBits) {
  constexpr std::uint64_t kRecorded = 0x5758e0cef1d3ba14;
  const std::uint64_t hash = crowd_hash(40, 480, 1);
  EXPECT_EQ(hash, kRecorded) << "0x" << std::hex << hash;
}

// Nine blocks of characters stepped by one, two and eight threads.
TEST(GoldenWalks, ACrowdHasTheRecordedBitsOnOneTwoAndEightThreads) {
  constexpr std::uint64_t kRecorded = 0x27b1182b714cce29;  // recorded when threads came
  for (std::size_t threads : {1, 2, 8}) {
    const std::uint64_t hash = crowd_hash(8 * gait::Crowd::kBlock + 5, 240, threads);
    EXPECT_EQ(hash, kRecorded) << threads << " threads: 0x" << std::hex << hash;
  }
}

}  // namespace

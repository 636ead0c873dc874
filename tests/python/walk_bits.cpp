// The walk the Python tests compare with, bit for bit: a built-in set's walker with the default
// options (1.75 m, 0.70 m steps), or walking at SPEED m/s, advanced FRAMES times by 1/120 s. Each
// line is a frame (the first the start): time, pelvis x and y, pelvis tilt, then the left and
// right legs' hip, knee, ankle and toe angles and velocities, as C99 hexadecimal floats (%a).
//   python_walk_bits STYLE FRAMES [SPEED]
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "fuzzygait/gait/walker.hpp"

namespace {

void print_state(const fuzzygait::gait::WalkerState& s) {
  std::printf("%a %a %a %a", s.time, s.pelvis.x, s.pelvis.y, s.pelvis_tilt);
  for (const fuzzygait::gait::LegState& leg : s.legs) {
    for (const fuzzygait::rig::LegAngles& a : {leg.angles, leg.velocity})
      std::printf(" %a %a %a %a", a.hip, a.knee, a.ankle, a.toe);
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace fuzzygait;
  if (argc != 3 && argc != 4) {
    std::fprintf(stderr, "usage: %s STYLE FRAMES [SPEED]\n", argv[0]);
    return 2;
  }
  try {
    const gait::ControllerSet set = gait::ControllerSet::builtin(argv[1]);
    const terrain::Terrain ground = terrain::Terrain::flat();
    gait::WalkerOptions options;
    if (argc == 4) options.speed = std::strtod(argv[3], nullptr);
    gait::Walker walker(set, options, ground);
    const long frames = std::strtol(argv[2], nullptr, 10);
    print_state(walker.state());
    for (long i = 0; i < frames; ++i) {
      walker.advance(1.0 / 120.0);
      print_state(walker.state());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}

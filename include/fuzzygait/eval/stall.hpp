// A walk that stopped going forward while it was asked to walk: a walker frozen at a stair's
// edge, or stepping in place before a riser. Found from the frames and the ground alone.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::eval {

// A walk stalls when its pelvis goes less than kStallDistance forward (+x, the walker's forward)
// over kStallWindow seconds. The slowest walks people keep up, climbing stairs, go about 0.2 m/s
// (Bovi et al. 2011: 0.28 body heights a second, so 0.41 m/s at 1.50 m); the walker climbs at
// about 0.2 m/s with its pelvis standing still up to half a second after a landing. A stall is a
// sixth of that pace over several steps' time.
inline constexpr double kStallWindow = 3.0;     // s
inline constexpr double kStallDistance = 0.10;  // m

struct Stall {
  double time = 0.0;      // s: the first frame from which the pelvis went less than the distance
  double pelvis_x = 0.0;  // m, at that frame
  double progress = 0.0;  // m the pelvis went forward over the window from there
  double window = 0.0;    // s
  double front_x = 0.0;   // m: the toe tip of the foot further forward
  std::size_t run = 0;    // its Terrain::runs() index: on Terrain::stairs, 0 before the stairs,
                          // k on tread k, the last the landing
  std::size_t runs = 0;   // how many runs the ground has
};

// The first stall of `motion` on `ground`: the first frame from which the pelvis goes less than
// `distance` forward in the next `window` seconds; nothing when the walk keeps going or is
// shorter than the window. Frames holding a NaN are skipped.
std::optional<Stall> find_stall(const Motion& motion, const terrain::Terrain& ground,
                                double window = kStallWindow, double distance = kStallDistance);

// The stall as a sentence naming when and where: "the walk stalled at 1.43 s with the pelvis at
// x = 0.82 m and the front foot on tread 0 of 0-8 (before the riser at x = 1.00 m): it went 0.01
// m forward in the next 3.0 s".
std::string describe(const Stall& stall, const terrain::Terrain& ground);

}  // namespace fuzzygait::eval

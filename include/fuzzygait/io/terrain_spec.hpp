// The ground as the command line spells it: `slope:8+stairs:0.17:0.28:6+flat`.
//
//   flat | flat:LENGTH                  level ground (LENGTH m when something follows; 2 m if not
//                                       given)
//   slope:DEG | slope:DEG:LENGTH        a ramp of DEG degrees, -25 to 25, uphill +; `ramp:` is the
//                                       same (LENGTH m when something follows; 4 m if not given)
//   stairs:RISE:TREAD:COUNT             COUNT steps of RISE m (0.05 to 0.25, negative going down)
//                                       and TREAD m (0.20 to 0.40), then a level landing
//   profile:FILE                        an x,y polyline in metres, a header line `x,y` first
//
// Parts joined by `+` follow one another (Terrain::sequence) from level ground that ends at
// x = 1 m; the last part goes on for ever (a slope) or is followed by level ground. A profile
// alone is the file's ground where the file puts it; within a chain it is moved to begin where
// the part before ends. A FILE cannot hold '+'.
#pragma once

#include <string_view>

#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::io {

// The ground a SPEC describes. Throws std::invalid_argument whose message begins with `option`
// and the part at fault ("--terrain: 'stairs:0.3:0.28:6': rise must be between ..."): an empty
// spec or part, an unknown kind, a missing or extra field, a field that is not a finite number
// (or a whole one for COUNT), a value out of its range, a profile file that cannot be read or
// holds a bad line (its file, line and column named), a wall taller than a leg climbs.
terrain::Terrain terrain_from_spec(std::string_view spec, std::string_view option = "--terrain");

}  // namespace fuzzygait::io

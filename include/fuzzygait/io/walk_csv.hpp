// The walk CSV: one row per frame (angles in degrees, positions in metres, x forward, y up), and
// the terrain CSV (the ground as an x,y polyline). Captured motion (eval::Motion::captured) has
// one more column after the others, `captured`, 1 on every row.
#pragma once

#include <iosfwd>
#include <string_view>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::io {

void write_walk_csv(std::ostream& out, const eval::Motion& motion);
// Reads a walk CSV by column name (extra columns are ignored). Throws fuzzy::ParseError naming
// the source, line and column for a missing column or a value that is not a number.
eval::Motion read_walk_csv(std::istream& in, std::string_view source);

void write_terrain_csv(std::ostream& out, const terrain::Terrain& terrain, double x0, double x1);
terrain::Terrain read_terrain_csv(std::istream& in, std::string_view source);

}  // namespace fuzzygait::io

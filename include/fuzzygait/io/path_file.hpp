// A path on the ground from a CSV file: a header line `x,z`, then one point a line, metres, in the
// ground plane (Y up, Z forward, X to the walker's left at the start). `fuzzygait walk --path`.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string_view>

#include "fuzzygait/path/path.hpp"

namespace fuzzygait::io {

// The polyline through the file's points, corners rounded at `corner_radius` (path::Path::
// polyline). Throws fuzzy::ParseError naming the source and line for a missing header, a row that
// is not two finite numbers, a point that repeats the one before it, fewer than two points, or a
// corner too sharp to walk.
path::Path read_path_csv(std::istream& in, std::string_view source, double corner_radius = 1.0);
path::Path read_path_file(const std::filesystem::path& file, double corner_radius = 1.0);

}  // namespace fuzzygait::io

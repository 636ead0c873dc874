#include "fuzzygait/io/terrain_spec.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/fuzzy/term.hpp"
#include "fuzzygait/io/walk_csv.hpp"

namespace fuzzygait::io {
namespace {

using terrain::Terrain;

std::vector<std::string> split(std::string_view text, char separator) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t end = text.find(separator, begin);
    parts.emplace_back(text.substr(begin, end == std::string_view::npos ? end : end - begin));
    if (end == std::string_view::npos) return parts;
    begin = end + 1;
  }
}

// One part of the spec, and how its errors begin.
class Part {
 public:
  Part(std::string_view option, std::string text) : text_(std::move(text)) {
    where_ = std::string(option) + ": '" + text_ + "': ";
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw std::invalid_argument(where_ + message);
  }

  // The fields after the kind: at least `required`, at most required + optional ones.
  std::vector<std::string> fields(const std::string& kind, const std::vector<const char*>& names,
                                  std::size_t required) const {
    std::vector<std::string> all = split(text_, ':');
    all.erase(all.begin());
    std::string usage = kind;
    for (std::size_t k = 0; k < names.size(); ++k)
      usage += std::string(k < required ? ":" : "[:") + names[k] + (k < required ? "" : "]");
    if (all.size() < required) {
      fail("missing " + std::string(names[all.size()]) + " (" + usage + ")");
    }
    if (all.size() > names.size()) {
      fail("an extra field '" + all[names.size()] + "' (" + usage + ")");
    }
    return all;
  }

  double number(const std::string& name, const std::string& text) const {
    const std::optional<double> value = fuzzy::parse_scalar(text);
    if (!value) fail(name + " '" + text + "' is not a number");
    if (!std::isfinite(*value)) fail(name + " '" + text + "' is not a finite number");
    return *value;
  }

  int whole(const std::string& name, const std::string& text) const {
    const double value = number(name, text);
    if (value != std::floor(value) || std::abs(value) > 1e6) {
      fail(name + " '" + text + "' is not a whole number");
    }
    return static_cast<int>(value);
  }

  const std::string& text() const { return text_; }

 private:
  std::string text_;
  std::string where_;
};

// The points of a profile file, its errors naming the file and line.
std::vector<terrain::Point> read_profile(const Part& part, const std::string& path) {
  if (path.empty()) part.fail("missing FILE (profile:FILE)");
  if (std::filesystem::is_directory(path)) part.fail(path + ": is a directory, not a file");
  std::ifstream in(path);
  if (!in) part.fail(path + ": cannot open the file");
  try {
    return read_terrain_csv(in, path).points();
  } catch (const std::exception& e) {  // fuzzy::ParseError, with the file and line
    part.fail(e.what());
  }
}

Terrain::Piece piece_of(const Part& part) {
  const std::string& text = part.text();
  const std::string kind = text.substr(0, text.find(':'));
  if (kind == "profile") {
    const std::size_t colon = text.find(':');
    return Terrain::profile_piece(
        read_profile(part, colon == std::string::npos ? std::string() : text.substr(colon + 1)));
  }
  Terrain::Piece piece;
  if (kind == "flat") {
    const std::vector<std::string> f = part.fields(kind, {"LENGTH"}, 0);
    piece = f.empty() ? Terrain::flat_piece() : Terrain::flat_piece(part.number("length", f[0]));
  } else if (kind == "slope" || kind == "ramp") {
    const std::vector<std::string> f = part.fields(kind, {"DEG", "LENGTH"}, 1);
    const double degrees = part.number("angle", f[0]);
    piece = f.size() == 1 ? Terrain::ramp_piece(degrees)
                          : Terrain::ramp_piece(degrees, part.number("length", f[1]));
  } else if (kind == "stairs") {
    const std::vector<std::string> f = part.fields(kind, {"RISE", "TREAD", "COUNT"}, 3);
    piece = Terrain::stairs_piece(part.number("rise", f[0]), part.number("tread", f[1]),
                                  part.whole("count", f[2]));
  } else {
    part.fail("unknown kind '" + kind +
              "' (flat, flat:LENGTH, slope:DEG[:LENGTH], ramp:DEG[:LENGTH], "
              "stairs:RISE:TREAD:COUNT or profile:FILE)");
  }
  // Each piece's range alone, so that the error names its part.
  try {
    Terrain::validate(piece);
  } catch (const std::invalid_argument& e) {
    part.fail(e.what());
  }
  return piece;
}

}  // namespace

Terrain terrain_from_spec(std::string_view spec, std::string_view option) {
  if (spec.empty()) {
    throw std::invalid_argument(std::string(option) +
                                ": empty (for example flat, slope:8 or stairs:0.17:0.28:10)");
  }
  std::vector<Part> parts;
  for (std::string& text : split(spec, '+'))
    parts.emplace_back(option, std::move(text));
  std::vector<Terrain::Piece> pieces;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (parts[i].text().empty()) {
      throw std::invalid_argument(std::string(option) + ": '" + std::string(spec) + "': part " +
                                  std::to_string(i + 1) + " is empty");
    }
    pieces.push_back(piece_of(parts[i]));
  }
  // A profile alone is the file's own ground, where it lies.
  if (pieces.size() == 1 && pieces[0].kind == Terrain::Piece::Kind::Profile) {
    return Terrain::polyline(pieces[0].points);
  }
  try {
    return Terrain::sequence(pieces);
  } catch (const std::invalid_argument& e) {  // where pieces meet: a wall, 1000 km
    throw std::invalid_argument(std::string(option) + ": '" + std::string(spec) + "': " + e.what());
  }
}

}  // namespace fuzzygait::io

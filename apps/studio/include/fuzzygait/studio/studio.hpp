// The studio's API: what its page reads and changes, as functions over JSON that the HTTP server
// (server.hpp) calls and a test calls in-process. One Studio is one person's session: the
// controller set being shaped with its history of edits, the walk's settings (step or speed,
// stature, terrain, cycles), the sets that may be opened and the set to compare with.
// docs/studio.md describes every request and answer.
//
// Every request is a JSON object; every answer is a JSON object. A request that cannot be met
// throws RequestError naming the field at fault and changes nothing: the set, its history and the
// settings stay as they were. Not thread-safe: the server calls one Studio under one lock.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fuzzygait::studio {

// A refused request: the HTTP status it answers with (400 malformed, 404 unknown, 409 nothing to
// undo or redo, 413 too large, 422 a value out of range; 500 for a save the disk refuses), the
// request's field at fault ("value", "step", "body", ...) and a sentence saying what went wrong.
class RequestError : public std::invalid_argument {
 public:
  RequestError(int status, std::string field, const std::string& message);
  int status() const { return status_; }
  const std::string& field() const { return field_; }
  // {"error": message, "field": field, "status": status}
  nlohmann::json to_json() const;

 private:
  int status_;
  std::string field_;
};

struct StudioOptions {
  // The built-in set (controllers/NAME, a --style) opened first when no folder is given.
  std::string style = "default";
  // Controller set folders that may be opened (sets of one's own, trained sets); the first is
  // opened first. Each must load (ControllerSet::load) when the Studio is made.
  std::vector<std::filesystem::path> folders;
  // Where `save` writes sets, one folder each (created when first needed); saved sets found there
  // may be opened. Only names of letters, digits, '-' and '_' are read or written in it.
  std::filesystem::path workspace = "studio-sets";
  // Terrain specs (io::terrain_from_spec) offered beside the built-in ones; these may name profile
  // files, which a request may not.
  std::vector<std::string> terrains;
  double step = 0.70;     // metres
  double stature = 1.75;  // metres
  int cycles = 10;        // gait cycles walked after the first
};

// The ranges a request's settings and values must lie in.
struct Limits {
  static constexpr double kMinStature = 1.40;  // metres
  static constexpr double kMaxStature = 2.10;
  static constexpr int kMinCycles = 2;
  static constexpr int kMaxCycles = 20;
  // A membership function's knot or parameter, an output word's value: finite and within this
  // of zero (an input's degrees or an output's degrees per second).
  static constexpr double kLargestValue = 1e4;
  static constexpr std::size_t kLongestText = 200;   // terrain specs, names, gesture ids
  static constexpr std::size_t kHistory = 200;       // undo steps kept
  static constexpr std::size_t kMostRules = 400;     // rules of one controller in an edit
  static constexpr std::size_t kLongestRule = 1000;  // characters of one rule
  // The largest body of a rules edit (the server's /api/rules; other requests take 64 KiB): the
  // most rules at their longest, each character written as JSON at worst ('"' and '\\' as two),
  // with quotes and commas, and room for the rest of the request.
  static constexpr std::size_t kLargestRulesBody = kMostRules * (2 * kLongestRule + 3) + 1024;
  // A drawn path (settings' "path" and "corner_radius"): its points, its length once its corners
  // are rounded (metres; the walk goes to its end, about 40 s at 1.3 m/s, an answer some 2.5
  // times a 10-cycle walk's) and the largest corner radius (the smallest is path::Path's, 0.5 m).
  static constexpr std::size_t kMostPathPoints = 256;
  static constexpr double kLongestPath = 50.0;
  static constexpr double kLargestCornerRadius = 20.0;
};

// A file to download: its name, MIME type and bytes.
struct Download {
  std::string filename;
  std::string content_type;
  std::string bytes;
};

class Studio {
 public:
  // Throws std::invalid_argument naming the style, folder or terrain spec that does not load, or
  // a setting out of its range.
  explicit Studio(StudioOptions options);
  ~Studio();
  Studio(const Studio&) = delete;
  Studio& operator=(const Studio&) = delete;

  // Everything the page shows but the walk: the current set (every controller with its inputs'
  // terms, output words and rules), the history, the settings and their limits, the sets and
  // terrains to choose from, the normative reference, the set compared with.
  nlohmann::json state() const;
  // The walk of the current set with the current settings (frames for the views, the ground, the
  // mean curves and their scores against the reference, the contact figures and the bounds
  // missed), and the compared set's walk when there is one.
  nlohmann::json walk();

  // Changes one number of the current set and answers the changed controller (or the set's
  // parameters), the history and the new walk. The request names what changes:
  //   {"controller": ID, "variable": INPUT, "knot": I, "value": X}      a partition's knot I
  //   {"controller": ID, "variable": OUTPUT, "term": WORD, "value": V}  an output word's value
  //   {"controller": ID, "variable": V, "term": T, "parameter": I, "value": X}  any term parameter
  //   {"set": NAME, "value": X}   one of the set's own numbers, a manifest key of
  //                                ControllerSet::manifest_numbers() ("inertia_s", ...)
  // and may carry "gesture": ID, so that the edits of one drag are one step of the history.
  nlohmann::json edit(const nlohmann::json& request);
  // {"controller": ID, "rules": [TEXT, ...]}: the controller's rules replaced, each read by the
  // library's FLL rule parser; one step of the history ("swing_knee: rule 3 edited"). Answers as
  // edit() does. A rule that does not read (an unknown word, a term its variable lacks) is
  // refused with 422 naming "rules", the rule's number and the word.
  nlohmann::json edit_rules(const nlohmann::json& request);
  // {"controller": ID, "variable": INPUT, "term": NAME, "action": "add" | "remove" | "shape",
  //  "shape": SHAPE, "parameters": [...]}: a term added to an input, removed from it, or given
  // another shape (Triangle, Trapezoid, Ramp, Gaussian), one step of the history ("swing_knee:
  // delta term 'far' added (Gaussian 0.5 0.2)"). Answers as edit() does. Refused with 422 naming
  // the field: a term rules read (naming them), a shape an input cannot hold, parameters out of
  // order or of no width, a name taken or one a rule could not read. docs/studio.md has the rest.
  nlohmann::json edit_term(const nlohmann::json& request);
  // {"time": S}: which rules fire at the walk's frame nearest S seconds (the page's frames, 30 a
  // second): for each of the eight slots' controllers the inputs it read there (from the leg it
  // drives), each rule's firing strength and the output, by the library's evaluator.
  nlohmann::json fired(const nlohmann::json& request);
  // {"step": M, "speed": M/S, "stature": M, "terrain": SPEC, "cycles": N, "path": [[X, Z], ...]
  // or null, "corner_radius": M}, any of them: the new settings and walk. A speed above 0 walks
  // by speed (the set's stride gives the step), a step or a speed of 0 by step length. A path
  // (path::Path::polyline of the points, x and z metres on the ground as the library has them,
  // corners rounded to corner_radius) is walked from its first point to its end, the whole body
  // posed on it; null walks straight ahead for `cycles`. A path is refused (422 "path", naming the
  // point) with fewer than 2 or more than Limits::kMostPathPoints points, a point repeated, a
  // corner too sharp for its legs, or longer than Limits::kLongestPath; a corner_radius below
  // path::Path::kSmallestRadius or above Limits::kLargestCornerRadius (422 "corner_radius").
  nlohmann::json change_settings(const nlohmann::json& request);
  // Steps back or forward through the history (an open too): the whole set, the set opened, the
  // history, the settings, the walk and the compared walk (which follows the set opened).
  nlohmann::json undo();
  nlohmann::json redo();
  // {"to": N}: undoes or redoes until the first N steps of the history (history's "steps") are
  // done, and answers as undo() does; N from 0 (before them all) to the steps' count.
  nlohmann::json go_to(const nlohmann::json& request);
  // {"set": ID}: opens a built-in style ("style:NAME", also a reset to it), a folder
  // ("folder:N") or a saved set ("saved:NAME") as the current set, one step of the history.
  nlohmann::json open(const nlohmann::json& request);
  // {"name": NAME}: writes the current set to WORKSPACE/NAME (manifest.json and FLL files, the
  // layout ControllerSet::load reads), replacing a set saved there before.
  nlohmann::json save(const nlohmann::json& request);
  // {"with": ID or null}: the set to walk beside the current one, with its walk and its view (as
  // state() shows the current set); "opened" is the current set as it was opened (before its
  // edits), other IDs as for open().
  nlohmann::json compare(const nlohmann::json& request);
  // The current walk as "walk.csv", "walk.bvh", "walk.glb" or "walk.terrain.csv".
  Download download(std::string_view filename);

 private:
  struct Session;
  std::unique_ptr<Session> session_;
};

}  // namespace fuzzygait::studio

// `fuzzygait walk`: walks a character with a controller set and writes its files: the walk CSV,
// the terrain, a BVH, the joint-angle curves against the normative band, and the poses.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

#include "commands.hpp"
#include "fuzzygait/body/follower.hpp"
#include "fuzzygait/body/humanoid_map.hpp"
#include "fuzzygait/body/skeleton_poser.hpp"
#include "fuzzygait/eval/evaluation.hpp"
#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/eval/stall.hpp"
#include "fuzzygait/eval/terrain_report.hpp"
#include "fuzzygait/io/bvh.hpp"
#include "fuzzygait/io/files.hpp"
#include "fuzzygait/io/gltf.hpp"
#include "fuzzygait/io/normative.hpp"
#include "fuzzygait/io/path_file.hpp"
#include "fuzzygait/io/skeleton_file.hpp"
#include "fuzzygait/io/terrain_spec.hpp"
#include "fuzzygait/io/walk_csv.hpp"
#include "fuzzygait/plot/svg.hpp"
#include "fuzzygait/plot/walk_plots.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::cli {
namespace {

namespace svg = plot::svg;

struct WalkOptions {
  double step = 0.70;
  double speed = 0.0;
  double stature = 1.75;
  // Lengths given one by one replace the stature's; the rig checks each (zero and negative too).
  std::optional<double> thigh, shank, ankle_height, heel, ball, toe;
  std::string style = "default";
  std::string controllers;
  int cycles = 10;
  double duration = 0.0;
  double fps = 120.0;
  std::string start_pose = "default";
  std::string stop_at;  // where the walk stops: metres along it, or "end" (of the path)
  std::string prefix = "out/walk";
  std::string reference = "schwartz2008_free";
  bool gltf = false;
  std::string terrain = "flat";
  std::string path;  // a path file: the whole body walks it
  double corner_radius = 1.0;
  std::string skeleton;  // a skeleton file: its proportions, and the body's BVH on it
};

// The whole body's walk (--path, --skeleton): a walker like the command's, bent onto the path as
// `humanoid` and posed on the skeleton, frame by frame at `fps`, until `frames` frames or, with
// frames 0, until the hips pass the path's end or stall (5 cm in 3 s: the sagittal walk then
// says where). Writes PREFIX.body.bvh and, with `gltf`, PREFIX.body.glb (the same frames);
// returns the frames walked.
std::size_t write_body_walk(const gait::ControllerSet& set, const gait::WalkerOptions& options,
                            const terrain::Terrain& ground, const path::Path& route,
                            const body::Humanoid& humanoid, const body::Skeleton& skeleton,
                            const body::SkeletonPoser& poser, double fps, std::size_t frames,
                            double stop_x, const std::string& prefix, bool gltf) {
  gait::Walker walker(set, options, ground);
  body::PathFollower follower(humanoid, route, walker);
  walker.go();  // (a standing start walks at once, the arms joining in as it goes)
  walker.stop_at(stop_x);
  std::size_t standing = 0;  // frames stood so far
  std::vector<double> travelled;
  const auto three_seconds = static_cast<std::size_t>(3.0 * fps);
  std::vector<body::Quat> rotations;
  std::vector<body::Vec3> roots;
  const auto longest = static_cast<std::size_t>(3600.0 * fps);
  for (std::size_t i = 0; frames > 0 ? i < frames : i < longest; ++i) {
    if (i > 0) walker.advance(1.0 / fps);
    rotations.resize(rotations.size() + poser.joint_count());
    roots.emplace_back();
    poser.pose(follower.update(walker),
               std::span(rotations).subspan(rotations.size() - poser.joint_count()), roots.back());
    travelled.push_back(walker.pose().pelvis.x);
    if (frames > 0) continue;
    standing = walker.standing() ? standing + 1 : 0;
    if (standing > static_cast<std::size_t>(fps)) break;  // stopped, and stood a second
    if (std::isnan(stop_x) && travelled.back() >= route.length() + 0.3) break;
    if (i >= three_seconds && travelled[i] - travelled[i - three_seconds] < 0.05) break;
  }
  io::write_file(prefix + ".body.bvh", [&](std::ostream& out) {
    io::write_skeleton_bvh(out, skeleton, rotations, roots, {.frame_time = 1.0 / fps});
  });
  if (gltf) {
    io::write_skeleton_gltf(prefix + ".body.glb", skeleton, rotations, roots,
                            {.frame_time = 1.0 / fps});
  }
  return roots.size();
}

// A distance (m) given as text: a finite number, or invalid_argument naming the option.
double parse_distance(const std::string& text, const std::string& option) {
  std::size_t used = 0;
  double value = std::numeric_limits<double>::quiet_NaN();
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value)) {
    throw std::invalid_argument(option + " must be a distance in metres or 'end', got '" + text +
                                "'");
  }
  return value;
}

gait::StartPose parse_start(const std::string& text) {
  gait::StartPose start;
  if (text == "default") return start;
  const std::string prefix = "random:";
  if (text.rfind(prefix, 0) == 0) {
    const std::string seed = text.substr(prefix.size());
    // Digits only: stoull alone takes "-5" (as 2^64 - 5), "+5" and leading blanks.
    const bool digits = !seed.empty() && std::all_of(seed.begin(), seed.end(),
                                                     [](char c) { return c >= '0' && c <= '9'; });
    if (digits) {
      try {
        start.seed = std::stoull(seed);
        start.random = true;
        return start;
      } catch (const std::out_of_range&) {  // past 64 bits: refused below
      }
    }
  }
  if (text == "standing") {
    start.standing = true;
    return start;
  }
  throw std::invalid_argument("--start-pose must be 'default', 'standing' or 'random:SEED', got '" +
                              text + "'");
}

// The ground written around the walk (m): from before its first frame to after its last, so that
// whatever reads the file has the same ground under every point of the walk.
constexpr double kGroundMargin = 1.0;

// The smallest and largest x of the pelvis and every leg point over the walk.
std::pair<double, double> walked_extent(const eval::Motion& motion) {
  double low = motion.frames.front().pose.pelvis.x;
  double high = low;
  for (const eval::Frame& f : motion.frames) {
    low = std::min(low, f.pose.pelvis.x);
    high = std::max(high, f.pose.pelvis.x);
    for (const rig::LegPoints& p : f.points) {
      for (const rig::Point& q : {p.hip, p.knee, p.ankle, p.heel, p.ball, p.tip}) {
        low = std::min(low, q.x);
        high = std::max(high, q.x);
      }
    }
  }
  return {low, high};
}

// The default set meets the contact bounds over its step range (docs/walk.md, "Step lengths");
// a style or a set of one's own may not, and the files are written all the same, so the reader
// is told.
void warn_about_contact(const std::vector<std::string>& missed) {
  if (missed.empty()) return;
  std::cerr << "fuzzygait: warning: this walk misses the contact bounds: ";
  for (std::size_t i = 0; i < missed.size(); ++i)
    std::cerr << (i > 0 ? "; " : "") << missed[i];
  std::cerr << "\n";
}

// Level ground at one height everywhere.
bool is_level(const terrain::Terrain& ground) {
  const std::vector<rig::Point>& p = ground.points();
  return std::all_of(p.begin(), p.end(), [&](const rig::Point& q) { return q.y == p[0].y; });
}

// The left stride the pictures show: stride 1 on level ground (the start from standing is
// stride 0); on other ground, the left stride beginning at the middle of the left strikes off
// level ground, with a stride after it for the two-stride loop.
int pictured_stride(const eval::Motion& motion, const eval::TerrainReport& report) {
  const std::vector<std::size_t> left = eval::heel_strikes(motion, rig::Side::Left);
  std::vector<std::size_t> off_level;
  for (const eval::TerrainStep& step : report.steps) {
    if (step.side == rig::Side::Left && step.footing != eval::Footing::Level) {
      off_level.push_back(step.frame);
    }
  }
  if (off_level.empty() || left.size() < 3) return 1;
  const std::size_t frame = off_level[(off_level.size() - 1) / 2];
  const auto at = std::find(left.begin(), left.end(), frame) - left.begin();
  return static_cast<int>(
      std::clamp<std::ptrdiff_t>(at, 0, static_cast<std::ptrdiff_t>(left.size()) - 3));
}

}  // namespace

void add_walk_command(CLI::App& app) {
  auto o = std::make_shared<WalkOptions>();
  CLI::App* walk = app.add_subcommand(
      "walk", "Walk a character with fuzzy controllers and write its files and plots");
  walk->add_option("--step", o->step,
                   "Step length, metres heel to heel (default 0.70, or a trained set's own)");
  walk->add_option("--speed", o->speed,
                   "Walking speed, m/s (instead of --step): the step follows the set's stride "
                   "relation, the cadence both");
  walk->add_option("--stature", o->stature,
                   "Body height, metres: segment lengths from anthropometric proportions "
                   "(default 1.75, or a trained set's own body)");
  walk->add_option("--thigh", o->thigh, "Thigh length, m (overrides the stature's)");
  walk->add_option("--shank", o->shank, "Shank length, m");
  walk->add_option("--ankle-height", o->ankle_height, "Ankle height above the sole, m");
  walk->add_option("--heel", o->heel, "Ankle to back of the heel, m");
  walk->add_option("--ball", o->ball, "Ankle to the ball of the foot, m");
  walk->add_option("--toe", o->toe, "Ball of the foot to the toe tip, m");
  walk->add_option("--style", o->style, "Built-in controller set (default, or a style)");
  walk->add_option("--controllers", o->controllers, "Controller set folder (manifest.json + FLL)");
  walk->add_option("--cycles", o->cycles, "Gait cycles to walk after the first (default 10)")
      ->check(CLI::Range(2, 10000));
  walk->add_option("--duration", o->duration, "Seconds to walk (instead of --cycles)");
  walk->add_option("--fps", o->fps, "Frames per second of the files, 10 to 2000 (default 120)");
  walk->add_option("--start-pose", o->start_pose,
                   "default (mid-stride), standing (feet side by side, then walks), or random:SEED "
                   "(awkward start)");
  walk->add_option("--stop-at", o->stop_at,
                   "Stops with the feet side by side at this distance along the walk (m), or at "
                   "the --path's end ('end'), and stands there");
  walk->add_option("-o,--output", o->prefix, "Prefix of the files written (default out/walk)");
  walk->add_option("--reference", o->reference, "Normative curves for the plot and summary");
  walk->add_flag("--gltf", o->gltf,
                 "Also write PREFIX.glb: glTF 2.0 with the skeleton, the animation, a skinned "
                 "body and the ground; with --path or --skeleton also PREFIX.body.glb, the "
                 "whole body's walk on its skeleton");
  walk->add_option("--path", o->path,
                   "Walk the whole body along a path: a CSV file of x,z points (metres, header "
                   "x,z); writes PREFIX.body.bvh and walks to the path's end unless --duration "
                   "or --cycles says otherwise");
  walk->add_option("--corner-radius", o->corner_radius,
                   "Radius the path's corners are rounded to, m (at least 0.5; default 1)");
  walk->add_option("--skeleton", o->skeleton,
                   "A humanoid skeleton (.bvh, .glb, .gltf or .vrm): the walk takes its leg "
                   "lengths and PREFIX.body.bvh poses it");
  walk->add_option("--terrain", o->terrain,
                   "Ground: flat, slope:DEG[:LENGTH], stairs:RISE:TREAD:COUNT or profile:FILE.csv, "
                   "joined by + (default flat)");
  walk->footer(
      "Writes PREFIX.csv (one row per frame), PREFIX.terrain.csv (the ground walked), PREFIX.bvh,\n"
      "PREFIX.svg (joint angles over the gait cycle against the normative band) and\n"
      "PREFIX.poses.svg; with --gltf also PREFIX.glb; with --path or --skeleton also\n"
      "PREFIX.body.bvh, the whole body in 3-D (arms, trunk, turns), and with --gltf\n"
      "PREFIX.body.glb, the same frames as glTF 2.0 (skeleton, skinned bones, animation Walk).\n"
      "--terrain: a slope (-25 to 25 deg) or stairs (RISE 0.05-0.25 m, negative going down;\n"
      "TREAD 0.20-0.40 m) start at x = 1 m after level ground; stairs end in a level landing;\n"
      "parts joined by + follow one another: slope:8+stairs:0.17:0.28:6+flat.");
  walk->callback([o, walk]() {
    // CLI11's range checks let NaN through (every comparison with it is false).
    if (walk->count("--duration") > 0 && !(o->duration > 0.0 && o->duration <= 36000.0)) {
      throw std::invalid_argument("--duration must be more than 0 and at most 36000 s, got " +
                                  common::number_text(o->duration));
    }
    if (!(o->fps >= 10.0 && o->fps <= 2000.0)) {
      throw std::invalid_argument("--fps must be between 10 and 2000, got " +
                                  common::number_text(o->fps));
    }
    check_output_prefix(o->prefix, "-o");
    // Everything that can be refused is refused before any file is written.
    const eval::Normative reference = io::load_normative(o->reference);
    const terrain::Terrain ground = io::terrain_from_spec(o->terrain, "--terrain");
    const gait::ControllerSet set = o->controllers.empty()
                                        ? gait::ControllerSet::builtin(o->style)
                                        : gait::ControllerSet::load(o->controllers);
    gait::WalkerOptions options;
    // A trained set walks its body and step (its manifest's "body") unless the command line
    // gives a body or a step.
    const bool body_given = walk->count("--stature") + walk->count("--thigh") +
                                walk->count("--shank") + walk->count("--ankle-height") +
                                walk->count("--heel") + walk->count("--ball") +
                                walk->count("--toe") >
                            0;
    if (set.body && !body_given) {
      options.segments = *set.body;
    } else {
      options.segments = rig::segments_from_stature(o->stature);
    }
    options.segments.thigh = o->thigh.value_or(options.segments.thigh);
    options.segments.shank = o->shank.value_or(options.segments.shank);
    options.segments.ankle_height = o->ankle_height.value_or(options.segments.ankle_height);
    options.segments.heel = o->heel.value_or(options.segments.heel);
    options.segments.ball = o->ball.value_or(options.segments.ball);
    options.segments.toe = o->toe.value_or(options.segments.toe);
    const bool speed_given = walk->count("--speed") > 0;
    if (speed_given && !(o->speed > 0.0)) {
      throw std::invalid_argument("--speed must be a speed above 0 m/s, got " +
                                  common::number_text(o->speed));
    }
    const bool step_given = walk->count("--step") > 0;
    if (speed_given && step_given) {
      throw std::invalid_argument(
          "give --speed or --step, not both: a walk by speed takes the "
          "step its set's stride relation gives");
    }
    // A trained set's body walks its own step unless a step or a speed is given.
    const bool own_pace = !speed_given && !step_given && set.body_step_length.has_value();
    options.speed = speed_given ? o->speed : 0.0;
    options.step_length = own_pace ? *set.body_step_length : o->step;
    options.start = parse_start(o->start_pose);
    // The whole body: on a path, on a skeleton (its legs are the walk's), or neither.
    const bool whole_body = !o->path.empty() || !o->skeleton.empty();
    std::optional<path::Path> route;
    std::optional<body::Skeleton> skeleton;
    std::optional<body::SkeletonPoser> poser;
    std::optional<body::Humanoid> humanoid;  // the walk's body: the skeleton's, or the stature's
    if (walk->count("--corner-radius") > 0 && o->path.empty()) {
      throw std::invalid_argument("--corner-radius rounds the corners of a --path: give one");
    }
    if (whole_body) {
      if (!o->skeleton.empty() && body_given) {
        throw std::invalid_argument(
            "give --skeleton or a body (--stature, --thigh, ...), not both: the skeleton's legs "
            "are the walk's");
      }
      route = o->path.empty() ? path::Path() : io::read_path_file(o->path, o->corner_radius);
      if (!o->skeleton.empty()) {
        const std::filesystem::path file(o->skeleton);
        const std::string extension = file.extension().string();
        if (extension == ".bvh") {
          skeleton = io::read_bvh_skeleton(file);
        } else if (extension == ".glb" || extension == ".gltf" || extension == ".vrm") {
          skeleton = io::read_gltf_skeleton(file);
        } else {
          throw std::invalid_argument("--skeleton " + o->skeleton +
                                      ": expected a .bvh, .glb, .gltf or .vrm file");
        }
        std::optional<body::HumanoidMap> map;
        if (extension != ".bvh") map = io::read_vrm_humanoid_map(file, *skeleton);
        poser.emplace(*skeleton, map ? *map : body::map_humanoid(*skeleton));
        humanoid = poser->humanoid();
        options.segments = humanoid->segments();
      } else {
        // The walk's legs (a trained set's, or given one by one), the stature's trunk and arms.
        body::Humanoid built = body::humanoid_with_legs(options.segments, o->stature);
        skeleton = body::skeleton_of(built);
        poser.emplace(*skeleton, body::map_humanoid(*skeleton));
        humanoid = std::move(built);
      }
    }
    const std::filesystem::path prefix(o->prefix);
    if (prefix.has_parent_path()) std::filesystem::create_directories(prefix.parent_path());
    std::size_t body_frames = 0;
    double stop_x = std::numeric_limits<double>::quiet_NaN();
    if (o->stop_at == "end") {
      if (!route) throw std::invalid_argument("--stop-at end stops at a --path's end: give one");
      stop_x = route->length();
    } else if (!o->stop_at.empty()) {
      stop_x = parse_distance(o->stop_at, "--stop-at");
    }
    if (whole_body && !o->path.empty() &&
        walk->count("--duration") + walk->count("--cycles") == 0) {
      // Along a path with no length given: to its end (or its stop), and the sagittal files as
      // long.
      body_frames = write_body_walk(set, options, ground, *route, *humanoid, *skeleton, *poser,
                                    o->fps, 0, stop_x, o->prefix, o->gltf);
      o->duration = static_cast<double>(body_frames - 1) / o->fps;
    } else if (!std::isnan(stop_x) && walk->count("--duration") + walk->count("--cycles") == 0) {
      throw std::invalid_argument(
          "--stop-at needs --duration (how long the walk lasts, standing "
          "at the end) or a --path");
    }
    gait::Walker walker(set, options, ground);
    walker.go();  // (a standing start walks at once)
    walker.stop_at(stop_x);
    const double step = walker.step_length();
    const eval::Motion motion = o->duration > 0.0 ? eval::record(walker, o->duration, o->fps)
                                                  : eval::record_cycles(walker, o->cycles, o->fps);
    if (whole_body && body_frames == 0) {
      body_frames = write_body_walk(set, options, ground, *route, *humanoid, *skeleton, *poser,
                                    o->fps, motion.frames.size(), stop_x, o->prefix, o->gltf);
    }
    io::write_file(o->prefix + ".csv",
                   [&motion](std::ostream& out) { io::write_walk_csv(out, motion); });
    io::write_file(o->prefix + ".terrain.csv", [&](std::ostream& out) {
      const auto [x0, x1] = walked_extent(motion);
      io::write_terrain_csv(out, ground, x0 - kGroundMargin, x1 + kGroundMargin);
    });
    io::write_file(o->prefix + ".bvh",
                   [&motion](std::ostream& out) { io::write_bvh(out, motion); });
    if (o->gltf) io::write_gltf(o->prefix + ".glb", motion, ground);
    std::cout << "walked " << motion.frames.size() << " frames (" << motion.frames.back().time
              << " s) with controller set '" << set.name << "'\n";
    std::vector<std::string> written = {o->prefix + ".csv", o->prefix + ".terrain.csv",
                                        o->prefix + ".bvh"};
    if (whole_body) {
      std::cout << "the whole body " << (o->path.empty() ? "straight ahead" : "along the path")
                << (o->path.empty() ? std::string()
                                    : " (" + common::number_text(route->length()) + " m)")
                << " on "
                << (o->skeleton.empty() ? std::string("the stature's skeleton") : o->skeleton)
                << ": " << body_frames << " frames\n";
      written.push_back(o->prefix + ".body.bvh");
      if (o->gltf) written.push_back(o->prefix + ".body.glb");
    }
    if (o->gltf) written.push_back(o->prefix + ".glb");
    // Off level ground, the contact bounds are the terrain's (every leg point, edges too).
    const bool level = is_level(ground);
    const eval::TerrainReport on_terrain = eval::evaluate_terrain(motion, ground);
    if (!level) warn_about_contact(eval::missed_contact_bounds(on_terrain));
    try {
      const eval::GaitReport report = eval::evaluate(motion, ground, &reference, step);
      std::cout << "against " << reference.name << ":\n" << eval::to_text(report);
      if (level) warn_about_contact(eval::missed_contact_bounds(report));
      plot::plot_gait_curves(report, &reference, {.title = "fuzzygait walk, " + set.name})
          .save(o->prefix + ".svg");
      written.push_back(o->prefix + ".svg");
    } catch (const std::invalid_argument& e) {
      std::cout << "not measured, no curves: " << e.what() << "\n";
    }
    try {
      // Off level ground: the whole walk over its ground first, then a loop and a filmstrip of a
      // stride on the ground's feature.
      const int stride = level ? 1 : pictured_stride(motion, on_terrain);
      std::vector<svg::Figure> figures;
      if (!level) {
        figures.push_back(
            plot::plot_walk_animation(motion, ground, {.strides = 0, .follow = false}));
      }
      figures.push_back(plot::plot_walk_animation(motion, ground, {.first_stride = stride}));
      figures.push_back(plot::plot_filmstrip(motion, ground, {.stride = stride}));
      std::vector<const svg::Figure*> stacked;
      for (const svg::Figure& f : figures)
        stacked.push_back(&f);
      io::write_file(o->prefix + ".poses.svg", svg::stack_figures(stacked));
      written.push_back(o->prefix + ".poses.svg");
    } catch (const std::invalid_argument& e) {
      std::cout << "no poses: " << e.what() << "\n";
    }
    std::cout << "wrote";
    for (const std::string& f : written)
      std::cout << " " << f;
    std::cout << "\n";
    // A frozen walk is a failure, not a walk: its files stay for a look, and the command fails
    // naming when and where the walk stopped.
    // (A walk told to stop is judged until its last steps to the spot.)
    eval::Motion judged = motion;
    if (!std::isnan(stop_x)) {
      const double last_steps = stop_x - 2.0 * walker.max_step_length();
      std::erase_if(judged.frames,
                    [&](const eval::Frame& f) { return f.pose.pelvis.x >= last_steps; });
    }
    if (const std::optional<eval::Stall> stall = eval::find_stall(judged, ground)) {
      throw std::runtime_error(eval::describe(*stall, ground) + "; the files are written");
    }
  });
}

}  // namespace fuzzygait::cli

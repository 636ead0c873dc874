// `fuzzygait mocap`: reads a walking clip (BVH) into the rig's terms and writes the files
// `fuzzygait walk` writes, so that every measure and plot of a walk applies to the clip.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "clip_options.hpp"
#include "commands.hpp"
#include "fuzzygait/eval/evaluation.hpp"
#include "fuzzygait/io/bvh.hpp"
#include "fuzzygait/io/files.hpp"
#include "fuzzygait/io/mocap.hpp"
#include "fuzzygait/io/normative.hpp"
#include "fuzzygait/io/walk_csv.hpp"
#include "fuzzygait/plot/svg.hpp"
#include "fuzzygait/plot/walk_plots.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::cli {
namespace {

namespace svg = plot::svg;

struct MocapOptions {
  std::string clip;
  std::string prefix = "out/mocap";
  ClipFlags reading;
  std::string reference = "schwartz2008_free";
};

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

void print_summary(const io::CapturedClip& c) {
  const eval::Motion& m = c.motion;
  std::cout << "read " << m.frames.size() << " frames at " << fixed(m.fps, 1) << " fps ("
            << fixed(m.frames.back().time, 3) << " s), skipped " << c.skipped_frames
            << (c.skipped_frames == 1 ? " frame" : " frames") << "\n";
  std::cout << "unit " << common::number_text(c.metres_per_unit) << " m ("
            << io::unit_name(c.metres_per_unit) << (c.unit_guessed ? ", guessed" : ", given")
            << "), up " << (c.up == io::UpAxis::Y ? "+Y" : "+Z")
            << (c.up_detected ? " (detected)" : " (given)") << ", root '" << c.root << "'\n";
  for (rig::Side side : rig::kSides) {
    const io::MeasuredLeg& l = c.legs[static_cast<std::size_t>(rig::index(side))];
    std::cout << (side == rig::Side::Left ? "left  " : "right ") << l.hip << " > " << l.knee
              << " > " << l.ankle << " > " << l.toe << (l.has_toes ? " > " + l.tip : "")
              << ": thigh " << fixed(l.thigh, 3) << " m, shank " << fixed(l.shank, 3) << " m, foot "
              << fixed(l.foot, 3) << " m"
              << (l.has_toes ? ", toes " + fixed(l.toes, 3) + " m" : ", no toes") << "\n";
  }
  const rig::Segments& s = m.segments;
  std::cout << "rig segments: thigh " << fixed(s.thigh, 3) << ", shank " << fixed(s.shank, 3)
            << ", ankle height " << fixed(s.ankle_height, 3) << ", heel " << fixed(s.heel, 3)
            << ", ball " << fixed(s.ball, 3) << ", toe " << fixed(s.toe, 3) << " m\n";
  std::cout << "heel strikes left " << c.events.heel_strikes[0].size() << ", right "
            << c.events.heel_strikes[1].size() << "; left cycles " << c.cycles.size()
            << "; cadence " << fixed(c.cadence, 1) << " steps/min, step length "
            << fixed(c.step_length, 3) << " m, speed " << fixed(c.speed, 2) << " m/s\n";
  for (const std::string& note : c.notes)
    std::cout << "note: " << note << "\n";
}

}  // namespace

void add_mocap_command(CLI::App& app) {
  auto o = std::make_shared<MocapOptions>();
  CLI::App* mocap = app.add_subcommand(
      "mocap", "Read a walking clip (BVH) into the rig's angles and write a walk's files");
  mocap->add_option("clip", o->clip, "BVH file of a walk")->required();
  mocap->add_option("-o,--output", o->prefix, "Prefix of the files written (default out/mocap)");
  add_clip_options(mocap, o->reading);
  mocap->add_option("--reference", o->reference, "Normative curves for the plot and summary");
  mocap->footer(
      "Writes PREFIX.csv (one row per frame, the walk CSV), PREFIX.terrain.csv (the floor),\n"
      "PREFIX.bvh (the rig's skeleton), PREFIX.svg (joint angles over the gait cycle against\n"
      "the normative band) and PREFIX.poses.svg. `fuzzygait eval PREFIX.csv` measures it.");
  mocap->callback([o]() {
    check_output_prefix(o->prefix, "-o");
    // PREFIX.bvh is written: it must not be the clip (`mocap walk.bvh -o walk`).
    std::error_code same_error;
    if (std::filesystem::equivalent(o->clip, o->prefix + ".bvh", same_error)) {
      throw std::invalid_argument("-o: '" + o->prefix + ".bvh' would overwrite the clip '" +
                                  o->clip + "'; choose another prefix");
    }
    // Everything that can be refused is refused before any file is written.
    const eval::Normative reference = io::load_normative(o->reference);
    const io::CapturedClip clip = io::read_clip(o->clip, clip_options(o->reading));
    const eval::Motion& motion = clip.motion;
    print_summary(clip);

    const std::filesystem::path prefix(o->prefix);
    if (prefix.has_parent_path()) std::filesystem::create_directories(prefix.parent_path());
    io::write_file(o->prefix + ".csv",
                   [&motion](std::ostream& out) { io::write_walk_csv(out, motion); });
    io::write_file(o->prefix + ".terrain.csv", [&](std::ostream& out) {
      const double x0 = motion.frames.front().pose.pelvis.x - 2.0;
      const double x1 = motion.frames.back().pose.pelvis.x + 2.0;
      io::write_terrain_csv(out, clip.ground, x0, x1);
    });
    io::write_file(o->prefix + ".bvh",
                   [&motion](std::ostream& out) { io::write_bvh(out, motion); });
    std::vector<std::string> written = {o->prefix + ".csv", o->prefix + ".terrain.csv",
                                        o->prefix + ".bvh"};
    const std::string title =
        "fuzzygait mocap, " + std::filesystem::path(o->clip).filename().string();
    try {
      const eval::GaitReport report = eval::evaluate(motion, clip.ground, &reference);
      std::cout << "against " << reference.name << ":\n" << eval::to_text(report);
      plot::plot_gait_curves(report, &reference, {.title = title}).save(o->prefix + ".svg");
      written.push_back(o->prefix + ".svg");
    } catch (const std::invalid_argument& e) {
      std::cout << "not measured, no curves: " << e.what() << "\n";
    }
    try {
      // A clip is in its stride from the start and holds few strides: the whole clip plays,
      // and the filmstrip shows its first stride.
      const svg::Figure animation =
          plot::plot_walk_animation(motion, clip.ground, {.first_stride = 0, .strides = 0});
      const svg::Figure filmstrip = plot::plot_filmstrip(motion, clip.ground, {.stride = 0});
      io::write_file(o->prefix + ".poses.svg", svg::stack_figures({&animation, &filmstrip}));
      written.push_back(o->prefix + ".poses.svg");
    } catch (const std::invalid_argument& e) {
      std::cout << "no poses: " << e.what() << "\n";
    }
    std::cout << "wrote";
    for (const std::string& f : written)
      std::cout << " " << f;
    std::cout << "\n";
  });
}

}  // namespace fuzzygait::cli

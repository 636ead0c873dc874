// `fuzzygait train`: learns a controller set from motion capture clips (learn::train) and writes
// it with a report: the error per joint before and after, and each clip's curves before and after
// against the clip. Ctrl-C stops the training and writes the best set found so far.
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "clip_options.hpp"
#include "commands.hpp"
#include "fuzzygait/io/controller_files.hpp"
#include "fuzzygait/io/files.hpp"
#include "fuzzygait/io/mocap.hpp"
#include "fuzzygait/learn/network.hpp"
#include "fuzzygait/learn/train.hpp"
#include "fuzzygait/learn/upper_body.hpp"
#include "fuzzygait/plot/walk_plots.hpp"

namespace fuzzygait::cli {
namespace {

// Set by the first Ctrl-C (SIGINT): the training stops after its current iteration. The second
// one ends the program at once (the handler puts the default back).
volatile std::sig_atomic_t interrupted = 0;
extern "C" void on_interrupt(int) {
  interrupted = 1;
  std::signal(SIGINT, SIG_DFL);
}

struct TrainCommandOptions {
  std::vector<std::string> clips;
  std::string output;
  std::string evaluate;  // the figures of the starting set alone, as JSON to this file
  int check_starts = 100;
  std::string base = "default";
  std::string controllers;
  std::string name;
  std::string description;
  ClipFlags reading;
  learn::TrainOptions train = learn::default_train_options();
  bool no_fits = false;
  bool base_structure = false;
};

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string clip_name(const std::string& path) {
  return std::filesystem::path(path).stem().string();
}

std::string score_text(const learn::ClipScore& s) {
  if (!s.walked) return "does not walk";
  return "thigh " + fixed(s.thigh, 1) + " knee " + fixed(s.knee, 1) + " ankle " +
         fixed(s.ankle, 1) + " deg, stance " + fixed(s.stance, 1) + " %, cadence " +
         fixed(s.cadence, 1);
}

nlohmann::ordered_json score_json(const learn::ClipScore& s) {
  nlohmann::ordered_json j;
  j["walked"] = s.walked;
  if (s.walked) {
    j["thigh_rmse_deg"] = s.thigh;
    j["knee_rmse_deg"] = s.knee;
    j["ankle_rmse_deg"] = s.ankle;
    j["stance_percent"] = s.stance;
    j["cadence_steps_per_min"] = s.cadence;
  }
  return j;
}

// One WalksCheck as a heading ("WHAT: N of M walks within BOUNDS"), a line per miss, and as
// `json`'s KEY_walks, KEY_within_bounds and KEY_misses.
std::string walks_check_text(const learn::WalksCheck& check, const std::string& what,
                             const std::string& bounds, const std::string& key,
                             nlohmann::ordered_json& json) {
  std::string text = what + ": " + std::to_string(check.within) + " of " +
                     std::to_string(check.walks) + " walks within " + bounds + "\n";
  for (const std::string& miss : check.misses)
    text += "  " + miss + "\n";
  json[key + "_walks"] = check.walks;
  json[key + "_within_bounds"] = check.within;
  json[key + "_misses"] = check.misses;
  return text;
}

// The grid's contact bounds, stairs and ramps, and the random starts of `set`, as text and into
// `json`.
std::string checks(const gait::ControllerSet& set, const learn::ClipsBody& body, int starts,
                   nlohmann::ordered_json& json) {
  std::string text = walks_check_text(learn::check_grid(set),
                                      "level grid (steps 0.50-0.85 m, statures 1.50-2.00 m)",
                                      "the contact bounds", "grid", json);
  text += walks_check_text(learn::check_terrain(set, body.body, body.step),
                           "stairs and ramps at the clips' body and step", "the bounds", "terrain",
                           json);
  if (starts > 0) {
    const learn::StartsCheck s = learn::check_starts(set, body.body, body.step, starts);
    text += "random starts at the clips' body and step: " + std::to_string(s.sound) + " of " +
            std::to_string(s.starts) + " sound, " + std::to_string(s.settled) +
            " settled within three steps\n";
    json["random_starts"] = s.starts;
    json["random_starts_sound"] = s.sound;
    json["random_starts_settled"] = s.settled;
  }
  return text;
}

// The words whose numbers moved, base -> trained, one line each.
// (A word the training added has no base value: "new".)
std::vector<std::string> moved_values(const gait::ControllerSet& base,
                                      const gait::ControllerSet& trained) {
  const learn::SetNetwork before(base);
  const learn::SetNetwork after(trained);
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < after.size(); ++i) {
    const std::string& name = after.weight(i).name;
    const std::size_t was = before.find(name);
    const double b = after.values()[i];
    char line[200];
    if (was == before.size()) {
      std::snprintf(line, sizeof line, "%-40s %10s -> %.4g", name.c_str(), "new", b);
    } else {
      const double a = before.values()[was];
      if (a == b) continue;
      std::snprintf(line, sizeof line, "%-40s %10.4g -> %.4g", name.c_str(), a, b);
    }
    lines.push_back(line);
  }
  for (int p = 0; p < gait::kUpperBodyCount; ++p) {
    const auto& a = base.upper_body[static_cast<std::size_t>(p)];
    const auto& b = trained.upper_body[static_cast<std::size_t>(p)];
    if (!a || !b) continue;
    const auto& was = a->engine().outputs;
    const auto& now = b->engine().outputs;
    if (was.size() != 1 || now.size() != 1 || was[0].terms.size() != now[0].terms.size()) continue;
    for (std::size_t t = 0; t < now[0].terms.size(); ++t) {
      const fuzzy::Term& old_term = was[0].terms[t];
      const fuzzy::Term& new_term = now[0].terms[t];
      if (old_term.parameters == new_term.parameters || old_term.parameters.size() != 1 ||
          new_term.parameters.size() != 1) {
        continue;
      }
      const std::string name = "upper_body_" +
                               std::string(gait::upper_body_name(static_cast<gait::UpperBody>(p))) +
                               "." + new_term.name;
      char line[200];
      std::snprintf(line, sizeof line, "%-40s %10.4g -> %.4g", name.c_str(), old_term.parameters[0],
                    new_term.parameters[0]);
      lines.push_back(line);
    }
  }
  return lines;
}

// The upper body's fit: per part, each clip's RMSE before and after (report text; JSON into
// `json`), and the clips that taught it nothing.
std::string upper_body_report(const std::optional<learn::UpperBodyFit>& fit,
                              const std::vector<learn::UpperBodyClip>& clips,
                              const std::vector<std::string>& without,
                              nlohmann::ordered_json& json) {
  std::string text = "\nupper body";
  nlohmann::ordered_json j;
  if (!fit) {
    text += ": not fitted (no clip shows arms, or the set has no upper body)\n";
  } else {
    text += " (RMSE against each clip, before -> after; the sway in % of the leg):\n";
    for (int p = 0; p < gait::kUpperBodyCount; ++p) {
      const auto i = static_cast<std::size_t>(p);
      if (!fit->fitted[i]) continue;
      const std::string part(gait::upper_body_name(static_cast<gait::UpperBody>(p)));
      text += "  " + part + ":";
      nlohmann::ordered_json per_clip = nlohmann::json::array();
      for (std::size_t c = 0; c < clips.size(); ++c) {
        text += " " + clips[c].name + " " + fixed(fit->rmse_before[i][c], 2) + " -> " +
                fixed(fit->rmse_after[i][c], 2);
        per_clip.push_back({{"clip", clips[c].name},
                            {"rmse_before", fit->rmse_before[i][c]},
                            {"rmse_after", fit->rmse_after[i][c]}});
      }
      text += "\n";
      j[part] = per_clip;
    }
    for (const std::string& note : fit->notes)
      text += "  " + note + "\n";
  }
  for (const std::string& w : without)
    text += "  no upper body in " + w + "\n";
  json["upper_body"] = j;
  return text;
}

}  // namespace

void add_train_command(CLI::App& app) {
  auto o = std::make_shared<TrainCommandOptions>();
  learn::TuneOptions& polish = o->train.polish;
  CLI::App* train = app.add_subcommand(
      "train", "Learn a controller set from motion capture clips (BVH) and write it with a report");
  train->add_option("clips", o->clips, "BVH files of walks")->required();
  train->add_option("-o,--output", o->output, "Folder to write the trained set and its report to");
  train->add_option("--evaluate", o->evaluate,
                    "Do not train: walk the starting set against the clips, check it on the grid "
                    "and from random starts, print the figures and write them as JSON to this file "
                    "('-' for standard output)");
  train
      ->add_option("--check-starts", o->check_starts,
                   "Random start poses the trained set is checked from (default 100)")
      ->check(CLI::Range(0, 100000));
  train->add_option("--base", o->base, "Built-in set to start from (default: default)");
  train->add_option("--controllers", o->controllers, "Controller set folder to start from");
  train->add_option("--name", o->name, "Name of the trained set (default: the folder's name)");
  train->add_option("--description", o->description, "Description of the trained set");
  add_clip_options(train, o->reading);
  train
      ->add_option("--generations", polish.generations,
                   "Generations of the closed-loop polish (CMA-ES; default 800)")
      ->check(CLI::Range(0, 1000000));
  train
      ->add_option("--polish", polish.polish_generations,
                   "Then generations on the rounded values (default 100)")
      ->check(CLI::Range(0, 1000000));
  train->add_option("--threads", polish.threads, "Walks evaluated in parallel (default 2)")
      ->check(CLI::Range(1, 1024));
  train->add_option("--seed", polish.seed, "Random seed (the result is deterministic for a seed)");
  train
      ->add_option("--steps-around", o->train.steps_around,
                   "Also keep the contact bounds at each clip's body walking these multiples of "
                   "its step (for example 0.7 1.2)")
      ->check(CLI::Range(0.3, 2.0));
  train->add_flag("--grid", o->train.grid,
                  "Also keep the level contact bounds on the step/stature grid (steps 0.50-0.85 m, "
                  "statures 1.50-2.00 m) while polishing: slower");
  train
      ->add_option("--recovery", o->train.recovery_starts,
                   "Random start poses that must settle into the gait while polishing")
      ->check(CLI::Range(0, 10000));
  train
      ->add_option("--fit-iterations", o->train.fit.max_iterations,
                   "Levenberg-Marquardt iterations of each fit at most (default 30)")
      ->check(CLI::Range(1, 100000));
  train->add_flag("--no-fits", o->no_fits, "Skip the fits: the closed-loop polish alone");
  train->add_flag("--base-structure", o->base_structure,
                  "Keep the base set's words: add none where its rules cannot follow the clips");
  train->footer(
      "Writes the set (manifest.json with the clips' body and step, and its FLL files) into\n"
      "the folder, with report.txt and report.json (error per joint before and after, the values\n"
      "that moved) and CLIP.svg per clip (its curves before and after training against the\n"
      "clip). `fuzzygait walk --controllers DIR` walks it at the clips' body and step.\n"
      "Ctrl-C stops the training and writes the best set found so far.");
  train->callback([o, train]() {
    if (train->count("--base") > 0 && !o->controllers.empty()) {
      throw std::invalid_argument("--base and --controllers both name the set to start from");
    }
    if (o->output.empty() && o->evaluate.empty()) {
      throw std::invalid_argument("-o: the folder to write the trained set to is required");
    }
    // Everything that can be refused is refused before the training starts.
    const gait::ControllerSet base = o->controllers.empty()
                                         ? gait::ControllerSet::builtin(o->base)
                                         : gait::ControllerSet::load(o->controllers);
    const learn::SetNetwork check(base);  // every slot of the partition shape
    const io::ClipOptions reading = clip_options(o->reading);
    std::vector<learn::TrainClip> clips;
    // What each clip shows of the arms, pelvis and chest, for the set's upper body.
    std::vector<std::optional<learn::UpperBodySeries>> upper_bodies;
    std::vector<std::string> no_upper_body;
    clips.reserve(o->clips.size());
    for (const std::string& path : o->clips) {
      const io::BvhClip bvh = io::read_bvh_file(path);
      io::CapturedClip clip = io::analyse_clip(bvh, path, reading);
      std::string why;
      upper_bodies.push_back(learn::capture_upper_body(bvh, clip, &why));
      if (!upper_bodies.back()) no_upper_body.push_back(clip_name(path) + ": " + why);
      clips.push_back(
          learn::make_train_clip(clip_name(path), std::move(clip.motion), std::move(clip.ground)));
      const learn::TrainClip& c = clips.back();
      std::cerr << "clip " << c.name << ": " << c.motion.frames.size() << " frames, "
                << c.report.cycles << (c.report.cycles == 1 ? " cycle" : " cycles") << ", step "
                << fixed(c.step_length, 3) << " m, stance " << fixed(c.report.stance_percent, 1)
                << " %, cadence " << fixed(c.report.cadence, 1) << " steps/min\n";
    }
    const learn::ClipsBody clips_body = learn::clips_body(clips);
    if (!o->evaluate.empty()) {
      nlohmann::ordered_json json;
      json["set"] = base.name;
      nlohmann::ordered_json per_clip = nlohmann::json::array();
      std::string text;
      for (const learn::TrainClip& c : clips) {
        const learn::ClipScore score = learn::score_clip(base, c);
        text += c.name + " (clip: stance " + fixed(c.report.stance_percent, 1) + " %, cadence " +
                fixed(c.report.cadence, 1) + ", step " + fixed(c.step_length, 3) +
                " m): " + score_text(score) + "\n";
        nlohmann::ordered_json j = score_json(score);
        j["clip"] = c.name;
        j["clip_stance_percent"] = c.report.stance_percent;
        j["clip_cadence_steps_per_min"] = c.report.cadence;
        per_clip.push_back(j);
      }
      json["clips"] = per_clip;
      text += checks(base, clips_body, o->check_starts, json);
      std::cout << text;
      if (o->evaluate == "-") {
        std::cout << json.dump(2) << "\n";
      } else {
        io::write_file(o->evaluate, json.dump(2) + "\n");
      }
      return;
    }
    learn::TrainOptions options = o->train;
    options.fits = !o->no_fits;
    options.structure = !o->base_structure;
    options.progress = [](const learn::TrainProgress& p) {
      const bool scored = !p.rmse.empty();
      if (!scored && p.iteration % 10 != 0) return;
      std::cerr << p.stage << (p.stage == "polish" ? " generation " : " iteration ") << p.iteration;
      if (p.cost > 0.0) std::cerr << ": cost " << fixed(p.cost, 3);
      for (const std::array<double, 3>& r : p.rmse) {
        std::cerr << " | thigh " << fixed(r[0], 2) << " knee " << fixed(r[1], 2) << " ankle "
                  << fixed(r[2], 2);
      }
      std::cerr << "\n";
    };
    interrupted = 0;
    options.stop = [] { return interrupted != 0; };
    const auto previous = std::signal(SIGINT, on_interrupt);
    learn::TrainResult result;
    try {
      result = learn::train(base, clips, options);
    } catch (...) {
      std::signal(SIGINT, previous);
      throw;
    }
    std::signal(SIGINT, previous);
    if (result.stopped) std::cerr << "stopped: writing the best set found so far\n";

    // The set, named, with the clips' body and step (their means), and its upper body fitted to
    // the clips that show one.
    gait::ControllerSet trained = result.set;
    std::vector<learn::UpperBodyClip> upper_clips;
    for (std::size_t k = 0; k < clips.size(); ++k) {
      if (upper_bodies[k]) upper_clips.push_back({clips[k].name, &clips[k], *upper_bodies[k]});
    }
    std::optional<learn::UpperBodyFit> upper_fit;
    if (!upper_clips.empty() && std::any_of(trained.upper_body.begin(), trained.upper_body.end(),
                                            [](const auto& c) { return c.has_value(); })) {
      upper_fit = learn::fit_upper_body(trained, upper_clips);
      trained.upper_body = upper_fit->set.upper_body;
    }
    const std::filesystem::path folder(o->output);
    trained.name = o->name.empty() ? folder.filename().string() : o->name;
    if (trained.name.empty()) trained.name = "trained";
    trained.body = clips_body.body;
    trained.body_step_length = clips_body.step;
    trained.body_speed = clips_body.speed;
    trained.description = o->description.empty()
                              ? "Trained on " + clips_body.names + " from '" + base.name + "'."
                              : o->description;
    io::save_controller_set(trained, folder);

    // The report: text, JSON and each clip's curves.
    std::string text = "fuzzygait train: '" + trained.name + "' from '" + base.name + "' on " +
                       std::to_string(clips.size()) + (clips.size() == 1 ? " clip" : " clips") +
                       " in " + fixed(result.seconds, 1) + " s" +
                       (result.stopped ? " (stopped early)" : "") + "\n";
    text += "closed-loop cost " + fixed(result.cost_before, 2) + " -> " +
            fixed(result.cost_after, 2) + "\n\n";
    nlohmann::ordered_json json;
    json["name"] = trained.name;
    json["base"] = base.name;
    json["seconds"] = result.seconds;
    json["stopped"] = result.stopped;
    json["cost_before"] = result.cost_before;
    json["cost_after"] = result.cost_after;
    nlohmann::ordered_json per_clip = nlohmann::json::array();
    std::vector<std::string> written;
    for (std::size_t k = 0; k < clips.size(); ++k) {
      const learn::TrainClip& c = clips[k];
      text += c.name + " (clip: stance " + fixed(c.report.stance_percent, 1) + " %, cadence " +
              fixed(c.report.cadence, 1) + ", step " + fixed(c.step_length, 3) + " m)\n";
      text += "  before: " + score_text(result.before[k]) + "\n";
      text += "  after:  " + score_text(result.after[k]) + "\n";
      nlohmann::ordered_json j;
      j["clip"] = c.name;
      j["step_length_m"] = c.step_length;
      j["clip_stance_percent"] = c.report.stance_percent;
      j["clip_cadence_steps_per_min"] = c.report.cadence;
      j["before"] = score_json(result.before[k]);
      j["after"] = score_json(result.after[k]);
      per_clip.push_back(j);
      std::vector<plot::LabelledReport> walks;
      if (result.before[k].walked)
        walks.push_back({"before: " + base.name, result.before[k].report});
      if (result.after[k].walked)
        walks.push_back({"after: " + trained.name, result.after[k].report});
      if (walks.empty()) continue;
      const eval::Normative reference = learn::clip_reference(c.report, "clip " + c.name);
      const std::filesystem::path picture = folder / (c.name + ".svg");
      plot::plot_curve_comparison(
          walks, &reference,
          {.title = c.name + ": before and after training",
           .joints = {plot::GaitJoint::Thigh, plot::GaitJoint::Knee, plot::GaitJoint::Ankle}})
          .save(picture);
      written.push_back(picture.string());
    }
    json["clips"] = per_clip;
    text += upper_body_report(upper_fit, upper_clips, no_upper_body, json);
    text += "\n" + checks(trained, clips_body, o->check_starts, json);
    if (!result.added.empty()) {
      text += "\nstructure added (the base's rules could not follow the clips):\n";
      nlohmann::ordered_json added = nlohmann::json::array();
      for (const learn::AddedWord& w : result.added) {
        const std::string slot(gait::slot_name(w.slot));
        text += "  " + slot + ": '" + w.input + " is " + w.word + "', peaking at " +
                fixed(w.peak, 1) + ", its rules those of '" + w.like + "': " + w.why + "\n";
        added.push_back({{"slot", slot},
                         {"input", w.input},
                         {"word", w.word},
                         {"peak", w.peak},
                         {"rules_like", w.like}});
      }
      json["structure_added"] = added;
    }
    text += "\nstages:\n";
    nlohmann::ordered_json stages = nlohmann::json::array();
    for (const learn::StageRecord& s : result.stages) {
      const std::string kept =
          s.kept == 0 ? ""
          : s.stage == "structure"
              ? ", " + std::to_string(s.kept) + (s.kept == 1 ? " word" : " words") + " added"
              : ", " + std::to_string(s.kept) + " controllers' values kept";
      text += "  " + s.stage + ": cost " + fixed(s.cost, 2) + kept + ", " + fixed(s.seconds, 2) +
              " s\n";
      stages.push_back(
          {{"stage", s.stage}, {"cost", s.cost}, {"kept", s.kept}, {"seconds", s.seconds}});
    }
    json["stages"] = stages;
    text += "\nvalues that moved (base -> trained):\n";
    nlohmann::ordered_json moved = nlohmann::json::array();
    for (const std::string& line : moved_values(base, trained)) {
      text += "  " + line + "\n";
      moved.push_back(line);
    }
    json["moved"] = moved;
    io::write_file(folder / "report.txt", text);
    io::write_file(folder / "report.json", json.dump(2) + "\n");
    std::cout << text;
    // A training that made the set worse, or whose walks fail, is no result: the files stay for
    // a look, the exit status says so.
    if (!std::isfinite(result.cost_after) ||
        (!result.stopped && !(result.cost_after < result.cost_before))) {
      throw std::runtime_error("the trained set walks no better than '" + base.name +
                               "' (closed-loop cost " + fixed(result.cost_before, 2) + " -> " +
                               fixed(result.cost_after, 2) +
                               "): the clips may not be walks this set can learn; see " +
                               (folder / "report.txt").string());
    }
    std::cout << "wrote the set '" << trained.name << "' to " << o->output << ", "
              << (folder / "report.txt").string() << ", " << (folder / "report.json").string();
    for (const std::string& f : written)
      std::cout << ", " << f;
    std::cout << "\n";
  });
}

}  // namespace fuzzygait::cli

// The offline library in Python: recorded motion (arrays, CSV, BVH), evaluation against normative
// curves (GaitReport), motion capture clips and training a set on them.
#include <pybind11/functional.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "fuzzygait/eval/evaluation.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/io/bvh.hpp"
#include "fuzzygait/io/files.hpp"
#include "fuzzygait/io/mocap.hpp"
#include "fuzzygait/io/normative.hpp"
#include "fuzzygait/io/walk_csv.hpp"
#include "fuzzygait/learn/train.hpp"

namespace fuzzygait::python {
namespace {

// A number as people write it: a whole number without a point, else Python's shortest text that
// reads back as the same double.
std::string number_text(double value) {
  if (std::floor(value) == value && std::abs(value) < 1e15) {
    return std::to_string(static_cast<long long>(value));
  }
  return py::repr(py::float_(value));
}

// One value of every frame, as an array of shape [frame] + `inner`.
template <class Values>
py::array_t<double> per_frame(const eval::Motion& m, std::vector<py::ssize_t> inner,
                              Values values) {
  std::vector<double> v;
  for (const eval::Frame& f : m.frames)
    values(f, v);
  inner.insert(inner.begin(), static_cast<py::ssize_t>(m.frames.size()));
  return copy_array(v, std::move(inner));
}

void bind_motion(py::module_& m) {
  py::class_<Motion>(m, "Motion",
                     "A walk as sampled frames (recorded by a Walker, read from a walk CSV or a "
                     "clip). Its arrays are copies: times (n), pelvis (n, 2), pelvis_tilt (n), "
                     "angles (n, 2, 4), points (n, 2, 6, 2), contact (n, 2).")
      .def_static(
          "read_csv",
          [](const std::filesystem::path& path) {
            std::ifstream in(path);
            if (!in) throw fuzzy::ParseError(path.string(), 0, "cannot open the file");
            return Motion{io::read_walk_csv(in, path.string()),
                          std::make_shared<terrain::Terrain>(terrain::Terrain::flat()),
                          std::nullopt};
          },
          py::arg("path"), "Reads a walk CSV (`fuzzygait walk`'s PREFIX.csv); the ground is level.")
      .def("__len__", [](const Motion& s) { return s.motion.frames.size(); })
      .def("__repr__",
           [](const Motion& s) {
             return "<fuzzygait.Motion of " + std::to_string(s.motion.frames.size()) +
                    " frames at " + number_text(s.motion.fps) + " fps>";
           })
      .def_property_readonly("fps", [](const Motion& s) { return s.motion.fps; })
      .def_property_readonly("captured", [](const Motion& s) { return s.motion.captured; })
      .def_property_readonly("segments",
                             [](const Motion& s) { return segments_dict(s.motion.segments); })
      .def_property_readonly("ground", [](const Motion& s) { return s.ground; })
      .def_property_readonly("commanded_step", [](const Motion& s) { return s.commanded_step; })
      .def_property_readonly("times",
                             [](const Motion& s) {
                               return per_frame(s.motion, {}, [](const eval::Frame& f, auto& v) {
                                 v.push_back(f.time);
                               });
                             })
      .def_property_readonly("pelvis",
                             [](const Motion& s) {
                               return per_frame(s.motion, {2}, [](const eval::Frame& f, auto& v) {
                                 v.push_back(f.pose.pelvis.x);
                                 v.push_back(f.pose.pelvis.y);
                               });
                             })
      .def_property_readonly("pelvis_tilt",
                             [](const Motion& s) {
                               return per_frame(s.motion, {}, [](const eval::Frame& f, auto& v) {
                                 v.push_back(f.pose.pelvis_tilt);
                               });
                             })
      .def_property_readonly("angles",
                             [](const Motion& s) {
                               return per_frame(s.motion, {2, 4},
                                                [](const eval::Frame& f, auto& v) {
                                                  for (const rig::LegAngles& a : f.pose.legs) {
                                                    for (double x : {a.hip, a.knee, a.ankle, a.toe})
                                                      v.push_back(x);
                                                  }
                                                });
                             })
      .def_property_readonly(
          "points",
          [](const Motion& s) {
            return per_frame(s.motion, {2, 6, 2}, [](const eval::Frame& f, auto& v) {
              for (const rig::LegPoints& p : f.points) {
                for (const rig::Point& q : {p.hip, p.knee, p.ankle, p.heel, p.ball, p.tip}) {
                  v.push_back(q.x);
                  v.push_back(q.y);
                }
              }
            });
          })
      .def_property_readonly(
          "contact",
          [](const Motion& s) {
            py::array_t<bool> a({static_cast<py::ssize_t>(s.motion.frames.size()), py::ssize_t{2}});
            auto r = a.mutable_unchecked<2>();
            for (std::size_t i = 0; i < s.motion.frames.size(); ++i) {
              for (std::size_t leg = 0; leg < 2; ++leg)
                r(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(leg)) =
                    s.motion.frames[i].contact[leg];
            }
            return a;
          })
      .def("to_csv",
           [](const Motion& s) {
             std::ostringstream out;
             io::write_walk_csv(out, s.motion);
             return out.str();
           })
      .def(
          "write_csv",
          [](const Motion& s, const std::filesystem::path& path) {
            io::write_file(path, [&s](std::ostream& out) { io::write_walk_csv(out, s.motion); });
          },
          py::arg("path"))
      .def(
          "write_bvh",
          [](const Motion& s, const std::filesystem::path& path) {
            io::write_file(path, [&s](std::ostream& out) { io::write_bvh(out, s.motion); });
          },
          py::arg("path"));
}

// The report's plain numbers, by name: the attributes and to_dict() both come from this table.
struct ReportNumber {
  const char* name;
  double eval::GaitReport::*member;
};
constexpr ReportNumber kReportNumbers[] = {
    {"cycle_time", &eval::GaitReport::cycle_time},
    {"cycle_time_sd", &eval::GaitReport::cycle_time_sd},
    {"cadence", &eval::GaitReport::cadence},
    {"speed", &eval::GaitReport::speed},
    {"stance_percent", &eval::GaitReport::stance_percent},
    {"step_length", &eval::GaitReport::step_length},
    {"step_length_sd", &eval::GaitReport::step_length_sd},
    {"knee_peak", &eval::GaitReport::knee_peak},
    {"knee_peak_percent", &eval::GaitReport::knee_peak_percent},
    {"thigh_range", &eval::GaitReport::thigh_range},
    {"pelvis_vertical_range", &eval::GaitReport::pelvis_vertical_range},
    {"pelvis_speed_ratio_min", &eval::GaitReport::pelvis_speed_ratio_min},
    {"pelvis_speed_ratio_max", &eval::GaitReport::pelvis_speed_ratio_max},
    {"pelvis_rise_speed", &eval::GaitReport::pelvis_rise_speed},
    {"thigh_overshoot", &eval::GaitReport::thigh_overshoot},
    {"knee_loading_peak", &eval::GaitReport::knee_loading_peak},
    {"ankle_push_off", &eval::GaitReport::ankle_push_off},
    {"max_slip", &eval::GaitReport::max_slip},
    {"max_penetration", &eval::GaitReport::max_penetration},
    {"min_toe_clearance", &eval::GaitReport::min_toe_clearance},
    {"max_heel_bounce", &eval::GaitReport::max_heel_bounce},
    {"max_velocity_jump", &eval::GaitReport::max_velocity_jump},
    {"typical_velocity_change", &eval::GaitReport::typical_velocity_change},
};

py::dict curve_dict(const eval::Curve& c) {
  py::dict d;
  d["mean"] = copy_array(std::vector<double>(c.mean.begin(), c.mean.end()), {eval::kCycleSamples});
  d["sd"] = copy_array(std::vector<double>(c.sd.begin(), c.sd.end()), {eval::kCycleSamples});
  return d;
}

py::object score_dict(const std::optional<eval::JointScore>& s) {
  if (!s) return py::none();
  py::dict d;
  d["rmse"] = s->rmse;
  d["pearson"] = s->pearson;
  d["within_2sd"] = s->within_2sd;
  d["acceleration_rms"] = s->acceleration_rms;
  d["reference_acceleration_rms"] = s->reference_acceleration_rms;
  d["acceleration_ratio"] = s->acceleration_ratio();
  return d;
}

// The left leg's mean curves and their scores, by joint.
constexpr std::pair<const char*, eval::Curve eval::GaitReport::*> kCurves[] = {
    {"thigh", &eval::GaitReport::thigh},
    {"knee", &eval::GaitReport::knee},
    {"ankle", &eval::GaitReport::ankle},
    {"toe", &eval::GaitReport::toe}};
constexpr std::pair<const char*, std::optional<eval::JointScore> eval::GaitReport::*> kScores[] = {
    {"thigh", &eval::GaitReport::thigh_score},
    {"knee", &eval::GaitReport::knee_score},
    {"ankle", &eval::GaitReport::ankle_score}};

py::dict curves_dict(const eval::GaitReport& r) {
  py::dict d;
  for (const auto& [name, curve] : kCurves)
    d[name] = curve_dict(r.*curve);
  return d;
}

py::dict scores_dict(const eval::GaitReport& r) {
  py::dict d;
  for (const auto& [name, score] : kScores)
    d[name] = score_dict(r.*score);
  return d;
}

py::list smoothness_list(const eval::GaitReport& r) {
  py::list joints;
  for (const eval::JointSmoothness& j : r.smoothness) {
    py::dict d;
    d["rms_acceleration"] = j.rms_acceleration;
    d["rms_jerk"] = j.rms_jerk;
    d["max_jerk"] = j.max_jerk;
    joints.append(d);
  }
  return joints;
}

py::dict report_dict(const eval::GaitReport& r) {
  py::dict d;
  d["cycles"] = r.cycles;
  for (const ReportNumber& n : kReportNumbers)
    d[n.name] = r.*n.member;
  d["step_error_percent"] = r.step_error_percent;
  d["smoothness"] = smoothness_list(r);
  d["curves"] = curves_dict(r);
  d["scores"] = scores_dict(r);
  return d;
}

void bind_report(py::module_& m) {
  py::class_<eval::GaitReport> report(
      m, "GaitReport",
      "How a walk measures (docs/measuring.md): timing, contact, smoothness, the left leg's mean "
      "curves (degrees over 51 samples of the cycle) and their scores against the reference.");
  report.def_readonly("cycles", &eval::GaitReport::cycles);
  for (const ReportNumber& n : kReportNumbers)
    report.def_readonly(n.name, n.member);
  report.def_readonly("step_error_percent", &eval::GaitReport::step_error_percent)
      .def_property_readonly("smoothness", &smoothness_list,
                             "hip, knee, ankle, toe: rms_acceleration, rms_jerk, max_jerk")
      .def_property_readonly("curves", &curves_dict, "thigh, knee, ankle, toe: {mean, sd}")
      .def_property_readonly("scores", &scores_dict,
                             "thigh, knee, ankle: {rmse, pearson, within_2sd, ...} or None")
      .def("to_dict", &report_dict)
      .def("__repr__",
           [](const eval::GaitReport& r) {
             return "<fuzzygait.GaitReport of " + std::to_string(r.cycles) + " cycles: cadence " +
                    number_text(r.cadence) + ", stance " + number_text(r.stance_percent) + " %>";
           })
      .def("to_text", [](const eval::GaitReport& r) { return eval::to_text(r); })
      .def("to_json", [](const eval::GaitReport& r) { return eval::to_json(r); })
      .def("missed_contact_bounds",
           [](const eval::GaitReport& r) { return eval::missed_contact_bounds(r); });

  m.def(
      "evaluate",
      [](const Motion& s, const std::optional<std::string>& reference,
         const std::optional<double>& step) {
        std::optional<eval::Normative> normative;
        if (reference) normative = io::load_normative(*reference);
        return eval::evaluate(s.motion, *s.ground, normative ? &*normative : nullptr,
                              step ? step : s.commanded_step);
      },
      py::arg("motion"), py::arg("reference") = "schwartz2008_free", py::arg("step") = py::none(),
      "Measures a walk as `fuzzygait eval` does, against normative curves (a built-in name or a "
      "CSV file; None: no scores) and the step it was asked for (default: the motion's).");
  m.def("normative_names", &io::builtin_normative_names, "The built-in reference curves.");
}

// A motion capture clip read into the rig's terms, with its name.
struct Clip {
  std::string name;
  io::CapturedClip clip;
};

io::ClipOptions clip_options(const std::optional<std::filesystem::path>& map,
                             const std::optional<std::string>& up,
                             const std::optional<double>& unit,
                             const std::optional<std::size_t>& skip) {
  io::ClipOptions o;
  if (map) o.mapping = io::read_leg_mapping_file(*map);
  if (up) {
    if (*up != "y" && *up != "z")
      throw std::invalid_argument("up must be 'y' or 'z', got '" + *up + "'");
    o.up = *up == "y" ? io::UpAxis::Y : io::UpAxis::Z;
  }
  if (unit && !(*unit > 0.0 && *unit <= 1000.0)) {
    throw std::invalid_argument("unit must be metres per unit, above 0 and at most 1000, got " +
                                number_text(*unit));
  }
  o.metres_per_unit = unit;
  o.skip = skip;
  return o;
}

void bind_clips(py::module_& m) {
  py::class_<Clip>(m, "Clip", "A walking clip (BVH) read into the rig's terms.")
      .def_readonly("name", &Clip::name)
      .def_property_readonly("motion",
                             [](const Clip& c) {
                               return Motion{c.clip.motion,
                                             std::make_shared<terrain::Terrain>(c.clip.ground),
                                             std::nullopt};
                             })
      .def_property_readonly("cadence", [](const Clip& c) { return c.clip.cadence; })
      .def_property_readonly("step_length", [](const Clip& c) { return c.clip.step_length; })
      .def_property_readonly("speed", [](const Clip& c) { return c.clip.speed; })
      .def_property_readonly("notes", [](const Clip& c) { return c.clip.notes; })
      .def_property_readonly("skipped_frames", [](const Clip& c) { return c.clip.skipped_frames; })
      .def_property_readonly("metres_per_unit",
                             [](const Clip& c) { return c.clip.metres_per_unit; })
      .def_property_readonly("unit",
                             [](const Clip& c) { return io::unit_name(c.clip.metres_per_unit); })
      .def_property_readonly("up",
                             [](const Clip& c) { return c.clip.up == io::UpAxis::Y ? "y" : "z"; })
      .def_property_readonly("cycles", [](const Clip& c) { return c.clip.cycles; })
      .def("__repr__", [](const Clip& c) {
        return "<fuzzygait.Clip '" + c.name + "': " + std::to_string(c.clip.motion.frames.size()) +
               " frames>";
      });
  m.def(
      "read_clip",
      [](const std::filesystem::path& path, const std::optional<std::filesystem::path>& map,
         const std::optional<std::string>& up, const std::optional<double>& unit,
         const std::optional<std::size_t>& skip) {
        return Clip{path.stem().string(), io::read_clip(path, clip_options(map, up, unit, skip))};
      },
      py::arg("path"), py::kw_only(), py::arg("map") = py::none(), py::arg("up") = py::none(),
      py::arg("unit") = py::none(), py::arg("skip") = py::none(),
      "Reads a BVH walking clip as `fuzzygait mocap` does: map (a leg mapping JSON file), up "
      "('y' or 'z'), unit (metres per BVH unit), skip (leading frames).");
}

// What train() returns.
struct Training {
  SetPtr set;
  double cost_before = 0.0;
  double cost_after = 0.0;
  double seconds = 0.0;
  bool stopped = false;
  py::list before;
  py::list after;
  py::list stages;
  py::list added;
};

py::dict clip_score_dict(const learn::ClipScore& s) {
  py::dict d;
  d["walked"] = s.walked;
  d["thigh"] = s.thigh;
  d["knee"] = s.knee;
  d["ankle"] = s.ankle;
  d["stance"] = s.stance;
  d["cadence"] = s.cadence;
  d["report"] = s.report;
  return d;
}

void check_range(const char* name, double value, double low, double high) {
  if (!(value >= low && value <= high)) {
    throw std::invalid_argument(std::string(name) + " must be between " + number_text(low) +
                                " and " + number_text(high) + ", got " + number_text(value));
  }
}

struct TrainArguments {
  std::optional<std::string> name;
  std::optional<std::string> description;
  int generations = 800;
  int polish = 100;
  int threads = 2;
  std::optional<std::uint64_t> seed;
  std::vector<double> steps_around;
  bool grid = false;
  int recovery = 0;
  int fit_iterations = 30;
  bool fits = true;
  bool base_structure = false;
  io::ClipOptions reading;  // for the clips given as paths
};

// The options `fuzzygait train` makes of its flags, checked as it checks them.
learn::TrainOptions train_options(const TrainArguments& a) {
  check_range("generations", a.generations, 0, 1000000);
  check_range("polish", a.polish, 0, 1000000);
  check_range("threads", a.threads, 1, 1024);
  check_range("recovery", a.recovery, 0, 10000);
  check_range("fit_iterations", a.fit_iterations, 1, 100000);
  for (double s : a.steps_around)
    check_range("steps_around", s, 0.3, 2.0);
  learn::TrainOptions o = learn::default_train_options();
  o.polish.generations = a.generations;
  o.polish.polish_generations = a.polish;
  o.polish.threads = a.threads;
  if (a.seed) o.polish.seed = *a.seed;
  o.steps_around = a.steps_around;
  o.grid = a.grid;
  o.recovery_starts = a.recovery;
  o.fit.max_iterations = a.fit_iterations;
  o.fits = a.fits;
  o.structure = !a.base_structure;
  return o;
}

Training train(const py::object& clips, const py::object& base_set, const TrainArguments& a,
               const py::object& progress) {
  learn::TrainOptions options = train_options(a);
  const SetPtr base = to_set(base_set);
  std::vector<learn::TrainClip> train_clips;
  for (const py::handle c : clips) {
    const Clip clip = py::isinstance<Clip>(c)
                          ? c.cast<Clip>()
                          : Clip{c.cast<std::filesystem::path>().stem().string(),
                                 io::read_clip(c.cast<std::filesystem::path>(), a.reading)};
    train_clips.push_back(learn::make_train_clip(clip.name, clip.clip.motion, clip.clip.ground));
  }
  const learn::ClipsBody body = learn::clips_body(train_clips);
  // A Python exception in `progress`, or Ctrl-C, stops the training after its iteration; the
  // exception is raised again, Ctrl-C keeps the best set so far (result.stopped).
  std::exception_ptr failure;
  bool interrupted = false;
  options.progress = [&](const learn::TrainProgress& p) {
    py::gil_scoped_acquire acquire;
    if (progress.is_none() || failure) return;
    try {
      py::dict d;
      d["stage"] = p.stage;
      d["iteration"] = p.iteration;
      d["cost"] = p.cost;
      d["rmse"] = p.rmse;
      progress(d);
    } catch (const py::error_already_set& e) {
      if (e.matches(PyExc_KeyboardInterrupt)) {
        interrupted = true;  // Ctrl-C while the callback ran
      } else {
        failure = std::current_exception();
      }
    }
  };
  options.stop = [&] {
    py::gil_scoped_acquire acquire;
    if (PyErr_CheckSignals() != 0) {
      PyErr_Clear();
      interrupted = true;
    }
    return interrupted || failure != nullptr;
  };
  learn::TrainResult result;
  {
    py::gil_scoped_release release;
    result = learn::train(*base, train_clips, options);
  }
  if (failure) std::rethrow_exception(failure);

  // Named, with the clips' body and step, as `fuzzygait train` writes it.
  auto trained = std::make_shared<gait::ControllerSet>(result.set);
  trained->name = a.name.value_or("trained");
  trained->description =
      a.description.value_or("Trained on " + body.names + " from '" + base->name + "'.");
  trained->body = body.body;
  trained->body_step_length = body.step;
  trained->body_speed = body.speed;
  Training t;
  t.set = trained;
  t.cost_before = result.cost_before;
  t.cost_after = result.cost_after;
  t.seconds = result.seconds;
  t.stopped = result.stopped;
  for (const learn::ClipScore& s : result.before)
    t.before.append(clip_score_dict(s));
  for (const learn::ClipScore& s : result.after)
    t.after.append(clip_score_dict(s));
  for (const learn::StageRecord& s : result.stages) {
    py::dict d;
    d["stage"] = s.stage;
    d["cost"] = s.cost;
    d["kept"] = s.kept;
    d["seconds"] = s.seconds;
    t.stages.append(d);
  }
  for (const learn::AddedWord& w : result.added) {
    py::dict d;
    d["slot"] = std::string(gait::slot_name(w.slot));
    d["input"] = w.input;
    d["word"] = w.word;
    d["peak"] = w.peak;
    d["rules_like"] = w.like;
    d["why"] = w.why;
    t.added.append(d);
  }
  return t;
}

void bind_training(py::module_& m) {
  py::class_<Training>(m, "Training", "What train() returns.")
      .def_readonly("set", &Training::set)
      .def_readonly("cost_before", &Training::cost_before)
      .def_readonly("cost_after", &Training::cost_after)
      .def_readonly("seconds", &Training::seconds)
      .def_readonly("stopped", &Training::stopped)
      .def_readonly("before", &Training::before)
      .def_readonly("after", &Training::after)
      .def_readonly("stages", &Training::stages)
      .def_readonly("added", &Training::added);
  m.def(
      "train",
      [](const py::object& clips, const py::object& base, std::optional<std::string> name,
         std::optional<std::string> description, int generations, int polish, int threads,
         std::optional<std::uint64_t> seed, std::vector<double> steps_around, bool grid,
         int recovery, int fit_iterations, bool fits, bool base_structure,
         const py::object& progress, const std::optional<std::filesystem::path>& map,
         const std::optional<std::string>& up, const std::optional<double>& unit,
         const std::optional<std::size_t>& skip) {
        const TrainArguments a{std::move(name),
                               std::move(description),
                               generations,
                               polish,
                               threads,
                               seed,
                               std::move(steps_around),
                               grid,
                               recovery,
                               fit_iterations,
                               fits,
                               base_structure,
                               clip_options(map, up, unit, skip)};
        return train(clips, base, a, progress);
      },
      py::arg("clips"), py::arg("base") = "default", py::kw_only(), py::arg("name") = py::none(),
      py::arg("description") = py::none(), py::arg("generations") = 800, py::arg("polish") = 100,
      py::arg("threads") = 2, py::arg("seed") = py::none(),
      py::arg("steps_around") = std::vector<double>{}, py::arg("grid") = false,
      py::arg("recovery") = 0, py::arg("fit_iterations") = 30, py::arg("fits") = true,
      py::arg("base_structure") = false, py::arg("progress") = py::none(),
      py::arg("map") = py::none(), py::arg("up") = py::none(), py::arg("unit") = py::none(),
      py::arg("skip") = py::none(),
      "Learns a set from clips (Clip objects, or BVH paths read with map, up, unit and skip as "
      "read_clip reads them) as `fuzzygait train` does, with its options and defaults. "
      "progress(dict) is called each iteration; Ctrl-C stops with the best "
      "set so far. Returns a Training: .set (named, with the clips' body and step), costs, "
      "per-clip scores before and after, stages, the words added.");
}

}  // namespace

void bind_offline(py::module_& m) {
  bind_motion(m);
  bind_report(m);
  bind_clips(m);
  bind_training(m);
}

}  // namespace fuzzygait::python

// The runtime in Python: controller sets, grounds, walkers and crowds. A crowd's state arrays are
// views of the crowd's own memory (no copies), read-only, each keeping the crowd alive.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/gait/crowd.hpp"
#include "fuzzygait/io/controller_files.hpp"
#include "fuzzygait/io/terrain_spec.hpp"

namespace fuzzygait::python {
namespace {

// The views below read these structs as rows of doubles.
static_assert(sizeof(rig::LegAngles) == 4 * sizeof(double));
static_assert(sizeof(rig::Point) == 2 * sizeof(double));
static_assert(sizeof(gait::Phase) == 1);

struct Crowd {
  SetPtr set;
  GroundPtr ground;
  gait::Crowd crowd;
};

// An option's value as T, or TypeError naming the option ("character 3: speed must be a number").
template <class T>
T option(const py::handle value, const std::string& who, const std::string& key, const char* what) {
  const auto refuse = [&] {
    return py::type_error(who + key + " must be " + what + ", not " +
                          std::string(py::str(py::type::handle_of(value).attr("__name__"))));
  };
  if constexpr (std::is_same_v<T, py::dict>) {
    if (!py::isinstance<py::dict>(value)) throw refuse();  // (a cast would call dict() on it)
  }
  if constexpr (std::is_same_v<T, bool>) {
    if (!py::isinstance<py::bool_>(value)) throw refuse();  // (a cast would take any truth)
  }
  try {
    return value.cast<T>();
  } catch (const py::cast_error&) {
    throw refuse();
  }
}

rig::Segments segments_from(const py::dict& given, rig::Segments s, const std::string& who) {
  for (const auto& [key, value] : given) {
    const std::string k = py::str(key);
    const auto v = option<double>(value, who, "segments: " + k, "a number");
    if (k == "thigh") {
      s.thigh = v;
    } else if (k == "shank") {
      s.shank = v;
    } else if (k == "ankle_height") {
      s.ankle_height = v;
    } else if (k == "heel") {
      s.heel = v;
    } else if (k == "ball") {
      s.ball = v;
    } else if (k == "toe") {
      s.toe = v;
    } else {
      throw std::invalid_argument(who + "segments: unknown segment '" + k +
                                  "' (thigh, shank, ankle_height, heel, ball, toe)");
    }
  }
  return s;
}

// A character's options from keywords, as `fuzzygait walk` makes them from its command line: a
// trained set walks its own body and step unless a stature, segments, a step or a speed is given.
// `who` prefixes messages ("character 3: ").
gait::WalkerOptions walker_options(const gait::ControllerSet& set, const py::dict& given,
                                   const std::string& who) {
  std::optional<double> step, speed, stature, time_step, warm_up;
  std::optional<std::uint64_t> seed;
  std::optional<std::size_t> event_capacity;
  bool standing = false;
  py::dict segments;
  for (const auto& [key, value] : given) {
    const std::string k = py::str(key);
    if (value.is_none()) continue;
    if (k == "step_length") {
      step = option<double>(value, who, k, "a number");
    } else if (k == "speed") {
      speed = option<double>(value, who, k, "a number");
    } else if (k == "stature") {
      stature = option<double>(value, who, k, "a number");
    } else if (k == "segments") {
      segments = option<py::dict>(value, who, k, "a dict of segment lengths");
    } else if (k == "time_step") {
      time_step = option<double>(value, who, k, "a number");
    } else if (k == "warm_up") {
      warm_up = option<double>(value, who, k, "a number");
    } else if (k == "seed") {
      seed = option<std::uint64_t>(value, who, k, "a whole number from 0 to 2**64 - 1");
    } else if (k == "event_capacity") {
      event_capacity = option<std::size_t>(value, who, k, "a whole number from 0 to 4096");
    } else if (k == "standing") {
      standing = option<bool>(value, who, k, "True or False");
    } else {
      throw std::invalid_argument(who + "unknown option '" + k +
                                  "' (step_length, speed, stature, segments, time_step, seed, "
                                  "warm_up, event_capacity, standing)");
    }
  }
  if (step && speed) {
    throw std::invalid_argument(who +
                                "give step_length or speed, not both: a walk by speed takes the "
                                "step its set's stride relation gives");
  }
  if (speed && !(*speed > 0.0)) {
    throw std::invalid_argument(who + "speed must be above 0 m/s");
  }
  gait::WalkerOptions o;  // its segments a 1.75 m adult's
  if (stature) {
    o.segments = rig::segments_from_stature(*stature);
  } else if (set.body && segments.empty()) {
    o.segments = *set.body;
  }
  o.segments = segments_from(segments, o.segments, who);
  const bool own_pace = !step && !speed && set.body_step_length.has_value();
  o.step_length = own_pace ? *set.body_step_length : step.value_or(o.step_length);
  o.speed = speed.value_or(0.0);
  o.time_step = time_step.value_or(o.time_step);
  o.start.warm_up = warm_up.value_or(o.start.warm_up);
  o.event_capacity = event_capacity.value_or(o.event_capacity);
  if (seed) {
    o.start.random = true;
    o.start.seed = *seed;
  }
  o.start.standing = standing;
  return o;
}

py::array_t<double> angles_array(const std::array<rig::LegAngles, 2>& legs) {
  std::vector<double> v;
  for (const rig::LegAngles& a : legs) {
    for (double x : {a.hip, a.knee, a.ankle, a.toe})
      v.push_back(x);
  }
  return copy_array(v, {2, 4});
}

py::array_t<double> point_array(rig::Point p) {
  return copy_array({p.x, p.y}, {2});
}

// [leg][hip, knee, ankle, heel, ball, tip][x, y].
void append_points(std::vector<double>& v, const rig::LegPoints& p) {
  for (const rig::Point& q : {p.hip, p.knee, p.ankle, p.heel, p.ball, p.tip}) {
    v.push_back(q.x);
    v.push_back(q.y);
  }
}

py::array_t<double> points_array(const gait::Walker& w) {
  std::vector<double> v;
  for (rig::Side side : rig::kSides)
    append_points(v, w.points(side));
  return copy_array(v, {2, 6, 2});
}

py::dict pose_dict(const rig::Pose& pose) {
  py::dict d;
  d["pelvis"] = point_array(pose.pelvis);
  d["pelvis_tilt"] = pose.pelvis_tilt;
  d["angles"] = angles_array(pose.legs);
  return d;
}

py::list events_list(const gait::Walker& w) {
  py::list events;
  for (const gait::EventRecord& e : w.events()) {
    py::dict d;
    d["time"] = e.time;
    d["side"] = e.side == rig::Side::Left ? "left" : "right";
    d["event"] = gait::name(e.event);
    d["where"] = point_array(e.where);
    events.append(d);
  }
  return events;
}

// A read-only array over `first` (no copy) whose base is `owner`, which keeps the memory alive.
template <class T>
py::array view(const py::object& owner, const T* first, std::vector<py::ssize_t> shape,
               std::vector<py::ssize_t> strides) {
  py::array a(py::dtype::of<T>(), std::move(shape), std::move(strides), first, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// An array over one member of every character's state, shaped [character] + `inner`: the
// characters a Walker apart, a leg a LegState apart.
template <class T>
py::array state_view(const py::object& owner, const T& (*member)(const gait::WalkerState&),
                     std::vector<py::ssize_t> inner, std::vector<py::ssize_t> inner_strides) {
  const std::span<const gait::Walker> walkers = owner.cast<const Crowd&>().crowd.walkers();
  const auto count = static_cast<py::ssize_t>(walkers.size());
  inner.insert(inner.begin(), count);
  inner_strides.insert(inner_strides.begin(), static_cast<py::ssize_t>(sizeof(gait::Walker)));
  const T* first = walkers.empty() ? nullptr : &member(walkers[0].state());
  return view(owner, first, std::move(inner), std::move(inner_strides));
}

// Character i of the crowd, or IndexError.
std::size_t check(const Crowd& c, std::size_t i) {
  if (i >= c.crowd.size()) {
    throw py::index_error("character " + std::to_string(i) + " of a crowd of " +
                          std::to_string(c.crowd.size()));
  }
  return i;
}

// Crowd.NAME: the view of one member of every character's state (see state_view).
template <class T>
void def_state_view(py::class_<Crowd>& crowd, const char* name,
                    const T& (*member)(const gait::WalkerState&), std::vector<py::ssize_t> inner,
                    std::vector<py::ssize_t> inner_strides, const char* doc) {
  crowd.def_property_readonly(
      name,
      [=](const py::object& self) { return state_view<T>(self, member, inner, inner_strides); },
      doc);
}

constexpr auto kLeg = static_cast<py::ssize_t>(sizeof(gait::LegState));
constexpr auto kDouble = static_cast<py::ssize_t>(sizeof(double));

void bind_sets_and_ground(py::module_& m) {
  py::class_<gait::ControllerSet, SetPtr>(
      m, "ControllerSet", "A controller set: one fuzzy controller per leg phase and joint.")
      .def_static(
          "builtin",
          [](const std::string& name) {
            return std::make_shared<gait::ControllerSet>(gait::ControllerSet::builtin(name));
          },
          py::arg("name") = "default", "A set compiled into the library: default, energetic, ...")
      .def_static(
          "load",
          [](const std::filesystem::path& folder) {
            return std::make_shared<gait::ControllerSet>(gait::ControllerSet::load(folder));
          },
          py::arg("folder"), "Reads FOLDER/manifest.json and the FLL files it names.")
      .def_static("builtin_names", &gait::ControllerSet::builtin_names)
      .def(
          "save",
          [](const gait::ControllerSet& set, const std::filesystem::path& folder) {
            io::save_controller_set(set, folder);
          },
          py::arg("folder"), "Writes manifest.json and the FLL files into the folder.")
      .def_readonly("name", &gait::ControllerSet::name)
      .def_readonly("description", &gait::ControllerSet::description)
      .def_readonly("inertia", &gait::ControllerSet::inertia)
      .def_readonly("pelvis_tilt", &gait::ControllerSet::pelvis_tilt)
      .def_readonly("cadence", &gait::ControllerSet::cadence)
      .def_readonly("acceleration", &gait::ControllerSet::acceleration)
      .def_property_readonly(
          "numbers",
          [](const gait::ControllerSet& set) {
            py::dict numbers;
            for (const gait::ControllerSet::ManifestNumber& n :
                 gait::ControllerSet::manifest_numbers())
              numbers[n.key] = n.get(set);
            return numbers;
          },
          "Every manifest number by its key, in the manifest's units.")
      .def_readonly("body_step_length", &gait::ControllerSet::body_step_length)
      .def_readonly("body_speed", &gait::ControllerSet::body_speed)
      .def_property_readonly("body",
                             [](const gait::ControllerSet& set) -> py::object {
                               if (!set.body) return py::none();
                               return segments_dict(*set.body);
                             })
      .def("__repr__", [](const gait::ControllerSet& set) {
        return "<fuzzygait.ControllerSet '" + set.name + "'>";
      });

  py::class_<terrain::Terrain, GroundPtr>(m, "Terrain", "The ground: a polyline of heights (m).")
      .def_static("flat",
                  [] { return std::make_shared<terrain::Terrain>(terrain::Terrain::flat()); })
      .def_static(
          "polyline",
          [](const py::array_t<double, py::array::c_style | py::array::forcecast>& xy) {
            if (xy.ndim() != 2 || xy.shape(1) != 2) {
              throw std::invalid_argument(
                  "Terrain.polyline: points must be an array of shape (n, 2)");
            }
            std::vector<rig::Point> points;
            for (py::ssize_t i = 0; i < xy.shape(0); ++i)
              points.push_back({xy.at(i, 0), xy.at(i, 1)});
            return std::make_shared<terrain::Terrain>(
                terrain::Terrain::polyline(std::move(points)));
          },
          py::arg("points"))
      .def_static(
          "from_spec",
          [](const std::string& spec) {
            return std::make_shared<terrain::Terrain>(io::terrain_from_spec(spec, "terrain"));
          },
          py::arg("spec"), "As `fuzzygait walk --terrain`: flat, slope:10, stairs:0.17:0.28:6, ...")
      .def_static(
          "ramp",
          [](double degrees, double start) {
            return std::make_shared<terrain::Terrain>(terrain::Terrain::ramp(degrees, start));
          },
          py::arg("degrees"), py::arg("start") = 1.0, "Level ground, then a slope from x = start.")
      .def_static(
          "stairs",
          [](double rise, double tread, int count, double start) {
            return std::make_shared<terrain::Terrain>(
                terrain::Terrain::stairs(rise, tread, count, start));
          },
          py::arg("rise"), py::arg("tread"), py::arg("count"), py::arg("start") = 1.0,
          "Level ground, then `count` steps (a negative rise goes down) and a landing.")
      .def("height", &terrain::Terrain::height, py::arg("x"))
      .def_property_readonly("points", [](const terrain::Terrain& t) {
        std::vector<double> v;
        for (const rig::Point& p : t.points()) {
          v.push_back(p.x);
          v.push_back(p.y);
        }
        return copy_array(v, {static_cast<py::ssize_t>(t.points().size()), 2});
      });

  m.def(
      "segments_from_stature",
      [](double stature) { return segments_dict(rig::segments_from_stature(stature)); },
      py::arg("stature"), "Segment lengths (m) from stature with Winter's proportions.");
}

void bind_walker(py::module_& m) {
  py::class_<Walker>(m, "Walker", "One character walking.")
      .def(
          py::init([](const py::object& set, const py::object& ground, const py::kwargs& options) {
            SetPtr s = to_set(set);
            GroundPtr g = to_ground(ground);
            const gait::WalkerOptions o = walker_options(*s, options, "");
            return std::unique_ptr<Walker>(new Walker{s, g, gait::Walker(*s, o, *g)});
          }),
          py::arg("set") = "default", py::arg("ground") = py::none(),
          "Options: step_length (m) or speed (m/s), stature (m) or segments (dict), time_step "
          "(s), seed (a random start pose), warm_up (s), event_capacity (events kept, default 64), "
          "standing (True: stands, feet side by side, until go()).")
      .def(
          "advance", [](Walker& w, double dt) { return w.walker.advance(dt); }, py::arg("dt"))
      .def(
          "set_speed", [](Walker& w, double v) { return w.walker.set_speed(v); },
          py::arg("metres_per_second"))
      .def(
          "set_step_length", [](Walker& w, double v) { return w.walker.set_step_length(v); },
          py::arg("metres"))
      .def(
          "stop", [](Walker& w) { w.walker.stop(); },
          "Stops on the spot: the next foot to lift closes beside the planted one, then the "
          "walker stands.")
      .def(
          "go", [](Walker& w) { w.walker.go(); },
          "Walks on from standing (or calls a stop off): a short first step, the body "
          "accelerating from rest.")
      .def_property_readonly("standing", [](const Walker& w) { return w.walker.standing(); })
      .def_property_readonly(
          "locomotion", [](const Walker& w) { return gait::name(w.walker.locomotion()); },
          "'walking', 'stopping' or 'standing'.")
      .def_property_readonly("set", [](const Walker& w) { return w.set; })
      .def_property_readonly("ground", [](const Walker& w) { return w.ground; })
      .def_property_readonly("time", [](const Walker& w) { return w.walker.time(); })
      .def_property_readonly("speed", [](const Walker& w) { return w.walker.speed(); })
      .def_property_readonly("step_length", [](const Walker& w) { return w.walker.step_length(); })
      .def_property_readonly("min_step_length",
                             [](const Walker& w) { return w.walker.min_step_length(); })
      .def_property_readonly("max_step_length",
                             [](const Walker& w) { return w.walker.max_step_length(); })
      .def_property_readonly("min_speed", [](const Walker& w) { return w.walker.min_speed(); })
      .def_property_readonly("max_speed", [](const Walker& w) { return w.walker.max_speed(); })
      .def_property_readonly("segments",
                             [](const Walker& w) { return segments_dict(w.walker.segments()); })
      .def("pose", [](const Walker& w) { return pose_dict(w.walker.pose()); })
      .def_property_readonly("pelvis",
                             [](const Walker& w) { return point_array(w.walker.pose().pelvis); })
      .def_property_readonly("pelvis_tilt",
                             [](const Walker& w) { return w.walker.pose().pelvis_tilt; })
      .def_property_readonly("angles",
                             [](const Walker& w) { return angles_array(w.walker.pose().legs); })
      .def_property_readonly("velocities",
                             [](const Walker& w) {
                               const gait::WalkerState& s = w.walker.state();
                               return angles_array({s.legs[0].velocity, s.legs[1].velocity});
                             })
      .def_property_readonly("points", [](const Walker& w) { return points_array(w.walker); })
      .def_property_readonly("in_contact",
                             [](const Walker& w) {
                               return py::make_tuple(w.walker.in_contact(rig::Side::Left),
                                                     w.walker.in_contact(rig::Side::Right));
                             })
      .def_property_readonly("phases",
                             [](const Walker& w) {
                               return py::make_tuple(gait::name(w.walker.phase(rig::Side::Left)),
                                                     gait::name(w.walker.phase(rig::Side::Right)));
                             })
      .def("__repr__",
           [](const Walker& w) {
             char time[32];
             std::snprintf(time, sizeof time, "%.3f", w.walker.time());
             return "<fuzzygait.Walker with '" + w.set->name + "' at " + time + " s>";
           })
      .def("events", [](const Walker& w) { return events_list(w.walker); })
      .def("clear_events", [](Walker& w) { w.walker.clear_events(); })
      .def(
          "record",
          [](Walker& w, double seconds, double fps) {
            const double step = w.walker.step_length();
            return Motion{eval::record(w.walker, seconds, fps), w.ground, step};
          },
          py::arg("seconds"), py::arg("fps") = 120.0,
          "Walks `seconds` and samples it at fps (frame 0 is the pose now).")
      .def(
          "record_cycles",
          [](Walker& w, int cycles, double fps) {
            const double step = w.walker.step_length();
            return Motion{eval::record_cycles(w.walker, cycles, fps), w.ground, step};
          },
          py::arg("cycles") = 10, py::arg("fps") = 120.0,
          "Walks until `cycles` left gait cycles after the first have completed, as `fuzzygait "
          "walk` does.");
}

void bind_crowd(py::module_& m) {
  m.attr("PHASES") = py::make_tuple("swing", "heel", "flat", "ball");
  py::class_<Crowd> crowd(
      m, "Crowd",
      "Characters sharing a set and a ground, stepped together. Its state arrays "
      "(angles, velocities, pelvis, pelvis_tilt, time, speed, phases) are read-only "
      "views of the crowd's memory: advance() changes them in place.");
  crowd
      .def(py::init([](const py::object& set, const py::object& characters,
                       const py::object& ground, std::size_t threads) {
             SetPtr s = to_set(set);
             GroundPtr g = to_ground(ground);
             std::vector<gait::WalkerOptions> options;
             if (py::isinstance<py::int_>(characters)) {
               const auto count = std::max<py::ssize_t>(characters.cast<py::ssize_t>(), 0);
               options.assign(static_cast<std::size_t>(count), walker_options(*s, py::dict(), ""));
             } else {
               for (const py::handle c : characters) {
                 const std::string who = "character " + std::to_string(options.size());
                 options.push_back(walker_options(
                     *s, option<py::dict>(c, who, "", "a dict of Walker options"), who + ": "));
               }
             }
             if (options.empty()) {
               throw std::invalid_argument("Crowd: characters must be at least 1");
             }
             gait::CrowdOptions cores;
             cores.threads = threads;
             return std::unique_ptr<Crowd>(new Crowd{s, g, gait::Crowd(*s, *g, options, cores)});
           }),
           py::arg("set") = "default", py::arg("characters") = 1, py::arg("ground") = py::none(),
           py::arg("threads") = 1,
           "characters: how many default characters, or a dict of Walker options for each; "
           "threads: how many step them (0: one a core), the walks the same bits on any number.")
      .def_property_readonly("workers", [](const Crowd& c) { return c.crowd.worker_count(); })
      .def("__len__", [](const Crowd& c) { return c.crowd.size(); })
      .def("__repr__",
           [](const Crowd& c) {
             return "<fuzzygait.Crowd of " + std::to_string(c.crowd.size()) + " with '" +
                    c.set->name + "'>";
           })
      .def(
          "events", [](const Crowd& c, std::size_t i) { return events_list(c.crowd[check(c, i)]); },
          py::arg("i"), "Character i's contact events since the last clear_events().")
      .def("clear_events", [](Crowd& c) { c.crowd.clear_events(); })
      .def(
          "advance", [](Crowd& c, double dt) { return c.crowd.advance(dt); }, py::arg("dt"),
          py::call_guard<py::gil_scoped_release>(),
          "Advances every character by dt seconds (Python's other threads run meanwhile).")
      .def(
          "set_speed", [](Crowd& c, std::size_t i, double v) { return c.crowd.set_speed(i, v); },
          py::arg("i"), py::arg("metres_per_second"))
      .def(
          "set_step_length",
          [](Crowd& c, std::size_t i, double v) { return c.crowd.set_step_length(i, v); },
          py::arg("i"), py::arg("metres"))
      .def(
          "stop", [](Crowd& c, std::size_t i) { return c.crowd.stop(i); }, py::arg("i"))
      .def(
          "standing", [](const Crowd& c, std::size_t i) { return c.crowd[check(c, i)].standing(); },
          py::arg("i"))
      .def(
          "go", [](Crowd& c, std::size_t i) { return c.crowd.go(i); }, py::arg("i"))
      .def_property_readonly("batched_controllers",
                             [](const Crowd& c) { return c.crowd.batched_controllers(); })
      .def(
          "pose",
          [](const Crowd& c, std::size_t i) { return pose_dict(c.crowd[check(c, i)].pose()); },
          py::arg("i"))
      .def("points", [](const Crowd& c) {
        std::vector<double> v;
        for (const gait::Walker& w : c.crowd.walkers()) {
          for (rig::Side side : rig::kSides)
            append_points(v, w.points(side));
        }
        return copy_array(v, {static_cast<py::ssize_t>(c.crowd.size()), 2, 6, 2});
      });
  using State = gait::WalkerState;
  def_state_view<double>(
      crowd, "angles", [](const State& s) -> const double& { return s.legs[0].angles.hip; }, {2, 4},
      {kLeg, kDouble}, "(n, 2, 4): [character][left, right][hip, knee, ankle, toe], rad");
  def_state_view<double>(
      crowd, "velocities", [](const State& s) -> const double& { return s.legs[0].velocity.hip; },
      {2, 4}, {kLeg, kDouble}, "(n, 2, 4): the joints' angular velocities, rad/s");
  def_state_view<double>(
      crowd, "pelvis", [](const State& s) -> const double& { return s.pelvis.x; }, {2}, {kDouble},
      "(n, 2): the hip joint centre, x forward and y up, m");
  def_state_view<double>(
      crowd, "pelvis_tilt", [](const State& s) -> const double& { return s.pelvis_tilt; }, {}, {},
      "(n): anterior tilt, rad");
  def_state_view<double>(
      crowd, "time", [](const State& s) -> const double& { return s.time; }, {}, {}, "(n): s");
  def_state_view<double>(
      crowd, "speed", [](const State& s) -> const double& { return s.speed; }, {}, {},
      "(n): the speed commanded now, m/s");
  def_state_view<std::uint8_t>(
      crowd, "phases",
      [](const State& s) -> const std::uint8_t& {
        return reinterpret_cast<const std::uint8_t&>(s.legs[0].phase);
      },
      {2}, {kLeg}, "(n, 2) uint8: each leg's phase, an index into fuzzygait.PHASES");
}

}  // namespace

SetPtr to_set(const py::object& set) {
  if (py::isinstance<py::str>(set)) {
    return std::make_shared<gait::ControllerSet>(
        gait::ControllerSet::builtin(set.cast<std::string>()));
  }
  if (py::isinstance<gait::ControllerSet>(set)) return set.cast<SetPtr>();
  return std::make_shared<gait::ControllerSet>(
      gait::ControllerSet::load(set.cast<std::filesystem::path>()));
}

GroundPtr to_ground(const py::object& ground) {
  if (ground.is_none()) return std::make_shared<terrain::Terrain>(terrain::Terrain::flat());
  if (py::isinstance<py::str>(ground)) {
    return std::make_shared<terrain::Terrain>(
        io::terrain_from_spec(ground.cast<std::string>(), "ground"));
  }
  return ground.cast<GroundPtr>();
}

void bind_walk(py::module_& m) {
  bind_sets_and_ground(m);
  bind_walker(m);
  bind_crowd(m);
}

}  // namespace fuzzygait::python

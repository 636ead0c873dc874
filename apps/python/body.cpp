// The whole body in Python: paths, the canonical humanoid, a follower that bends a walker's walk
// onto a path, and a game's skeleton (from arrays or read from BVH, glTF or VRM) posed from it.
// Arrays in and out are NumPy copies; quaternions are (w, x, y, z). A follower keeps its Path and
// the Walker it was made with alive (the C++ follower keeps pointers to the path and the walker's
// set).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "fuzzygait/body/follower.hpp"
#include "fuzzygait/body/humanoid.hpp"
#include "fuzzygait/body/humanoid_map.hpp"
#include "fuzzygait/body/skeleton.hpp"
#include "fuzzygait/body/skeleton_poser.hpp"
#include "fuzzygait/io/skeleton_file.hpp"
#include "fuzzygait/path/path.hpp"

namespace fuzzygait::python {
namespace {

using PathPtr = std::shared_ptr<path::Path>;
using HumanoidPtr = std::shared_ptr<body::Humanoid>;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

struct Follower {
  PathPtr path;       // (the Python Path is kept alive too: keep_alive)
  py::object walker;  // the Python Walker it was made with, which holds its set
  body::PathFollower follower;
};

// A game's skeleton and, read from a VRM file, the humanoid map the file declares.
struct Skeleton {
  body::Skeleton skeleton;
  std::optional<body::HumanoidMap> declared;
};

struct Poser {
  std::shared_ptr<Skeleton> skeleton;
  body::HumanoidMap map;
  body::SkeletonPoser poser;
};

std::string shape_text(const py::array& a) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i)
    text += (i > 0 ? ", " : "") + std::to_string(a.shape(i));
  return text + (a.ndim() == 1 ? ",)" : ")");
}

// `a` as an array of shape (rows, columns) (rows < 0: any), or ValueError naming `what`.
void check_shape(const DoubleArray& a, py::ssize_t rows, py::ssize_t columns,
                 const std::string& what) {
  if (a.ndim() != 2 || a.shape(1) != columns || (rows >= 0 && a.shape(0) != rows)) {
    throw std::invalid_argument(what + " must be an array of shape (" +
                                (rows >= 0 ? std::to_string(rows) : std::string("n")) + ", " +
                                std::to_string(columns) + "), got " + shape_text(a));
  }
}

std::vector<double> flat(const std::vector<body::Vec3>& v) {
  std::vector<double> out;
  for (const body::Vec3& p : v)
    out.insert(out.end(), {p.x, p.y, p.z});
  return out;
}
std::vector<double> flat(const std::vector<body::Quat>& v) {
  std::vector<double> out;
  for (const body::Quat& q : v)
    out.insert(out.end(), {q.w, q.x, q.y, q.z});
  return out;
}
template <std::size_t N>
py::array_t<double> vec_array(const std::array<body::Vec3, N>& v) {
  return copy_array(flat(std::vector<body::Vec3>(v.begin(), v.end())),
                    {static_cast<py::ssize_t>(N), 3});
}
py::array_t<double> vec_array(const std::vector<body::Vec3>& v) {
  return copy_array(flat(v), {static_cast<py::ssize_t>(v.size()), 3});
}
py::array_t<double> quat_array(const std::vector<body::Quat>& q) {
  return copy_array(flat(q), {static_cast<py::ssize_t>(q.size()), 4});
}

py::tuple pose_arrays(const body::BodyPose& pose) {
  return py::make_tuple(vec_array(pose.position),
                        quat_array({pose.rotation.begin(), pose.rotation.end()}));
}

const Walker& walker_of(const py::object& walker) {
  if (!py::isinstance<Walker>(walker)) {
    throw py::type_error("walker must be a fuzzygait.Walker, not " +
                         std::string(py::str(py::type::handle_of(walker).attr("__name__"))));
  }
  return walker.cast<const Walker&>();
}

body::Joint joint_named(const std::string& name) {
  const std::optional<body::Joint> joint = body::joint_named(name);
  if (!joint) {
    throw std::invalid_argument("no body joint '" + name + "' (fuzzygait.JOINTS lists them)");
  }
  return *joint;
}

py::tuple joint_names() {
  py::list names;
  for (std::size_t j = 0; j < body::kJointCount; ++j)
    names.append(std::string(body::name(static_cast<body::Joint>(j))));
  return py::tuple(names);
}

py::tuple joint_parents() {
  py::list parents;
  for (std::size_t j = 0; j < body::kJointCount; ++j) {
    const auto p = body::parent(static_cast<body::Joint>(j));
    parents.append(p ? body::index(*p) : -1);
  }
  return py::tuple(parents);
}

using Joint = body::SkeletonJoint;

// One member of every joint of a skeleton.
template <class T>
std::vector<T> each_joint(const Skeleton& s, T Joint::*member) {
  std::vector<T> values;
  for (const Joint& joint : s.skeleton.joints)
    values.push_back(joint.*member);
  return values;
}

// Skeleton(names, parents, offsets, rotations=None, metres_per_unit=1.0).
body::Skeleton skeleton_from_arrays(const std::vector<std::string>& names,
                                    const std::vector<int>& parents, const DoubleArray& offsets,
                                    const std::optional<DoubleArray>& rotations,
                                    double metres_per_unit) {
  const auto n = static_cast<py::ssize_t>(names.size());
  if (static_cast<py::ssize_t>(parents.size()) != n) {
    throw std::invalid_argument("Skeleton: parents must hold one index per name (" +
                                std::to_string(n) + "), got " + std::to_string(parents.size()));
  }
  check_shape(offsets, n, 3, "Skeleton: offsets");
  if (rotations) check_shape(*rotations, n, 4, "Skeleton: rotations");
  body::Skeleton s;
  s.metres_per_unit = metres_per_unit;
  for (py::ssize_t i = 0; i < n; ++i) {
    body::SkeletonJoint joint;
    joint.name = names[static_cast<std::size_t>(i)];
    joint.parent = parents[static_cast<std::size_t>(i)];
    joint.offset = {offsets.at(i, 0), offsets.at(i, 1), offsets.at(i, 2)};
    if (rotations) {
      const DoubleArray& r = *rotations;
      joint.rotation = {r.at(i, 0), r.at(i, 1), r.at(i, 2), r.at(i, 3)};
    }
    s.joints.push_back(std::move(joint));
  }
  body::validate(s);
  return s;
}

// A skeleton file: .bvh, or .glb, .gltf and .vrm (with the humanoid map a VRM file declares).
Skeleton read_skeleton(const std::filesystem::path& file, std::optional<double> metres_per_unit) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".bvh") return {io::read_bvh_skeleton(file, metres_per_unit), std::nullopt};
  if (extension == ".glb" || extension == ".gltf" || extension == ".vrm") {
    if (metres_per_unit) {
      throw std::invalid_argument(file.string() +
                                  ": metres_per_unit is for BVH files; glTF's unit is the metre");
    }
    Skeleton s{io::read_gltf_skeleton(file), std::nullopt};
    s.declared = io::read_vrm_humanoid_map(file, s.skeleton);
    return s;
  }
  throw std::invalid_argument(file.string() + ": expected a .bvh, .glb, .gltf or .vrm file");
}

// The map a poser uses: by hand ({body joint name: skeleton joint name}), else the file's, else
// by name.
body::HumanoidMap map_for(const Skeleton& s, const py::object& given) {
  if (given.is_none()) return s.declared ? *s.declared : body::map_humanoid(s.skeleton);
  std::vector<body::NamedJoint> names;
  for (const auto& [key, value] : given.cast<py::dict>())
    names.push_back({joint_named(py::str(key)), py::str(value)});
  return body::map_humanoid(s.skeleton, names);
}

py::dict map_dict(const body::HumanoidMap& map, const body::Skeleton& skeleton) {
  py::dict d;
  for (std::size_t j = 0; j < body::kJointCount; ++j) {
    const int s = map.joint[j];
    if (s >= 0) {
      d[py::str(std::string(body::name(static_cast<body::Joint>(j))))] =
          skeleton.joints[static_cast<std::size_t>(s)].name;
    }
  }
  return d;
}

void bind_path(py::module_& m) {
  py::class_<path::Path, PathPtr>(
      m, "Path",
      "A curve on the ground (x, z metres; headings in radians from +Z, left +): straight pieces "
      "and circular arcs, by distance along it.")
      .def(py::init([](const std::optional<std::vector<std::pair<double, double>>>& pieces,
                       std::pair<double, double> start, double heading) {
             if (!pieces) return std::make_shared<path::Path>();
             std::vector<path::Piece> given;
             for (const auto& [length, curvature] : *pieces)
               given.push_back({length, curvature});
             return std::make_shared<path::Path>(path::GroundPoint{start.first, start.second},
                                                 heading, std::move(given));
           }),
           py::arg("pieces") = py::none(), py::arg("start") = std::make_pair(0.0, 0.0),
           py::arg("heading") = 0.0,
           "pieces: (length m, curvature 1/m, left +; 0 straight) in order from `start` at "
           "`heading`; None: straight ahead along +Z without end.")
      .def_static(
          "polyline",
          [](const DoubleArray& points, double corner_radius) {
            check_shape(points, -1, 2, "Path.polyline: points");
            std::vector<path::GroundPoint> given;
            for (py::ssize_t i = 0; i < points.shape(0); ++i)
              given.push_back({points.at(i, 0), points.at(i, 1)});
            return std::make_shared<path::Path>(path::Path::polyline(given, corner_radius));
          },
          py::arg("points"), py::arg("corner_radius") = 1.0,
          "Through the (n, 2) x, z points, each corner rounded by an arc of corner_radius (m) or "
          "the largest that fits.")
      .def_property_readonly("length", &path::Path::length)
      .def_property_readonly("pieces",
                             [](const path::Path& p) {
                               std::vector<std::pair<double, double>> pieces;
                               for (const path::Piece& piece : p.pieces())
                                 pieces.emplace_back(piece.length, piece.curvature);
                               return pieces;
                             })
      .def(
          "at",
          [](const path::Path& p, double distance) {
            const path::PathSample s = p.at(distance);
            py::dict d;
            d["x"] = s.point.x;
            d["z"] = s.point.z;
            d["heading"] = s.heading;
            d["curvature"] = s.curvature;
            return d;
          },
          py::arg("distance"),
          "The path at `distance` m along it (straight on past either end): x, z, heading, "
          "curvature.")
      .def("__repr__", [](const path::Path& p) {
        return "<fuzzygait.Path of " + std::to_string(p.pieces().size()) + " pieces, " +
               std::string(py::str(py::float_(p.length()))) + " m>";
      });
}

void bind_humanoid(py::module_& m) {
  m.attr("JOINTS") = joint_names();
  m.attr("JOINT_PARENTS") = joint_parents();
  py::class_<body::Humanoid, HumanoidPtr>(
      m, "Humanoid",
      "The canonical body of 26 joints (fuzzygait.JOINTS, VRM's names), each joint's offset from "
      "its parent in the reference pose: upright facing +Z, Y up, X to the left, arms hanging.")
      .def(py::init([](double stature) {
             return std::make_shared<body::Humanoid>(body::humanoid_from_stature(stature));
           }),
           py::arg("stature") = 1.75, "Winter's proportions for a stature (m, 0.5 to 3).")
      .def_static(
          "from_walker",
          [](const py::object& walker, std::optional<double> stature) {
            return std::make_shared<body::Humanoid>(
                body::humanoid_with_legs(walker_of(walker).walker.segments(), stature));
          },
          py::arg("walker"), py::arg("stature") = py::none(),
          "The walker's legs under a stature's trunk and arms (default: the stature the legs "
          "stand for, leg length / 0.530).")
      .def_property_readonly("offsets", [](const body::Humanoid& h) { return vec_array(h.offset); })
      .def_readonly("heel", &body::Humanoid::heel)
      .def_property_readonly("hip_width", &body::Humanoid::hip_width)
      .def_property_readonly("segments",
                             [](const body::Humanoid& h) { return segments_dict(h.segments()); })
      .def_property_readonly_static("names", [](const py::object&) { return joint_names(); })
      .def_property_readonly_static("parents", [](const py::object&) { return joint_parents(); });
}

void bind_follower(py::module_& m) {
  py::class_<Follower>(
      m, "PathFollower",
      "The walker's walk bent onto a path, the whole body posed in the world each frame. It holds "
      "its path, its walker and the walker's set.")
      .def(py::init([](const py::object& humanoid, const PathPtr& path, const py::object& walker,
                       std::optional<double> step_width,
                       std::optional<double> step_width_per_leg_length, double swing_release,
                       double look_ahead, bool upper_body) {
             const Walker& w = walker_of(walker);
             if (!path) throw py::type_error("path must be a fuzzygait.Path, not None");
             const body::Humanoid h = humanoid.is_none()
                                          ? body::humanoid_with_legs(w.walker.segments())
                                          : humanoid.cast<const body::Humanoid&>();
             body::FollowerOptions o;
             if (step_width && step_width_per_leg_length) {
               throw std::invalid_argument(
                   "PathFollower: give step_width or step_width_per_leg_length, not both");
             }
             if (step_width) {
               o.step_width_per_leg_length = *step_width / h.segments().leg_length();
             }
             if (step_width_per_leg_length) {
               o.step_width_per_leg_length = *step_width_per_leg_length;
             }
             o.swing_release = swing_release;
             o.look_ahead = look_ahead;
             o.upper_body = upper_body;
             return std::unique_ptr<Follower>(
                 new Follower{path, walker, body::PathFollower(h, *path, w.walker, o)});
           }),
           py::keep_alive<1, 3>(), py::arg("humanoid"), py::arg("path"), py::arg("walker"),
           py::kw_only(), py::arg("step_width") = py::none(),
           py::arg("step_width_per_leg_length") = py::none(),
           py::arg("swing_release") = body::FollowerOptions{}.swing_release,
           py::arg("look_ahead") = body::FollowerOptions{}.look_ahead, py::arg("upper_body") = true,
           "humanoid: the body (its legs the walker's), or None for Humanoid.from_walker(walker); "
           "step_width (m) or step_width_per_leg_length (default 0.11): the feet's centre lines "
           "apart; swing_release, look_ahead (m), upper_body: as C++'s FollowerOptions.")
      .def(
          "update",
          [](Follower& f, const py::object& walker) {
            const Walker& w = walker.is_none() ? walker_of(f.walker) : walker_of(walker);
            return pose_arrays(f.follower.update(w.walker));
          },
          py::arg("walker") = py::none(),
          "Poses the body for the walker now (default: the follower's own); call it once a frame "
          "after walker.advance(). Returns (positions (26, 3) m, rotations (26, 4) w, x, y, z).")
      .def_property_readonly(
          "positions", [](const Follower& f) { return vec_array(f.follower.pose().position); })
      .def_property_readonly("rotations",
                             [](const Follower& f) {
                               const auto& r = f.follower.pose().rotation;
                               return quat_array({r.begin(), r.end()});
                             })
      .def_property_readonly("heels",
                             [](const Follower& f) { return vec_array(f.follower.pose().heel); })
      .def_property_readonly("local_rotations",
                             [](const Follower& f) {
                               const auto local = body::local_rotations(f.follower.pose());
                               return quat_array({local.begin(), local.end()});
                             })
      .def_property_readonly("pelvis_drop",
                             [](const Follower& f) { return f.follower.pelvis_drop(); })
      .def_property_readonly(
          "humanoid",
          [](const Follower& f) { return std::make_shared<body::Humanoid>(f.follower.humanoid()); })
      .def_readonly("path", &Follower::path)
      .def_readonly("walker", &Follower::walker)
      .def_property_readonly_static("names", [](const py::object&) { return joint_names(); })
      .def_property_readonly_static("parents", [](const py::object&) { return joint_parents(); });
}

void bind_skeleton(py::module_& m) {
  py::class_<Skeleton, std::shared_ptr<Skeleton>>(
      m, "Skeleton",
      "A game's skeleton: joint names, parent indices (-1 for the root, joint 0), rest offsets "
      "(n, 3) in its units and rest rotations (n, 4) relative to the parent.")
      .def(py::init([](const std::vector<std::string>& names, const std::vector<int>& parents,
                       const DoubleArray& offsets, const std::optional<DoubleArray>& rotations,
                       double metres_per_unit) {
             return std::make_shared<Skeleton>(
                 Skeleton{skeleton_from_arrays(names, parents, offsets, rotations, metres_per_unit),
                          std::nullopt});
           }),
           py::arg("names"), py::arg("parents"), py::arg("offsets"),
           py::arg("rotations") = py::none(), py::arg("metres_per_unit") = 1.0)
      .def_static(
          "read",
          [](const std::filesystem::path& file, std::optional<double> metres_per_unit) {
            return std::make_shared<Skeleton>(read_skeleton(file, metres_per_unit));
          },
          py::arg("path"), py::arg("metres_per_unit") = py::none(),
          "A .bvh file's hierarchy (its unit guessed from the legs unless given), or a .glb, "
          ".gltf or .vrm file's first skin.")
      .def("__len__", [](const Skeleton& s) { return s.skeleton.size(); })
      .def_property_readonly("names", [](const Skeleton& s) { return each_joint(s, &Joint::name); })
      .def_property_readonly("parents",
                             [](const Skeleton& s) { return each_joint(s, &Joint::parent); })
      .def_property_readonly(
          "offsets", [](const Skeleton& s) { return vec_array(each_joint(s, &Joint::offset)); })
      .def_property_readonly(
          "rotations",
          [](const Skeleton& s) { return quat_array(each_joint(s, &Joint::rotation)); })
      .def_property_readonly("metres_per_unit",
                             [](const Skeleton& s) { return s.skeleton.metres_per_unit; })
      .def_property_readonly("declared_map",
                             [](const Skeleton& s) -> py::object {
                               if (!s.declared) return py::none();
                               return map_dict(*s.declared, s.skeleton);
                             })
      .def("__repr__", [](const Skeleton& s) {
        return "<fuzzygait.Skeleton of " + std::to_string(s.skeleton.size()) + " joints>";
      });

  py::class_<Poser>(m, "SkeletonPoser",
                    "Poses a skeleton from the body: its humanoid walks on the skeleton's legs.")
      .def(py::init([](const std::shared_ptr<Skeleton>& skeleton, const py::object& map) {
             if (!skeleton) throw py::type_error("skeleton must be a fuzzygait.Skeleton");
             body::HumanoidMap chosen = map_for(*skeleton, map);
             body::SkeletonPoser poser(skeleton->skeleton, chosen);
             return std::unique_ptr<Poser>(new Poser{skeleton, chosen, std::move(poser)});
           }),
           py::arg("skeleton"), py::arg("map") = py::none(),
           "map: {body joint name: skeleton joint name} by hand; None: the VRM file's, else by "
           "name (CMU, Mixamo, VRM, VRoid, Unreal).")
      .def_property_readonly(
          "humanoid",
          [](const Poser& p) { return std::make_shared<body::Humanoid>(p.poser.humanoid()); })
      .def_property_readonly("map",
                             [](const Poser& p) { return map_dict(p.map, p.skeleton->skeleton); })
      .def_readonly("skeleton", &Poser::skeleton)
      .def_property_readonly("joint_count", [](const Poser& p) { return p.poser.joint_count(); })
      .def(
          "pose",
          [](const Poser& p, const DoubleArray& positions, const DoubleArray& rotations) {
            check_shape(positions, body::kJointCount, 3, "SkeletonPoser.pose: positions");
            check_shape(rotations, body::kJointCount, 4, "SkeletonPoser.pose: rotations");
            body::BodyPose pose;
            for (py::ssize_t j = 0; j < static_cast<py::ssize_t>(body::kJointCount); ++j) {
              const auto i = static_cast<std::size_t>(j);
              pose.position[i] = {positions.at(j, 0), positions.at(j, 1), positions.at(j, 2)};
              pose.rotation[i] = {rotations.at(j, 0), rotations.at(j, 1), rotations.at(j, 2),
                                  rotations.at(j, 3)};
            }
            std::vector<body::Quat> local(p.poser.joint_count());
            body::Vec3 root;
            p.poser.pose(pose, local, root);
            return py::make_tuple(quat_array(local), copy_array({root.x, root.y, root.z}, {3}));
          },
          py::arg("positions"), py::arg("rotations"),
          "The skeleton posed as the body's (26, 3) positions and (26, 4) rotations show it: "
          "(local rotations (n, 4), the root's position (3,) in skeleton units). A pose that is "
          "not finite gives the rest pose.");
}

}  // namespace

void bind_body(py::module_& m) {
  bind_path(m);
  bind_humanoid(m);
  bind_follower(m);
  bind_skeleton(m);
}

}  // namespace fuzzygait::python

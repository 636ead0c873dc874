// What the Python module's files share: the objects a Python walker, crowd or motion keeps alive
// (the controller set and ground it walks), and arrays over C++ data.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::python {

namespace py = pybind11;

// Sets and grounds are held by shared pointers: every walker, crowd and motion made with one
// holds it too, so Python may drop its own reference first.
using SetPtr = std::shared_ptr<gait::ControllerSet>;
using GroundPtr = std::shared_ptr<terrain::Terrain>;

// A Python Walker: the C++ walker with the set and ground it keeps alive.
struct Walker {
  SetPtr set;
  GroundPtr ground;
  gait::Walker walker;
};

// A set given as a ControllerSet, a built-in name (str) or a folder (os.PathLike).
SetPtr to_set(const py::object& set);
// A ground given as a Terrain, a terrain spec such as "slope:10" (str), or None (level ground).
GroundPtr to_ground(const py::object& ground);

// A recorded or captured walk with the ground it was walked on and the step it was asked for
// (none for captured motion and walks read from CSV): what evaluate() needs besides the frames.
struct Motion {
  eval::Motion motion;
  GroundPtr ground;
  std::optional<double> commanded_step;
};

// The segments as a dict {"thigh": ..., ...} (metres).
py::dict segments_dict(const rig::Segments& segments);

// An array of `shape` over `data` (row-major), copied.
py::array_t<double> copy_array(const std::vector<double>& data, std::vector<py::ssize_t> shape);

void bind_walk(py::module_& m);     // ControllerSet, Terrain, Walker, Crowd (walk.cpp)
void bind_offline(py::module_& m);  // Motion, evaluate, clips, train (offline.cpp)
void bind_body(py::module_& m);     // Path, Humanoid, PathFollower, Skeleton, ... (body.cpp)

}  // namespace fuzzygait::python

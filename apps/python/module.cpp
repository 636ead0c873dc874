// import fuzzygait: the module, and how the library's errors become Python exceptions.
//   std::invalid_argument (a bad option, rig, step, set)    ValueError, the library's message
//   fuzzy::ParseError, io::MocapError (a file's line)        fuzzygait.ParseError (a ValueError)
//                                                            with .source and .line
//   std::filesystem::filesystem_error                       OSError
//   other std::runtime_error                                RuntimeError
// The messages are the library's: they name the file, line and field.
#include <Python.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <string>

#include "bindings.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/io/mocap.hpp"

namespace fuzzygait::python {
namespace {

// fuzzygait.ParseError, created once with the module (never freed: the module is never unloaded).
PyObject* parse_error_type = nullptr;

void raise_parse_error(const char* what, const std::string& source, int line) {
  py::object type = py::reinterpret_borrow<py::object>(parse_error_type);
  py::object error = type(what);
  error.attr("source") = source;
  error.attr("line") = line;
  PyErr_SetObject(parse_error_type, error.ptr());
}

void translate(std::exception_ptr thrown) {
  try {
    if (thrown) std::rethrow_exception(thrown);
  } catch (const fuzzy::ParseError& e) {
    raise_parse_error(e.what(), e.source(), e.line());
  } catch (const io::MocapError& e) {
    raise_parse_error(e.what(), e.source(), e.line());
  } catch (const std::filesystem::filesystem_error& e) {
    PyErr_SetString(PyExc_OSError, e.what());
  }
}

}  // namespace

py::dict segments_dict(const rig::Segments& s) {
  py::dict d;
  d["thigh"] = s.thigh;
  d["shank"] = s.shank;
  d["ankle_height"] = s.ankle_height;
  d["heel"] = s.heel;
  d["ball"] = s.ball;
  d["toe"] = s.toe;
  return d;
}

py::array_t<double> copy_array(const std::vector<double>& data, std::vector<py::ssize_t> shape) {
  py::array_t<double> a(shape);
  std::copy(data.begin(), data.end(), a.mutable_data());
  return a;
}

}  // namespace fuzzygait::python

PYBIND11_MODULE(fuzzygait, m) {
  namespace fp = fuzzygait::python;
  m.doc() =
      "fuzzygait: procedural human walking driven by fuzzy controllers (docs/python.md). "
      "Controller sets, walkers and crowds; the whole body on a path and a game's skeleton; "
      "recording, evaluating against normative curves, "
      "motion capture clips and training.";
  fp::parse_error_type =
      PyErr_NewExceptionWithDoc("fuzzygait.ParseError",
                                "A file the library cannot read: .source names it, .line the line "
                                "(0 for the whole file).",
                                PyExc_ValueError, nullptr);
  m.attr("__version__") = FUZZYGAIT_VERSION;
  m.attr("ParseError") = fp::py::reinterpret_borrow<fp::py::object>(fp::parse_error_type);
  fp::py::register_exception_translator(fp::translate);
  fp::bind_walk(m);
  fp::bind_offline(m);
  fp::bind_body(m);
}

// The `_tsrir` extension: thin bindings over the toolkit's libraries (the very functions the
// programs call), numpy arrays in and out, the GIL released while C++ works. The Python package
// `tsrir` (src/python/tsrir/__init__.py) wraps it: arguments are checked and converted there
// (tsrir/_convert.py), so what reaches these bindings has the right types.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <mutex>
#include <string>
#include <vector>

#include "bindings.h"
#include "util/error.h"
#include "util/log.h"

namespace py = pybind11;

namespace {

// The library's warnings, kept until the Python side collects them (_take_warnings) and re-issues
// them through `warnings`: they may be logged from threads that do not hold the GIL.
std::mutex g_warnings_mutex;
std::vector<std::string> g_warnings;

}  // namespace

PYBIND11_MODULE(_tsrir, m) {
  m.doc() = "tsrir: far-field speech augmentation (the toolkit's C++ library from Python)";
  // The toolkit's one exception type: bad input, with a message naming what was wrong.
  py::register_exception<tsrir::Error>(m, "Error", PyExc_ValueError);
  // A value of the wrong kind that got past the Python-side checks is a TypeError, as in Python.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::cast_error& e) {
      PyErr_SetString(PyExc_TypeError, (std::string("wrong argument type: ") + e.what()).c_str());
    }
  });
  tsrir::set_warning_handler([](const std::string& message) {
    std::lock_guard<std::mutex> lock(g_warnings_mutex);
    g_warnings.push_back(message);
  });
  m.def(
      "_take_warnings",
      [] {
        std::lock_guard<std::mutex> lock(g_warnings_mutex);
        std::vector<std::string> out;
        out.swap(g_warnings);
        return out;
      },
      "The library's warnings since the last call (tsrir/_convert.py re-issues them through `warnings`).");
  tsrir::python::bind_audio(m);
  tsrir::python::bind_simulate(m);
  tsrir::python::bind_metrics(m);
  tsrir::python::bind_reverberate(m);
  tsrir::python::bind_eq(m);
  tsrir::python::bind_lists(m);
  tsrir::python::bind_augmenter(m);
}

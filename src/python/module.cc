// The `_tsrir` extension: thin bindings over the toolkit's libraries (the very functions the
// programs call), numpy arrays in and out, the GIL released while C++ works. The Python package
// `tsrir` (src/python/tsrir/__init__.py) re-exports it.
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "util/error.h"

namespace py = pybind11;

PYBIND11_MODULE(_tsrir, m) {
  m.doc() = "tsrir: far-field speech augmentation (the toolkit's C++ library from Python)";
  // The toolkit's one exception type: bad input, with a message naming what was wrong.
  py::register_exception<tsrir::Error>(m, "Error", PyExc_ValueError);
  tsrir::python::bind_audio(m);
  tsrir::python::bind_simulate(m);
  tsrir::python::bind_metrics(m);
  tsrir::python::bind_reverberate(m);
  tsrir::python::bind_eq(m);
  tsrir::python::bind_lists(m);
  tsrir::python::bind_augmenter(m);
}

// numpy <-> the toolkit's sample containers. Arrays are copied into std::vector<float> while the
// GIL is held (so C++ work can then run with it released) and results are moved into new numpy
// arrays without another copy.
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace tsrir::python {

namespace py = pybind11;
using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// A 1-D array (any real dtype, converted to float32). `what` names the argument in errors.
std::vector<float> to_samples(const py::handle& array, const std::string& what);
// A 1-D array as one channel, or a 2-D array (channels, samples).
std::vector<std::vector<float>> to_channels(const py::handle& array, const std::string& what);

// Takes ownership of the vector's storage.
py::array_t<float> to_numpy(std::vector<float>&& samples);
// (channels, samples); all channels the same length.
py::array_t<float> to_numpy(const std::vector<std::vector<float>>& channels);

}  // namespace tsrir::python

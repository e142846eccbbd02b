#include "arrays.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "util/error.h"

namespace tsrir::python {

std::vector<float> to_samples(const py::handle& array, const std::string& what) {
  FloatArray a = FloatArray::ensure(array);
  if (!a) throw Error(what + ": expected a numeric array");
  if (a.ndim() != 1) throw Error(what + ": expected a 1-D array, got " + std::to_string(a.ndim()) + " dimensions");
  const float* p = a.data();
  std::vector<float> out(p, p + a.shape(0));
  for (size_t i = 0; i < out.size(); ++i)
    if (!std::isfinite(out[i])) throw Error(what + ": sample " + std::to_string(i) + " is not finite");
  return out;
}

std::vector<std::vector<float>> to_channels(const py::handle& array, const std::string& what) {
  FloatArray a = FloatArray::ensure(array);
  if (!a) throw Error(what + ": expected a numeric array");
  if (a.ndim() == 1) return {to_samples(a, what)};
  if (a.ndim() != 2) throw Error(what + ": expected a 1-D or 2-D (channels, samples) array");
  std::vector<std::vector<float>> out(static_cast<size_t>(a.shape(0)));
  const size_t n = static_cast<size_t>(a.shape(1));
  for (size_t c = 0; c < out.size(); ++c) {
    const float* p = a.data() + c * n;
    out[c].assign(p, p + n);
    for (size_t i = 0; i < n; ++i)
      if (!std::isfinite(out[c][i]))
        throw Error(what + ": channel " + std::to_string(c) + " sample " + std::to_string(i) + " is not finite");
  }
  return out;
}

py::array_t<float> to_numpy(std::vector<float>&& samples) {
  auto* owned = new std::vector<float>(std::move(samples));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  return py::array_t<float>({static_cast<py::ssize_t>(owned->size())}, {sizeof(float)}, owned->data(),
                            free_when_done);
}

py::array_t<float> to_numpy(const std::vector<std::vector<float>>& channels) {
  const size_t rows = channels.size(), cols = rows ? channels[0].size() : 0;
  py::array_t<float> out({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(cols)});
  float* p = out.mutable_data();
  for (size_t c = 0; c < rows; ++c) {
    if (channels[c].size() != cols) throw Error("internal: channels of different lengths");
    std::copy(channels[c].begin(), channels[c].end(), p + c * cols);
  }
  return out;
}

}  // namespace tsrir::python

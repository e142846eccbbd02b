// Helpers shared by the simulator tests.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/model.h"
#include "sim/room_list.h"

namespace tsrir::sim::test {

inline RoomSpec room_from_line(const std::string& line) { return parse_room_list_line(line, "test:1"); }

inline Signal simulate(const std::string& line, const std::string& model = "gas", double fs = 16000.0,
                       double length_s = 1.0, uint64_t seed = 0) {
  const RoomSpec room = room_from_line(line);
  return Model::parse(model).render(room, fs, static_cast<size_t>(std::llround(length_s * fs)), seed);
}

inline double energy(const std::vector<float>& x, size_t begin = 0, size_t end = SIZE_MAX) {
  double e = 0.0;
  const float* p = x.data();
  const size_t stop = std::min(end, x.size());
  for (size_t i = begin; i < stop; ++i) e += static_cast<double>(p[i]) * p[i];
  return e;
}

inline size_t peak_index(const std::vector<float>& x) {
  size_t best = 0;
  for (size_t i = 1; i < x.size(); ++i) {
    if (std::abs(x[i]) > std::abs(x[best])) best = i;
  }
  return best;
}

}  // namespace tsrir::sim::test

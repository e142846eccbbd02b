#include "dsp/bands.h"

#include <cstdio>

namespace tsrir {

std::string octave_band_label(double centre_hz) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", centre_hz);
  return buf;
}

int octave_band_index(double centre_hz) {
  for (int i = 0; i < kNumOctaveBands; ++i)
    if (std::fabs(kOctaveCentersHz[i] - centre_hz) < 1e-6 * centre_hz) return i;
  return -1;
}

}  // namespace tsrir

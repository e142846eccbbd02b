// The feature pass's helpers against signals made here (src/diagnose/rir_features.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "diagnose/rir_features.h"

namespace tsrir {
namespace {

constexpr double kPi = 3.14159265358979323846;

// onset_time_s (used where only the onset is needed) is compute_features' onset, bit for bit, and
// finds a band-limited impulse at 100.3 samples under a -30 dB decaying tail within half a sample
// (the parabolic peak interpolation on |h| is biased towards the nearest sample for a sinc).
TEST(RirFeatures, OnsetTimeIsTheFeaturePassOnset) {
  Signal rir;
  rir.sample_rate_hz = 16000;
  rir.samples.assign(8000, 0.0f);
  for (int i = 80; i < 121; ++i) {
    const double t = i - 100.3;
    rir.samples[i] = float(std::sin(kPi * t) / (kPi * t));
  }
  uint32_t state = 7;
  for (int i = 140; i < 8000; ++i) {
    state = state * 1664525u + 1013904223u;
    rir.samples[i] += float(0.03 * (double(state >> 8) / double(1 << 24) - 0.5) * std::exp(-(i - 140) / 1500.0));
  }
  const double onset = diagnose::onset_time_s(rir);
  EXPECT_EQ(onset, diagnose::compute_features(rir, 200.0).onset_s);
  EXPECT_NEAR(onset * rir.sample_rate_hz, 100.3, 0.5);
}

}  // namespace
}  // namespace tsrir

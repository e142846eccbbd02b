// Test-side helpers for the EQ tests: RIR-like signals made without the
// EQ code (exponentially decaying noise with a direct impulse; RBJ-cookbook biquads), so hidden
// effects are generated independently of what is tested.
#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/signal.h"
#include "test_support.h"
#include "util/rng.h"

namespace eqtest {

// Decaying Gaussian noise (energy envelope exp(-13.8 t / T60)) starting 1 ms after a direct
// impulse at `direct_index` whose energy is `drr_db` above the reverberant energy.
inline tsrir::Signal decaying_noise_rir(const std::string& id, double fs, size_t length, double t60_s,
                                        size_t direct_index, double drr_db, uint64_t seed) {
  tsrir::Rng rng(seed);
  tsrir::Signal s;
  s.id = id;
  s.sample_rate_hz = fs;
  s.samples.assign(length, 0.0f);
  const size_t start = direct_index + static_cast<size_t>(0.001 * fs);
  double reverb_energy = 0.0;
  std::vector<double> tail(length, 0.0);
  for (size_t n = start; n < length; ++n) {
    const double t = (n - start) / fs;
    tail[n] = rng.normal() * std::exp(-6.9078 * t / t60_s);  // amplitude: -60 dB at T60
    reverb_energy += tail[n] * tail[n];
  }
  const double direct = std::sqrt(reverb_energy * std::pow(10.0, drr_db / 10.0));
  double peak = direct;
  for (double v : tail) peak = std::max(peak, std::abs(v));
  for (size_t n = 0; n < length; ++n) s.samples[n] = static_cast<float>(0.9 * tail[n] / peak);
  s.samples[direct_index] = static_cast<float>(0.9 * direct / peak);
  return s;
}

struct Biquad {
  double b0 = 1, b1 = 0, b2 = 0, a1 = 0, a2 = 0;
};

// RBJ audio-EQ cookbook peaking filter: gain_db at f0, bandwidth set by q.
inline Biquad peaking_biquad(double f0, double gain_db, double q, double fs) {
  const double a = std::pow(10.0, gain_db / 40.0), w = 2 * M_PI * f0 / fs, alpha = std::sin(w) / (2 * q);
  const double a0 = 1 + alpha / a;
  return {(1 + alpha * a) / a0, -2 * std::cos(w) / a0, (1 - alpha * a) / a0, -2 * std::cos(w) / a0, (1 - alpha / a) / a0};
}

// RBJ cookbook second-order low-pass.
inline Biquad lowpass_biquad(double fc, double q, double fs) {
  const double w = 2 * M_PI * fc / fs, alpha = std::sin(w) / (2 * q), c = std::cos(w);
  const double a0 = 1 + alpha;
  return {(1 - c) / 2 / a0, (1 - c) / a0, (1 - c) / 2 / a0, -2 * c / a0, (1 - alpha) / a0};
}

// RBJ cookbook high shelf (shelf slope S = 1): gain_db above ~f0.
inline Biquad high_shelf_biquad(double f0, double gain_db, double fs) {
  const double a = std::pow(10.0, gain_db / 40.0), w = 2 * M_PI * f0 / fs, c = std::cos(w);
  const double alpha = std::sin(w) / 2 * std::sqrt(2.0), sa = 2 * std::sqrt(a) * alpha;
  const double a0 = (a + 1) - (a - 1) * c + sa;
  return {a * ((a + 1) + (a - 1) * c + sa) / a0, -2 * a * ((a - 1) + (a + 1) * c) / a0,
          a * ((a + 1) + (a - 1) * c - sa) / a0, 2 * ((a - 1) - (a + 1) * c) / a0, ((a + 1) - (a - 1) * c - sa) / a0};
}

inline void apply_biquad(const Biquad& f, std::vector<float>* x) {
  double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
  for (float& v : *x) {
    const double y = f.b0 * v + f.b1 * x1 + f.b2 * x2 - f.a1 * y1 - f.a2 * y2;
    x2 = x1;
    x1 = v;
    y2 = y1;
    y1 = y;
    v = static_cast<float>(y);
  }
}

// |H(f)| in dB of a biquad.
inline double biquad_gain_db(const Biquad& f, double freq_hz, double fs) {
  const double w = 2 * M_PI * freq_hz / fs;
  const std::complex<double> z1 = std::polar(1.0, -w), z2 = std::polar(1.0, -2 * w);
  const std::complex<double> h = (f.b0 + f.b1 * z1 + f.b2 * z2) / (1.0 + f.a1 * z1 + f.a2 * z2);
  return 20 * std::log10(std::abs(h));
}

}  // namespace eqtest

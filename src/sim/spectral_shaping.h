// Helpers shared by the broadband extension components: smooth magnitude curves defined by
// octave-band values, and minimum-phase FIR design from a magnitude response.
#pragma once
#include <vector>

#include "sim/room.h"

namespace tsrir::sim {

// dB value at f_hz interpolated between octave-band values with the complementary crossover
// weights of the model's band filters (constant below 62.5 Hz and above 8 kHz).
double interpolate_band_db(const BandValues& band_db, double f_hz);

// Minimum-phase FIR (real cepstrum method) whose magnitude follows magnitude_db(f) (callable
// through the table `magnitude_db` sampled at k * fs / fft_size, k = 0..fft_size/2). The result
// is `num_taps` long with a half-Hann fade over its last quarter.
std::vector<float> minimum_phase_fir(const std::vector<double>& magnitude_db, size_t fft_size, size_t num_taps);

// Multiplies the spectrum of x (zero-padded by `pad` samples against wrap-around) by the real,
// zero-phase gain(f_hz) and returns the first x.size() samples.
std::vector<float> zero_phase_filter(const std::vector<float>& x, double sample_rate_hz, size_t pad,
                                     double (*gain)(double f_hz, const void* arg), const void* arg);

}  // namespace tsrir::sim

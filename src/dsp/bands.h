// The octave bands used throughout (GSound's 8 absorption bands, ISO 3382 octaves, the EQ's
// sample points): exact base-2 centres 1000 * 2^k, edges centre * 2^(+-1/2).
#pragma once
#include <array>
#include <cmath>
#include <string>

namespace tsrir {

constexpr int kNumOctaveBands = 8;
constexpr std::array<double, kNumOctaveBands> kOctaveCentersHz = {62.5, 125.0, 250.0, 500.0,
                                                                  1000.0, 2000.0, 4000.0, 8000.0};
inline double octave_lower_edge_hz(double centre_hz) { return centre_hz / std::sqrt(2.0); }
inline double octave_upper_edge_hz(double centre_hz) { return centre_hz * std::sqrt(2.0); }
// Label used in tables and JSON: "62.5", "125", ..., "8000".
std::string octave_band_label(double centre_hz);
// Index of a centre in kOctaveCentersHz, or -1.
int octave_band_index(double centre_hz);

}  // namespace tsrir

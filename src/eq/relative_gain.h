// Sub-band relative gains of an RIR (TS-RIR sec. 3.2, stage 1): the level at the 7 sample points
// 62.5, 125, 250, 500, 2000, 4000, 8000 Hz relative to the level at 1000 Hz, read off the
// magnitude spectrum of the whole RIR.
//
// How a level is read off the spectrum (--gain-method):
//   octave (default): mean |H|^2 over the bins in [f/sqrt2, f*sqrt2]. Single bins of an RIR
//                     spectrum scatter by +-5..10 dB (Rayleigh statistics); the octave mean does not.
//   smooth:           mean |H|^2 over [f/2^(1/6), f*2^(1/6)] (1/3-octave smoothing sampled at f).
//   bin:              the nearest FFT bin (the literal reading of the paper).
// Bands are clipped at Nyquist: at 16 kHz the 8000 Hz octave is [5657, 8000] Hz. Rates below
// 16 kHz, where the 8000 Hz point itself is above Nyquist, are rejected (error), never guessed.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "io/signal.h"
#include "util/options.h"

namespace tsrir {

constexpr int kEqNumPoints = 7;
constexpr std::array<double, kEqNumPoints> kEqPointsHz = {62.5, 125.0, 250.0, 500.0, 2000.0, 4000.0, 8000.0};
constexpr double kEqReferenceHz = 1000.0;
// The 8 nodes of the EQ curve (points plus reference), ascending; node kEqReferenceNode is 1 kHz.
constexpr int kEqNumNodes = 8;
constexpr std::array<double, kEqNumNodes> kEqNodesHz = {62.5, 125.0, 250.0, 500.0, 1000.0, 2000.0, 4000.0, 8000.0};
constexpr int kEqReferenceNode = 4;
// Node index of sample point k (skips the reference).
inline int eq_node_of_point(int k) { return k < kEqReferenceNode ? k : k + 1; }

using RelativeGainsDb = std::array<double, kEqNumPoints>;

enum class GainMethod { kOctave, kSmooth, kBin };
const Choices<GainMethod>& gain_method_choices();        // "octave" | "smooth" | "bin"
GainMethod parse_gain_method(const std::string& name);
std::string gain_method_name(GainMethod method);

// Lowest sample rate the EQ accepts (the 8000 Hz point must not lie above Nyquist).
constexpr double kEqMinSampleRateHz = 16000.0;

// FFT size used to read gains of an RIR of `num_samples` samples: at least 16384 (about 1 Hz
// resolution at 16 kHz, so the 62.5 Hz octave spans ~45 bins), and never shorter than the RIR.
size_t eq_fft_size(size_t num_samples);

// The bins of each of the 8 node bands (points + reference) on one FFT grid.
class EqBandGrid {
 public:
  EqBandGrid(size_t fft_size, double sample_rate_hz, GainMethod method);
  size_t fft_size() const { return fft_size_; }
  double sample_rate_hz() const { return sample_rate_hz_; }
  GainMethod method() const { return method_; }
  // Inclusive bin range [first, last] of node band j (0..7).
  size_t first_bin(int node) const { return first_[node]; }
  size_t last_bin(int node) const { return last_[node]; }
  double bin_hz(size_t bin) const { return bin * sample_rate_hz_ / fft_size_; }

  // Mean power per node band from a power spectrum with fft_size/2+1 bins.
  std::array<double, kEqNumNodes> band_powers(const std::vector<double>& power) const;
  // Relative gains (dB) from band powers. Throws Error (naming `what`) if the reference band or
  // any point band holds no energy.
  static RelativeGainsDb relative_gains(const std::array<double, kEqNumNodes>& band_power, const std::string& what);

 private:
  size_t fft_size_;
  double sample_rate_hz_;
  GainMethod method_;
  std::array<size_t, kEqNumNodes> first_{}, last_{};
};

// Throws Error (naming `what`) unless the rate is one the EQ handles.
void check_eq_sample_rate(double sample_rate_hz, const std::string& what);

// Relative gains of one RIR. Errors name rir.id: silent RIR, band without energy, bad rate.
RelativeGainsDb relative_gains_db(const Signal& rir, GainMethod method);

}  // namespace tsrir

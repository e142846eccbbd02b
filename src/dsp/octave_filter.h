// Octave-band Butterworth bandpass filters as cascades of biquads (second-order sections), and
// their application forward, time-reversed, or as a bank of bands sharing one input.
// Design follows MATLAB's butter(N, [W1 W2]) (analog prototype -> lowpass-to-bandpass -> bilinear
// transform with pre-warped edges); the ANSI S1.1-1986 octave (octdsgn) widens the edges so the
// order-N response meets the standard's class mask. Sections instead of one 2N-order polynomial
// keep low bands at high rates (62.5 Hz at 48 kHz) numerically exact.
#pragma once
#include <complex>
#include <cstddef>
#include <vector>

namespace tsrir {

struct Biquad {
  // H(z) = (b0 + b1 z^-1 + b2 z^-2) / (1 + a1 z^-1 + a2 z^-2)
  double b0 = 1, b1 = 0, b2 = 0, a1 = 0, a2 = 0;
};

struct SosFilter {
  std::vector<Biquad> sections;
};

struct BandEdgesHz {
  double low_hz = 0;
  double high_hz = 0;
};

// Digital Butterworth bandpass of order 2N (N sections) with -3 dB points exactly at low_hz and
// high_hz, unit gain at the (warped) geometric centre. Throws Error unless
// 0 < low_hz < high_hz < fs/2 and order >= 1.
SosFilter butterworth_bandpass(int order, double low_hz, double high_hz, double sample_rate_hz);

// octdsgn's pre-distorted edges for an order-N octave at centre fc: fc/sqrt(2)/alpha and
// fc*sqrt(2)*alpha, beta = (pi/2N)/sin(pi/2N), alpha = (1 + sqrt(1 + 8 beta^2)) / (4 beta).
BandEdgesHz ansi_octave_edges_hz(double center_hz, int order = 3);
SosFilter ansi_octave_filter(double center_hz, double sample_rate_hz, int order = 3);

// Frequency response at freq_hz.
std::complex<double> sos_response(const SosFilter& filter, double freq_hz, double sample_rate_hz);

// Causal filtering from zero state (MATLAB filter(b, a, x)), double-precision state.
void sos_filter(const SosFilter& filter, const float* x, size_t n, double* y);
std::vector<double> sos_filter(const SosFilter& filter, const std::vector<float>& x);
// Time-reversed filtering: y = reverse(filter(reverse(x))). The filter's ringing then precedes
// the events instead of prolonging the decay (ISO 3382-1 permits B*T > 4 instead of 16).
std::vector<double> sos_filter_reversed(const SosFilter& filter, const std::vector<float>& x);

// Several filters with the same number of sections over one input in a single pass (the band
// loop vectorises). out[b] receives filter b's output (resized to n). Throws Error if the
// filters' section counts differ.
void sos_filter_bank(const std::vector<SosFilter>& filters, const float* x, size_t n, bool time_reversed,
                     std::vector<std::vector<double>>* out);

// What Schroeder integration needs of a time-reversed bank, from the same single pass: filtering
// time-reversed runs from the last sample to the first, as the backward sums do, so each output is
// squared and added to its band's sum as it is made (no second and third pass over the bands).
struct BankEnergies {
  // y_b[i]^2 (y_b as sos_filter_bank(time_reversed)) at energy[i * stride + b], sample-major so the
  // pass stores whole vectors; stride = the number of bands rounded up to a multiple of 8, the
  // rest of a row is 0.
  std::vector<double> energy;
  size_t stride = 0;
  std::vector<std::vector<double>> tail;  // tail[b][i] = sum_{k>=i} y_b[k]^2 added from the end; n + 1 values
  std::vector<double> peak;               // max_i y_b[i]^2
  double at(size_t b, size_t i) const { return energy[i * stride + b]; }
};
void sos_filter_bank_energies(const std::vector<SosFilter>& filters, const float* x, size_t n, BankEnergies* out);

}  // namespace tsrir

// What rir-diagnose measures on every RIR, measured or simulated alike; each detection compares
// these between a measured RIR and its simulation (paired), over the whole set.
#pragma once
#include <utility>
#include <vector>

#include "io/signal.h"
#include "metrics/rir_metrics.h"
#include "sim/room.h"

namespace tsrir::diagnose {

using sim::BandValues;

struct FeatureOptions {
  // Low-frequency analysis range: modes are looked for in [lf_min_hz, Schroeder frequency].
  double lf_min_hz = 30.0;
  double lf_max_hz = 250.0;      // upper end of the low-frequency spectral distance
  double direct_pre_ms = 0.5;    // direct-sound window around the onset
  double direct_post_ms = 2.5;
  double tail_begin_ms = 20.0;   // reverberant-tail window for spectral shape, after the onset
  double tail_end_ms = 300.0;
  // Early window and band of the echo-density statistic. 2-20 ms and 1-7 kHz, not the 5-45 ms and
  // 1-4 kHz of Abel & Huang's usual set-up: in a 90 m3 room the response is already nearly
  // Gaussian by 5-45 ms in a 3 kHz band (normalised density 0.94-1.0 whether the surfaces scatter
  // 10 % or 95 %), so the statistic had no room to move; earlier and with twice the bandwidth
  // (shorter reflection wavelets) it starts at ~0.7 and moves 2.5x as far for the same change of
  // scattering on the tests' independent generator (docs/results/diagnose_power.md).
  double echo_density_begin_ms = 2.0;
  double echo_density_end_ms = 20.0;
  double echo_density_low_hz = 1000.0;   // below: the room's modes, not its reflections
  double echo_density_high_hz = 7000.0;  // capped at 0.45 x the sample rate
  // Late-field spectral persistence (room_modes): the power spectrum's fine structure in
  // consecutive windows of persistence_window_ms from persistence_begin_ms after the onset (after
  // the baseline's image sources end: ~100 ms in a 90 m3 room, ~120 ms in R3VIVAL's 144 m3), from
  // lf_min_hz to persistence_schroeder_factor x the stated room's Schroeder frequency. A modal
  // field's spectrum keeps its peaks from one window to the next (every mode rings at its own
  // frequency); a diffuse field's (the simulation's noise tail, measurement noise) is a new draw
  // in every window. Four windows of 150 ms: the larger t-value on the tests' generator than two of
  // 250 ms or five of 120 ms (docs/results/diagnose_power.md).
  double persistence_begin_ms = 150.0;
  double persistence_window_ms = 150.0;
  int persistence_windows = 4;
  double persistence_schroeder_factor = 2.0;
  double persistence_trend_hz = 10.0;  // the local mean the fine structure is taken against
};

struct RirFeatures {
  double onset_s = 0.0;          // first arrival (interpolated peak of the first strong sample)
  double energy = 0.0;           // sum of squares
  RirMetrics metrics;            // iso definition with Lundeby noise handling
  BandValues decay_rate_per_s;   // 13.8155 / T30 (T20 where T30 is not measurable; else NaN)
  BandValues early_decay_rate_per_s;  // 13.8155 / EDT (the first 10 dB: the band's own decay even
                                      // where a slower neighbour's leakage dominates its T30)
  BandValues t30_s;
  BandValues level_db;           // metrics' band level re broadband energy
  BandValues direct_band_db;     // energy of the direct-sound window per band, dB (NaN = unreliable)
  BandValues tail_band_db;       // energy of the reverberant window per band, dB
  BandValues late_power;         // per-sample power of the last 10 % per band (noise estimate)
  BandValues late_decay_band_db;  // the same per band (NaN above Nyquist)
  double late_decay_db = 0.0;    // decay between 70-80 % and 90-100 % of the file (median, 500..4k)
  double tail_level_db = 0.0;    // energy of the last 10 % of the active part re the total energy, dB
  double echo_density = 0.0;     // mean normalised echo density (FeatureOptions' band) in the early window
  std::vector<double> lf_spectrum_db;  // 1 Hz grid from 0 to lf_max_hz, 3 Hz power smoothing
  double lf_energy_ratio = 0.0;  // energy below the Schroeder frequency / total energy
  // The end of the part above digital silence (trailing 10 ms blocks more than kSilenceDb below
  // the strongest block: zero padding, a file cut and padded). The tail metrics stop there.
  double active_end_s = 0.0;
  std::vector<double> block_energy;  // energy per 10 ms block from the file's start, re the total energy
  // Late-field spectral persistence per pair of consecutive windows (FeatureOptions::persistence_*):
  // the correlation of the two windows' fine structure (power re its local mean); NaN for a window
  // past the active part.
  std::vector<double> persistence_pairs;
};

// Digital silence: a 10 ms block this far below the RIR's strongest block (float zero padding,
// the end of a file cut and padded) is not part of the response.
inline constexpr double kSilenceDb = 150.0;

// The tail level of `f` in the window of `reference`'s last 10 % of its active part (energy re the
// total, dB): measured and simulated compared over the same span, which never reaches into the
// measurement's digital silence.
double tail_level_in_window_db(const RirFeatures& f, const RirFeatures& reference);

// The number of persistence pairs whose windows end within `reference`'s active part (never in
// the measurement's digital silence; measurement noise only lowers the persistence it dilutes),
// and the mean persistence of `f` over those first `pairs` pairs (NaN for none).
size_t persistence_pairs_in_span(const RirFeatures& reference, const FeatureOptions& options = {});
double mean_persistence(const RirFeatures& f, size_t pairs);

// `schroeder_hz`: the stated room's Schroeder frequency (the low-frequency energy share and the
// persistence range).
RirFeatures compute_features(const Signal& rir, double schroeder_hz, const FeatureOptions& options = {});

// The first arrival in seconds, as compute_features(...).onset_s (interpolated peak of the first
// sample within 12 dB of the RIR's peak) without the rest of the feature pass.
double onset_time_s(const Signal& rir);

// Early echo density (echo_density_low_hz..high_hz, echo_density_begin_ms..end_ms after the onset) of x convolved with
// y's direct sound (2 ms around its onset, unit energy), and of y convolved with x's: both then
// carry both measurement chains, so a transducer's colouration or ringing in one of them does not
// read as a denser tail. Returns {density of x, density of y}.
std::pair<double, double> cross_equalised_echo_density(const Signal& x, double onset_x_s, const Signal& y,
                                                       double onset_y_s, const FeatureOptions& options = {});

// Bands whose direct-sound level is resolvable at this rate by the short direct window.
bool direct_band_reliable(int band, double sample_rate_hz);

// RMS difference of two mean-removed LF spectra between lf_min_hz and their end, dB.
double lf_spectral_distance_db(const std::vector<double>& a, const std::vector<double>& b, double lf_min_hz);

// Normalised echo density profile (Abel & Huang): fraction of samples beyond one standard
// deviation in a sliding window, divided by erfc(1/sqrt 2); evaluated at the given centres.
double mean_echo_density(const std::vector<float>& x, double sample_rate_hz, size_t begin, size_t end);

// Energy decay curve in dB (Schroeder) of the broadband RIR from the onset, one value per
// `step_s`, for plotting.
std::vector<double> edc_db_curve(const Signal& rir, double onset_s, double step_s, double length_s);

}  // namespace tsrir::diagnose

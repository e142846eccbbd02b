// The catalog of causes rir-diagnose looks for, and the statistical decision for each.
//
// Every decision is over the whole set. The null hypothesis is "measured = the baseline model
// with another seed" (the baseline is random: diffuse-tail noise). Each statistic is a per-RIR
// paired difference d_i = f(measured_i) - f(simulated_i, seed A); the same statistic between
// seed B and seed A, e_i = f(sim_B_i) - f(sim_A_i), is the null calibration: the decision rule
// applied to e must not fire (reported as null_statistic; if it fires, the statistic is not
// trusted and the effect is not reported as detected). Thresholds (two conditions each: a test
// that the set's differences are not chance at p < kAlpha, Bonferroni-corrected over bands, AND
// an effect size a listener/metric would notice; all decided on the fit half of the set only):
//   time_offset          |onset_meas - onset_sim| > max(0.6 ms, 5 MAD of the null) in more RIRs
//                        than a 5 % per-RIR false-alarm rate explains (binomial p < kAlpha), and
//                        the median |difference| above the same threshold.
//   noise_floor          decay over the last 30 % of the file (level at 70-80 % minus 90-100 %,
//                        500 Hz..4 kHz median), paired: mean difference < -6 dB at p < kAlpha,
//                        and the measured late decay flat (set median < 3 dB). A double-slope
//                        decay (slow modes, filter leakage) still decays and is not noise.
//   transducer_response  direct-sound spectral shape (band levels, mean over bands removed):
//                        some band |mean| > 1 dB at p < kAlpha / bands, and the tail's shape
//                        agrees (correlation of the mean shapes > 0.6).
//   room_modes           mode prominence (spectrum maxima within the modal half-bandwidth of the
//                        stated room's predicted modes minus maxima at midpoints between modes,
//                        each relative to the local mean level over +-10 Hz so that a smooth trend
//                        such as a loudspeaker's low-frequency roll-off cancels): mean difference
//                        > 0.5 dB, p < kAlpha. When band_absorption is also
//                        detected, room_modes is decided again against band-refitted
//                        simulations (lower absorption makes the image sources more modal).
//   air_absorption       per-room, per-band mean log decay-rate ratios fitted by one ISO 9613-1
//                        band decay increase for all rooms (humidity and scale fitted): the fit
//                        must remove > 90 % of the chi-square, improve it by > 20 over no change
//                        AND over one uniform rate factor for all bands (a room size error), leave no
//                        room's band significant, and predict > 5 % faster decay in the top band.
//   band_absorption      some room's band log decay-rate ratio (after the air fit, when air is
//                        detected) beyond ln(1.08) at p < kAlpha / (rooms x bands). Bands below
//                        twice the Schroeder frequency are left to room_modes when it is detected.
//   diffuse_scattering   early (5-45 ms) echo density of the 1-4 kHz band, each RIR convolved
//                        with the other's direct sound (so colouration cancels): |mean
//                        difference| > 0.05, p < kAlpha.
// Air absorption and per-band absorption both only change decay rates per band: the tool reports
// air only when one ISO 9613-1 curve explains the whole mismatch; otherwise the mismatch is
// band_absorption (which then also absorbs any air absorption).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "diagnose/rir_features.h"
#include "io/signal.h"
#include "sim/room.h"

namespace tsrir::diagnose {

constexpr double kAlpha = 1e-3;

// Every threshold of the decisions above, in one place (written to findings.json as
// "thresholds"); the prose above says why each has its value.
struct DetectionThresholds {
  double alpha = kAlpha;                      // per-decision p (Bonferroni over bands/rooms)
  double time_offset_min_ms = 0.6;            // 0.2 m of path: position errors of +-0.1 m
  double time_offset_null_mads = 5.0;         // or 5 MAD of the seed-vs-seed onset spread
  double time_offset_rirs_rate = 0.05;        // per-RIR false-alarm rate of the binomial test
  double noise_floor_min_db = 6.0;            // late decay this much below the simulation's
  double noise_floor_flat_db = 3.0;           // and the measured late decay flatter than this
  double room_modes_min_db = 0.5;             // mode prominence above the simulation's
  double scattering_min_echo_density = 0.05;  // early echo density difference
  double transducer_min_db = 1.0;             // direct-sound band shape departure
  double transducer_min_correlation = 0.6;    // of the direct and tail shapes
  double band_min_rate_ratio = 1.08;          // per-band decay-rate departure
  double air_min_top_rate_ratio = 1.05;       // predicted top-band decay increase
  double air_max_chi2_fraction = 0.1;         // chi-square the air curve may leave
  double air_min_chi2_improvement = 20.0;     // over no change and over a uniform rate factor
};
inline constexpr DetectionThresholds kThresholds{};

// The room a set-up belongs to for per-room refits: its room id when the list gives one, else its
// dimensions and stated absorption (lines that differ only in positions share a room).
std::string room_group(const sim::RoomSpec& room);

// Catalog order (the order of findings.json).
const std::vector<std::string>& effect_catalog();

struct Finding {
  std::string effect;
  bool detected = false;
  double confidence = 0.0;
  std::string evidence;
  std::vector<std::pair<std::string, double>> parameters;  // fitted values (when detected)
  double statistic = 0.0;        // the effect-size statistic on measured vs simulated
  double null_statistic = 0.0;   // the same on seed B vs seed A
  double threshold = 0.0;
  std::string statistic_unit;
};

// Everything the detections and fits look at, per RIR in set order.
struct SetObservations {
  std::vector<sim::RoomSpec> rooms;
  std::vector<Signal> measured;
  std::vector<Signal> simulated;       // baseline, seed A
  std::vector<RirFeatures> meas, sim_a, sim_b;
  std::vector<std::vector<double>> mode_freqs_hz;
  std::vector<double> schroeder_hz;
  std::vector<double> t60_low_s;       // stated Eyring T60 at 125 Hz
  // Cross-equalised early echo densities: {measured, sim A} and {sim B, sim A}.
  std::vector<std::pair<double, double>> echo_density_meas_a, echo_density_b_a;
  // Set when room_modes was ruled out by a re-check: band_absorption then tests the low bands too.
  bool room_modes_ruled_out = false;
};

// Per-band summaries the report plots.
struct BandSummary {
  BandValues mean_log_rate_ratio{}, se_log_rate_ratio{};   // ln(rate_meas / rate_sim)
  BandValues mean_level_delta_db{}, se_level_delta_db{};   // level_meas - level_sim
  BandValues direct_shape_db{}, tail_shape_db{};           // transducer shapes
  BandValues air_fit_log_ratio{};                          // the fitted air curve
};

std::vector<Finding> detect_effects(const SetObservations& obs, BandSummary* summary);

// The air fit's parameters (used by fitting as well): humidity (%) and scale.
struct AirFit {
  double humidity_percent = 50.0;
  double scale = 0.0;
  double chi2_zero = 0.0, chi2_fit = 0.0;
};
// One mean log decay-rate ratio (measured / simulated) of one band in one room.
struct RateObservation {
  int band = 0;
  double mean_log_ratio = 0.0;
  double standard_error = 1.0;
  double base_rate_per_s = 1.0;  // the simulation's decay rate
};
// Fits the ISO curve at the stated temperature (humidity and scale on grids) by weighted least
// squares over all observations.
AirFit fit_air(const std::vector<RateObservation>& observations, double temperature_c, double speed_of_sound_m_s);
// ln((base + scale * increase(humidity)) / base) for one band.
double air_log_ratio(int band, const AirFit& fit, double base_rate, double temperature_c, double speed_of_sound_m_s);

}  // namespace tsrir::diagnose

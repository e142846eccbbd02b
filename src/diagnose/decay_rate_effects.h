// What air_absorption and band_absorption share (effect_air_absorption.cc,
// effect_band_absorption.cc): both only change decay rates per band, so they are decided from one
// analysis of the per-room, per-band mean log decay-rate ratios ln(rate_measured / rate_simulated).
// The cross-effect rule between them: the tool reports air only when one ISO 9613-1 curve explains
// the whole mismatch (better than no change and better than one uniform rate factor, a room size
// error); otherwise any band that departs is band_absorption, which then also absorbs air's share.
// Bands below twice the Schroeder frequency are left to room_modes when it is detected, except a
// decay faster than simulated there (modes less damped than the simulation's only slow it).
//
// Also here: the band refit (per-room factors on the absorption exponent that match the measured
// decay, by analysis by synthesis), which band_absorption's extension fits and which other effects
// decide against (band_refitted below: a decay mismatch is the simpler cause).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "diagnose/effect.h"
#include "sim/room.h"

namespace tsrir::diagnose {

struct AirAbsorptionThresholds {
  double min_top_rate_ratio = 1.05;
  double max_chi2_fraction = 0.1;
  double min_chi2_improvement = 20.0;
  std::vector<Threshold> list() const;
};
inline constexpr AirAbsorptionThresholds kAirThresholds{};

struct BandAbsorptionThresholds {
  double min_rate_ratio = 1.08;
  double max_size_error = 0.05;
  std::vector<Threshold> list() const;
};
inline constexpr BandAbsorptionThresholds kBandThresholds{};

// The air fit's parameters: humidity (%) and scale of the ISO curve at the stated temperature.
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

// The decision analysis of one side: measured vs seed A, or seed B vs seed A (null).
struct DecayRateSide {
  AirFit fit;
  bool air_fires = false;
  bool band_fires = false;
  int worst_band = -1;
  double worst_ratio = 0.0;   // the largest raw per-band, per-room mean log ratio beyond geometry's share
  std::string worst_room;
  BandValues air_curve{};     // the fitted air curve per tested band (NaN elsewhere)
  // Bands below twice the Schroeder frequency (room_modes detected) that decay faster than
  // simulated in some room (test_low_bands_faster): band_absorption's beyond the fitted modes.
  std::vector<int> low_faster_bands;
  double uniform_chi2 = 0.0;  // chi-square of one rate factor for all bands
};
struct DecayRateAnalysis {
  std::vector<std::vector<double>> q;  // per band, per RIR: ln(rate_meas / rate_A)
  std::vector<int> tested;             // bands decided on
  size_t num_rooms = 0;
  double t_crit = 0.0;                 // per band and room (Bonferroni)
  double schroeder_hz = 0.0;           // median over the set
  bool low_bands_left_to_modes = false;
  DecayRateSide measured, null;
};
// `room_modes_detected`: the bands below twice the Schroeder frequency are tested only for a decay
// faster than simulated (DecayRateSide::low_faster_bands).
DecayRateAnalysis analyse_decay_rates(const SetObservations& obs, bool room_modes_detected);

// Per-band factors of the band_absorption component for the RIRs idx (one room): median measured
// over simulated decay rate, the air fit's share removed (air_fit.scale = 0: none); bands below
// keep_below_hz stay 1.
sim::BandValues band_absorption_scales(const SetObservations& obs, const std::vector<size_t>& idx, const AirFit& air_fit,
                                       double keep_below_hz);
std::string band_absorption_spec(const sim::BandValues& scale);  // "band_absorption:s62.5=..,..."

// Analysis by synthesis: renders the RIRs idx with `model_prefix` + band_absorption(scale),
// measures their decay rates like the measurements', and corrects each band's factor by the
// remaining ratio (mean of the T30 and EDT log ratios), `iterations` times. Needed because
// octave-band T30 leaks: a band decaying much faster than its neighbours measures slower than it
// is, in the measurement and in the simulation alike, so matching measured rates (not true
// rates) gives the right factor.
sim::BandValues refine_band_scales(const SetObservations& obs, const std::vector<size_t>& idx, sim::BandValues scale,
                                   const std::string& model_prefix, const DiagnoseOptions& options, int iterations,
                                   double keep_below_hz);

// The band refit per room (room_group): the baseline with every band's absorption refitted to the
// measured decay (all bands, no air share: band_absorption_scales + 3 refinements), as a model
// spec. What any user would try first; the gain table's second baseline (diagnose.h).
std::map<std::string, std::string> band_refit_models(const SetObservations& obs, const DiagnoseOptions& options);
// The same refit pooled over every RIR of `obs` (one set of band scales for all rooms): the
// refitted baseline of a held-out RIR whose room has no RIR in the fit half.
std::string band_refit_pooled_model(const SetObservations& obs, const DiagnoseOptions& options);

// `obs` with seeds A and B re-rendered (features recomputed) with band_refit_models.
SetObservations render_band_refitted(const SetObservations& obs, const DiagnoseOptions& options);

// The explain-away reference of the effects whose statistic a decay mismatch also moves
// (source_directivity, transducer_response): render_band_refitted of the fit half, rendered once
// per decision pass (DecisionContext::reference "band_refitted").
inline constexpr const char* kBandRefittedReference = "band_refitted";
const SetObservations& band_refitted(const DecisionContext& ctx);

}  // namespace tsrir::diagnose

// Fitting the model extensions of the detected effects on the fit part of the set. Each fit
// writes its values into the finding's parameters and yields, per room, the extended model spec
// (baseline + the detected effects' components).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "diagnose/diagnose.h"
#include "diagnose/effects.h"

namespace tsrir::diagnose {

// Extended model spec per effective room id.
std::map<std::string, std::string> fit_extensions(const SetObservations& obs, const std::vector<size_t>& fit_index,
                                                  const DiagnoseOptions& options, std::vector<Finding>* findings);

// Per-band factors of the band_absorption component for the RIRs idx (one room): median measured
// over simulated decay rate, the air fit's share removed (air_fit.scale = 0: none); bands below
// keep_below_hz stay 1.
sim::BandValues band_absorption_scales(const SetObservations& obs, const std::vector<size_t>& idx, const AirFit& air_fit,
                                       double keep_below_hz);
std::string band_absorption_spec(const sim::BandValues& scale);  // "band_absorption:s62.5=..,..."

// Analysis by synthesis: renders the RIRs idx with `model_prefix` + band_absorption(scale),
// measures their decay rates like the measurements', and corrects each band's factor by the
// remaining ratio (mean of the T30 and EDT log ratios), `iterations` times. Needed because octave-band T30 leaks: a band decaying much
// faster than its neighbours measures slower than it is, in the measurement and in the
// simulation alike, so matching measured rates (not true rates) gives the right factor.
sim::BandValues refine_band_scales(const SetObservations& obs, const std::vector<size_t>& idx, sim::BandValues scale,
                                   const std::string& model_prefix, const DiagnoseOptions& options, int iterations,
                                   double keep_below_hz);

// Renders one set-up with a model spec at the measured length and rate.
Signal render_rir(const std::string& model_spec, const sim::RoomSpec& room, double sample_rate_hz, size_t num_samples,
                  uint64_t seed);

}  // namespace tsrir::diagnose

// What the two definitions of the parameters (rir_metrics.h: MetricsDefinition) share: ISO 3382-1
// (metrics_iso.h) and IoSR irStats (metrics_irstats.h); rir_metrics.cc checks an RIR and picks
// one. Internal to src/metrics.
#pragma once
#include <string>
#include <vector>

#include "dsp/octave_filter.h"
#include "metrics/rir_metrics.h"

namespace tsrir::metrics_detail {

constexpr double kNaN = kMetricsNaN;
constexpr int kOctaveOrder = 3;  // ANSI S1.1 order-3 (6th-order bandpass), as octdsgn

void validate(const Signal& rir);           // what both definitions need of an RIR
std::string band_name(double center_hz);  // "500 Hz", "broadband"
std::string rir_name(const Signal& rir);   // "RIR '<id>'"
RirMetrics metrics_of(const Signal& rir);  // its id and rate, nothing measured yet
// Filters for one (rate, band centres), designed once per thread: designs cost microseconds each
// but RIR sets usually share one rate.
const std::vector<SosFilter>& band_filters(double fs, const std::vector<double>& centers);
// The single-number values: mean of the 500 Hz and 1 kHz bands, NaN (with a reason) otherwise.
void set_mid_band_values(RirMetrics* m);
double energy_sum(const std::vector<float>& h, size_t begin, size_t end);

// Per-thread buffers reused from one RIR to the next (both definitions): a 1 s RIR needs a few MB
// of scratch, and fresh allocations of that size cost page faults on every RIR.
struct MetricsWorkspace {
  std::vector<std::vector<double>> bands;  // band outputs (irstats)
  std::vector<double> energy;              // broadband squared samples from the onset
  std::vector<double> tail;                // backward sums of the broadband energy
  BankEnergies band_energies;              // each band's squared samples and their backward sums (iso)
  std::vector<double> db;                  // EDC in dB over the fit ranges
};
MetricsWorkspace& metrics_workspace();

}  // namespace tsrir::metrics_detail

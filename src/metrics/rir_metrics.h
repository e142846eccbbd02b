// Acoustic parameters of one room impulse response: Schroeder decay, T20/T30/EDT per octave band,
// T60, DRR and C50, under one of two definitions:
//   iso     -- ISO 3382-1: onset 20 dB below the peak, octave bands (ANSI order-3 Butterworth)
//              filtered time-reversed (no filter ringing added to the decay; each band's EDC
//              starts at its own onset when that is earlier, so the direct sound the reversed
//              filter smears forward is counted), noise floor handled as Lundeby truncation +
//              compensation with the noise power subtracted (Chu), T30 from -5..-35 dB (T20 from
//              -5..-25 dB when the dynamic range is too small for T30; ISO's 10 dB margin: T30
//              needs 45 dB peak-to-noise, T20 35 dB, EDT 20 dB), EDT from 0..-10 dB;
//              T60 = mean T30 of the 500 Hz and 1 kHz bands. DRR and C50 use the same
//              noise-compensated broadband decay for their late energy.
//   irstats -- exactly what the TS-RIR paper's Table 1 used (IoSR irStats, docs/reference/spec-digest.md §1.2):
//              broadband peak as t0, causal 3rd-order ANSI Butterworth octaves, direct 0..-60 dB fit
//              on the raw EDC, DRR with +-2.5 ms around the peak, CTE (= C50) from 2.5 ms before the
//              peak to 50 ms after.
// Values that cannot be measured are NaN, with a line in `warnings` saying why; never guessed.
// metric_columns.h declares each single-number parameter (unit, definition per convention, output).
#pragma once
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "io/signal.h"
#include "util/options.h"

namespace tsrir {

enum class MetricsDefinition { kIso, kIrstats };
// "iso" | "irstats"; anything else throws Error.
const Choices<MetricsDefinition>& metrics_definition_choices();  // "iso" | "irstats"
MetricsDefinition parse_metrics_definition(const std::string& name);
std::string metrics_definition_name(MetricsDefinition definition);

struct MetricsOptions {
  MetricsDefinition definition = MetricsDefinition::kIso;
  // iso only: noise subtraction, Lundeby truncation at the noise intersection and compensation
  // of the cut tail. Off: the EDC integrates the whole file (noise included), as irstats does.
  bool lundeby = true;
  // Direct-sound window for DRR, around the direct-sound peak (largest |h|): [peak - pre, peak + post].
  // Everything after it is reverberant. irstats fixes both to round(2.5 ms * fs) samples.
  double direct_pre_ms = 2.5;
  double direct_post_ms = 2.5;
  // Early/late split for clarity (C50): iso measures from the onset; irstats from the peak.
  double clarity_time_ms = 50.0;
  // iso onset: first sample whose energy is within this many dB of the peak energy.
  double onset_threshold_db = 20.0;

  void Register(OptionsItf* opts);
};

constexpr double kMetricsNaN = std::numeric_limits<double>::quiet_NaN();

struct BandMetrics {
  double center_hz = 0.0;
  double t20_s = kMetricsNaN;
  double t30_s = kMetricsNaN;
  double edt_s = kMetricsNaN;
  // The definition's reverberation time for this band: iso = T30 (T20 when T30 is unmeasurable,
  // with a warning); irstats = the direct 0..-60 dB fit.
  double rt_s = kMetricsNaN;
  // Band energy relative to the broadband energy of the whole RIR, dB.
  double level_db = kMetricsNaN;
  // Peak-to-noise ratio of the band's decay (iso with Lundeby; NaN otherwise), dB.
  double dynamic_range_db = kMetricsNaN;
};

struct RirMetrics {
  std::string id;
  double sample_rate_hz = 0.0;
  double t60_s = kMetricsNaN;   // mean rt_s of the 500 Hz and 1 kHz bands
  double edt_s = kMetricsNaN;   // mean EDT of the 500 Hz and 1 kHz bands
  double drr_db = kMetricsNaN;
  double c50_db = kMetricsNaN;  // the paper's CTE
  double d50_percent = kMetricsNaN;  // definition (Deutlichkeit), ISO 3382-1
  double c80_db = kMetricsNaN;       // clarity with an 80 ms limit, ISO 3382-1
  size_t onset_sample = 0;      // iso onset, or the irstats peak
  size_t peak_sample = 0;       // largest |h|
  BandMetrics broadband;        // center_hz = 0
  std::vector<BandMetrics> bands;  // ascending centre frequency
  std::vector<std::string> warnings;

  const BandMetrics* band(double center_hz) const;  // nullptr if not measured
};

// Octave centres (of kOctaveCentersHz) measured at this rate: iso keeps bands whose upper edge
// lies below Nyquist; irstats keeps fs/200 < fc < fs/5 (at 16 kHz: 125..2000 Hz).
std::vector<double> metrics_band_centers_hz(double sample_rate_hz, MetricsDefinition definition);

// Schroeder backward integration E(n) = sum_{k >= n} h[k]^2 of h[begin, end), in dB relative to
// E(begin). Samples where E = 0 come out as -inf.
std::vector<double> schroeder_decay_db(const std::vector<float>& h, size_t begin = 0,
                                       size_t end = std::numeric_limits<size_t>::max());

// Measures one RIR. Throws Error naming signal.id for input that cannot be measured at all: empty,
// NaN/Inf samples, silence, non-positive rate, or too short for the clarity window. Per-band
// failures (insufficient dynamic range) give NaN plus a warning instead.
RirMetrics measure_rir(const Signal& rir, const MetricsOptions& options = {});

}  // namespace tsrir

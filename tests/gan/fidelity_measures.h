// Measures of the TS-RIRGAN translation-fidelity suite (issues 17 and 34): does a translated RIR
// carry the real domain's hidden effect while keeping ITS OWN input's acoustics where that effect
// does not act? Written here, independently of src/metrics and src/gan (zero-phase Butterworth
// bands, Schroeder decay, log-envelope correlation), so that the test and bench/gan's seed sweep
// share one definition.
//
// Per RIR, eight parameters in three bands: low (< 200 Hz), mid (500-1000 Hz: below every hidden
// effect above 500 Hz, whose crossovers are at 2-3 kHz) and high (> 4 kHz: above them):
//   lf_db        energy below 200 Hz re the mid band's (the low-frequency effects);
//   tilt_db      the high band's energy re the mid band's;
//   t60_*_s      the band's decay after the direct sound (Schroeder, -5..-25 dB fit x 3);
//   drr_*_db     the band's energy in [onset - 1 ms, onset + 2.5 ms] re the rest;
//   early_*_db   the band's energy in [onset + 2.5 ms, onset + 50 ms] re what follows.
// For each hidden-effect kind, fidelity_plan() says which parameters it MOVES (each checked on its
// own: the translations' mean must gain 0.5-1.5 of the real-synthetic gap) and which it leaves
// alone (each checked to stay its own input's: rank correlation input -> output where the
// parameter varies from RIR to RIR, and the median error).
#pragma once
#include <limits>
#include <string>
#include <vector>

#include "fidelity_domains.h"
#include "io/signal.h"

namespace tsrir_test {

enum class FidelityParameter { kLowFrequency, kTilt, kT60Mid, kT60High, kDrrMid, kDrrHigh, kEarlyMid, kEarlyHigh };
constexpr int kNumFidelityParameters = 8;
const char* parameter_name(FidelityParameter p);

struct RirFidelityMeasures {
  double onset_ms = 0;  // first sample within 20 dB of the peak
  double value[kNumFidelityParameters] = {};  // NaN where unmeasurable (a T60 whose decay is too short)
  double operator[](FidelityParameter p) const { return value[int(p)]; }
};
RirFidelityMeasures measure_fidelity_rir(const tsrir::Signal& rir);

struct FidelityPlan {
  std::vector<FidelityParameter> moved, kept;
};
FidelityPlan fidelity_plan(HiddenEffect kind);

// The early fine structure: above 500 Hz, log energy in 1 ms frames from start + 2 ms to
// start + 200 ms, with its least-squares line removed (the decay), so that what is left is the
// RIR's own pattern of reflections and noise. `start_sample` is the INPUT's onset for a
// translated RIR, so that an output and its input are compared over the same samples.
std::vector<double> early_log_envelope(const tsrir::Signal& rir, long start_sample);
// What the translation added below 200 Hz: over 200 ms from the input's onset `start_sample`, the
// output's zero-phase low-passed part less its projection on the input's (so that a level change
// adds nothing). *relative_db (if given): its energy re the input's low band's over the same samples.
std::vector<double> low_band_addition(const tsrir::Signal& input, const tsrir::Signal& output, long start_sample,
                                      double* relative_db = nullptr);
double pearson(const std::vector<double>& a, const std::vector<double>& b);
double spearman(const std::vector<double>& a, const std::vector<double>& b);

// A kept parameter's bounds: rank correlation input -> output at least min_spearman (not checked
// where it is NaN: parameters that hardly vary between the suite's RIRs, whose ranks are noise) and
// median |output - input| at most max_median_error (dB; for T60s relative: |out/in - 1|).
struct KeepBound {
  double min_spearman;
  double max_median_error;
};
constexpr double kNoRank = std::numeric_limits<double>::quiet_NaN();

// Bounds of the suite. The moved and onset bounds, the envelope and the additions' bound are
// issue 17's (fixed before any training was measured against them); the kept parameters' bounds
// are checked against held-out draws of seeds the tests never use (`gan-fidelity-suite
// --calibrate`: the oracle translation's measurement noise must pass them, the wrong-band
// translations must not; bench/RESULTS.md, "TS-RIRGAN translation fidelity, issue 34").
struct FidelityBounds {
  double min_moved = 0.5, max_moved = 1.5;      // each moved parameter, fraction of the real-synthetic gap
  KeepBound keep[kNumFidelityParameters] = {
      {kNoRank, 1.0},   // lf_db
      {kNoRank, 1.0},   // tilt_db
      {0.8, 0.15},     // t60_mid_s
      {0.8, 0.15},     // t60_high_s
      {0.7, 1.5},      // drr_mid_db
      {0.7, 1.5},      // drr_high_db
      {0.7, 1.5},      // early_mid_db
      {0.7, 1.5},      // early_high_db
  };
  double max_onset_error_ms = 1.0, min_onset_fraction = 0.9;  // >= 90% of RIRs within 1 ms
  double min_own_minus_other = 0.3;             // mean own-input minus other-input correlation
  // What a translation ADDS below 200 Hz must differ from RIR to RIR, as the low-frequency effects
  // do (random frequencies and phases: mean pairwise correlation ~0), not be one template pasted at
  // every onset (~1). Added after the first configurations were seen pasting one (0.77) while the
  // other measures could not tell. The bound is halfway between the two.
  double max_added_correlation = 0.5;
  // Additions weaker than this (dB re the input's own low band over the same 200 ms) are left out
  // of that mean (issue 34; 0 if none is left).
  double min_added_db = -20.0;
};

struct ParameterReport {
  FidelityParameter parameter = FidelityParameter::kLowFrequency;
  bool moved_check = false;  // moved by the kind (else: kept, if in the plan's kept list)
  bool kept_check = false;
  // Means (T60s: geometric means, and `moved` on their logarithms): of the reference sets, of the
  // inputs and of their translations; moved = (translated - input) / (real - synthetic).
  double synthetic_mean = 0, real_mean = 0, input_mean = 0, translated_mean = 0, moved = 0;
  double spearman = 0, median_error = 0;  // input -> output
};

struct FidelityReport {
  HiddenEffect kind = HiddenEffect::kLowFrequency;
  int count = 0;
  std::vector<ParameterReport> parameters;  // every parameter, in FidelityParameter order
  double onset_fraction_within = 0, onset_max_error_ms = 0;
  double own_correlation = 0, other_correlation = 0;
  double added_correlation = 0;  // mean over pairs of the below-200 Hz additions' correlation
  int unmeasurable_t60 = 0;
  std::vector<std::string> failures;  // empty = passed
  std::string per_rir;                // one line per translated RIR: input -> output measures
  bool passed() const { return failures.empty(); }
  std::string summary() const;        // one line, every number
  const ParameterReport& operator[](FidelityParameter p) const { return parameters[size_t(p)]; }
};

// The gap a translation must cross: the mean parameters of large held-out synthetic and real sets
// (not the inputs: the inputs' own mean, against a real set as small as theirs, would put the
// sampling noise of two small means into every "moved").
struct FidelityReference {
  std::vector<tsrir::Signal> synthetic, real;
};

// `inputs[i]` was translated into `outputs[i]`; `reference` is of the real domain of `kind`.
FidelityReport evaluate_fidelity(HiddenEffect kind, const std::vector<tsrir::Signal>& inputs,
                                 const std::vector<tsrir::Signal>& outputs, const FidelityReference& reference,
                                 const FidelityBounds& bounds = FidelityBounds());

}  // namespace tsrir_test

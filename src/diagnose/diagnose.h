// rir-diagnose: simulate the measured set-ups with the toolkit's model, show where the simulation
// departs from the measurements, name the physical cause (the effect registry, effect.h), extend
// the model with it (sim/extension_components.h), and measure the gain on RIRs the fit did not see.
#pragma once
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "diagnose/diagnose_options.h"
#include "diagnose/effect.h"
#include "io/signal.h"
#include "sim/room.h"

namespace tsrir::diagnose {

// A held-out gain counts when the paired test gives p below this (and the gain is positive).
constexpr double kGainAlpha = kDecision.gain_alpha;


// A paired comparison of two models' per-RIR errors over the held-out RIRs: gain = mean of
// (error of the first - error of the second); a gain counts at p < kGainAlpha.
struct PairedGain {
  double gain = 0.0;
  double gain_se = NAN;  // standard error of the paired per-RIR difference
  double t = 0.0;        // gain / gain_se
  double p = 1.0;        // two-sided p of t at n - 1 degrees of freedom
  size_t n = 0;
  bool better() const { return gain > 0.0 && p < kGainAlpha; }  // the second model is significantly better
  bool worse() const { return gain < 0.0 && p < kGainAlpha; }   // ... significantly worse
};

struct MetricGain {
  std::string name;
  std::string unit;
  double baseline = 0.0;     // mean absolute error over the eval ids: the baseline model
  double refitted = 0.0;     // the baseline with every band's absorption refitted to the measured decay
  double extended = 0.0;     // the extended model
  double gain = 0.0;         // baseline - extended
  double gain_se = 0.0;      // standard error of the paired per-RIR difference
  double t = 0.0;            // paired t statistic (gain / gain_se)
  double p = 1.0;            // two-sided p of t at n - 1 degrees of freedom
  size_t n = 0;
  PairedGain vs_refitted;    // refitted - extended: what the extension adds beyond the band refit
};

// What one detected effect adds beyond the band refit (the cheap fix): the refitted baseline plus
// this effect's extension alone, against the refitted baseline, on the effect's gain metric; and
// the metrics it makes significantly worse there.
struct EffectGain {
  std::string effect;
  std::string metric, unit;
  double refitted = 0.0, with_effect = 0.0;  // mean absolute errors
  PairedGain gain;
  std::vector<std::string> worse;
};

// A metric the extended model makes significantly worse than the baseline on the held-out RIRs,
// and the detected effects whose extension does it (the extended model without it is
// significantly better on that metric).
struct Regression {
  std::string metric, unit;
  double baseline = 0.0, extended = 0.0;
  PairedGain vs_baseline;
  std::vector<std::string> caused_by;
};

struct ExampleCurves {
  std::string id;
  std::vector<double> edc_meas_db, edc_base_db, edc_ext_db;       // 5 ms steps from the onset
  std::vector<double> lf_meas_db, lf_base_db, lf_ext_db;          // 1 Hz grid
  std::vector<double> mode_freqs_hz;
  Signal measured, baseline, extended;
};

struct Diagnosis {
  const EffectRegistry* registry = nullptr;  // the catalog the findings follow
  std::vector<Finding> findings;       // registry (catalog) order
  // What the catalog leaves unexplained (unexplained.h): effect "unexplained", detected when a
  // view departs after the extensions are fitted; its evidence says which, where and how far.
  Finding unexplained;
  std::string baseline_model;
  std::map<std::string, std::string> extended_model_by_room;
  std::map<std::string, std::string> refitted_model_by_room;  // the band refit, per room (room_group)
  std::vector<MetricGain> gains;       // gain_metrics() order
  std::vector<EffectGain> effect_gains;  // detected effects other than the band refit's own, registry order
  std::vector<Regression> regressions;
  std::vector<std::string> fit_ids, eval_ids;
  std::vector<ExampleCurves> examples;
  double sample_rate_hz = 0.0;
  size_t num_rirs = 0;
  double seconds = 0.0;
  // Onset scatter for the report: stated time of flight, measured and simulated onsets (ms).
  std::vector<double> flight_ms, onset_meas_ms, onset_sim_ms;
};

// Measured RIRs (any rate; resampled) paired with their stated set-ups by id. Every measured
// id needs a room; rooms without a measurement are ignored. `measured_where` (optional, one per
// measured RIR: where it was listed) prefixes the error of a measured RIR that cannot be
// analysed (silent, too short).
Diagnosis diagnose_set(const std::vector<sim::RoomSpec>& rooms, const std::vector<Signal>& measured,
                       const DiagnoseOptions& options, const std::vector<std::string>& measured_where = {},
                       const EffectRegistry& registry = effect_registry());

// findings.json, report.html and extended_models (<room-id> <model spec> per line) into out_dir
// (replaced atomically); returns the stdout summary.
std::string write_diagnosis(const Diagnosis& diagnosis, const std::string& out_dir, const std::string& command_line);

std::string diagnosis_summary(const Diagnosis& diagnosis);
void write_findings_json(const Diagnosis& diagnosis, std::ostream& out);

}  // namespace tsrir::diagnose

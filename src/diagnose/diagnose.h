// rir-diagnose: simulate the measured set-ups with the toolkit's model, show where the simulation
// departs from the measurements, name the physical cause (the effect registry, effect.h), extend
// the model with it (sim/extension_components.h), and measure the gain on RIRs the fit did not see.
#pragma once
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

struct MetricGain {
  std::string name;
  std::string unit;
  double baseline = 0.0;     // mean absolute error over the eval ids
  double extended = 0.0;
  double gain = 0.0;         // baseline - extended
  double gain_se = 0.0;      // standard error of the paired per-RIR difference
  double t = 0.0;            // paired t statistic (gain / gain_se)
  double p = 1.0;            // two-sided p of t at n - 1 degrees of freedom
  size_t n = 0;
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
  std::string baseline_model;
  std::map<std::string, std::string> extended_model_by_room;
  std::vector<MetricGain> gains;
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

// The EQ over whole RIR sets (scp, rir_list or a single file; see io/rir_set.h): measure the
// relative gains of a set, fit a model on a real set, and equalize a set into an output dir.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "eq/eq_model.h"
#include "eq/equalize.h"
#include "io/audio_io.h"

namespace tsrir {

struct RirGains {
  std::string id;
  RelativeGainsDb gains_db{};
};

struct GainStats {
  size_t count = 0;
  RelativeGainsDb mean_db{};
  RelativeGainsDb std_db{};   // sample standard deviation (n - 1)
};
GainStats summarize_gains(const std::vector<RelativeGainsDb>& gains);
// "point_hz  mean  std" table (several columns of stats side by side), for logs and docs.
std::string format_gain_stats(const std::vector<std::string>& names, const std::vector<GainStats>& stats);

struct MeasureSetOptions {
  GainMethod gain_method = GainMethod::kOctave;
  // > 0: RIRs at other rates are resampled to it (the count is logged); 0: every RIR must have
  // the rate of the first one, else an error naming the RIR.
  double sample_rate_hz = 0.0;
  int num_threads = 1;
};

// Gains of every RIR in `set_path`, in listing order. *rate_hz receives the common rate.
std::vector<RirGains> measure_rir_set(const std::string& set_path, const MeasureSetOptions& options, double* rate_hz);

// '<id> <7 gains>' lines in listing order (atomic; "-" = stdout).
void save_gains_table(const std::vector<RirGains>& rows, const std::string& path);

struct FitSetOptions {
  MeasureSetOptions measure;
  GmmFitOptions mixture;
};
EqModel fit_eq_model_on_set(const std::string& real_set_path, const FitSetOptions& options);

struct ApplySetOptions {
  EqApplyOptions eq;            // gain_method is taken from the model
  uint64_t seed = 0;            // target draws: one stream per RIR id (independent of threads)
  bool resample = false;        // inputs at another rate than the model: resample (else error)
  int num_threads = 1;
  SampleFormat format = SampleFormat::kInt16;
  std::string report_path;      // optional per-RIR table: before, target, achieved gains
};

struct ApplySetSummary {
  GainStats before, target, achieved;   // achieved = measured on the written RIRs
  size_t clamped = 0;
};

// Equalizes every RIR of `in_set_path` to draws from `model` and writes <out_dir>/<id>.wav,
// rir.scp and rir_list (same ids). Nothing appears under out_dir unless every RIR succeeded.
ApplySetSummary equalize_rir_set(const EqModel& model, const std::string& in_set_path, const std::string& out_dir,
                                 const ApplySetOptions& options);

}  // namespace tsrir

// rir-perturb over a whole RIR set (scp, rir_list or one file; io/rir_set.h): every RIR perturbed
// as rir_perturb.h describes, written with its id and room id into a toolkit-owned output dir
// (<out>/<id>.wav, rir.scp, rir_list), and the set's T60, DRR and C50 measured before and after
// (rir-metrics' ISO definitions) so that the log shows what the control changed.
#pragma once
#include <string>

#include "io/audio_io.h"
#include "perturb/rir_perturb.h"
#include "util/options.h"

namespace tsrir {

struct PerturbSetOptions {
  RirPerturbation perturbation;
  Seed seed = 0;
  int num_threads = 1;
  SampleFormat format = SampleFormat::kInt16;

  void Register(OptionsItf* opts);
};

// Means over the set (NaN where no RIR could be measured).
struct PerturbSetSummary {
  size_t count = 0;
  size_t rescaled = 0;    // RIRs scaled down to fit 16-bit output
  double t60_before_s = 0, t60_after_s = 0;
  double drr_before_db = 0, drr_after_db = 0;
  double c50_before_db = 0, c50_after_db = 0;
};

PerturbSetSummary perturb_rir_set(const std::string& in_set_path, const std::string& out_dir,
                                  const PerturbSetOptions& options);

// "T60 0.94 -> 0.31 s, DRR ... (n RIRs)" for the log.
std::string format_perturb_summary(const PerturbSetSummary& summary);

}  // namespace tsrir

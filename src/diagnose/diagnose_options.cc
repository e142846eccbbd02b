#include "diagnose/diagnose_options.h"

#include <cmath>

#include "io/common_options.h"
#include "util/error.h"

namespace tsrir::diagnose {

void DiagnoseOptions::Register(OptionsItf* opts) {
  opts->Register("sample-rate", &sample_rate_hz, "analysis sample rate, Hz (measured RIRs are resampled)");
  opts->RegisterAlias("fs", "sample-rate");
  opts->Register("model", &baseline_model, "baseline model (rir-simulate --model syntax)");
  CommonOptions(opts)
      .seed(&seed, "the simulations (seed, seed+1 for the null calibration, seed+2 for evaluation)")
      .threads(&num_threads, "simulations and fits run in parallel");
}

void DiagnoseOptions::Validate() const {
  if (num_threads < 1) throw Error("--num-threads must be at least 1");
  if (!(sample_rate_hz > 0.0 && std::isfinite(sample_rate_hz))) throw Error("--sample-rate must be a positive rate in Hz");
}

}  // namespace tsrir::diagnose

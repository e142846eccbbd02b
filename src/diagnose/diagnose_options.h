// rir-diagnose's options, registered by the library (util/options.h): the program only registers
// DiagnoseOptions, parses and calls diagnose_set (diagnose.h).
#pragma once
#include <cstddef>
#include <string>

#include "util/options.h"

namespace tsrir::diagnose {

struct DiagnoseOptions {
  double sample_rate_hz = 16000.0;   // measured RIRs are resampled to this rate
  std::string baseline_model = "gas";
  Seed seed = 1;                     // seeds seed (A), seed+1 (B, null calibration), seed+2 (evaluation)
  int num_threads = 2;
  size_t max_scattering_fit_rirs = 24;  // RIRs rendered per scattering value when refitting it
  // Library callers that need only the decisions (bench/diagnose's sweeps count detections) turn
  // off the held-out evaluation (gain table, held-out checks, second baseline); not an option of
  // the program, which always judges its findings.
  bool held_out_evaluation = true;

  // --sample-rate (alias --fs), --model, --seed (alias --random-seed), --num-threads.
  void Register(OptionsItf* opts);
  // Throws Error for values no diagnosis can run with (the option's name in the message).
  void Validate() const;
};

}  // namespace tsrir::diagnose

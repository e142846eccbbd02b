// rir-eq's options, registered by the library (util/options.h) and turned into the set-level
// option structs of eq_set.h with their validation here, so the program only registers and reads.
// One struct serves the four modes; each registers the options it uses:
//   fit     measure + fit + --seed (EM initialisation) + --num-threads
//   apply   apply + --seed (target draws) + --num-threads
//   gains   measure + --num-threads
//   one-shot (rir-eq --real=...)  all of them, --real and --model-out
#pragma once
#include <string>

#include "eq/eq_set.h"
#include "util/options.h"

namespace tsrir {

enum class EqProgramMode { kFit, kApply, kGains, kOneShot };

// The distribution fitted to the real gains: the paper's independent Gaussian per sample point, or
// a Gaussian mixture over the 7-D gain vectors.
enum class EqModelKind { kIndependent, kMixture };

struct RirEqOptions {
  // measuring (fit, gains)
  GainMethod gain_method = GainMethod::kOctave;
  double sample_rate_hz = 16000.0;
  // fitting
  EqModelKind model = EqModelKind::kIndependent;
  int components = 1;
  CovarianceType covariance = CovarianceType::kDiagonal;
  int em_restarts = 4;
  // applying: taps, window, refinements, node bounds and level live in EqApplyOptions
  EqApplyOptions eq;
  SampleFormat format = SampleFormat::kInt16;
  bool resample = false;
  std::string report;
  // shared
  Seed seed = 0;
  int num_threads = 1;
  // one-shot
  std::string real;
  std::string model_out;

  void Register(OptionsItf* opts, EqProgramMode mode);

  // The set-level options, validated (Error naming the option on a bad combination or value).
  MeasureSetOptions measure_options() const;
  FitSetOptions fit_options() const;
  ApplySetOptions apply_options() const;
};

}  // namespace tsrir

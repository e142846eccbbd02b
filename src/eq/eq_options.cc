#include "eq/eq_options.h"

#include "io/common_options.h"
#include "util/error.h"

namespace tsrir {
namespace {

void register_measure(RirEqOptions* o, OptionsItf* opts, bool fitting) {
  opts->RegisterEnum("gain-method", &o->gain_method, gain_method_choices(),
                     "How a gain is read off the spectrum: octave (mean power over the octave band, clipped at "
                     "Nyquist: 8 kHz at fs=16 kHz is [5657, 8000] Hz), smooth (1/3 octave) or bin (nearest bin)");
  opts->Register("sample-rate", &o->sample_rate_hz,
                 fitting ? "Resample real RIRs at other rates to this rate (logged); 0 = all RIRs must share one rate"
                         : "Resample RIRs at other rates to this rate (logged); 0 = all RIRs must share one rate");
  opts->RegisterAlias("fs", "sample-rate");
}

void register_fit(RirEqOptions* o, OptionsItf* opts) {
  opts->RegisterEnum("model", &o->model, {{"indep", EqModelKind::kIndependent}, {"gmm", EqModelKind::kMixture}},
                     "indep: an independent Gaussian per point (the paper's reading); gmm: Gaussian mixture over the "
                     "7-D gain vectors (EM)");
  opts->Register("components", &o->components, "Mixture components (--model=gmm)");
  opts->RegisterEnum("covariance", &o->covariance, covariance_type_choices(), "Mixture covariance (--model=gmm)");
  opts->Register("em-restarts", &o->em_restarts, "EM runs from different seeds; the best likelihood wins");
}

void register_apply(RirEqOptions* o, OptionsItf* opts) {
  opts->Register("taps", &o->eq.fir.taps,
                 "EQ FIR length, odd (type I linear phase); 0 = 2049 at 16 kHz scaled with the rate (128 ms)");
  opts->RegisterEnum("window", &o->eq.fir.window, fir_window_choices(), "FIR design window");
  opts->Register("refine-iterations", &o->eq.refine_iterations,
                 "Newton refinements of the node gains so the filtered RIR's gains hit the target (0 = one design)");
  opts->Register("max-boost-db", &o->eq.max_boost_db, "Largest boost of any EQ node (dB); boosts raise noise");
  opts->Register("max-cut-db", &o->eq.max_cut_db, "Largest cut of any EQ node (dB)");
  opts->RegisterEnum("level", &o->eq.level, eq_level_choices(),
                     "Output level: peak (keep max |x|), energy (keep sum x^2) or none");
  CommonOptions(opts).audio_format(&o->format);
  opts->Register("resample", &o->resample, "Resample inputs whose rate differs from the model's (else an error)");
  opts->Register("report", &o->report, "Write per-RIR gains (before, target, achieved) to this file");
}

}  // namespace

void RirEqOptions::Register(OptionsItf* opts, EqProgramMode mode) {
  switch (mode) {
    case EqProgramMode::kFit:
      register_measure(this, opts, true);
      register_fit(this, opts);
      CommonOptions(opts).seed(&seed, "the EM initialisation (--model=gmm)");
      break;
    case EqProgramMode::kApply:
      register_apply(this, opts);
      CommonOptions(opts).seed(&seed, "the target-gain draws (one stream per RIR id)");
      break;
    case EqProgramMode::kGains:
      register_measure(this, opts, false);
      break;
    case EqProgramMode::kOneShot:
      opts->Register("real", &real, "Real RIR set to fit the model on (required in this mode)");
      opts->Register("model-out", &model_out, "Also save the fitted model here");
      register_measure(this, opts, true);
      register_fit(this, opts);
      register_apply(this, opts);
      CommonOptions(opts).seed(&seed, "the EM initialisation and of the target-gain draws");
      break;
  }
  CommonOptions(opts).threads(&num_threads, "RIRs are processed in parallel");
}

MeasureSetOptions RirEqOptions::measure_options() const {
  MeasureSetOptions o;
  o.gain_method = gain_method;
  o.sample_rate_hz = sample_rate_hz;
  o.num_threads = num_threads;
  return o;
}

FitSetOptions RirEqOptions::fit_options() const {
  FitSetOptions o;
  o.measure = measure_options();
  if (model == EqModelKind::kIndependent) {
    if (components != 1 || covariance != CovarianceType::kDiagonal) {
      throw Error("--components and --covariance apply to --model=gmm only");
    }
  }
  if (components < 1) throw Error("--components must be >= 1");
  o.mixture.num_components = components;
  o.mixture.covariance_type = covariance;
  o.mixture.seed = seed;
  o.mixture.restarts = em_restarts;
  return o;
}

ApplySetOptions RirEqOptions::apply_options() const {
  if (eq.fir.taps != 0 && (eq.fir.taps < 3 || eq.fir.taps % 2 == 0)) {
    throw Error("--taps must be 0 (automatic) or odd and >= 3, got " + std::to_string(eq.fir.taps));
  }
  if (eq.refine_iterations < 0) throw Error("--refine-iterations must be >= 0");
  if (!(eq.max_boost_db > 0) || !(eq.max_cut_db > 0)) throw Error("--max-boost-db and --max-cut-db must be positive");
  ApplySetOptions o;
  o.seed = seed;
  o.eq = eq;
  o.format = format;
  o.resample = resample;
  o.num_threads = num_threads;
  o.report_path = report;
  return o;
}

}  // namespace tsrir

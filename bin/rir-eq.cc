// rir-eq: real-world sub-band room equalization of RIR sets (TS-RIR sec. 3.2).
#include <malloc.h>

#include <iostream>
#include <string>

#include "eq/eq_set.h"
#include "io/owned_output.h"
#include "util/cli.h"
#include "util/error.h"

using namespace tsrir;

namespace {

const char* kUsage =
    "rir-eq: sub-band room equalization. Fits the distribution of real RIRs' relative gains at\n"
    "62.5, 125, 250, 500, 2000, 4000, 8000 Hz (dB re 1000 Hz) and equalizes other RIRs (e.g.\n"
    "simulated ones) to gains drawn from it with linear-phase FIRs; the direct sound stays in place\n"
    "and length and level convention are kept. Sets are scp files, Kaldi rir_lists or single files.\n"
    "\n"
    "Usage:\n"
    "  rir-eq fit [options] <real-rir-scp> <model-out>\n"
    "  rir-eq apply [options] <model> <in-rir-scp> <out-dir>\n"
    "  rir-eq [options] --real=<real-rir-scp> <in-rir-scp> <out-dir>      (fit + apply)\n"
    "  rir-eq gains [options] <rir-scp> <gains-out|->                     (measure only)\n"
    "apply writes <out-dir>/<id>.wav, rir.scp and rir_list with the input ids.\n"
    "\n"
    "Examples:\n"
    "  rir-eq fit --sample-rate=16000 --model=gmm --components=2 --covariance=full real/rir.scp eq.model\n"
    "  rir-eq apply --seed=7 eq.model sim/rir.scp sim_eq\n"
    "  rir-eq --real=real/rir.scp --seed=7 sim/rir.scp sim_eq\n"
    "  rir-eq gains sim_eq/rir.scp -\n"
    "Run 'rir-eq <fit|apply|gains> --help' for the options of one mode.\n";

struct Settings {
  // measuring / fitting
  std::string gain_method = "octave";
  double sample_rate_hz = 16000.0;
  std::string model = "indep";
  int components = 1;
  std::string covariance = "diag";
  int em_restarts = 4;
  // applying
  int seed = 0;
  int taps = 0;
  std::string window = "hamming";
  int refine_iterations = 3;
  double max_boost_db = 24.0;
  double max_cut_db = 60.0;
  std::string level = "peak";
  std::string sample_format = "int16";
  bool resample = false;
  std::string report;
  // both
  int num_threads = 1;
  // one-shot
  std::string real;
  std::string model_out;
};

void add_measure_options(CommandLine& cl, Settings& s, bool fitting) {
  cl.option("gain-method", &s.gain_method,
            "How a gain is read off the spectrum: octave (mean power over the octave band, clipped at "
            "Nyquist: 8 kHz at fs=16 kHz is [5657, 8000] Hz), smooth (1/3 octave) or bin (nearest bin)");
  cl.option("sample-rate", &s.sample_rate_hz,
            fitting ? "Resample real RIRs at other rates to this rate (logged); 0 = all RIRs must share one rate"
                    : "Resample RIRs at other rates to this rate (logged); 0 = all RIRs must share one rate");
}

void add_fit_options(CommandLine& cl, Settings& s) {
  cl.option("model", &s.model,
            "indep: an independent Gaussian per point (the paper's reading); gmm: Gaussian mixture over the "
            "7-D gain vectors (EM)");
  cl.option("components", &s.components, "Mixture components (--model=gmm)");
  cl.option("covariance", &s.covariance, "Mixture covariance: diag or full (--model=gmm)");
  cl.option("em-restarts", &s.em_restarts, "EM runs from different seeds; the best likelihood wins");
}

void add_apply_options(CommandLine& cl, Settings& s) {
  cl.option("taps", &s.taps, "EQ FIR length, odd (type I linear phase); 0 = 2049 at 16 kHz scaled with the rate (128 ms)");
  cl.option("window", &s.window, "FIR design window: hamming, hann or blackman");
  cl.option("refine-iterations", &s.refine_iterations,
            "Newton refinements of the node gains so the filtered RIR's gains hit the target (0 = one design)");
  cl.option("max-boost-db", &s.max_boost_db, "Largest boost of any EQ node (dB); boosts raise noise");
  cl.option("max-cut-db", &s.max_cut_db, "Largest cut of any EQ node (dB)");
  cl.option("level", &s.level, "Output level: peak (keep max |x|), energy (keep sum x^2) or none");
  cl.option("format", &s.sample_format, "Output wav samples: int16 or float");
  cl.flag("resample", &s.resample, "Resample inputs whose rate differs from the model's (else an error)");
  cl.option("report", &s.report, "Write per-RIR gains (before, target, achieved) to this file");
}

GmmFitOptions mixture_options(const Settings& s) {
  GmmFitOptions o;
  if (s.model == "indep") {
    if (s.components != 1 || s.covariance != "diag") {
      throw Error("--components and --covariance apply to --model=gmm only");
    }
    o.num_components = 1;
    o.covariance_type = CovarianceType::kDiagonal;
  } else if (s.model == "gmm") {
    o.num_components = s.components;
    o.covariance_type = parse_covariance_type(s.covariance);
  } else {
    throw Error("unknown --model '" + s.model + "' (expected indep or gmm)");
  }
  if (s.components < 1) throw Error("--components must be >= 1");
  o.seed = static_cast<uint64_t>(s.seed);
  o.restarts = s.em_restarts;
  return o;
}

FitSetOptions fit_options(const Settings& s) {
  FitSetOptions o;
  o.measure.gain_method = parse_gain_method(s.gain_method);
  o.measure.sample_rate_hz = s.sample_rate_hz;
  o.measure.num_threads = s.num_threads;
  o.mixture = mixture_options(s);
  return o;
}

ApplySetOptions apply_options(const Settings& s) {
  ApplySetOptions o;
  o.seed = static_cast<uint64_t>(s.seed);
  o.eq.fir.taps = s.taps;
  o.eq.fir.window = parse_fir_window(s.window);
  if (s.taps != 0 && (s.taps < 3 || s.taps % 2 == 0)) {
    throw Error("--taps must be 0 (automatic) or odd and >= 3, got " + std::to_string(s.taps));
  }
  if (s.refine_iterations < 0) throw Error("--refine-iterations must be >= 0");
  if (!(s.max_boost_db > 0) || !(s.max_cut_db > 0)) throw Error("--max-boost-db and --max-cut-db must be positive");
  o.eq.refine_iterations = s.refine_iterations;
  o.eq.max_boost_db = s.max_boost_db;
  o.eq.max_cut_db = s.max_cut_db;
  o.eq.level = parse_eq_level(s.level);
  o.format = parse_sample_format(s.sample_format);
  o.resample = s.resample;
  o.num_threads = s.num_threads;
  o.report_path = s.report;
  return o;
}

void log_model(const EqModel& m) {
  GainStats st;
  st.count = static_cast<size_t>(m.fitted_rirs);
  st.mean_db = m.mean_db();
  st.std_db = m.std_db();
  log_info("model (" + std::to_string(m.mixture.components.size()) + " component(s), " +
           covariance_type_name(m.mixture.covariance_type) + ", " + std::to_string(m.fitted_rirs) + " RIRs at " +
           std::to_string(static_cast<long>(m.sample_rate_hz)) + " Hz):\n" + format_gain_stats({"model"}, {st}));
}

void log_apply(const ApplySetSummary& s) {
  log_info("equalized " + std::to_string(s.before.count) + " RIRs; relative gains (dB re 1 kHz):\n" +
           format_gain_stats({"before", "target", "achieved"}, {s.before, s.target, s.achieved}));
}

int fit_main(int argc, const char* const* argv) {
  Settings s;
  CommandLine cl("rir-eq fit",
                 "rir-eq fit: measure the relative gains of real RIRs and fit their distribution.\n"
                 "Usage: rir-eq fit [options] <real-rir-scp> <model-out>\n"
                 "Example: rir-eq fit --model=gmm --components=2 --covariance=full real/rir.scp eq.model\n");
  add_measure_options(cl, s, true);
  add_fit_options(cl, s);
  cl.option("seed", &s.seed, "Seed of the EM initialisation (--model=gmm)");
  cl.option("num-threads", &s.num_threads, "Threads");
  const auto args = cl.parse(argc, argv, 2, 2);
  const EqModel model = fit_eq_model_on_set(args[0], fit_options(s));
  save_eq_model(model, args[1]);
  log_model(model);
  return 0;
}

int apply_main(int argc, const char* const* argv) {
  Settings s;
  CommandLine cl("rir-eq apply",
                 "rir-eq apply: equalize RIRs to relative gains drawn from a fitted model.\n"
                 "Usage: rir-eq apply [options] <model> <in-rir-scp> <out-dir>\n"
                 "Example: rir-eq apply --seed=7 --num-threads=4 eq.model sim/rir.scp sim_eq\n");
  add_apply_options(cl, s);
  cl.option("seed", &s.seed, "Seed of the target-gain draws (one stream per RIR id)");
  cl.option("num-threads", &s.num_threads, "Threads");
  register_output_options(&cl);
  const auto args = cl.parse(argc, argv, 3, 3);
  const ApplySetOptions options = apply_options(s);
  const EqModel model = load_eq_model(args[0]);
  log_apply(equalize_rir_set(model, args[1], args[2], options));
  return 0;
}

int gains_main(int argc, const char* const* argv) {
  Settings s;
  CommandLine cl("rir-eq gains",
                 "rir-eq gains: write each RIR's relative gains (dB re 1000 Hz) at 62.5 ... 8000 Hz as\n"
                 "'<id> <7 values>' lines and log their per-point mean and standard deviation.\n"
                 "Usage: rir-eq gains [options] <rir-scp> <gains-out|->\n"
                 "Example: rir-eq gains --sample-rate=16000 real/rir.scp real_gains.txt\n");
  add_measure_options(cl, s, false);
  cl.option("num-threads", &s.num_threads, "Threads");
  const auto args = cl.parse(argc, argv, 2, 2);
  MeasureSetOptions o;
  o.gain_method = parse_gain_method(s.gain_method);
  o.sample_rate_hz = s.sample_rate_hz;
  o.num_threads = s.num_threads;
  double rate = 0;
  const std::vector<RirGains> rows = measure_rir_set(args[0], o, &rate);
  save_gains_table(rows, args[1]);
  std::vector<RelativeGainsDb> all;
  for (const RirGains& r : rows) all.push_back(r.gains_db);
  log_info(std::to_string(rows.size()) + " RIRs at " + std::to_string(static_cast<long>(rate)) +
           " Hz, relative gains (dB re 1 kHz):\n" + format_gain_stats({args[0]}, {summarize_gains(all)}));
  return 0;
}

int one_shot_main(int argc, const char* const* argv) {
  Settings s;
  CommandLine cl("rir-eq", kUsage);
  cl.option("real", &s.real, "Real RIR set to fit the model on (required in this mode)");
  cl.option("model-out", &s.model_out, "Also save the fitted model here");
  add_measure_options(cl, s, true);
  add_fit_options(cl, s);
  add_apply_options(cl, s);
  cl.option("seed", &s.seed, "Seed of the EM initialisation and of the target-gain draws");
  cl.option("num-threads", &s.num_threads, "Threads");
  register_output_options(&cl);
  const auto args = cl.parse(argc, argv, 2, 2);
  if (s.real.empty()) throw Error("--real=<real-rir-scp> is required (or use 'rir-eq fit' / 'rir-eq apply')\n\n" + cl.usage_text());
  const ApplySetOptions options = apply_options(s);
  const EqModel model = fit_eq_model_on_set(s.real, fit_options(s));
  log_model(model);
  if (!s.model_out.empty()) save_eq_model(model, s.model_out);
  log_apply(equalize_rir_set(model, args[0], args[1], options));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Every RIR allocates and frees a few spectra of ~64-128 kB; keeping freed memory in the heap
  // instead of unmapping it removed ~0.5 ms of page-fault time per RIR (bench/eq).
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  const std::string mode = argc > 1 ? argv[1] : "";
  const std::string program = mode == "fit" || mode == "apply" || mode == "gains" ? "rir-eq " + mode : "rir-eq";
  return run_program(program, [&]() {
    if (mode == "fit") return fit_main(argc - 1, argv + 1);
    if (mode == "apply") return apply_main(argc - 1, argv + 1);
    if (mode == "gains") return gains_main(argc - 1, argv + 1);
    return one_shot_main(argc, argv);
  });
}

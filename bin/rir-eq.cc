// rir-eq: real-world sub-band room equalization of RIR sets (TS-RIR sec. 3.2).
#include <malloc.h>

#include <iostream>
#include <string>

#include "eq/eq_options.h"
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
    "apply writes <out-dir>/<id>.wav, rir.scp and rir_list with the input ids. A multichannel RIR (a\n"
    "microphone array's) keeps its channels in order: the EQ is designed on channel 0 and the same\n"
    "filter and level factor are applied to every channel (their time and level differences stay).\n"
    "\n"
    "Examples:\n"
    "  rir-eq fit --sample-rate=16000 --model=gmm --components=2 --covariance=full real/rir.scp eq.model\n"
    "  rir-eq apply --seed=7 eq.model sim/rir.scp sim_eq\n"
    "  rir-eq --real=real/rir.scp --seed=7 sim/rir.scp sim_eq\n"
    "  rir-eq gains sim_eq/rir.scp -\n"
    "Run 'rir-eq <fit|apply|gains> --help' for the options of one mode.\n";

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
  RirEqOptions s;
  CommandLine cl("rir-eq fit",
                 "rir-eq fit: measure the relative gains of real RIRs and fit their distribution.\n"
                 "Usage: rir-eq fit [options] <real-rir-scp> <model-out>\n"
                 "Example: rir-eq fit --model=gmm --components=2 --covariance=full real/rir.scp eq.model\n");
  s.Register(&cl, EqProgramMode::kFit);
  const auto args = cl.parse(argc, argv, 2, 2);
  const EqModel model = fit_eq_model_on_set(args[0], s.fit_options());
  save_eq_model(model, args[1]);
  log_model(model);
  return 0;
}

int apply_main(int argc, const char* const* argv) {
  RirEqOptions s;
  CommandLine cl("rir-eq apply",
                 "rir-eq apply: equalize RIRs to relative gains drawn from a fitted model.\n"
                 "Usage: rir-eq apply [options] <model> <in-rir-scp> <out-dir>\n"
                 "Example: rir-eq apply --seed=7 --num-threads=4 eq.model sim/rir.scp sim_eq\n");
  s.Register(&cl, EqProgramMode::kApply);
  OutputPolicy policy(cl.program());
  policy.Register(&cl);
  const auto args = cl.parse(argc, argv, 3, 3);
  install_output_policy(policy);
  const ApplySetOptions options = s.apply_options();
  const EqModel model = load_eq_model(args[0]);
  log_apply(equalize_rir_set(model, args[1], args[2], options));
  return 0;
}

int gains_main(int argc, const char* const* argv) {
  RirEqOptions s;
  CommandLine cl("rir-eq gains",
                 "rir-eq gains: write each RIR's relative gains (dB re 1000 Hz) at 62.5 ... 8000 Hz as\n"
                 "'<id> <7 values>' lines and log their per-point mean and standard deviation.\n"
                 "Usage: rir-eq gains [options] <rir-scp> <gains-out|->\n"
                 "Example: rir-eq gains --sample-rate=16000 real/rir.scp real_gains.txt\n");
  s.Register(&cl, EqProgramMode::kGains);
  const auto args = cl.parse(argc, argv, 2, 2);
  double rate = 0;
  const std::vector<RirGains> rows = measure_rir_set(args[0], s.measure_options(), &rate);
  save_gains_table(rows, args[1]);
  std::vector<RelativeGainsDb> all;
  for (const RirGains& r : rows) all.push_back(r.gains_db);
  log_info(std::to_string(rows.size()) + " RIRs at " + std::to_string(static_cast<long>(rate)) +
           " Hz, relative gains (dB re 1 kHz):\n" + format_gain_stats({args[0]}, {summarize_gains(all)}));
  return 0;
}

int one_shot_main(int argc, const char* const* argv) {
  RirEqOptions s;
  CommandLine cl("rir-eq", kUsage);
  s.Register(&cl, EqProgramMode::kOneShot);
  OutputPolicy policy(cl.program());
  policy.Register(&cl);
  const auto args = cl.parse(argc, argv, 2, 2);
  install_output_policy(policy);
  if (s.real.empty()) throw Error("--real=<real-rir-scp> is required (or use 'rir-eq fit' / 'rir-eq apply')\n" + cl.hint());
  const ApplySetOptions options = s.apply_options();
  const EqModel model = fit_eq_model_on_set(s.real, s.fit_options());
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

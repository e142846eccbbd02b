#include "perturb/perturb_set.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include "io/common_options.h"
#include "io/owned_output.h"
#include "io/rir_set.h"
#include "metrics/rir_metrics.h"
#include "util/error.h"
#include "util/parallel.h"
#include "util/strings.h"

namespace tsrir {
namespace {

struct MeasuredPair {
  double t60[2], drr[2], c50[2];
};

// Mean of the finite values (NaN when there are none).
double finite_mean(const std::vector<MeasuredPair>& rows, double (MeasuredPair::*field)[2], int which) {
  double sum = 0.0;
  size_t n = 0;
  for (const MeasuredPair& r : rows) {
    const double v = (r.*field)[which];
    if (std::isfinite(v)) {
      sum += v;
      ++n;
    }
  }
  return n ? sum / double(n) : std::nan("");
}

// int16 holds at most 32767/32768: a louder RIR is scaled down as a whole (its shape is what counts).
bool fit_int16(Signal& rir) {
  constexpr float kFullScale = 32767.0f / 32768.0f;
  float peak = 0.0f;
  for (float v : rir.samples) peak = std::max(peak, std::fabs(v));
  if (peak <= kFullScale) return false;
  for (float& v : rir.samples) v *= kFullScale / peak;
  return true;
}

}  // namespace

void PerturbSetOptions::Register(OptionsItf* opts) {
  perturbation.Register(opts);
  CommonOptions(opts)
      .seed(&seed, "the ringing modes' frequencies and phases, per RIR id")
      .threads(&num_threads, "RIRs are perturbed in parallel; results do not depend on it")
      .audio_format(&format);
}

PerturbSetSummary perturb_rir_set(const std::string& in_set_path, const std::string& out_dir,
                                  const PerturbSetOptions& options) {
  options.perturbation.validate();
  if (options.num_threads < 1) throw Error("--num-threads must be >= 1");
  const std::vector<RirRef> refs = read_rir_refs(in_set_path, run_inputs());
  if (refs.empty()) throw Error(in_set_path + ": no RIRs listed");
  RirSetWriter writer(out_dir, options.format);
  std::vector<MeasuredPair> measured(refs.size());
  std::atomic<size_t> rescaled{0};
  parallel_for(refs.size(), options.num_threads, [&](size_t i) {
    const Signal in = load_rir(refs[i]);
    Signal out;
    try {
      out = perturb_rir(in, options.perturbation, options.seed, nullptr);
    } catch (const Error& e) {
      throw Error(refs[i].where + ": " + e.what());
    }
    if (options.format == SampleFormat::kInt16 && fit_int16(out)) ++rescaled;
    const RirMetrics before = measure_rir(in), after = measure_rir(out);
    measured[i] = {{before.t60_s, after.t60_s}, {before.drr_db, after.drr_db}, {before.c50_db, after.c50_db}};
    writer.add(out, refs[i].room_id);
  });
  writer.commit();
  PerturbSetSummary s;
  s.count = refs.size();
  s.rescaled = rescaled;
  s.t60_before_s = finite_mean(measured, &MeasuredPair::t60, 0);
  s.t60_after_s = finite_mean(measured, &MeasuredPair::t60, 1);
  s.drr_before_db = finite_mean(measured, &MeasuredPair::drr, 0);
  s.drr_after_db = finite_mean(measured, &MeasuredPair::drr, 1);
  s.c50_before_db = finite_mean(measured, &MeasuredPair::c50, 0);
  s.c50_after_db = finite_mean(measured, &MeasuredPair::c50, 1);
  return s;
}

std::string format_perturb_summary(const PerturbSetSummary& s) {
  return std::to_string(s.count) + " RIRs; mean T60 " + format_double(s.t60_before_s, 3) + " -> " +
         format_double(s.t60_after_s, 3) + " s, DRR " + format_double(s.drr_before_db, 3) + " -> " +
         format_double(s.drr_after_db, 3) + " dB, C50 " + format_double(s.c50_before_db, 3) + " -> " +
         format_double(s.c50_after_db, 3) + " dB (rir-metrics, ISO)" +
         (s.rescaled ? "; " + std::to_string(s.rescaled) + " scaled down to fit 16-bit output" : "");
}

}  // namespace tsrir

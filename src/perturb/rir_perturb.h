// Controlled mismatches of real RIRs: the positive controls of the downstream experiment
// (docs/results/downstream.md). Each perturbation changes one acoustic parameter by a known amount
// and leaves the rest of the response as measured, so that training data made with the perturbed
// set differs from data made with the real set in that parameter alone:
//   t60_scale       the decay after the direct sound re-weighted by one exponential envelope,
//                   g(t) = exp(-k (t - t_d)) for t >= t_d (t_d = direct peak + direct_post_ms),
//                   k = 3 ln(10) (1 / (s T) - 1 / T) with T the RIR's own T60 (ISO, mean T30 of
//                   500 Hz and 1 kHz): every band's energy decay rate grows by the same 2k, so the
//                   mid-band T60 becomes s T and other bands move by the same rate (not the same
//                   factor). For s > 1 the envelope grows, so the measurement noise after the
//                   Lundeby intersection is faded out first (20 ms raised cosine) instead of
//                   being amplified; the length of the file is kept, so a stretched decay is cut
//                   where the input ends.
//   drr_offset_db   the direct window [peak - direct_pre_ms, peak + direct_post_ms] scaled by
//                   10^(d/20) with 0.5 ms raised-cosine ramps inside the window: DRR moves by ~d.
//   lf_ringing_db   damped low-frequency modes added from the direct sound on: kLfModes sinusoids
//                   at log-uniform frequencies in [lf_min_hz, lf_max_hz], random phases, each with
//                   decay time lf_t60_s and a 2 ms rise; their total energy is lf_ringing_db above
//                   the RIR's own energy below lf_max_hz.
// Perturbations compose in that order. Random draws (mode frequencies and phases) come from
// (seed, RIR id), so a set perturbs the same way with any number of threads.
#pragma once
#include <cstdint>
#include <string>

#include "io/signal.h"
#include "util/options.h"

namespace tsrir {

struct RirPerturbation {
  double t60_scale = 1.0;          // 1 = unchanged
  double drr_offset_db = 0.0;      // 0 = unchanged
  double lf_ringing_db = -200.0;   // <= -100 = none
  double lf_min_hz = 40.0;
  double lf_max_hz = 200.0;
  double lf_t60_s = 1.5;
  double direct_pre_ms = 2.5;      // the direct window, as rir-metrics' DRR uses it
  double direct_post_ms = 2.5;

  void Register(OptionsItf* opts);
  void validate() const;           // Error naming the option
  bool changes_decay() const { return t60_scale != 1.0; }
  bool changes_direct() const { return drr_offset_db != 0.0; }
  bool adds_ringing() const { return lf_ringing_db > -100.0; }
};

constexpr int kLfModes = 8;

// What one perturbation did, for the set's log and its report table.
struct PerturbationRecord {
  double t60_in_s = 0.0;           // the T60 the envelope was computed from (NaN: not re-weighted)
  double decay_rate_change_per_s = 0.0;   // k
  size_t noise_cut_sample = 0;     // where the noise was faded out (0: not faded)
  double ringing_energy_ratio_db = -200.0;
};

// Throws Error naming rir.id when the RIR cannot be perturbed as asked (e.g. its T60 cannot be
// measured, or it has no direct sound to scale).
Signal perturb_rir(const Signal& rir, const RirPerturbation& p, std::uint64_t seed, PerturbationRecord* record);

}  // namespace tsrir

// Data of the TS-RIRGAN translation-fidelity suite (issues 17 and 34), generated here by code
// independent of src/gan and src/sim: a direct impulse, a few discrete early reflections and an
// exponentially decaying white-noise tail. Each RIR draws its own acoustics (onset, broadband
// T60, DRR, reflections) from wide ranges; the two unpaired domains share these distributions and
// differ by a hidden effect that only the "real" domain has. A run's hidden effect is one KIND
// (HiddenEffect), and within it every real RIR draws its own parameters at random (frequencies,
// phases, crossovers, times, strengths), so that no one template holds it:
// - low-frequency (below 200 Hz): per RIR one of 1-3 decaying room modes, a cluster of weak modes,
//   or a mode excited by a late reflection (LowFrequencyEffect);
// - decay (above a 2-3 kHz crossover): the band's decay speeds up from a drawn time on (20-80 ms
//   after the onset), by 1.6-2.5x: a per-band decay change that varies over time;
// - direct (above 2-3 kHz): the direct sound is 4-9 dB stronger, as from a source whose
//   directivity grows with frequency and that is aimed at the microphone;
// - early (above 2-3 kHz): the reverberant part's first 30-80 ms are 3-8 dB stronger.
// The effects above 500 Hz scale one part of the RIR in time (its part above the crossover, by
// the tests' own Butterworth high-pass, fidelity_filters.h: zero-phase for the reverberant part,
// causal for the direct sound; nothing comes before the direct sound): the real RIRs keep the fine
// structure they share with their synthetic twins, which is what the translation must keep too.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "io/signal.h"

namespace tsrir_test {

constexpr double kEffectMaxHz = 200.0;

enum class HiddenEffect { kLowFrequency, kDecay, kDirect, kEarly };
constexpr int kNumHiddenEffects = 4;
const char* hidden_effect_name(HiddenEffect kind);
// "low-frequency", "decay", "direct", "early"; false for any other name.
bool parse_hidden_effect(const std::string& name, HiddenEffect* kind);

enum class LowFrequencyEffect {
  kNone,
  kModes,          // 1-3 decaying room modes at 50-180 Hz, random phases, starting at the onset
  kModalCluster,   // 12-24 weak modes spread over 40-180 Hz: a diffuse low-frequency excess
  kDelayedBoom,    // one strong mode excited by a reflection 5-40 ms after the direct sound
};
constexpr int kNumLowFrequencyKinds = 3;
const char* effect_name(LowFrequencyEffect kind);

struct FidelityDomainSpec {
  double sample_rate_hz = 16000.0;
  double length_s = 1.0;
  double onset_min_s = 0.003, onset_max_s = 0.060;
  double t60_min_s = 0.20, t60_max_s = 0.80;     // log-uniform
  double drr_min_db = -6.0, drr_max_db = 8.0;    // uniform
  bool hidden_effect = false;                    // the "real" domain
  HiddenEffect effect = HiddenEffect::kLowFrequency;
  // Low-frequency effect energy re the RIR's direct + reverberant energy, dB (uniform).
  double effect_min_db = -6.0, effect_max_db = 0.0;
  // The effects above 500 Hz act above a crossover drawn per RIR in this range (Hz).
  double crossover_min_hz = 2000.0, crossover_max_hz = 3000.0;
  double decay_start_min_s = 0.020, decay_start_max_s = 0.080;  // after the onset
  double decay_speedup_min = 1.6, decay_speedup_max = 2.5;      // decay rate multiplier
  double direct_min_db = 4.0, direct_max_db = 9.0;
  double early_min_db = 3.0, early_max_db = 8.0;
  double early_min_s = 0.030, early_max_s = 0.080;              // after the onset
};

// What was drawn for one RIR (the base acoustics, then its hidden effects; "none" / 0 where the
// kind has no such effect).
struct FidelityRir {
  tsrir::Signal signal;
  double onset_s = 0, t60_s = 0, drr_db = 0;
  LowFrequencyEffect effect = LowFrequencyEffect::kNone;
  double decay_speedup = 0, direct_db = 0, early_db = 0;
};

// Deterministic: RIR i depends on (seed, name, i) only, and its base acoustics do not depend on the
// spec's hidden effect (they are drawn first), so the real spec with a synthetic domain's name and
// seed gives those synthetic RIRs with their own hidden effects added (the oracle translation).
std::vector<FidelityRir> make_fidelity_domain(const FidelityDomainSpec& spec, const std::string& name,
                                              int count, uint64_t seed);
// Writes <dir>/<id>.wav (float) and <dir>/rir.scp; returns the scp path.
std::string write_fidelity_domain(const std::vector<FidelityRir>& rirs, const std::string& dir);

}  // namespace tsrir_test

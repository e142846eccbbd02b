// Data of the TS-RIRGAN translation-fidelity suite (issue 17), generated here by code independent
// of src/gan and src/sim: a direct impulse, a few discrete early reflections and an exponentially
// decaying white-noise tail. Each RIR draws its own acoustics (onset, broadband T60, DRR,
// reflections) from wide ranges; the two unpaired domains share these distributions and differ by
// a hidden low-frequency effect that only the "real" domain has, drawn per RIR at random from
// several kinds, with random frequencies, phases, levels and decays, so that no one template
// holds it. Every kind acts below kEffectMaxHz; the measures read the RIR's own acoustics above
// kAcousticsMinHz, where no effect acts.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "io/signal.h"

namespace tsrir_test {

constexpr double kEffectMaxHz = 200.0;
constexpr double kAcousticsMinHz = 500.0;

enum class LowFrequencyEffect {
  kNone,
  kModes,          // 1-3 decaying room modes at 50-180 Hz, random phases, starting at the onset
  kModalCluster,   // 12-24 weak modes spread over 40-180 Hz: a diffuse low-frequency excess
  kDelayedBoom,    // one strong mode excited by a reflection 5-40 ms after the direct sound
};
constexpr int kNumEffectKinds = 3;
const char* effect_name(LowFrequencyEffect kind);

struct FidelityDomainSpec {
  double sample_rate_hz = 16000.0;
  double length_s = 1.0;
  double onset_min_s = 0.003, onset_max_s = 0.060;
  double t60_min_s = 0.20, t60_max_s = 0.80;     // log-uniform
  double drr_min_db = -6.0, drr_max_db = 8.0;    // uniform
  bool hidden_effect = false;                    // the "real" domain
  // Effect energy re the RIR's direct + reverberant energy, dB (uniform).
  double effect_min_db = -6.0, effect_max_db = 0.0;
};

struct FidelityRir {
  tsrir::Signal signal;
  double onset_s = 0, t60_s = 0, drr_db = 0;
  LowFrequencyEffect effect = LowFrequencyEffect::kNone;
};

// Deterministic: RIR i depends on (seed, name, i) only.
std::vector<FidelityRir> make_fidelity_domain(const FidelityDomainSpec& spec, const std::string& name,
                                              int count, uint64_t seed);
// Writes <dir>/<id>.wav (float) and <dir>/rir.scp; returns the scp path.
std::string write_fidelity_domain(const std::vector<FidelityRir>& rirs, const std::string& dir);

}  // namespace tsrir_test

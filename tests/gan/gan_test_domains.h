// Two unpaired RIR domains for the TS-RIRGAN tests, generated here with code independent of the
// GAN: exponentially decaying Gaussian noise after a direct-path impulse. Both domains share the
// onset delay distribution and the broadband decay (the controls); the "real" domain also hides a
// decaying low-frequency room mode (the effect) that the "synthetic" one lacks.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "io/signal.h"

namespace tsrir_test {

struct DomainSpec {
  double sample_rate_hz = 16000.0;
  double length_s = 0.5;
  double onset_min_s = 0.005, onset_max_s = 0.080;
  double t60_min_s = 0.20, t60_max_s = 0.35;
  double tail_amplitude = 0.3;      // relative to the unit direct impulse
  double mode_hz = 250.0;           // the hidden effect (real domain only)
  double mode_amplitude = 0.0;      // 0 = no mode
  double mode_decay_s = 0.25;       // T60 of the mode
  // A mode excited by the direct sound starts in sine phase at the onset; true draws the phase.
  bool random_mode_phase = false;
};

// Deterministic: RIR i of a domain depends on (seed, name, i) only.
std::vector<tsrir::Signal> make_domain(const DomainSpec& spec, const std::string& name, int count,
                                       uint64_t seed);
// Writes <dir>/<id>.wav (float) and <dir>/rir.scp; returns the scp path.
std::string write_domain(const std::vector<tsrir::Signal>& rirs, const std::string& dir);

}  // namespace tsrir_test

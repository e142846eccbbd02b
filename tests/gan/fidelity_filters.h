// Filters of the TS-RIRGAN translation-fidelity suite (its data and its measures), written here
// independently of src/dsp, src/metrics and src/gan: 4th-order Butterworth sections (bilinear
// transform), run forward and backward for the measures and the reverberant part's effects (so
// that nothing moves in time) and forward only for the direct sound's (so that nothing comes
// before it).
#pragma once
#include <vector>

namespace tsrir_test {

// x filtered forward and backward by a 4th-order Butterworth low- or high-pass (zero phase,
// magnitude squared: -6 dB at cutoff_hz).
std::vector<double> zero_phase(const std::vector<double>& x, double cutoff_hz, double sample_rate_hz, bool high_pass);
// The part of x above cutoff_hz: x through the CAUSAL high-pass (the Butterworth run forward
// only), so that nothing starts before x does. The direct kind adds (gain - 1) times this part:
// a high-shelf whose step is about the gain, causal as a physical source's or room's response, and below
// the crossover it changes little (4th order: 24 dB less per octave below it). (x minus its
// causal low-pass, a complementary split, is not that: the low-pass's phase lag leaves a part of
// x that grows with frequency far below the crossover, and the effects above 2-3 kHz then moved
// the suite's 500-1000 Hz and sub-200 Hz measures: the direct kind's oracle failed its kept
// checks, drr_mid_db by 3.6 dB.)
std::vector<double> above(const std::vector<double>& x, double cutoff_hz, double sample_rate_hz);

}  // namespace tsrir_test

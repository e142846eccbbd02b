// Complementary zero-phase octave filters for summing band signals (Model's band -> broadband
// step). Band k's gain is 1 around its centre and crosses to each neighbour as cos^2 / sin^2 over
// kCrossoverWidthOctaves centred on the octave edge f_k * 2^(+-1/2), so the gains sum to exactly
// 1 at every frequency; band 0 extends to DC and band 7 to Nyquist. The half-octave crossover keeps
// a band's decay from leaking into its neighbours' octaves (a full-octave cos^2 made the 500 Hz
// T30 of a room with steeply frequency-dependent absorption read 14% long) while the filters stay
// short in time (tens of ms at 62.5 Hz). Filtering is circular over a buffer padded by 0.15 s, so the filters'
// (short, symmetric) tails do not wrap into the RIR.
#pragma once
#include <vector>

#include "sim/model.h"

namespace tsrir::sim {

constexpr double kCrossoverWidthOctaves = 0.5;

// Gain of band `band` at frequency f_hz.
double octave_crossover_gain(int band, double f_hz);

}  // namespace tsrir::sim

// The EQ filter (TS-RIR sec. 3.2, stage 2): a linear-phase FIR designed by the window method from
// gains at the 8 EQ nodes (62.5 ... 8000 Hz, 1 kHz included).
//
// The desired curve is linear in dB against log2(frequency) between nodes, held at the 62.5 Hz
// value down to the lower edge of the 62.5 Hz octave (44.2 Hz), then faded (linearly in log
// frequency) to 0 dB at 31.25 Hz, and held at the 8000 Hz value up to Nyquist.
// Why fade instead of holding down to DC: nothing below 44 Hz is measured, and simulated RIRs
// carry a large DC / infrasonic component (every image source adds a positive impulse). Holding
// a +8 dB low-frequency correction down to DC amplified that component into a slow offset that
// dropped the DRR of rir-simulate output by up to 5 dB in the acceptance test.
// Interpolating in log-frequency gives each octave the same shape; firwin2-style interpolation
// in linear frequency would spread the 4-8 kHz change over most of the spectrum and squeeze
// 62.5-125 Hz into a handful of bins.
//
// The length is odd (type I): only a type I linear-phase filter can have a non-zero gain at
// Nyquist, which the 8000 Hz node needs at 16 kHz. The Hamming main lobe is ~4 fs/N wide, so
// 2049 taps at 16 kHz (31 Hz) resolve the 62.5 -> 125 Hz step.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "eq/relative_gain.h"
#include "util/options.h"

namespace tsrir {

using EqNodeGainsDb = std::array<double, kEqNumNodes>;

enum class FirWindow { kHamming, kHann, kBlackman };
const Choices<FirWindow>& fir_window_choices();      // "hamming" | "hann" | "blackman"
FirWindow parse_fir_window(const std::string& name);
std::string fir_window_name(FirWindow window);

struct EqFirOptions {
  // Odd, >= 3; 0 = automatic: 2049 at 16 kHz, scaled with the rate (a fixed 128 ms span), so the
  // frequency resolution at 62.5 Hz does not depend on the rate.
  int taps = 0;
  FirWindow window = FirWindow::kHamming;
};

// Position of a frequency on the EQ curve: the curve there is
// node_weight * gain[node] + next_weight * gain[node + 1] (next_weight 0 at the ends).
struct EqCurvePosition {
  int node = 0;
  double node_weight = 1.0;
  double next_weight = 0.0;
};
constexpr double kEqFadeStartHz = 44.19417382415922;  // 62.5 / sqrt(2)
constexpr double kEqFadeEndHz = 31.25;
EqCurvePosition eq_curve_position(double freq_hz);
double eq_curve_db(const EqNodeGainsDb& node_gains_db, double freq_hz);

// The length actually used at this rate.
int eq_fir_taps(const EqFirOptions& options, double sample_rate_hz);

// Designs the filter; result has eq_fir_taps() samples, symmetric about (taps-1)/2 (its group
// delay in samples). Throws Error for an even or too small length, or a rate the EQ rejects.
std::vector<float> design_eq_fir(const EqNodeGainsDb& node_gains_db, double sample_rate_hz,
                                 const EqFirOptions& options = {});

// Size of the dense frequency grid the design samples the curve on (a power of two >= 4x taps,
// >= 8192) -- large enough that the time aliasing of the sampled curve is negligible: the
// curve's sharpest feature (the 31.25 -> 44.2 Hz fade) has a response of ~80 ms, well inside the
// +-256 ms the 8192-point grid leaves at 16 kHz.
size_t eq_fir_design_grid_size(int taps);

}  // namespace tsrir

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include "dsp/convolve.h"
#include "eq/eq_fir.h"
#include "eq/equalize.h"
#include "util/error.h"
#include "util/rng.h"

using namespace tsrir;

namespace {

// |H(f)| in dB by a direct double-precision DTFT of the taps (independent of the FFT design path).
double response_db(const std::vector<float>& h, double f, double fs) {
  std::complex<double> acc = 0;
  for (size_t n = 0; n < h.size(); ++n) acc += static_cast<double>(h[n]) * std::polar(1.0, -2 * M_PI * f / fs * n);
  return 20 * std::log10(std::abs(acc));
}

const EqNodeGainsDb kTypicalNodes = {8.0, 5.0, -3.0, 2.0, 0.0, -4.0, -8.0, -12.0};

}  // namespace

TEST(EqCurve, LinearInLogFrequencyAndHeldOutside) {
  const EqNodeGainsDb g = kTypicalNodes;
  for (int j = 0; j < kEqNumNodes; ++j) EXPECT_NEAR(eq_curve_db(g, kEqNodesHz[j]), g[j], 1e-12);
  // Half an octave above 62.5 Hz the curve is halfway between the two nodes.
  EXPECT_NEAR(eq_curve_db(g, 62.5 * std::sqrt(2.0)), 0.5 * (g[0] + g[1]), 1e-9);
  EXPECT_NEAR(eq_curve_db(g, 4000 * std::pow(2.0, 0.25)), 0.75 * g[6] + 0.25 * g[7], 1e-9);
  // Held down to the 62.5 Hz octave's lower edge, then faded to 0 dB at 31.25 Hz (and below).
  EXPECT_NEAR(eq_curve_db(g, 62.5 / std::sqrt(2.0)), g[0], 1e-9);
  EXPECT_NEAR(eq_curve_db(g, std::sqrt(31.25 * 62.5 / std::sqrt(2.0))), 0.5 * g[0], 1e-9);
  EXPECT_EQ(eq_curve_db(g, 31.25), 0.0);
  EXPECT_EQ(eq_curve_db(g, 0.0), 0.0);
  EXPECT_EQ(eq_curve_db(g, 15000.0), g[7]);
}

TEST(EqFir, TypeOneLinearPhase) {
  for (FirWindow w : {FirWindow::kHamming, FirWindow::kHann, FirWindow::kBlackman}) {
    EqFirOptions o;
    o.window = w;
    const std::vector<float> h = design_eq_fir(kTypicalNodes, 16000, o);
    ASSERT_EQ(h.size(), 2049u);
    for (size_t i = 0; i < h.size() / 2; ++i) ASSERT_EQ(h[i], h[h.size() - 1 - i]) << "tap " << i;
    // Symmetric about the centre means the phase is exactly -w (N-1)/2: check the group delay by
    // the phase of the DTFT at a few frequencies, after removing the linear term.
    for (double f : {100.0, 1000.0, 3000.0}) {
      std::complex<double> acc = 0;
      const double c = (h.size() - 1) / 2.0;
      for (size_t n = 0; n < h.size(); ++n) acc += static_cast<double>(h[n]) * std::polar(1.0, -2 * M_PI * f / 16000 * (n - c));
      EXPECT_LT(std::abs(acc.imag()), 1e-6 * std::abs(acc)) << f;  // zero-phase after removing the delay
    }
  }
}

TEST(EqFir, RequestedGainsAtTheEightNodes) {
  // Within 0.5 dB at each node (the tolerance): the window smooths the curve over its
  // main lobe (~4 fs/N = 31 Hz at 16 kHz), which matters only at the 62.5 Hz kink.
  for (double fs : {16000.0, 48000.0}) {
    const std::vector<float> h = design_eq_fir(kTypicalNodes, fs);
    for (int j = 0; j < kEqNumNodes; ++j) {
      EXPECT_NEAR(response_db(h, kEqNodesHz[j], fs), kTypicalNodes[j], 0.5) << kEqNodesHz[j] << " Hz at " << fs;
    }
  }
  // A wilder random curve at 16 kHz (+-10 dB per node).
  Rng rng(5);
  EqNodeGainsDb g{};
  for (int j = 0; j < kEqNumNodes; ++j) g[j] = j == kEqReferenceNode ? 0.0 : rng.uniform(-10, 10);
  const std::vector<float> h = design_eq_fir(g, 16000);
  for (int j = 0; j < kEqNumNodes; ++j) EXPECT_NEAR(response_db(h, kEqNodesHz[j], 16000), g[j], 0.5) << kEqNodesHz[j];
}

TEST(EqFir, NoGroupDelayShiftAfterCompensation) {
  const std::vector<float> h = design_eq_fir(kTypicalNodes, 16000);
  // An impulse stays where it was.
  std::vector<float> x(8000, 0.0f);
  x[1500] = 1.0f;
  const std::vector<float> y = filter_zero_delay(x, h);
  ASSERT_EQ(y.size(), x.size());
  const size_t peak = std::max_element(y.begin(), y.end(), [](float a, float b) { return std::abs(a) < std::abs(b); }) - y.begin();
  EXPECT_EQ(peak, 1500u);
  // On noise, the output equals the double-precision reference convolution advanced by (N-1)/2.
  Rng rng(3);
  std::vector<float> noise(6000);
  for (float& v : noise) v = static_cast<float>(rng.normal());
  const std::vector<float> yn = filter_zero_delay(noise, h);
  const std::vector<double> ref = direct_convolve(std::vector<double>(noise.begin(), noise.end()),
                                                  std::vector<double>(h.begin(), h.end()));
  double max_err = 0, max_ref = 0;
  for (size_t n = 0; n < yn.size(); ++n) {
    max_err = std::max(max_err, std::abs(yn[n] - ref[n + 1024]));
    max_ref = std::max(max_ref, std::abs(ref[n + 1024]));
  }
  EXPECT_LT(max_err, 1e-5 * max_ref);  // float FFT rounding relative to the peak
}

TEST(EqFir, RejectsEvenLengthsAndLowRates) {
  EXPECT_EQ(eq_fir_taps({}, 16000), 2049);
  EXPECT_EQ(eq_fir_taps({}, 48000), 6145);
  EXPECT_EQ(design_eq_fir(kTypicalNodes, 44100).size(), static_cast<size_t>(eq_fir_taps({}, 44100)));
  EqFirOptions o;
  o.taps = 2048;
  EXPECT_THROW(design_eq_fir(kTypicalNodes, 16000, o), Error);
  o.taps = 1;
  EXPECT_THROW(design_eq_fir(kTypicalNodes, 16000, o), Error);
  EXPECT_THROW(design_eq_fir(kTypicalNodes, 8000), Error);
  EXPECT_THROW(parse_fir_window("kaiser"), Error);
}

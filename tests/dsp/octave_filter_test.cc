// Octave-band Butterworth design and filtering (src/dsp/octave_filter.h).
#include "dsp/octave_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>

#include "dsp/bands.h"
#include "util/error.h"

namespace tsrir {
namespace {

double db(double x) { return 20.0 * std::log10(x); }

// Analog Butterworth bandpass magnitude at the pre-warped frequency: the bilinear transform maps
// the digital response exactly onto it, so this checks pole placement, pairing and gain at once.
double analog_bandpass_magnitude(int order, double low_hz, double high_hz, double f_hz, double fs) {
  auto warp = [&](double f) { return 2 * fs * std::tan(M_PI * f / fs); };
  const double w1 = warp(low_hz), w2 = warp(high_hz), w = warp(f_hz);
  const double q = (w * w - w1 * w2) / (w * (w2 - w1));
  return 1.0 / std::sqrt(1.0 + std::pow(q * q, order));
}

TEST(OctaveFilter, AnsiEdgesMatchOctdsgnValuesAt16k) {
  // docs/reference/spec-digest.md §1.2: at 16 kHz the 500 Hz band is 358.9-696.5 Hz, the 1 kHz band 717.8-1393.1 Hz.
  const BandEdgesHz e500 = ansi_octave_edges_hz(500.0, 3);
  const BandEdgesHz e1k = ansi_octave_edges_hz(1000.0, 3);
  EXPECT_NEAR(e500.low_hz, 358.9, 0.05);
  EXPECT_NEAR(e500.high_hz, 696.5, 0.05);
  EXPECT_NEAR(e1k.low_hz, 717.8, 0.05);
  EXPECT_NEAR(e1k.high_hz, 1393.1, 0.05);
}

TEST(OctaveFilter, ButterworthMatchesAnalogPrototypeEverywhere) {
  for (double fs : {16000.0, 48000.0}) {
    for (int order : {1, 2, 3, 4, 6}) {
      for (double fc : {62.5, 250.0, 1000.0, 4000.0}) {
        const double lo = fc / std::sqrt(2.0), hi = fc * std::sqrt(2.0);
        const SosFilter f = butterworth_bandpass(order, lo, hi, fs);
        ASSERT_EQ((int)f.sections.size(), order);
        for (double r = 0.125; r <= 8.0; r *= std::pow(2.0, 0.25)) {
          const double freq = fc * r;
          if (freq >= fs / 2) break;
          const double got = std::abs(sos_response(f, freq, fs));
          const double want = analog_bandpass_magnitude(order, lo, hi, freq, fs);
          // Relative 1e-7: double-precision design; deep stopband values are compared in dB.
          EXPECT_NEAR(db(got), db(want), 1e-6) << "fs " << fs << " order " << order << " fc " << fc << " f " << freq;
        }
        EXPECT_NEAR(db(std::abs(sos_response(f, lo, fs))), -3.0103, 1e-4);
        EXPECT_NEAR(db(std::abs(sos_response(f, hi, fs))), -3.0103, 1e-4);
      }
    }
  }
}

TEST(OctaveFilter, PolesInsideUnitCircleForLowBandsAtHighRates) {
  for (double fs : {48000.0, 96000.0}) {
    const SosFilter f = ansi_octave_filter(31.25, fs, 3);
    for (const Biquad& q : f.sections) {
      // Poles of 1 + a1 z^-1 + a2 z^-2: |z|^2 = a2 for a complex pair.
      EXPECT_LT(q.a2, 1.0);
      EXPECT_GT(q.a2, 0.9);
    }
  }
}

TEST(OctaveFilter, RejectsImpossibleDesigns) {
  EXPECT_THROW(butterworth_bandpass(3, 5000, 9000, 16000), Error);
  EXPECT_THROW(butterworth_bandpass(0, 100, 200, 16000), Error);
  EXPECT_THROW(butterworth_bandpass(3, 300, 200, 16000), Error);
}

TEST(OctaveFilter, CausalFilteringMatchesDifferenceEquation) {
  const SosFilter f = ansi_octave_filter(1000.0, 16000.0, 3);
  std::mt19937 gen(3);
  std::normal_distribution<float> normal;
  std::vector<float> x(2000);
  for (float& v : x) v = normal(gen);
  // Reference: each section as a direct-form I difference equation.
  std::vector<double> ref(x.begin(), x.end());
  for (const Biquad& q : f.sections) {
    std::vector<double> out(ref.size());
    for (size_t n = 0; n < ref.size(); ++n) {
      double acc = q.b0 * ref[n];
      if (n >= 1) acc += q.b1 * ref[n - 1] - q.a1 * out[n - 1];
      if (n >= 2) acc += q.b2 * ref[n - 2] - q.a2 * out[n - 2];
      out[n] = acc;
    }
    ref = out;
  }
  const std::vector<double> y = sos_filter(f, x);
  for (size_t n = 0; n < x.size(); ++n) ASSERT_NEAR(y[n], ref[n], 1e-9) << n;
}

TEST(OctaveFilter, BankEqualsSingleFiltersForwardAndReversed) {
  std::vector<SosFilter> filters;
  for (double fc : {62.5, 125.0, 500.0, 2000.0, 4000.0}) filters.push_back(ansi_octave_filter(fc, 16000.0, 3));
  std::mt19937 gen(5);
  std::normal_distribution<float> normal;
  std::vector<float> x(3001);
  for (float& v : x) v = normal(gen);
  for (bool reversed : {false, true}) {
    std::vector<std::vector<double>> out;
    sos_filter_bank(filters, x.data(), x.size(), reversed, &out);
    ASSERT_EQ(out.size(), filters.size());
    for (size_t b = 0; b < filters.size(); ++b) {
      const std::vector<double> single = reversed ? sos_filter_reversed(filters[b], x) : sos_filter(filters[b], x);
      for (size_t n = 0; n < x.size(); ++n) ASSERT_NEAR(out[b][n], single[n], 1e-12) << b << " " << n;
    }
  }
}

// sos_filter_bank_energies against the bank's time-reversed output squared and summed from the end
// by plain loops: the same values to the bit (the decay analysis' results rest on that), for one
// group of eight lanes, for two (ten bands), and for filters outside the bandpass form.
void expect_energies_of_bank(const std::vector<SosFilter>& filters, const std::vector<float>& x) {
  std::vector<std::vector<double>> y;
  sos_filter_bank(filters, x.data(), x.size(), /*time_reversed=*/true, &y);
  BankEnergies e;
  sos_filter_bank_energies(filters, x.data(), x.size(), &e);
  ASSERT_EQ(e.tail.size(), filters.size());
  ASSERT_EQ(e.peak.size(), filters.size());
  ASSERT_GE(e.stride, filters.size());
  for (size_t b = 0; b < filters.size(); ++b) {
    ASSERT_EQ(e.tail[b].size(), x.size() + 1);
    double sum = 0.0, peak = 0.0;
    EXPECT_EQ(e.tail[b][x.size()], 0.0);
    for (size_t i = x.size(); i-- > 0;) {
      const double energy = y[b][i] * y[b][i];
      sum += energy;
      peak = std::max(peak, energy);
      ASSERT_EQ(e.at(b, i), energy) << b << " " << i;
      ASSERT_EQ(e.tail[b][i], sum) << b << " " << i;
    }
    EXPECT_EQ(e.peak[b], peak) << b;
    EXPECT_GT(peak, 0.0);
  }
}

TEST(OctaveFilter, BankEnergiesAreTheBankSquaredAndSummedFromTheEnd) {
  std::mt19937 gen(11);
  std::normal_distribution<float> normal;
  std::vector<float> x(2501);
  for (float& v : x) v = normal(gen);
  std::vector<SosFilter> seven, ten;
  for (double fc : kOctaveCentersHz) {
    if (fc < 8000.0) seven.push_back(ansi_octave_filter(fc, 16000.0, 3));
  }
  for (double fc : {31.25, 62.5, 125.0, 250.0, 500.0, 1000.0, 2000.0, 4000.0, 8000.0, 11000.0}) {
    ten.push_back(ansi_octave_filter(fc, 48000.0, 2));
  }
  expect_energies_of_bank(seven, x);
  expect_energies_of_bank(ten, x);
  std::vector<SosFilter> general = seven;
  for (SosFilter& f : general) f.sections[0].b1 = 0.25;  // no longer b0 (1 - z^-2)
  expect_energies_of_bank(general, x);
}

TEST(OctaveFilter, TimeReversedFilteringIsTheMirrorImage) {
  const SosFilter f = ansi_octave_filter(250.0, 16000.0, 3);
  std::vector<float> impulse(4000, 0.0f);
  impulse[3999] = 1.0f;
  const std::vector<double> rev = sos_filter_reversed(f, impulse);
  std::vector<float> forward_impulse(4000, 0.0f);
  forward_impulse[0] = 1.0f;
  const std::vector<double> fwd = sos_filter(f, forward_impulse);
  for (size_t n = 0; n < 4000; ++n) ASSERT_DOUBLE_EQ(rev[3999 - n], fwd[n]);
}

}  // namespace
}  // namespace tsrir

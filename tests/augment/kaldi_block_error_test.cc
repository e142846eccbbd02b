// --kaldi-compat's error model against Kaldi's algorithm itself, written out independently here:
// FFTbasedBlockConvolveSignals (feat/signal.cc) with a direct real DFT in Kaldi's packed layout
// [X_0, X_{L/2}, re X_1, im X_1, ...], the packed pairs multiplied as complex numbers (the first one
// too, which is the defect), the inverse and overlap-add as Kaldi does them, in double precision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "augment/kaldi_block_error.h"
#include "augment/reverberate.h"
#include "dsp/convolve.h"

namespace {

using Vec = std::vector<double>;

// Kaldi's packed real DFT of length L (forward) and its unnormalised inverse.
Vec packed_dft(const Vec& x) {
  const size_t L = x.size();
  Vec out(L, 0.0);
  for (size_t k = 0; k <= L / 2; ++k) {
    double re = 0, im = 0;
    for (size_t n = 0; n < L; ++n) {
      const double a = -2 * M_PI * static_cast<double>(k * n % L) / static_cast<double>(L);
      re += x[n] * std::cos(a);
      im += x[n] * std::sin(a);
    }
    if (k == 0) out[0] = re;
    else if (k == L / 2) out[1] = re;
    else {
      out[2 * k] = re;
      out[2 * k + 1] = im;
    }
  }
  return out;
}
Vec packed_idft(const Vec& X) {
  const size_t L = X.size();
  Vec x(L, 0.0);
  for (size_t n = 0; n < L; ++n) {
    double v = X[0] + X[1] * ((n % 2) ? -1.0 : 1.0);
    for (size_t k = 1; k < L / 2; ++k) {
      const double a = 2 * M_PI * static_cast<double>(k * n % L) / static_cast<double>(L);
      v += 2 * (X[2 * k] * std::cos(a) - X[2 * k + 1] * std::sin(a));
    }
    x[n] = v;
  }
  return x;
}

Vec kaldi_block_convolve(const Vec& filter, const Vec& signal_in) {
  const size_t M = filter.size(), N = signal_in.size(), out_len = N + M - 1;
  size_t L = 1;
  while (L < 4 * M) L *= 2;
  const size_t B = L - M + 1;
  Vec signal = signal_in;
  signal.resize(out_len, 0.0);
  Vec fpad(L, 0.0);
  std::copy(filter.begin(), filter.end(), fpad.begin());
  const Vec F = packed_dft(fpad);
  Vec temp(M - 1, 0.0);
  for (size_t po = 0; po < out_len; po += B) {
    const size_t len = std::min(B, out_len - po);
    Vec block(L, 0.0);
    for (size_t i = 0; i < len; ++i) block[i] = signal[po + i];
    Vec X = packed_dft(block);
    for (size_t k = 0; k < L / 2; ++k) {  // ElementwiseProductOfFft: every pair as a complex number
      const double re = F[2 * k] * X[2 * k] - F[2 * k + 1] * X[2 * k + 1];
      const double im = F[2 * k] * X[2 * k + 1] + F[2 * k + 1] * X[2 * k];
      X[2 * k] = re;
      X[2 * k + 1] = im;
    }
    Vec y = packed_idft(X);
    for (double& v : y) v /= static_cast<double>(L);
    if (po + B < out_len) {
      for (size_t i = 0; i < B; ++i) signal[po + i] = y[i];
      for (size_t i = 0; i < M - 1; ++i) signal[po + i] += temp[i];
      for (size_t i = 0; i < M - 1; ++i) temp[i] = y[B + i];
    } else {
      for (size_t i = 0; i < out_len - po; ++i) signal[po + i] = y[i];
      for (size_t i = 0; i < std::min(M - 1, out_len - po); ++i) signal[po + i] += temp[i];
    }
  }
  return signal;
}

TEST(KaldiBlockError, ExactConvolutionPlusModelIsKaldisAlgorithm) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  for (size_t m : {1u, 2u, 4u, 7u, 33u}) {
    for (size_t n : {1u, 5u, 50u, 301u}) {
      std::vector<float> x(n), h(m);
      for (float& v : x) v = static_cast<float>(0.3 * g(rng) + 0.2);  // a DC offset makes X_0 large
      for (float& v : h) v = static_cast<float>(0.5 * g(rng));
      const Vec want = kaldi_block_convolve(Vec(h.begin(), h.end()), Vec(x.begin(), x.end()));
      const std::vector<double> exact = tsrir::direct_convolve(Vec(x.begin(), x.end()), Vec(h.begin(), h.end()));
      std::vector<float> got(exact.begin(), exact.end());
      tsrir::add_kaldi_block_error(x, h, got.data(), got.size());
      ASSERT_EQ(got.size(), want.size());
      double worst = 0, worst_error = 0;
      for (size_t i = 0; i < got.size(); ++i) {
        worst = std::max(worst, std::fabs(got[i] - want[i]));
        worst_error = std::max(worst_error, std::fabs(exact[i] - want[i]));
      }
      EXPECT_LT(worst, 1e-5) << "M " << m << " N " << n;
      // The defect itself is there to be modelled (not a rounding effect) for all but tiny signals.
      if (n >= 5 && m >= 2) {
        EXPECT_GT(worst_error, 1e-3) << "M " << m << " N " << n;
      }
    }
  }
}

TEST(KaldiBlockError, OneTapHalfIsNotHalfInKaldi) {
  // The parity test's exact-answer case: h = {0.5, 0, 0, 0}: L = 16, 13 samples per block.
  std::vector<float> x(40);
  for (size_t i = 0; i < x.size(); ++i) x[i] = static_cast<float>(i % 3) * 0.25f;
  const std::vector<float> h = {0.5f, 0.0f, 0.0f, 0.0f};
  std::vector<float> y(x.size() + 3, 0.0f);
  for (size_t i = 0; i < x.size(); ++i) y[i] = 0.5f * x[i];
  tsrir::add_kaldi_block_error(x, h, y.data(), y.size());
  const Vec want = kaldi_block_convolve(Vec(h.begin(), h.end()), Vec(x.begin(), x.end()));
  for (size_t i = 0; i < y.size(); ++i) EXPECT_NEAR(y[i], want[i], 1e-6) << i;
  EXPECT_GT(std::fabs(want[0] - 0.0), 0.01);  // x[0] = 0, yet Kaldi's first output is not
}

TEST(KaldiBlockError, CompatShiftFalseRepeatsTheHead) {
  std::vector<float> x(500), h(37, 0.0f);
  for (size_t i = 0; i < x.size(); ++i) x[i] = static_cast<float>(std::sin(0.1 * static_cast<double>(i)));
  h[0] = 1.0f;
  h[10] = 0.4f;
  h[36] = -0.2f;
  tsrir::PreparedRir rir(h, 16000.0);
  tsrir::ReverbOptions o;
  o.shift_output = false;
  o.kaldi_compat = true;
  const std::vector<float> out = tsrir::reverberate_channel(x, 16000.0, &rir, {}, o);
  ASSERT_EQ(out.size(), x.size() + h.size() - 1);
  for (size_t k = 0; k + 1 < h.size(); ++k) EXPECT_EQ(out[x.size() + k], out[k]) << k;
  o.kaldi_compat = false;  // ours: the reverberant tail
  const std::vector<float> ours = tsrir::reverberate_channel(x, 16000.0, &rir, {}, o);
  EXPECT_NE(ours[x.size()], ours[0]);
}

TEST(KaldiBlockError, TruncationTowardZero) {
  std::vector<float> v = {1.7f / 32768, -1.7f / 32768, 0.99999f, -1.5f, 2.0f, 0.0f};
  EXPECT_EQ(tsrir::kaldi_truncate_to_int16(&v), 2);
  EXPECT_EQ(v[0], 1.0f / 32768);
  EXPECT_EQ(v[1], -1.0f / 32768);
  EXPECT_EQ(v[2], 32767.0f / 32768);
  EXPECT_EQ(v[3], -1.0f);
  EXPECT_EQ(v[4], 32767.0f / 32768);
  EXPECT_EQ(v[5], 0.0f);
}

}  // namespace

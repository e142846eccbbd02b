// The band-gain generator's full-band stage (src/gan/gan_band_gain.h), against references
// written here in float64 with other formulations: the band responses add up to one, equal gains
// give the input back, constant gains filter the input by their interpolation over frequency (a
// direct DTFT of the impulse response), time-varying gains follow their knots (a sinusoid's
// envelope against a piecewise-linear interpolation written here), nothing changes before the
// onset, and a new stage changes nothing yet passes a gradient to its head.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <set>

#include "gan/gan_band_gain.h"
#include "gan/gan_networks.h"

#include <c10/core/InferenceMode.h>
#include <torch/fft.h>

using namespace tsrir;
using namespace tsrir::gan;

namespace {

constexpr double kFs = 16000.0;
constexpr int64_t kLength = 16384;

GeneratorSpec band_gain_spec(int width) {
  GeneratorSpec spec;
  spec.width = width;
  spec.decoder = GanDecoder::kLight;
  spec.kind = GanGenerator::kBandGain;
  spec.correction_max_hz = 500.0;
  return spec;
}

// Sets the head to output `raw` [bands][knots - 1] for every input (weights zero, bias raw).
void set_head(BandGain& stage, const std::vector<std::vector<double>>& raw) {
  torch::NoGradGuard no_grad;
  stage->head->weight.zero_();
  for (int b = 0; b < kBandGainBands; ++b) {
    for (int k = 0; k + 1 < kBandGainKnots; ++k) stage->head->bias[b * (kBandGainKnots - 1) + k] = raw[b][k];
  }
}

// The frequency at which band b's response is one and every other band's zero: the geometric
// middle between its edges (band 0 and the last band: well inside them).
double band_centre_hz(int b) {
  if (b == 0) return 100.0;
  if (b == kBandGainBands - 1) return 7000.0;
  return std::sqrt(kBandEdgesHz[b - 1] * kBandEdgesHz[b]);
}

}  // namespace

TEST(BandGain, ResponsesAreNonNegativeAndAddUpToOne) {
  const int64_t n = 18432;
  const auto r = band_gain_responses(n);
  ASSERT_EQ(int(r.size()), kBandGainBands);
  for (size_t i = 0; i < r[0].size(); ++i) {
    double sum = 0;
    for (const auto& band : r) {
      EXPECT_GE(band[i], 0.0f);
      sum += band[i];
    }
    EXPECT_NEAR(sum, 1.0, 1e-6) << "bin " << i;
  }
  for (int b = 0; b < kBandGainBands; ++b) {
    const size_t bin = size_t(std::lround(band_centre_hz(b) * double(n) / kFs));
    EXPECT_NEAR(r[size_t(b)][bin], 1.0, 2e-3) << "band " << b;
  }
}

TEST(BandGain, BandSignalsAddUpToTheInput) {
  torch::manual_seed(3);
  BandGain stage(16);
  const torch::Tensor x = torch::randn({2, 1, kLength}) * torch::exp(-torch::arange(kLength) / 3000.0);
  const torch::Tensor bands = stage->band_signals(x);
  ASSERT_EQ(bands.sizes(), torch::IntArrayRef({2, kBandGainBands, kLength}));
  EXPECT_LT(((bands.sum(1, true) - x).norm() / x.norm()).item<double>(), 1e-5);
}

// Gains constant in time: the stage is a time-invariant filter whose response at each band's
// centre is that band's gain. Measured by a float64 DTFT of the impulse response at those
// frequencies (not at FFT bins). The impulse sits well inside the segment, so that its band
// signals (zero-phase filters, ringing on both sides) are whole.
TEST(BandGain, ConstantGainsFilterAtEachBandsCentreByItsGain) {
  BandGain stage(16);
  std::vector<std::vector<double>> raw(kBandGainBands);
  for (int b = 0; b < kBandGainBands; ++b) raw[b].assign(kBandGainKnots - 1, 0.6 * std::sin(1.0 + 2.0 * b));
  set_head(stage, raw);
  torch::NoGradGuard no_grad;
  const torch::Tensor features = torch::rand({1, 16, 64});
  const torch::Tensor v = stage->knot_log_gains(features);  // [1, bands, knots]
  torch::Tensor impulse = torch::zeros({1, 1, kLength});
  impulse[0][0][6000] = 1.0;
  const torch::Tensor onset = torch::zeros({1, 1, 1}, torch::kLong);  // the gains' knots: all past by 6000
  const torch::Tensor h = (impulse + stage->forward(impulse, features, onset)).to(torch::kDouble).flatten();
  const auto a = h.accessor<double, 1>();
  for (int b = 0; b < kBandGainBands; ++b) {
    const double f = band_centre_hz(b);
    std::complex<double> response = 0;
    for (int64_t n = 0; n < kLength; ++n) response += a[n] * std::polar(1.0, -2 * M_PI * f * double(n) / kFs);
    const double expected = std::exp(v[0][b][3].item<double>());
    EXPECT_NEAR(std::abs(response), expected, 0.01 * expected) << "band " << b << " at " << f << " Hz";
  }
}

// Gains that vary over the knots: a sinusoid at a band's centre comes out with that band's gain
// as its envelope, linear in log gain between the knots (ms after the onset), held before the
// first and after the last.
TEST(BandGain, TimeVaryingGainsFollowTheKnots) {
  BandGain stage(16);
  std::vector<std::vector<double>> raw(kBandGainBands, std::vector<double>(kBandGainKnots - 1, 0.0));
  const int band = 3;
  for (int k = 0; k + 1 < kBandGainKnots; ++k) raw[band][k] = 0.8 * std::cos(0.9 * k);
  set_head(stage, raw);
  torch::NoGradGuard no_grad;
  const torch::Tensor features = torch::rand({1, 16, 64});
  const torch::Tensor v = stage->knot_log_gains(features).to(torch::kDouble);
  const double f = band_centre_hz(band);
  const int64_t onset_sample = 800;
  const torch::Tensor t = torch::arange(kLength, torch::kDouble);
  const torch::Tensor x = torch::sin(2 * M_PI * f * t / kFs).to(torch::kFloat).view({1, 1, -1});
  const torch::Tensor onset = torch::full({1, 1, 1}, onset_sample, torch::kLong);
  const torch::Tensor y = (x + stage->forward(x, features, onset)).to(torch::kDouble).flatten();
  auto expected_log_gain = [&](int64_t n) {
    const double ms = std::clamp((double(n) - double(onset_sample)) * 1000.0 / kFs, kKnotMs[0], kKnotMs[kBandGainKnots - 1]);
    int k = 0;
    while (k + 2 < kBandGainKnots && ms > kKnotMs[k + 1]) ++k;
    const double w = (ms - kKnotMs[k]) / (kKnotMs[k + 1] - kKnotMs[k]);
    return (1 - w) * v[0][band][k].item<double>() + w * v[0][band][k + 1].item<double>();
  };
  // Samples near the sinusoid's crests (|x| > 0.9), away from the ends of the segment.
  int checked = 0;
  for (int64_t n = 2000; n < kLength - 2000; n += 37) {
    const double xn = x[0][0][n].item<double>();
    if (std::abs(xn) < 0.9) continue;
    EXPECT_NEAR(y[n].item<double>() / xn, std::exp(expected_log_gain(n)), 0.03) << "sample " << n;
    ++checked;
  }
  // And in the first milliseconds, where the knots are densest (2-3 ms apart).
  for (int64_t n = onset_sample + 40; n < onset_sample + 400; ++n) {
    const double xn = x[0][0][n].item<double>();
    if (std::abs(xn) < 0.95) continue;
    EXPECT_NEAR(y[n].item<double>() / xn, std::exp(expected_log_gain(n)), 0.06) << "sample " << n;
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

// A new band-gain generator draws the same weights as a residual one of the same seed (its head
// is registered last and starts at zero), so its output is the residual one's brought back to the
// input's peak; and the head's gradient is not zero there (no saddle, unlike a zero waveform
// correction).
TEST(BandGain, NewGeneratorIsTheResidualOneAndItsHeadGetsAGradient) {
  torch::manual_seed(9);
  Generator band_gain(band_gain_spec(4), GanInit::kHe);
  torch::manual_seed(9);
  GeneratorSpec residual_spec = band_gain_spec(4);
  residual_spec.kind = GanGenerator::kResidual;
  Generator residual(residual_spec, GanInit::kHe);
  torch::Tensor x = torch::zeros({2, 1, kLength});
  x[0][0][300] = 1.0, x[1][0][2000] = -1.0;
  x.narrow(2, 2100, 8000).normal_(0, 0.05);
  const GeneratorPass pass = band_gain->pass(x);
  const torch::Tensor& y = pass.output;
  {
    torch::NoGradGuard no_grad;
    const torch::Tensor r = residual->forward(x);
    const torch::Tensor peak_in = std::get<0>(x.abs().max(-1, true)), peak_r = std::get<0>(r.abs().max(-1, true));
    EXPECT_LT((y - r * peak_in / peak_r).abs().max().item<double>(), 1e-6);
    EXPECT_LT((std::get<0>(y.abs().max(-1, true)) - peak_in).abs().max().item<double>(), 1e-6);
  }
  const torch::Tensor loss = (y - 0.5 * x).pow(2).mean();
  const auto named = band_gain->named_parameters();
  const torch::Tensor head_weight = named["band_gain.head.weight"];
  const torch::Tensor grad = torch::autograd::grad({loss}, {head_weight})[0];
  EXPECT_GT(grad.abs().max().item<double>(), 0.0);
  EXPECT_EQ(pass.log_gains.sizes(), torch::IntArrayRef({2, kBandGainBands, kBandGainKnots}));
}

// Whatever the weights, nothing is added before each input's onset (what is there is the input
// at the one level the output's peak normalisation sets for the whole RIR); after it the whole
// band may change.
TEST(BandGain, NothingChangesBeforeTheOnsetAndTheWholeBandMayAfter) {
  torch::manual_seed(10);
  Generator g(band_gain_spec(4), GanInit::kHe);
  torch::NoGradGuard no_grad;
  for (auto& p : g->parameters()) p.normal_(0, 0.05);
  torch::Tensor x = torch::zeros({2, 1, kLength});
  x[0][0][300] = 1.0, x[1][0][5000] = -1.0;
  x.narrow(2, 5001, 6000).normal_(0, 0.02);
  x.narrow(2, 301, 4000).normal_(0, 0.02);
  const torch::Tensor y = g->forward(x);
  EXPECT_TRUE(torch::equal(y[0][0].narrow(0, 0, 300), x[0][0].narrow(0, 0, 300)));  // silence stays silent
  // Row 1 has noise before its onset: it comes out scaled by one factor, nothing added to it.
  const torch::Tensor before_in = x[1][0].narrow(0, 0, 5000).to(torch::kDouble);
  const torch::Tensor before_out = y[1][0].narrow(0, 0, 5000).to(torch::kDouble);
  const double level = (before_out * before_in).sum().item<double>() / before_in.pow(2).sum().item<double>();
  EXPECT_GT(level, 0.0);
  EXPECT_LT((before_out - level * before_in).abs().max().item<double>(), 1e-6 * before_in.abs().max().item<double>());
  // Above 4 kHz (beyond the waveform correction's 500 Hz), the output differs from the input.
  const torch::Tensor change = (y - x).to(torch::kDouble).flatten(1);
  const torch::Tensor power = torch::fft::rfft(change).abs().pow(2);
  const int64_t from = int64_t(4000.0 * kLength / kFs);
  EXPECT_GT(power.narrow(1, from, power.size(1) - from).sum().item<double>(), 1e-6);
}

// gas-to-real's inference mode (FFT form of the bottleneck) against training's direct form, for
// the default generator with an active stage: what the network adds is equal within float32
// rounding; and an RIR's output and gradient do not depend on the rest of its batch (the
// identity-free joint step relies on it).
TEST(BandGain, TranslationForwardEqualsTrainingAndRowsAreIndependent) {
  torch::manual_seed(33);
  Generator g(band_gain_spec(8), GanInit::kHe);
  {
    torch::NoGradGuard no_grad;
    for (auto& p : g->parameters()) p.mul_(2.0);
    for (auto& p : g->named_parameters()) {
      if (p.key().rfind("band_gain.", 0) == 0) p.value().normal_(0, 0.05);
    }
  }
  torch::Tensor x = torch::randn({4, 1, kLength}) * 0.05 * torch::exp(-torch::arange(kLength) / 2000.0);
  for (int b = 0; b < 4; ++b) x[b][0][100 + 300 * b] = 1.0;
  torch::Tensor training, translation;
  {
    torch::NoGradGuard no_grad;
    training = g->forward(x);
  }
  {
    c10::InferenceMode inference;
    translation = g->forward(x);
  }
  EXPECT_GT(((training - x).norm() / x.norm()).item<double>(), 1e-3);
  EXPECT_LT(((translation - training).norm() / (training - x).norm()).item<double>(), 1e-5);
  auto loss_and_grads = [&](const torch::Tensor& batch) {
    const torch::Tensor y = g->forward(batch).narrow(0, 0, 2);
    const torch::Tensor loss = (y - 0.5 * x.narrow(0, 0, 2)).abs().mean();
    return std::make_pair(y.detach(), torch::autograd::grad({loss}, g->parameters()));
  };
  const auto [y_alone, grad_alone] = loss_and_grads(x.narrow(0, 0, 2));
  const auto [y_all, grad_all] = loss_and_grads(x);
  EXPECT_LT(((y_alone - y_all).norm() / y_alone.norm()).item<double>(), 1e-6);
  for (size_t i = 0; i < grad_alone.size(); ++i) {
    const double scale = grad_all[i].norm().item<double>();
    EXPECT_LE((grad_alone[i] - grad_all[i]).norm().item<double>(), 1e-4 * scale + 1e-12) << "parameter " << i;
  }
}

// The gain identity holds every band's knots after the direct sound and the lowest band's direct
// sound, nothing else: each log gain set to a distinct value (its index) is found among the held
// ones exactly when it is one of those.
TEST(BandGain, IdentityHoldsTheKnotsAfterTheDirectSoundAndTheLowBandsDirectSound) {
  const int64_t rows = 2, count = kBandGainBands * kBandGainKnots;
  const torch::Tensor gains = torch::arange(rows * count, torch::kFloat).reshape({rows, kBandGainBands, kBandGainKnots});
  for (const int direct_bands : {1, 0, 3}) {
  const torch::Tensor held = identity_held_gains(gains, direct_bands);
  ASSERT_EQ(held.dim(), 2);
  ASSERT_EQ(held.size(0), rows);
  for (int64_t r = 0; r < rows; ++r) {
    const auto values = held[r].contiguous();
    const float* v = values.data_ptr<float>();
    const std::set<float> found(v, v + values.numel());
    EXPECT_EQ(found.size(), size_t(values.numel()));  // none twice
    for (int band = 0; band < kBandGainBands; ++band) {
      for (int knot = 0; knot < kBandGainKnots; ++knot) {
        const bool want = knot >= kDirectSoundKnots || band < direct_bands;
        EXPECT_EQ(found.count(float(r * count + band * kBandGainKnots + knot)) == 1, want)
            << band << " " << knot << " " << direct_bands;
      }
    }
    // The rest of the direct sound is what direct_gains_above() selects: every knot once, in one of the two.
    const torch::Tensor rest = direct_gains_above(gains, direct_bands);
    ASSERT_TRUE(rest.defined());
    const auto rest_values = rest[r].contiguous();
    const float* w = rest_values.data_ptr<float>();
    std::set<float> all(found);
    for (int64_t i = 0; i < rest_values.numel(); ++i) EXPECT_TRUE(all.insert(w[i]).second) << w[i];
    EXPECT_EQ(all.size(), size_t(count));
  }
  }
  EXPECT_FALSE(direct_gains_above(gains, kBandGainBands).defined());
  EXPECT_EQ(kBandEdgesHz[0], 250.0);
}


#include "gan/gan_band_gain.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <tuple>

#include <torch/fft.h>

namespace tsrir {
namespace gan {
namespace {

constexpr double kRateHz = 16000.0;
// Zeros after the 16384 samples before the FFT: the band filters' responses (a few ms, the
// 250 Hz half-octave crossfade's ~40 ms) must not wrap around onto the RIR's start.
constexpr int64_t kGuardSamples = 2048;
constexpr int64_t kSliceLength = 16384;
constexpr double kHeadScale = 0.5;

// 0 below edge * 2^(-w/2), 1 above edge * 2^(w/2), a raised cosine in log2(f) between
// (w = kCrossfadeOctaves).
double crossfade(double hz, double edge_hz) {
  if (hz <= 0) return 0.0;
  const double u = std::log2(hz / edge_hz) / kCrossfadeOctaves + 0.5;
  if (u <= 0) return 0.0;
  if (u >= 1) return 1.0;
  return 0.5 - 0.5 * std::cos(M_PI * u);
}

}  // namespace

std::vector<std::vector<float>> band_gain_responses(int64_t fft_length) {
  const int64_t bins = fft_length / 2 + 1;
  std::vector<std::vector<float>> out(kBandGainBands, std::vector<float>(size_t(bins)));
  // Band b passes what the crossfade at its lower edge has let in and the one at its upper edge
  // has not yet passed on (band 0 has no lower edge, the last band no upper one): the sum over
  // the bands telescopes to 1 at every frequency.
  for (int64_t i = 0; i < bins; ++i) {
    const double hz = double(i) * kRateHz / double(fft_length);
    for (int b = 0; b < kBandGainBands; ++b) {
      const double lower = b == 0 ? 1.0 : crossfade(hz, kBandEdgesHz[b - 1]);
      const double upper = b + 1 < kBandGainBands ? crossfade(hz, kBandEdgesHz[b]) : 0.0;
      out[size_t(b)][size_t(i)] = float(lower - upper);
    }
  }
  return out;
}

torch::Tensor band_gain_response_tensor(int64_t fft_length) {
  const auto rows = band_gain_responses(fft_length);
  torch::Tensor t = torch::empty({int64_t(rows.size()), int64_t(rows[0].size())});
  for (size_t b = 0; b < rows.size(); ++b) {
    std::memcpy(t[int64_t(b)].data_ptr<float>(), rows[b].data(), rows[b].size() * sizeof(float));
  }
  return t;
}

KnotPosition knot_positions(const torch::Tensor& onset, int64_t length, double sample_rate_hz) {
  torch::NoGradGuard no_grad;
  const torch::Tensor knots = torch::tensor(std::vector<double>(kKnotMs, kKnotMs + kBandGainKnots),
                                            onset.options().dtype(torch::kFloat));
  const torch::Tensor position = torch::arange(length, onset.options().dtype(torch::kFloat)).view({1, 1, -1});
  const torch::Tensor ms = ((position - onset.to(torch::kFloat)) * (1000.0 / sample_rate_hz))
                               .clamp(kKnotMs[0], kKnotMs[kBandGainKnots - 1]);  // [batch, 1, n]
  // The segment [knot k, knot k + 1] holding each sample (the last segment holds the last knot).
  KnotPosition p;
  p.segment = (torch::bucketize(ms, knots, /*out_int32=*/false, /*right=*/true) - 1).clamp(0, kBandGainKnots - 2);
  const torch::Tensor from = knots.index_select(0, p.segment.flatten()).view_as(ms);
  const torch::Tensor to = knots.index_select(0, (p.segment + 1).flatten()).view_as(ms);
  p.fraction = (ms - from) / (to - from);
  return p;
}

torch::Tensor identity_held_gains(const torch::Tensor& log_gains, int direct_bands) {
  const int64_t knots = log_gains.size(2);
  const torch::Tensor after = log_gains.narrow(2, kDirectSoundKnots, knots - kDirectSoundKnots).flatten(1);
  if (direct_bands <= 0) return after;
  return torch::cat({after, log_gains.narrow(1, 0, direct_bands).narrow(2, 0, kDirectSoundKnots).flatten(1)}, 1);
}

torch::Tensor direct_gains_above(const torch::Tensor& log_gains, int first_band) {
  const int64_t bands = log_gains.size(1) - first_band;
  if (bands <= 0) return torch::Tensor();
  return log_gains.narrow(1, first_band, bands).narrow(2, 0, kDirectSoundKnots).flatten(1);
}

torch::Tensor interpolate_knots(const torch::Tensor& values, const KnotPosition& at) {
  const int64_t batch = values.size(0), rows = values.size(1), n = at.segment.size(-1);
  const torch::Tensor segment = at.segment.expand({batch, rows, n});
  const torch::Tensor from = values.gather(2, segment), to = values.gather(2, segment + 1);
  return from + (to - from) * at.fraction;
}

BandGainImpl::BandGainImpl(int feature_channels) {
  // Mean and maximum over positions of each feature channel -> one log gain per band and per
  // knot but the first (the direct-sound window's two knots share one value).
  head = register_module("head", torch::nn::Linear(2 * feature_channels, kBandGainBands * (kBandGainKnots - 1)));
  torch::NoGradGuard no_grad;
  head->weight.zero_();
  head->bias.zero_();
  fft_length_ = 18432;  // 2^11 * 9 >= 16384 + kGuardSamples
  responses_ = register_buffer("band_responses", band_gain_response_tensor(fft_length_));
}

torch::Tensor BandGainImpl::knot_log_gains(const torch::Tensor& features) {
  torch::Tensor pooled = torch::cat({features.mean(-1), std::get<0>(features.max(-1))}, 1).to(torch::kFloat);
  // At unit RMS over the channels, and the head's output scaled down: RMSProp moves every weight
  // by about the learning rate per step whatever its gradient, so the gain of a head fed with
  // raw features (hundreds of channels of O(1-10) activations) moved by ~0.05 neper per step
  // and ran to its +-24 dB bound within the first hundred steps, where the tanh no longer passes
  // a gradient (a width-16 run, bench/RESULTS.md). With these, a step moves a gain by at most
  // ~kHeadScale * lr * channels (4e-3 neper at width 16).
  pooled = pooled / pooled.pow(2).mean(1, true).sqrt().clamp_min(1e-6);
  const torch::Tensor raw =
      kHeadScale * head->forward(pooled.to(features.scalar_type())).to(torch::kFloat).view({-1, kBandGainBands, kBandGainKnots - 1});
  // Bounded: a log gain of L * tanh(raw / L) nepers, L = kMaxGainDb in nepers (amplitude).
  const double limit = kMaxGainDb * std::log(10.0) / 20.0;
  const torch::Tensor v = limit * torch::tanh(raw / limit);
  return torch::cat({v.narrow(2, 0, 1), v}, 2);  // the direct-sound value at both of its knots
}

torch::Tensor BandGainImpl::band_signals(const torch::Tensor& input) {
  const int64_t n = input.size(-1);
  torch::Tensor responses = responses_;
  int64_t fft_length = fft_length_;
  if (n != kSliceLength) {  // other lengths (tests): responses for their own FFT length
    fft_length = n + kGuardSamples;
    responses = band_gain_response_tensor(fft_length).to(input.device());
  }
  // float32: the CPU FFT has no bfloat16.
  const torch::Tensor spectrum = torch::fft::rfft(input.to(torch::kFloat), fft_length, -1);  // [batch, 1, bins]
  return torch::fft::irfft(spectrum * responses.to(torch::kFloat), fft_length, -1).narrow(-1, 0, n);
}

torch::Tensor BandGainImpl::forward(const torch::Tensor& input, const torch::Tensor& features,
                                    const torch::Tensor& onset, torch::Tensor* log_gains) {
  const int64_t n = input.size(-1);
  const torch::Tensor knots = knot_log_gains(features);
  if (log_gains) *log_gains = knots;
  const torch::Tensor log_gain = interpolate_knots(knots, knot_positions(onset, n, kRateHz));
  return (torch::expm1(log_gain) * band_signals(input)).sum(1, true);
}

}  // namespace gan
}  // namespace tsrir

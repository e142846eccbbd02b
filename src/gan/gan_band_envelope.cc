#include "gan/gan_band_envelope.h"

#include <cmath>
#include <string>
#include <vector>

#include <torch/fft.h>

#include "gan/gan_band_gain.h"
#include "gan/gan_networks.h"

namespace tsrir {
namespace gan {
namespace {

constexpr int kEnvelopeLayers = 3;
constexpr int kEnvelopeKernel = 5;

int64_t frame_count(int64_t n) { return (n - kEnvelopeFrameLength) / kEnvelopeHop + 1; }

// The power spectrum's sum over the bins of each frame [..., L] as the envelope frames it.
torch::Tensor frame_power(const torch::Tensor& windowed) {
  // (|X|^2 as re^2 + im^2: the complex abs has no gradient at 0)
  return torch::view_as_real(torch::fft::rfft(windowed, kEnvelopeFrameLength, -1)).pow(2).sum(-1);
}

// [batch, 1, 1]: the energy of signal [batch, n] in its peak +-kDirectHalfWindow samples as one
// cell of all bands would hold it: that stretch at a frame's centre (samples outside the signal
// count as 0), windowed, its power summed over the bins (the band responses sum to 1 at every bin).
torch::Tensor direct_sound_cell(const torch::Tensor& signal, const torch::Tensor& window) {
  const int64_t n = signal.size(-1);
  const torch::Tensor peak = signal.abs().argmax(-1, true);  // [batch, 1]
  const torch::Tensor index = peak + torch::arange(-kDirectHalfWindow, kDirectHalfWindow, peak.options());
  const torch::Tensor inside = (index >= 0).logical_and(index < n);
  const torch::Tensor direct = signal.gather(-1, index.clamp(0, n - 1)) * inside;  // [batch, 2 * half]
  const torch::Tensor centre = window.narrow(0, kEnvelopeFrameLength / 2 - kDirectHalfWindow, 2 * kDirectHalfWindow);
  const torch::Tensor frame = torch::constant_pad_nd(direct * centre, {kEnvelopeFrameLength / 2 - kDirectHalfWindow,
                                                                       kEnvelopeFrameLength / 2 - kDirectHalfWindow});
  return frame_power(frame).sum(-1).view({-1, 1, 1});
}

}  // namespace

torch::Tensor envelope_window() { return torch::hann_window(kEnvelopeFrameLength, torch::kFloat); }

torch::Tensor envelope_band_responses() { return band_gain_response_tensor(kEnvelopeFrameLength); }

torch::Tensor band_log_envelope(const torch::Tensor& x, const torch::Tensor& window, const torch::Tensor& responses,
                                const GanEnvelopeMap& map) {
  const torch::Tensor signal = x.to(torch::kFloat).squeeze(1);  // [batch, n]
  const torch::Tensor frames = signal.unfold(-1, kEnvelopeFrameLength, kEnvelopeHop) * window;  // [batch, F, L]
  const torch::Tensor power = frame_power(frames);  // [batch, F, bins]
  const torch::Tensor energy = torch::matmul(responses, power.transpose(1, 2));  // [batch, bands, F]
  // Relative to the reference, floored below it: the same map at any gain.
  const torch::Tensor level = map.reference == GanEnvelopeReference::kLoudestCell
                                  ? std::get<0>(energy.flatten(1).max(1)).view({-1, 1, 1})
                                  : direct_sound_cell(signal, window);
  const double floor = std::pow(10.0, map.floor_db / 10.0);
  return torch::log10(energy / level.clamp_min(1e-30) + floor) * 0.5;  // 10 log10(.) / 20 dB
}

EnvelopeCriticImpl::EnvelopeCriticImpl(int width, int64_t slice_length, GanInit init, EnvelopeCriticKind kind,
                                       const GanEnvelopeMap& map)
    : kind_(kind), map_(map) {
  // Separable: each layer's channels are the bands' own groups, half the joint form's channels in
  // each band (5.5x the joint form's in all; the joint form's in each would be 11x).
  const int64_t groups = kind == EnvelopeCriticKind::kSeparable ? kBandGainBands : 1;
  int64_t in = kBandGainBands, frames = frame_count(slice_length);
  for (int i = 0; i < kEnvelopeLayers; ++i) {
    const int64_t out = groups == 1 ? int64_t(width) << (i + 1) : groups * (int64_t(width) << i);
    // Stride 2, padding k/2: ceil(F / 2) frames out, 'same' as the waveform critic's layers.
    auto conv = torch::nn::Conv1d(
        torch::nn::Conv1dOptions(in, out, kEnvelopeKernel).stride(2).padding(kEnvelopeKernel / 2).groups(groups));
    init_layer(conv->weight, conv->bias, init, double(in / groups) * kEnvelopeKernel);
    down_.push_back(register_module("envelope_conv_" + std::to_string(i), conv));
    in = out;
    frames = (frames + 1) / 2;
  }
  if (kind == EnvelopeCriticKind::kJoint) {
    output_ = register_module("envelope_output", torch::nn::Linear(in * frames, 1));
    init_layer(output_->weight, output_->bias, GanInit::kGlorot, 0.0);
  } else {
    // A band's linear logit of all its channels and frames: a grouped convolution as long as the frames.
    band_output_ = register_module("envelope_band_output",
                                   torch::nn::Conv1d(torch::nn::Conv1dOptions(in, groups, frames).groups(groups)));
    init_layer(band_output_->weight, band_output_->bias, GanInit::kGlorot, 0.0);
  }
  window_ = register_buffer("envelope_window", envelope_window());
  responses_ = register_buffer("envelope_band_responses", envelope_band_responses());
}

torch::Tensor EnvelopeCriticImpl::forward(const torch::Tensor& x) {
  return logit_of_levels(band_log_envelope(x, window_, responses_, map_).to(x.scalar_type()));
}

torch::Tensor EnvelopeCriticImpl::logit_of_levels(const torch::Tensor& levels) {
  torch::Tensor h = levels;
  for (auto& layer : down_) h = torch::leaky_relu(layer->forward(h), 0.2);
  if (kind_ == EnvelopeCriticKind::kJoint) return output_->forward(h.flatten(1)).squeeze(1);
  // The bands' mean, not their sum: RMSProp moves every weight about as far per step whatever its
  // gradient, and this last layer has 5.5x the joint one's inputs, so a sum moved the logit ~5x
  // further per step (on R3VIVAL its discriminator losses ran 10-50x the joint critic's; bench/RESULTS.md).
  return band_output_->forward(h).flatten(1).mean(1);  // [batch, bands, 1] -> [batch]
}

}  // namespace gan
}  // namespace tsrir

#include "gan/gan_networks.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <tuple>
#include <utility>

#include <c10/core/InferenceMode.h>
#include <torch/fft.h>

#include "gan/gan_binwise_product.h"
#include "gan/gan_weight_average.h"
#include "util/error.h"

namespace tsrir {
namespace gan {
namespace {

constexpr double kResidualInitGain = 0.1;

// The smallest 2^a 3^b 5^c >= n (lengths pocketfft and MKL transform fastest).
int64_t fast_fft_length(int64_t n) {
  for (int64_t m = std::max<int64_t>(n, 1);; ++m) {
    int64_t r = m;
    for (int64_t p : {2, 3, 5}) {
      while (r % p == 0) r /= p;
    }
    if (r == 1) return m;
  }
}

}  // namespace

void init_layer(torch::Tensor& weight, torch::Tensor& bias, GanInit init, double fan) {
  if (init == GanInit::kLoaded) return;
  torch::NoGradGuard no_grad;
  if (init == GanInit::kHe) {
    const double limit = std::sqrt(6.0 / fan);  // uniform, variance 2/fan (ReLU gain)
    weight.uniform_(-limit, limit);
  } else {
    // Glorot's limit depends on fan_in + fan_out only, so torch's [out, in, k] and TF's
    // [k, in, out] layouts give the same distribution.
    torch::nn::init::xavier_uniform_(weight);
  }
  torch::nn::init::zeros_(bias);
}

ConvParametersImpl::ConvParametersImpl(int in_channels, int out_channels, int kernel_length) {
  weight = register_parameter("weight", torch::empty({out_channels, in_channels, kernel_length}));
  bias = register_parameter("bias", torch::empty({out_channels}));
}

void ConvParametersImpl::draw_as_torch_conv1d() {
  torch::NoGradGuard no_grad;
  torch::nn::init::kaiming_uniform_(weight, std::sqrt(5.0));
  const double fan_in = double(weight.size(1) * weight.size(2));
  torch::nn::init::uniform_(bias, -1.0 / std::sqrt(fan_in), 1.0 / std::sqrt(fan_in));
}

SameConv1dImpl::SameConv1dImpl(int in_channels, int out_channels, int kernel_length, int stride,
                               GanInit init)
    : kernel_length_(kernel_length), stride_(stride) {
  conv_ = register_module("conv", ConvParameters(in_channels, out_channels, kernel_length));
  if (init == GanInit::kLoaded) return;
  // Conv1d's own draws, then ours over them: the random numbers every model so far was made with.
  conv_->draw_as_torch_conv1d();
  init_layer(conv_->weight, conv_->bias, init, double(in_channels) * kernel_length);
}

torch::Tensor SameConv1dImpl::forward_direct(const torch::Tensor& x) {
  const int64_t length = x.size(2);
  const int64_t out = (length + stride_ - 1) / stride_;
  const int64_t pad_total = std::max<int64_t>((out - 1) * stride_ + kernel_length_ - length, 0);
  const int64_t left = pad_total / 2;
  return torch::conv1d(torch::constant_pad_nd(x, {left, pad_total - left}, 0.0), conv_->weight, conv_->bias,
                       stride_);
}

torch::Tensor SameConv1dImpl::forward(const torch::Tensor& x) {
  if (!fft_applies(x)) return forward_direct(x);
  const int64_t length = x.size(2), pad_total = kernel_length_ - 1, left = pad_total / 2;
  return correlate_by_fft(torch::constant_pad_nd(x, {left, pad_total - left}, 0.0), length);
}

bool SameConv1dImpl::fft_applies(const torch::Tensor& x) const {
  // Below ~8 taps the transforms cost more than they save. Weights made under InferenceMode
  // have no version counter, so a kept spectrum could not notice their change: direct form.
  const torch::Tensor& weight = conv_->weight;
  return stride_ == 1 && kernel_length_ >= 8 && c10::InferenceMode::is_enabled() && x.device().is_cpu() &&
         x.scalar_type() == torch::kFloat && weight.scalar_type() == torch::kFloat && !weight.is_inference();
}

torch::Tensor SameConv1dImpl::correlate_by_fft(const torch::Tensor& padded, int64_t out_length) {
  // y[n] = b + sum_j padded[n + j] w[j], n < out_length: a circular correlation of length
  // fft_length >= padded length has no wrap-around there, and correlation is X * conj(W).
  const int64_t fft_length = fast_fft_length(padded.size(2));
  const torch::Tensor& weight = conv_->weight;  // [out, in, k]
  if (!kernel_spectrum_.defined() || spectrum_fft_length_ != fft_length ||
      spectrum_version_ != int64_t(weight._version()) || spectrum_weight_data_ != weight.data_ptr()) {
    // conj(W[f]) = sum_j w[j] exp(+2 pi i j f / n): two real products of the bins x k DFT
    // matrix with the taps as [k, in * out], which give the [bins, in, out] layout directly
    // (torch::fft::rfft of out * in rows of k taps padded to n, then a transposing copy, took
    // ~0.6 s per 512 x 512 layer; this ~0.05 s once its memory is mapped).
    const int64_t k = kernel_length_, bins = fft_length / 2 + 1, out = weight.size(0), in = weight.size(1);
    const torch::Tensor angle = torch::arange(bins, torch::kDouble).view({bins, 1}) *
                                torch::arange(k, torch::kDouble).view({1, k}) * (2.0 * M_PI / double(fft_length));
    const torch::Tensor taps = weight.permute({2, 1, 0}).reshape({k, in * out});
    kernel_spectrum_ = torch::complex(torch::matmul(torch::cos(angle).to(torch::kFloat), taps),
                                      torch::matmul(torch::sin(angle).to(torch::kFloat), taps))
                           .view({bins, in, out});
    spectrum_fft_length_ = fft_length;
    spectrum_version_ = int64_t(weight._version());
    spectrum_weight_data_ = weight.data_ptr();
  }
  const torch::Tensor x_spectrum = torch::fft::rfft(padded, fft_length, -1).permute({2, 0, 1});  // [bins, batch, in]
  const torch::Tensor y_spectrum = binwise_complex_matmul(x_spectrum, kernel_spectrum_);          // [bins, batch, out]
  return torch::fft::irfft(y_spectrum.permute({1, 2, 0}), fft_length, -1).narrow(-1, 0, out_length) +
         conv_->bias.view({1, -1, 1});
}

SameConvTranspose1dImpl::SameConvTranspose1dImpl(int in_channels, int out_channels, int kernel_length,
                                                 int stride, GanInit init)
    : out_channels_(out_channels), kernel_length_(kernel_length), stride_(stride) {
  weight = register_parameter("weight", torch::empty({in_channels, out_channels, kernel_length}));
  bias = register_parameter("bias", torch::empty({out_channels}));
  init_layer(weight, bias, init, double(in_channels) * kernel_length / stride);
  // Output n = s*m + r takes x[m + o] * w[j] for j = (r + p) - s*o (0 <= j < k), o an offset.
  const int s = stride, k = kernel_length, p = std::max(k - s, 0) / 2;
  auto tap = [&](int r, int o) { return r + p - s * o; };
  int o_min = 0, o_max = 0;
  for (int r = 0; r < s; ++r) {
    for (int o = -k; o <= k; ++o) {
      const int j = tap(r, o);
      if (j >= 0 && j < k) {
        o_min = std::min(o_min, o);
        o_max = std::max(o_max, o);
      }
    }
  }
  phase_taps_ = o_max - o_min + 1;
  pad_left_ = -o_min;
  pad_right_ = o_max;
  std::vector<int64_t> index;
  for (int r = 0; r < s; ++r) {
    for (int u = 0; u < phase_taps_; ++u) {
      const int j = tap(r, u + o_min);
      index.push_back(j >= 0 && j < k ? j : k);
    }
  }
  // A buffer, so module->to(device) moves it with the weights.
  phase_index_ = register_buffer("phase_index", torch::tensor(index, torch::kInt64));
}

torch::Tensor SameConvTranspose1dImpl::forward(const torch::Tensor& x) {
  const int64_t batch = x.size(0), length = x.size(2), in = weight.size(0);
  const torch::Tensor w_ext = torch::constant_pad_nd(weight, {0, 1}, 0.0);  // tap k = 0
  const torch::Tensor phase_kernels =
      // Module::to(dtype) casts buffers too, integer ones included: cast the index back.
      w_ext.index_select(2, phase_index_.to(torch::kLong))
          .view({in, out_channels_, stride_, phase_taps_})
          .permute({2, 1, 0, 3})
          .reshape({stride_ * out_channels_, in, phase_taps_});
  const torch::Tensor phases = torch::conv1d(torch::constant_pad_nd(x, {pad_left_, pad_right_}, 0.0),
                                             phase_kernels, bias.repeat({stride_}));
  return phases.view({batch, stride_, out_channels_, length})
      .permute({0, 2, 3, 1})
      .reshape({batch, out_channels_, stride_ * length});
}

std::vector<float> correction_lowpass_taps(double max_hz) {
  constexpr double kRateHz = 16000.0;
  if (!(max_hz > 0 && max_hz < kRateHz / 2)) throw Error("--correction-max-hz must be in (0, 8000) or 0");
  // Blackman-windowed sinc whose stopband (below -70 dB) starts at max_hz: a transition band of
  // max_hz / 3 (Blackman: ~5.5 fs / taps wide) below it, the -6 dB point in its middle.
  const double transition_hz = max_hz / 3.0;
  const double cutoff_hz = max_hz - transition_hz / 2.0;
  int taps = int(std::lround(5.5 * kRateHz / transition_hz)) | 1;
  taps = std::min(taps, 8191);
  const int mid = taps / 2;
  const double fc = cutoff_hz / kRateHz;
  std::vector<double> h(taps);
  double sum = 0;
  for (int n = 0; n < taps; ++n) {
    const double k = double(n - mid);
    const double sinc = k == 0 ? 2 * fc : std::sin(2 * M_PI * fc * k) / (M_PI * k);
    const double phase = 2 * M_PI * double(n) / double(taps - 1);
    h[n] = sinc * (0.42 - 0.5 * std::cos(phase) + 0.08 * std::cos(2 * phase));
    sum += h[n];
  }
  std::vector<float> out(taps);
  for (int n = 0; n < taps; ++n) out[n] = float(h[n] / sum);
  return out;
}

torch::Tensor lowpass_same(const torch::Tensor& x, const torch::Tensor& taps) {
  // Linear phase, centred: 'same' length, no delay; the same sum as
  //   conv1d(constant_pad_nd(x, {half, half}), taps)   (conv1d correlates: y[n] = sum_j x[n + j - half] taps[j])
  // computed as a linear convolution with the reversed taps through real FFTs, because the
  // direct form (529 taps at 500 Hz, one channel) costs about a third of a width-16 generator's
  // forward pass (bench/RESULTS.md, gan_forward_bench). float32 inside: the CPU FFT has no
  // bfloat16.
  const int64_t n = x.size(-1), k = taps.size(-1), half = k / 2;
  int64_t length = 1;
  while (length < n + k - 1) length *= 2;
  const torch::Tensor xf = x.to(torch::kFloat);
  const torch::Tensor reversed = taps.to(torch::kFloat).flip({-1}).view({1, 1, k});
  const torch::Tensor full = torch::fft::irfft(torch::fft::rfft(xf, length, -1) * torch::fft::rfft(reversed, length, -1),
                                               length, -1);
  return full.narrow(-1, half, n).to(x.scalar_type());
}

GeneratorSpec GeneratorSpec::of(const GanSettings& s) {
  return {s.width, s.kernel_length, s.decoder, s.generator, s.correction_max_hz, s.generator_activation};
}

GeneratorImpl::GeneratorImpl(const GeneratorSpec& spec, GanInit init) {
  negative_slope_ = spec.activation == GanActivation::kLeakyRelu ? 0.2 : 0.0;
  residual_ = spec.kind != GanGenerator::kOriginal;
  const int w = spec.width, kernel_length = spec.kernel_length;
  const int down_channels[9][2] = {{1, w},         {w, 2 * w},     {2 * w, 4 * w},
                                   {4 * w, 8 * w}, {8 * w, 8 * w}, {8 * w, 8 * w},
                                   {8 * w, 8 * w}, {8 * w, 8 * w}, {8 * w, 8 * w}};
  for (int i = 0; i < 9; ++i) {
    down_.push_back(register_module("downconv_" + std::to_string(i),
                                    SameConv1d(down_channels[i][0], down_channels[i][1], kernel_length,
                                               i < 4 ? 4 : 1, init)));
  }
  // The original's comments say 256/128/64 on the way up ("light"); its code uses dim * 16, 8, 4.
  int m[3];
  decoder_multipliers(spec.decoder, m);
  const int up_channels[4][2] = {{8 * w, m[0] * w}, {m[0] * w, m[1] * w}, {m[1] * w, m[2] * w}, {m[2] * w, 1}};
  for (int i = 0; i < 4; ++i) {
    up_.push_back(register_module("upconv_" + std::to_string(i + 1),
                                  SameConvTranspose1d(up_channels[i][0], up_channels[i][1], kernel_length, 4, init)));
  }
  if (residual_ && init != GanInit::kLoaded) {
    // The correction starts small but not zero: the last layer's initial weights are scaled down
    // 10x (-20 dB re a unit-RMS input), so a new residual generator is the identity within a small
    // random correction. Not exactly zero, because the translation has to ADD energy (room modes of
    // random phase): at a zero correction the gradient of any energy-like feature of the output
    // with respect to the correction is zero too (d|c|^2/dc = 2c), a saddle that training leaves
    // only by chance (issue 17: identical runs stayed the identity for some seeds, not others).
    torch::NoGradGuard no_grad;
    up_.back()->weight.mul_(kResidualInitGain);
    up_.back()->bias.zero_();
  }
  if (spec.correction_max_hz > 0) {
    if (!residual_) {
      throw Error("--correction-max-hz needs --generator=residual or band-gain (it band-limits the correction)");
    }
    const std::vector<float> taps = correction_lowpass_taps(spec.correction_max_hz);
    // A buffer (moves with the module), not a parameter: the band is fixed, not learned.
    lowpass_ = register_buffer("correction_lowpass",
                               torch::tensor(taps, torch::kFloat).view({1, 1, int64_t(taps.size())}));
  }
  // Registered after the other layers, so that a band-gain generator draws the same initial
  // weights as a residual one of the same seed (the head starts at zero, drawing nothing).
  if (spec.kind == GanGenerator::kBandGain) band_gain_ = register_module("band_gain", BandGain(8 * w));
}

Generator make_generator(const GanSettings& s, GanInit init) { return Generator(GeneratorSpec::of(s), init); }

torch::Tensor GeneratorImpl::activate(const torch::Tensor& x) const {
  return negative_slope_ > 0 ? torch::leaky_relu(x, negative_slope_) : torch::relu(x);
}

GeneratorPass GeneratorImpl::pass(torch::Tensor x) {
  GeneratorPass result;
  if (!residual_) {
    for (auto& layer : down_) x = activate(layer->forward(x));
    for (size_t i = 0; i + 1 < up_.size(); ++i) x = activate(up_[i]->forward(x));
    result.output = torch::tanh(up_.back()->forward(x));
    return result;
  }
  const torch::Tensor input = x;
  torch::Tensor scale, onset, mask;
  {
    // The network sees each RIR at unit RMS and its correction is scaled back by that RMS. A
    // peak-normalised RIR is mostly a quiet tail (RMS ~1e-2), so without this every hidden
    // activation is ~1e-2 and the last layer's weights would have to grow to O(1) to make a
    // correction of the input's own size: thousands of lr-sized RMSProp steps. The scale is a
    // property of the input, not learned, so no gradient flows through it.
    torch::NoGradGuard no_grad;
    scale = input.to(torch::kFloat).pow(2).mean(-1, true).sqrt().clamp_min(1e-8).to(input.scalar_type());
    // Causal: an RIR is silent before its direct sound, so nothing is added before the input's
    // onset (its first sample within 20 dB of its peak, as ISO 3382's onset).
    const torch::Tensor magnitude = input.abs().to(torch::kFloat);
    const torch::Tensor above = magnitude >= 0.1 * std::get<0>(magnitude.max(-1, true));
    onset = above.to(torch::kFloat).argmax(-1, true);  // first maximum: first true
    const torch::Tensor position = torch::arange(input.size(-1), onset.options()).view({1, 1, -1});
    mask = (position >= onset).to(input.scalar_type());
  }
  x = input / scale;
  for (auto& layer : down_) x = activate(layer->forward(x));
  const torch::Tensor features = x;
  for (size_t i = 0; i + 1 < up_.size(); ++i) x = activate(up_[i]->forward(x));
  torch::Tensor correction = up_.back()->forward(x);
  if (lowpass_.defined()) {
    // The FFT form, ~7-10x faster for this filter than the direct 529-tap sum
    // (bench/gan/gan_forward_bench --lowpass-compare=1) and equal to it within float32
    // rounding, gradient included (tests/gan). Training and translation both use it.
    correction = lowpass_same(correction, lowpass_);
  }
  // The network works at the input's unit RMS, so this is the correction's energy re the input's.
  // Only a pass with gradients can be penalised: translation and no-grad passes skip the work.
  if (torch::GradMode::is_enabled()) {
    result.correction_ms = (correction.to(torch::kFloat) * mask.to(torch::kFloat)).pow(2).mean({1, 2});
  }
  torch::Tensor added = correction.to(input.scalar_type()) * scale;
  if (!band_gain_) {
    result.output = input + added * mask;
    return result;
  }
  added = added + band_gain_->forward(input, features, onset, &result.log_gains).to(input.scalar_type());
  // At the input's peak level, as every RIR the discriminators see (the inputs are peak-normalised):
  // otherwise a stronger direct sound (a directional source) would also be a louder RIR, which no
  // real one is, and a translation would have to cut everything else instead.
  const torch::Tensor output = input + added * mask;
  torch::Tensor input_peak;
  {
    torch::NoGradGuard no_grad;
    input_peak = std::get<0>(input.abs().max(-1, true));
  }
  result.output = output * (input_peak / std::get<0>(output.abs().max(-1, true)).clamp_min(1e-8));
  return result;
}

DiscriminatorImpl::DiscriminatorImpl(int width, int kernel_length, GanInit init, GanDiscView view,
                                     const GanEnvelopeMap& envelope_map) {
  int in = 1;
  for (int i = 0; i < 5; ++i) {
    const int out = width << i;
    down_.push_back(register_module("downconv_" + std::to_string(i), SameConv1d(in, out, kernel_length, 4, init)));
    in = out;
  }
  // 16384 / 4^5 = 16 positions of 16w channels.
  output_ = register_module("output", torch::nn::Linear(16 * in, 1));
  // The linear logit keeps Glorot under either init (no ReLU follows it).
  init_layer(output_->weight, output_->bias, GanInit::kGlorot, 0.0);
  // Built after the waveform layers, so those draw the same initial weights with either view.
  if (view != GanDiscView::kWaveform) {
    const EnvelopeCriticKind kind =
        view == GanDiscView::kWaveformSeparableEnvelope ? EnvelopeCriticKind::kSeparable : EnvelopeCriticKind::kJoint;
    envelope_ = register_module("envelope", EnvelopeCritic(width, 16384, init, kind, envelope_map));
  }
}

torch::Tensor DiscriminatorImpl::forward(torch::Tensor x) {
  const torch::Tensor envelope_logit = envelope_ ? envelope_->forward(x) : torch::Tensor();
  for (auto& layer : down_) x = torch::leaky_relu(layer->forward(x), 0.2);
  x = x.transpose(1, 2).reshape({x.size(0), -1});
  const torch::Tensor logit = output_->forward(x).squeeze(1);
  return envelope_ ? logit + envelope_logit.to(logit.scalar_type()) : logit;
}

TfRmsProp::TfRmsProp(std::vector<torch::Tensor> params, double learning_rate, double decay, double epsilon,
                     double initial_mean_square)
    : params_(std::move(params)), learning_rate_(learning_rate), decay_(decay), epsilon_(epsilon) {
  for (const auto& p : params_) mean_square_.push_back(torch::full_like(p, initial_mean_square).detach());
}

void TfRmsProp::step(const std::vector<torch::Tensor>& grads) {
  torch::NoGradGuard no_grad;
  for (size_t i = 0; i < params_.size(); ++i) {
    const auto& g = grads.at(i);
    if (!g.defined()) continue;
    auto& ms = mean_square_[i];
    ms.mul_(decay_).addcmul_(g, g, 1.0 - decay_);
    params_[i].addcdiv_(g, (ms + epsilon_).sqrt_(), -learning_rate_);
  }
}

CycleGan::CycleGan(const GanSettings& s, torch::Device device) : settings(s) {
  // Construction order fixes which random numbers each network's initialiser draws.
  const GanInit init = s.init;
  g_real = make_generator(s, init);
  g_synthetic = make_generator(s, init);
  d_real = Discriminator(s.width, s.kernel_length, init, s.disc_view, s.envelope_map);
  d_synthetic = Discriminator(s.width, s.kernel_length, init, s.disc_view, s.envelope_map);
  torch::nn::Module* modules[4] = {g_real.get(), g_synthetic.get(), d_real.get(), d_synthetic.get()};
  for (auto* m : modules) {
    m->to(device);
    optimizers.emplace_back(m->parameters(), s.learning_rate, 0.9, 1e-10, s.rmsprop_initial_ms);
  }
  // Built last, so that the four networks draw the same initial weights with or without them
  // (nothing after construction draws from torch's generator); their weights are overwritten.
  if (s.generator_average_decay > 0) {
    g_real_average = make_generator(s, init);
    g_synthetic_average = make_generator(s, init);
    for (auto [average, live] : {std::pair{g_real_average, g_real}, std::pair{g_synthetic_average, g_synthetic}}) {
      average->to(device);
      start_weight_average(*average, *live);
    }
  }
}

void set_torch_threads(int num_threads) {
  torch::set_num_threads(std::max(1, num_threads));
}

torch::Device torch_device(ComputeDevice device) {
  require_compute_device(device);
  return device == ComputeDevice::kCuda ? torch::Device(torch::kCUDA) : torch::Device(torch::kCPU);
}

long long count_parameters(torch::nn::Module& module) {
  long long n = 0;
  for (const auto& p : module.parameters()) n += p.numel();
  return n;
}

}  // namespace gan

void require_compute_device(ComputeDevice device) {
  if (device != ComputeDevice::kCuda) return;
  // hasCUDA: LibTorch's CUDA library is loaded (a CUDA build whose libtorch_cuda the program links).
  if (!at::hasCUDA()) {
    throw Error("--device=cuda: this program's LibTorch has no CUDA support (Debian's libtorch is CPU-only; "
                "build against a CUDA LibTorch, and check that `ldd` on the program lists libtorch_cuda.so: "
                "docs/recipe.md, 'Building with a CUDA LibTorch')");
  }
  if (torch::cuda::device_count() == 0) {
    throw Error("--device=cuda: LibTorch has CUDA support but sees no GPU (nvidia-smi, CUDA_VISIBLE_DEVICES, "
                "the driver)");
  }
}
}  // namespace tsrir

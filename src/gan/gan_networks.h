// TS-RIRGAN networks and optimiser (LibTorch; their checkpoints: gan_checkpoint.h). Private to src/gan (and its unit
// tests): nothing outside the GAN area may include torch.
#pragma once
#include <torch/torch.h>

#include <string>
#include <vector>

#include "gan/compute_device.h"
#include "gan/gan_band_envelope.h"
#include "gan/gan_band_gain.h"
#include "gan/gan_settings.h"

namespace tsrir {
namespace gan {

// Kernel initialisation (GanInit). kGlorot is the original's (TF1 tf.layers default,
// Glorot-uniform). kHe (He-uniform, ReLU gain, fan = the inputs summed per output) is a departure
// for small CPU models: with Glorot the 13 un-normalised ReLU layers shrink the signal by ~3e-4, so
// a generator's output starts near zero and does not depend on its input for hundreds of steps.
// Biases start at zero. `fan` is the number of inputs summed into one output (in*k for a conv,
// in*k/stride for the transposed conv), used by kHe only.
// kLoaded leaves the layer as it is.
void init_layer(torch::Tensor& weight, torch::Tensor& bias, GanInit init, double fan);

// torch::nn::Conv1d's parameters under its names (weight [out, in, k], then bias [out]) without
// its module: Conv1d's constructor draws them (Kaiming-uniform) with no way to skip it, and
// SameConv1d's layers were Conv1d modules, so stored models keep their names ("conv.weight").
class ConvParametersImpl : public torch::nn::Module {
 public:
  ConvParametersImpl(int in_channels, int out_channels, int kernel_length);
  // The draws torch::nn::Conv1d's constructor makes (LibTorch 1.13 and 2.x: Kaiming-uniform with
  // a = sqrt(5), then the bias uniform in +-1/sqrt(fan_in)), in its order.
  void draw_as_torch_conv1d();
  torch::Tensor weight, bias;
};
TORCH_MODULE(ConvParameters);

// tf.layers.conv1d(padding='SAME'): out = ceil(L/s), pad_total = max((out-1)s + k - L, 0), the
// smaller half on the left. Cross-correlation, bias, Glorot-uniform kernel, zero bias.
//
// Under c10::InferenceMode (translation), a stride-1 float32 layer on the CPU computes the same
// sum by FFT: per frequency one complex [batch, in] x [in, out] product instead of k real ones
// (the frequencies shared among torch's threads, gan_binwise_product.h),
// ~6x fewer operations for k = 25 at the generator's bottleneck (length 64, 8w channels), which
// holds 62 % of the light decoder's direct-form FLOPs at width 64 (forward 1.4x faster measured,
// bench/RESULTS.md; the transposed and strided layers, 7-8 taps after their phase split, measured
// slower by FFT and stay direct). The kernel's spectrum is computed once and kept (recomputed
// when the weights change or move); training (autograd, NoGradGuard) always takes the direct
// form, so the FFT form changes translation only by float32 rounding (tests/gan:
// GanLayers.FftSameConvEqualsTheDirectForm). Cost: the kept spectrum, 2(n/2+1)/k times the
// weights' memory (n, the FFT length, >= length + k - 1): ~96 MB per bottleneck layer at width 64.
class SameConv1dImpl : public torch::nn::Module {
 public:
  SameConv1dImpl(int in_channels, int out_channels, int kernel_length, int stride,
                 GanInit init = GanInit::kGlorot);
  torch::Tensor forward(const torch::Tensor& x);
  // The direct form whatever the mode (the FFT form's reference in tests and benchmarks).
  torch::Tensor forward_direct(const torch::Tensor& x);

 private:
  bool fft_applies(const torch::Tensor& x) const;
  torch::Tensor correlate_by_fft(const torch::Tensor& padded, int64_t out_length);
  int kernel_length_, stride_;
  ConvParameters conv_{nullptr};
  // conj(rfft(weight, fft_length)) as [bins, in, out], and what it was computed from.
  torch::Tensor kernel_spectrum_;
  int64_t spectrum_fft_length_ = 0, spectrum_version_ = -1;
  const void* spectrum_weight_data_ = nullptr;
};
TORCH_MODULE(SameConv1d);

// tf.layers.conv2d_transpose(padding='SAME') on [B, 1, L, C]: out = s*L, the adjoint of the SAME
// conv, i.e. y[n] = sum over s*i + j - p = n of x[i] w[j] with p = floor((k - s)/2). The weight
// is stored as torch's ConvTranspose1d weight [in, out, k]. It is computed as ONE stride-1 conv
// with s*out channels (one per output phase, sub-kernels of ceil(k/s)+1 taps) followed by an
// interleave: LibTorch's CPU transposed convolution (col2im) is 5-40x slower than its conv.
class SameConvTranspose1dImpl : public torch::nn::Module {
 public:
  SameConvTranspose1dImpl(int in_channels, int out_channels, int kernel_length, int stride,
                          GanInit init = GanInit::kGlorot);
  torch::Tensor forward(const torch::Tensor& x);
  torch::Tensor weight, bias;

 private:
  int out_channels_, kernel_length_, stride_;
  int64_t phase_taps_ = 0, pad_left_ = 0, pad_right_ = 0;
  torch::Tensor phase_index_;  // [stride * phase_taps] indices into k (k = a zero tap)
};
TORCH_MODULE(SameConvTranspose1d);

// What a generator is built from (GanSettings' architecture fields).
struct GeneratorSpec {
  int width = 64;
  int kernel_length = 25;
  GanDecoder decoder = GanDecoder::kOriginal;
  GanGenerator kind = GanGenerator::kOriginal;
  double correction_max_hz = 0.0;
  GanActivation activation = GanActivation::kRelu;
  static GeneratorSpec of(const GanSettings& settings);
};

// What one generator pass computes beside its output, for training's penalties. Returned, not
// kept in the module, so that one generator can run on two threads at once (training's lanes,
// gan_train.cc).
struct GeneratorPass {
  torch::Tensor output;  // [batch, 1, 16384]
  // Band-gain generators: the log gains [batch, bands, knots] (nepers) (training penalises them,
  // --gain-weight); undefined for the other kinds.
  torch::Tensor log_gains;
  // Residual and band-gain generators: the waveform correction's mean square per RIR [batch], in
  // units of the input's mean square (training penalises it, --correction-weight); undefined for
  // the original generator and for a pass without gradients (translation).
  torch::Tensor correction_ms;
};

// G_SR / G_RS: 4 strided convs (w, 2w, 4w, 8w), 5 stride-1 convs (8w), 3 transposed convs
// (16w, 8w, 4w for decoder "original"; 4w, 2w, w for "light") and a transposed conv to 1 channel;
// ReLU elsewhere; no normalisation. Input and output [B, 1, 16384].
// kind original (the paper): tanh on the last layer, no skip connection, so the output is
// whatever the bottleneck (16384/256 = 64 positions) can carry of the input.
// kind residual (a departure): the last layer's output is a correction ADDED to the input, and
// that layer starts small, so a new generator is near the identity: each output starts as its own
// input and training only learns what to change. The correction is causal: zero before the
// input's onset (first sample within 20 dB of its peak), since an RIR is silent before its direct
// sound (without this, small models added sound before the direct sound and moved onsets by up
// to 17 ms). The paper's form has to rebuild every RIR's fine structure through the bottleneck;
// small CPU models never learn to and output one input-independent template instead (issue 17).
// correction_max_hz > 0 (residual, band-gain): the correction passes a fixed linear-phase
// low-pass (Blackman-windowed sinc, stopband below -70 dB from correction_max_hz up, -6 dB at 5/6
// of it) before the causal mask, so it adds low-frequency structure only (gan_settings.h says why).
// kind band-gain (the toolkit's default since issue 34; a departure): the residual's low-passed correction plus
// gan_band_gain.h's smooth gain per band and per time knot after the onset, applied to the input's
// own band signals and predicted from the bottleneck's features: the whole band's levels (direct
// sound, early energy, decay per band) can change while each input keeps its fine structure. Its
// output is scaled to the input's peak (the discriminators see peak-normalised RIRs only).
class GeneratorImpl : public torch::nn::Module {
 public:
  explicit GeneratorImpl(const GeneratorSpec& spec, GanInit init = GanInit::kGlorot);
  torch::Tensor forward(torch::Tensor x) { return pass(std::move(x)).output; }
  // The forward pass with what the penalties need. Changes nothing in the module.
  GeneratorPass pass(torch::Tensor x);

 private:
  torch::Tensor activate(const torch::Tensor& x) const;
  bool residual_ = false;
  double negative_slope_ = 0.0;  // 0: ReLU (the original); 0.2: leaky
  torch::Tensor lowpass_;  // [1, 1, taps] when band-limited, else undefined
  std::vector<SameConv1d> down_;
  std::vector<SameConvTranspose1d> up_;
  BandGain band_gain_{nullptr};  // band-gain generators only
};
TORCH_MODULE(Generator);

// D_R / D_S (WaveGAN): 5 stride-4 convs (w .. 16w) with LeakyReLU 0.2, flatten in TF's
// [length, channel] order, dense to one linear logit. Input [B, 1, 16384], output [B].
// view kWaveformEnvelope (a departure): plus gan_band_envelope.h's critic of the band levels in
// dB, whose logit is added to the waveform's; kWaveformSeparableEnvelope: the same with that critic's
// per-band form (one critic per band, their logits averaged). `envelope_map`: how that critic maps
// band energies to levels (its reference and floor; read only with an envelope view).
class DiscriminatorImpl : public torch::nn::Module {
 public:
  DiscriminatorImpl(int width, int kernel_length, GanInit init = GanInit::kGlorot,
                    GanDiscView view = GanDiscView::kWaveform, const GanEnvelopeMap& envelope_map = {});
  torch::Tensor forward(torch::Tensor x);

 private:
  std::vector<SameConv1d> down_;
  torch::nn::Linear output_{nullptr};
  EnvelopeCritic envelope_{nullptr};
};
TORCH_MODULE(Discriminator);

// tf.train.RMSPropOptimizer (momentum 0): ms <- decay*ms + (1-decay)*g^2 with ms starting at
// ONE (TF's slot initialiser, unlike torch's zeros), var <- var - lr*g/sqrt(ms + eps).
class TfRmsProp {
 public:
  // initial_mean_square: TF's 1 (the original) or 0 (torch/Keras): with 1, gradients of ~1e-3
  // give steps ~1000x smaller than lr until ms has decayed to g^2 (0.9^n = 1e-6: ~130 steps).
  TfRmsProp(std::vector<torch::Tensor> params, double learning_rate, double decay = 0.9,
            double epsilon = 1e-10, double initial_mean_square = 1.0);
  // Applies one update with gradients ordered as params() (undefined ones are skipped).
  void step(const std::vector<torch::Tensor>& grads);
  std::vector<torch::Tensor>& mean_square() { return mean_square_; }
  const std::vector<torch::Tensor>& params() const { return params_; }
  void set_learning_rate(double learning_rate) { learning_rate_ = learning_rate; }

 private:
  std::vector<torch::Tensor> params_, mean_square_;
  double learning_rate_, decay_, epsilon_;
};

// A generator as `settings` describe it (width, kernel, decoder, generator kind, correction band).
Generator make_generator(const GanSettings& settings, GanInit init);
// The low-pass taps of a band-limited correction (odd length, unit DC gain), at 16 kHz.
std::vector<float> correction_lowpass_taps(double cutoff_hz);
// x [batch, 1, n] filtered by taps [1, 1, k] (k odd), centred, 'same' length: the sum
// conv1d(constant_pad_nd(x, {k/2, k/2}), taps) computes, by FFT; differentiable; x's dtype.
torch::Tensor lowpass_same(const torch::Tensor& x, const torch::Tensor& taps);

// The four networks and their optimisers.
struct CycleGan {
  CycleGan(const GanSettings& settings, torch::Device device);
  GanSettings settings;
  Generator g_real{nullptr};        // G_SR: synthetic -> real
  Generator g_synthetic{nullptr};   // G_RS: real -> synthetic
  Discriminator d_real{nullptr};
  Discriminator d_synthetic{nullptr};
  std::vector<TfRmsProp> optimizers;  // g_real, g_synthetic, d_real, d_synthetic
  // settings.generator_average_decay > 0: the moving averages of g_real's and g_synthetic's
  // weights (gan_weight_average.h), same architecture, no gradients; null otherwise.
  Generator g_real_average{nullptr};
  Generator g_synthetic_average{nullptr};
};

void set_torch_threads(int num_threads);
// The torch device of --device (require_compute_device's Error when cuda cannot be used).
torch::Device torch_device(ComputeDevice device);
long long count_parameters(torch::nn::Module& module);

}  // namespace gan
}  // namespace tsrir

// Unit tests of the TS-RIRGAN building blocks against float64 references written from the
// TensorFlow definitions (docs/reference/spec-digest.md §3.7), plus parameter counts, optimiser and checkpoints.
#include <gtest/gtest.h>

#include <tuple>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <utility>

#include <c10/core/CPUAllocator.h>
#include <c10/core/InferenceMode.h>
#include <torch/version.h>

#include "gan/gan_bfloat16.h"
#include "gan/gan_binwise_product.h"
#include "gan/gan_checkpoint.h"
#include "gan/gan_networks.h"
#include "gan/gan_runtime.h"
#include "gan/gan_tensor_allocator.h"
#include "gan/gan_weight_average.h"
#include "util/error.h"
#include "util/remove_tree.h"

namespace fs = std::filesystem;
using namespace tsrir;
using namespace tsrir::gan;

namespace {

GeneratorSpec spec_of(int width, GanDecoder decoder = GanDecoder::kOriginal, GanGenerator kind = GanGenerator::kOriginal,
                      double correction_max_hz = 0.0) {
  GeneratorSpec spec;
  spec.width = width;
  spec.decoder = decoder;
  spec.kind = kind;
  spec.correction_max_hz = correction_max_hz;
  return spec;
}

// TF conv1d SAME, stride s: y[c_out][m] = b + sum_{c,j} x[c][s*m + j - left] w[c_out][c][j].
std::vector<double> reference_same_conv(const torch::Tensor& x, const torch::Tensor& w,
                                        const torch::Tensor& b, int s, int64_t* out_len) {
  const int64_t cin = x.size(0), L = x.size(1), cout = w.size(0), k = w.size(2);
  const int64_t out = (L + s - 1) / s;
  const int64_t left = std::max<int64_t>((out - 1) * s + k - L, 0) / 2;
  auto xa = x.accessor<float, 2>();
  auto wa = w.accessor<float, 3>();
  std::vector<double> y(cout * out);
  for (int64_t co = 0; co < cout; ++co) {
    for (int64_t m = 0; m < out; ++m) {
      double acc = b[co].item<double>();
      for (int64_t c = 0; c < cin; ++c) {
        for (int64_t j = 0; j < k; ++j) {
          const int64_t i = s * m + j - left;
          if (i >= 0 && i < L) acc += double(xa[c][i]) * wa[co][c][j];
        }
      }
      y[co * out + m] = acc;
    }
  }
  *out_len = out;
  return y;
}

// TF conv2d_transpose SAME, stride s: y[n] = b + sum over s*i + j - left = n of x[i] w[j],
// n in [0, s*L), left = floor((k - s)/2); w as [in, out, k].
std::vector<double> reference_same_conv_transpose(const torch::Tensor& x, const torch::Tensor& w,
                                                  const torch::Tensor& b, int s) {
  const int64_t cin = x.size(0), L = x.size(1), cout = w.size(1), k = w.size(2);
  const int64_t left = (k - s) / 2, n_out = s * L;
  auto xa = x.accessor<float, 2>();
  auto wa = w.accessor<float, 3>();
  std::vector<double> y(cout * n_out);
  for (int64_t co = 0; co < cout; ++co) {
    for (int64_t n = 0; n < n_out; ++n) y[co * n_out + n] = b[co].item<double>();
    for (int64_t c = 0; c < cin; ++c) {
      for (int64_t i = 0; i < L; ++i) {
        for (int64_t j = 0; j < k; ++j) {
          const int64_t n = s * i + j - left;
          if (n >= 0 && n < n_out) y[co * n_out + n] += double(xa[c][i]) * wa[c][co][j];
        }
      }
    }
  }
  return y;
}

double max_abs_diff(const torch::Tensor& got, const std::vector<double>& want) {
  auto g = got.contiguous().view({-1});
  EXPECT_EQ(g.numel(), int64_t(want.size()));
  double worst = 0.0;
  for (int64_t i = 0; i < g.numel(); ++i) worst = std::max(worst, std::abs(g[i].item<double>() - want[i]));
  return worst;
}

std::string temp_dir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("tsrir_gan_test_" + name + "_" + std::to_string(::getpid()));
  remove_tree(p.string());
  fs::create_directories(p);
  return p.string();
}

}  // namespace

// Float32 accumulation of at most 25*16 products of O(1) values: 1e-4 absolute is ~100 ulp.
TEST(GanLayers, SameConvMatchesTensorFlowDefinition) {
  torch::manual_seed(1);
  for (int stride : {1, 4}) {
    for (int64_t L : {64, 256, 67}) {
      SameConv1d conv(3, 5, 25, stride);
      torch::NoGradGuard no_grad;
      conv->named_parameters()["conv.bias"].uniform_(-0.5, 0.5);
      const torch::Tensor x = torch::randn({1, 3, L});
      int64_t out_len = 0;
      const auto want = reference_same_conv(x[0], conv->named_parameters()["conv.weight"],
                                            conv->named_parameters()["conv.bias"], stride, &out_len);
      const torch::Tensor y = conv->forward(x);
      ASSERT_EQ(y.size(2), out_len) << "stride " << stride << " L " << L;
      EXPECT_LT(max_abs_diff(y[0], want), 1e-4) << "stride " << stride << " L " << L;
    }
  }
}

// Translation's FFT form of a stride-1 layer (InferenceMode, float32, CPU) against the float64
// reference written from TF's definition, beside the direct form: same 1e-4 bound (O(1) values,
// at most 25 * 16 products). Then the kept kernel spectrum must follow the weights: changed in
// place (an optimiser step) or replaced (a checkpoint load), the FFT form still equals the new
// direct form; and a layer whose weights were made under InferenceMode (no version counter)
// takes the direct form, bit for bit.
// SameConv1d's layers were torch::nn::Conv1d modules until 2026-12-05; their parameters now live in
// ConvParameters, which draws what Conv1d's constructor drew, in its order, so that a seed gives the
// models it gave before (and every fidelity run stands). Checked against LibTorch's own Conv1d; and
// a generator built to receive stored weights (GanInit::kLoaded) draws none for its layers.
TEST(GanLayers, ConvParametersDrawAsTorchConv1dAndLoadedGeneratorsDrawNothing) {
  for (const auto& [in, out, k] : {std::tuple{1, 4, 25}, std::tuple{16, 32, 25}, std::tuple{3, 5, 7}}) {
    torch::manual_seed(11);
    torch::nn::Conv1d reference(torch::nn::Conv1dOptions(in, out, k));
    const torch::Tensor after_reference = torch::rand({4});
    torch::manual_seed(11);
    ConvParameters drawn(in, out, k);
    drawn->draw_as_torch_conv1d();
    EXPECT_TRUE(torch::equal(drawn->weight, reference->weight)) << in << " " << out << " " << k;
    EXPECT_TRUE(torch::equal(drawn->bias, reference->bias)) << in << " " << out << " " << k;
    EXPECT_TRUE(torch::equal(torch::rand({4}), after_reference));  // the same number of draws
    ASSERT_EQ(drawn->named_parameters().keys(), reference->named_parameters().keys());
  }
  GanSettings settings;
  settings.width = 4;
  settings.generator = GanGenerator::kResidual;
  settings.correction_max_hz = 500;
  torch::manual_seed(12);
  const torch::Tensor first = torch::rand({4});
  torch::manual_seed(12);
  make_generator(settings, GanInit::kLoaded);
  EXPECT_TRUE(torch::equal(torch::rand({4}), first)) << "a generator built for stored weights drew random numbers";
  // A band-gain generator's head is a torch::nn::Linear, whose constructor draws (0.3 % of the
  // weights at width 64): exactly that, nothing more.
  settings.generator = GanGenerator::kBandGain;
  torch::manual_seed(12);
  BandGain(8 * settings.width);
  const torch::Tensor after_head = torch::rand({4});
  torch::manual_seed(12);
  make_generator(settings, GanInit::kLoaded);
  EXPECT_TRUE(torch::equal(torch::rand({4}), after_head));
  torch::manual_seed(12);
  make_generator(settings, GanInit::kHe);
  EXPECT_FALSE(torch::equal(torch::rand({4}), first));
}

TEST(GanLayers, FftSameConvEqualsTheDirectForm) {
  torch::manual_seed(31);
  for (int kernel : {25, 9}) {
    for (int64_t L : {64, 67, 256}) {
      SameConv1d conv(16, 8, kernel, 1);
      {
        torch::NoGradGuard no_grad;
        conv->named_parameters()["conv.bias"].uniform_(-0.5, 0.5);
      }
      const torch::Tensor x = torch::randn({3, 16, L});
      torch::Tensor fft_form, direct_form;
      {
        c10::InferenceMode inference;
        fft_form = conv->forward(x);
        direct_form = conv->forward_direct(x);
      }
      ASSERT_EQ(fft_form.sizes(), direct_form.sizes());
      EXPECT_FALSE(torch::equal(fft_form, direct_form)) << "the FFT form was not taken (kernel " << kernel << ")";
      for (int b = 0; b < 3; ++b) {
        int64_t out_len = 0;
        const auto want = reference_same_conv(x[b], conv->named_parameters()["conv.weight"],
                                              conv->named_parameters()["conv.bias"], 1, &out_len);
        EXPECT_LT(max_abs_diff(fft_form[b], want), 1e-4) << "kernel " << kernel << " L " << L;
      }
      EXPECT_LT((fft_form - direct_form).abs().max().item<double>(), 1e-4);
    }
  }
  SameConv1d conv(8, 8, 25, 1);
  const torch::Tensor x = torch::randn({2, 8, 64});
  auto fft_vs_direct = [&] {
    c10::InferenceMode inference;
    return (conv->forward(x) - conv->forward_direct(x)).abs().max().item<double>();
  };
  EXPECT_LT(fft_vs_direct(), 1e-4);
  torch::Tensor weight = conv->named_parameters()["conv.weight"];
  {
    torch::NoGradGuard no_grad;
    weight.mul_(-3.0);  // in place: same storage, new version
  }
  EXPECT_LT(fft_vs_direct(), 3e-4) << "kept spectrum not recomputed after an in-place change";
  {
    torch::NoGradGuard no_grad;
    weight.set_(torch::randn(weight.sizes()));  // new storage
  }
  EXPECT_LT(fft_vs_direct(), 1e-4) << "kept spectrum not recomputed after the weights were replaced";
  c10::InferenceMode inference;
  SameConv1d made_in_inference(8, 8, 25, 1);
  EXPECT_TRUE(torch::equal(made_in_inference->forward(x), made_in_inference->forward_direct(x)));
}

// The FFT form's per-bin products shared among threads (one cgemm per bin, gan_binwise_product.h)
// against complex128 products done by torch (zgemm, another routine and precision), on sizes
// that are not multiples of anything and an input that is a permuted view, as correlate_by_fft
// passes it; then the whole FFT convolution with the sharing on and off against the direct form.
TEST(GanLayers, BinwiseProductSharedAmongThreadsEqualsEachBinsProduct) {
  set_openblas_threads(1);  // as every program sets it
  set_torch_threads(2);
#if TORCH_VERSION_MAJOR >= 2
  // pip/conda LibTorch 2.x brings MKL, not OpenBLAS: no cblas_cgemm to share, so the products take
  // torch::matmul (which every other test here goes through). Debian's 1.13 must have it.
  if (!binwise_product_is_parallel()) GTEST_SKIP() << "no OpenBLAS cblas_cgemm in this LibTorch's process";
#endif
  ASSERT_TRUE(binwise_product_is_parallel()) << "OpenBLAS's cblas_cgemm not found in the process, or torch has one thread";
  torch::manual_seed(33);
  const int64_t bins = 7, rows = 3, inner = 37, cols = 5;
  const torch::Tensor x =
      torch::complex(torch::randn({rows, inner, bins}), torch::randn({rows, inner, bins})).permute({2, 0, 1});
  const torch::Tensor w = torch::complex(torch::randn({bins, inner, cols}), torch::randn({bins, inner, cols}));
  ASSERT_FALSE(x.is_contiguous());
  const torch::Tensor shared = binwise_complex_matmul(x, w);
  const torch::Tensor want = torch::matmul(x.to(torch::kComplexDouble), w.to(torch::kComplexDouble));
  ASSERT_EQ(shared.sizes(), want.sizes());
  const double scale = want.abs().max().item<double>();
  EXPECT_LT((shared.to(torch::kComplexDouble) - want).abs().max().item<double>() / scale, 1e-6);

  allow_parallel_binwise_product(false);
  EXPECT_FALSE(binwise_product_is_parallel());
  EXPECT_TRUE(torch::equal(binwise_complex_matmul(x, w), torch::matmul(x, w))) << "the switch did not give torch::matmul";
  allow_parallel_binwise_product(true);
  set_openblas_threads(2);
  EXPECT_FALSE(binwise_product_is_parallel()) << "a threaded OpenBLAS must not be called from several threads";
  set_openblas_threads(1);

  SameConv1d conv(24, 20, 25, 1);
  const torch::Tensor signal = torch::randn({5, 24, 83});
  c10::InferenceMode inference;
  const torch::Tensor direct = conv->forward_direct(signal);
  const torch::Tensor parallel_form = conv->forward(signal);
  allow_parallel_binwise_product(false);
  const torch::Tensor serial_form = conv->forward(signal);
  allow_parallel_binwise_product(true);
  EXPECT_LT((parallel_form - direct).abs().max().item<double>(), 1e-4);
  EXPECT_LT((parallel_form - serial_form).abs().max().item<double>(), 1e-5);
}

// The default generator (width 16, residual, 500 Hz correction, light decoder) under InferenceMode
// (gas-to-real; FFT form at the bottleneck) against the same generator under NoGradGuard (direct
// form, as in training): the corrections (output minus input, what the network adds) equal
// within float32 rounding. A new generator's correction (last layer scaled to 10 %) is used: it is
// the whole network's output, so the comparison sees every layer, not the input passed through.
TEST(GanNetworks, TranslationForwardEqualsTrainingForward) {
  torch::manual_seed(32);
  Generator g(spec_of(16, GanDecoder::kLight, GanGenerator::kResidual, 500.0), GanInit::kHe);
  torch::Tensor x = torch::randn({2, 1, 16384}) * 0.05;
  x.narrow(2, 200, 1).fill_(1.0);
  torch::Tensor training, translation;
  {
    torch::NoGradGuard no_grad;
    training = g->forward(x);
  }
  {
    c10::InferenceMode inference;
    translation = g->forward(x);
  }
  const double correction = (training - x).norm().item<double>() / x.norm().item<double>();
  EXPECT_GT(correction, 1e-3) << "the correction is too small for the comparison to mean anything";
  const double difference = ((translation - training).norm() / (training - x).norm()).item<double>();
  std::cerr << "relative correction " << correction << ", FFT vs direct (of the correction) " << difference << "\n";
  EXPECT_LT(difference, 1e-5);
}

TEST(GanLayers, SameConvTransposeMatchesTensorFlowDefinition) {
  torch::manual_seed(2);
  for (int kernel : {25, 8}) {
    SameConvTranspose1d up(4, 3, kernel, 4);
    torch::NoGradGuard no_grad;
    up->bias.uniform_(-0.5, 0.5);
    const torch::Tensor x = torch::randn({2, 4, 64});
    const torch::Tensor y = up->forward(x);
    ASSERT_EQ(y.size(2), 256);
    for (int b = 0; b < 2; ++b) {
      EXPECT_LT(max_abs_diff(y[b], reference_same_conv_transpose(x[b], up->weight, up->bias, 4)), 1e-4)
          << "kernel " << kernel;
    }
  }
}

// The transposed layer's gradient must be that of the definition: compare with LibTorch's own
// ConvTranspose1d (padding 10, cropped), an independent implementation of the same operator.
TEST(GanLayers, SameConvTransposeGradientMatchesLibTorch) {
  torch::manual_seed(3);
  SameConvTranspose1d up(6, 5, 25, 4);
  const torch::Tensor x = torch::randn({2, 6, 32}, torch::requires_grad());
  const torch::Tensor g_out = torch::randn({2, 5, 128});
  const torch::Tensor ours = (up->forward(x) * g_out).sum();
  const auto ours_grads = torch::autograd::grad({ours}, {x, up->weight, up->bias});
  const torch::Tensor w = up->weight.detach().clone().requires_grad_(true);
  const torch::Tensor b = up->bias.detach().clone().requires_grad_(true);
  const torch::Tensor theirs =
      (torch::conv_transpose1d(x, w, b, 4, 10).narrow(2, 0, 128) * g_out).sum();
  const auto their_grads = torch::autograd::grad({theirs}, {x, w, b});
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT((ours_grads[i] - their_grads[i]).abs().max().item<double>(), 1e-3) << "gradient " << i;
  }
}

// Spec-digest §3.2/3.3 counts for the paper's width: 66.57 M per generator, 17.43 M per
// discriminator (exact: derived from the layer table).
TEST(GanNetworks, PaperWidthParameterCountsAndShapes) {
  Generator g(spec_of(64));
  Discriminator d(64, 25);
  const long long conv = 25;
  const long long g_expected = conv * (1 * 64 + 64 * 128 + 128 * 256 + 256 * 512 + 5 * 512 * 512 +
                                       512 * 1024 + 1024 * 512 + 512 * 256 + 256 * 1) +
                               (64 + 128 + 256 + 512 + 5 * 512 + 1024 + 512 + 256 + 1);
  EXPECT_EQ(count_parameters(*g), g_expected);
  EXPECT_NEAR(count_parameters(*g) / 1e6, 66.57, 0.01);
  EXPECT_NEAR(count_parameters(*d) / 1e6, 17.43, 0.01);
  Generator small(spec_of(4));
  Discriminator small_d(4, 25);
  torch::NoGradGuard no_grad;
  const torch::Tensor x = torch::randn({2, 1, 16384});
  const torch::Tensor y = small->forward(x);
  EXPECT_EQ(y.sizes(), x.sizes());
  EXPECT_LE(y.abs().max().item<double>(), 1.0);  // tanh output
  EXPECT_EQ(small_d->forward(x).sizes(), torch::IntArrayRef({2}));
}

// Glorot-uniform: every kernel value within sqrt(6/(fan_in+fan_out)), variance limit^2/3.
TEST(GanNetworks, GlorotUniformInitialisation) {
  torch::manual_seed(4);
  SameConv1d conv(64, 128, 25, 4);
  const torch::Tensor w = conv->named_parameters()["conv.weight"];
  const double limit = std::sqrt(6.0 / (25.0 * (64 + 128)));
  EXPECT_LE(w.abs().max().item<double>(), limit);
  EXPECT_NEAR(w.var().item<double>(), limit * limit / 3.0, 0.02 * limit * limit);
  EXPECT_EQ(conv->named_parameters()["conv.bias"].abs().max().item<double>(), 0.0);
}

// The light decoder (the original's code comments: 256/128/64 up channels at width 64) is the
// 41.4 M-parameter generator the toolchain's speed figures were measured with.
TEST(GanNetworks, LightDecoderParameterCount) {
  Generator g(spec_of(64, GanDecoder::kLight));
  const long long g_expected = 25LL * (1 * 64 + 64 * 128 + 128 * 256 + 256 * 512 + 5 * 512 * 512 +
                                       512 * 256 + 256 * 128 + 128 * 64 + 64 * 1) +
                               (64 + 128 + 256 + 512 + 5 * 512 + 256 + 128 + 64 + 1);
  EXPECT_EQ(count_parameters(*g), g_expected);
  EXPECT_NEAR(count_parameters(*g) / 1e6, 41.4, 0.05);
}

// --generator=residual: output = input + a correction. A new generator starts NEAR its input (the
// last layer's kernels are He x 0.1, not zero: an all-zero last layer is a saddle where no hidden
// layer gets gradient); the original's tanh generator does not start near it at all.
TEST(GanNetworks, ResidualGeneratorStartsNearTheIdentity) {
  torch::manual_seed(7);
  Generator residual(spec_of(4, GanDecoder::kLight, GanGenerator::kResidual), GanInit::kHe);
  Generator original(spec_of(4, GanDecoder::kLight), GanInit::kHe);
  torch::Tensor x = torch::randn({3, 1, 16384}) * 0.1;
  x.narrow(2, 0, 1).fill_(1.0);  // onset at the first sample: the whole RIR may be corrected
  torch::NoGradGuard no_grad;
  auto relative = [&](const torch::Tensor& y) { return ((y - x).norm() / x.norm()).item<double>(); };
  const double r = relative(residual->forward(x));
  EXPECT_GT(r, 1e-4);
  EXPECT_LT(r, 0.3);
  EXPECT_GT(relative(original->forward(x)), 0.5);
  EXPECT_EQ(count_parameters(*residual), count_parameters(*original));
  // The correction is causal: samples before each input's onset (its first sample within 20 dB of
  // the peak) stay exactly the input's.
  torch::Tensor rir = torch::zeros({2, 1, 16384});
  rir[0][0][300] = 1.0, rir[1][0][5000] = -1.0;
  rir.narrow(2, 6000, 4000).normal_(0, 0.02);
  for (auto& p : residual->parameters()) p.normal_(0, 0.05);
  const torch::Tensor y = residual->forward(rir);
  EXPECT_TRUE(torch::equal(y[0][0].narrow(0, 0, 300), rir[0][0].narrow(0, 0, 300)));
  EXPECT_TRUE(torch::equal(y[1][0].narrow(0, 0, 5000), rir[1][0].narrow(0, 0, 5000)));
  EXPECT_GT((y[1][0].narrow(0, 5000, 11384) - rir[1][0].narrow(0, 5000, 11384)).abs().max().item<double>(), 1e-4);
}

// --correction-weight's statistic: the mean square, per RIR, of what the residual generator added
// (output - input, read off the output, not the network's inner tensor) after the onset, divided by
// the input's mean square; zero before the onset. Undefined for the original generator and after a
// pass without gradients (translation, which nothing penalises).
TEST(GanNetworks, CorrectionMeanSquareIsWhatTheOutputAddedReTheInput) {
  torch::manual_seed(13);
  Generator g(spec_of(4, GanDecoder::kLight, GanGenerator::kResidual), GanInit::kHe);
  {
    torch::NoGradGuard no_grad;
    for (auto& p : g->parameters()) p.normal_(0, 0.05);
  }
  torch::Tensor x = torch::zeros({2, 1, 16384});
  x[0][0][200] = 1.0, x[1][0][4000] = 0.5;  // onsets at different samples, different levels
  x.narrow(2, 4100, 8000).normal_(0, 0.01);
  const GeneratorPass pass = g->pass(x);
  const torch::Tensor added = (pass.output - x).detach().to(torch::kDouble).flatten(1);
  const torch::Tensor input_ms = x.to(torch::kDouble).flatten(1).pow(2).mean(1);
  const torch::Tensor expected = added.pow(2).mean(1) / input_ms;
  const torch::Tensor got = pass.correction_ms.detach().to(torch::kDouble);
  ASSERT_EQ(got.size(0), 2);
  for (int i = 0; i < 2; ++i) {
    EXPECT_GT(expected[i].item<double>(), 1e-8);
    EXPECT_NEAR(got[i].item<double>(), expected[i].item<double>(), 1e-3 * expected[i].item<double>());
  }
  {
    torch::NoGradGuard no_grad;
    EXPECT_FALSE(g->pass(x).correction_ms.defined());
  }
  Generator original(spec_of(4, GanDecoder::kLight), GanInit::kHe);
  EXPECT_FALSE(original->pass(x).correction_ms.defined());
}

// --correction-max-hz: whatever the weights, the correction has nothing left from max_hz up
// (stopband < -70 dB by design; asserted -60 dB of the correction's own energy, measured with a
// windowed FFT, not with the filter's taps), and the band below max_hz is corrected.
TEST(GanNetworks, BandLimitedCorrectionLeavesTheBandAboveMaxHz) {
  torch::manual_seed(11);
  const double max_hz = 500.0, fs = 16000.0;
  Generator g(spec_of(4, GanDecoder::kLight, GanGenerator::kResidual, max_hz), GanInit::kHe);
  torch::NoGradGuard no_grad;
  for (auto& p : g->parameters()) p.normal_(0, 0.05);
  torch::Tensor x = torch::randn({2, 1, 16384}) * 0.05 * torch::exp(-torch::arange(16384) / 3000.0);
  x.narrow(2, 0, 1).fill_(1.0);  // onset at sample 0: the causal mask is all ones
  const torch::Tensor c = (g->forward(x) - x).to(torch::kDouble).flatten(1);
  // Hann-windowed, so that the 16384-sample segment's own edges do not leak into the band.
  const torch::Tensor power = torch::fft::rfft(c * torch::hann_window(16384, torch::kDouble)).abs().pow(2);
  const int64_t edge = int64_t(std::ceil(max_hz * 16384 / fs));
  const double below = power.narrow(1, 0, edge).sum().item<double>();
  const double above = power.narrow(1, edge, power.size(1) - edge).sum().item<double>();
  EXPECT_GT(below, 0.0);
  EXPECT_LT(above, 1e-6 * below) << "above/below " << above / below;
  const std::vector<float> taps = correction_lowpass_taps(max_hz);
  EXPECT_EQ(taps.size() % 2, 1u);
  double dc = 0;
  for (float t : taps) dc += t;
  EXPECT_NEAR(dc, 1.0, 1e-4);
}

// The FFT form of the correction's low-pass computes the direct sum conv1d computes (float64
// reference, taps made asymmetric so that a flipped kernel would show), and its gradient too.
TEST(GanNetworks, FftLowpassEqualsTheDirectConvolution) {
  torch::manual_seed(12);
  const std::vector<float> design = correction_lowpass_taps(500.0);
  torch::Tensor taps = torch::tensor(design).view({1, 1, -1});
  taps = taps * torch::linspace(0.5, 1.5, taps.size(2)).view({1, 1, -1});  // asymmetric
  const int64_t half = taps.size(2) / 2;
  torch::Tensor x = torch::randn({3, 1, 16384}).requires_grad_(true);
  const torch::Tensor fast = lowpass_same(x, taps);
  const torch::Tensor x64 = x.detach().to(torch::kDouble).requires_grad_(true);
  const torch::Tensor direct = torch::conv1d(torch::constant_pad_nd(x64, {half, half}, 0.0), taps.to(torch::kDouble));
  ASSERT_EQ(fast.sizes(), x.sizes());
  const double error = ((fast.to(torch::kDouble) - direct).norm() / direct.norm()).item<double>();
  EXPECT_LT(error, 1e-5) << "relative RMS error " << error;  // float32 FFTs of 32768 points
  const torch::Tensor weight = torch::randn({3, 1, 16384});
  const torch::Tensor g_fast = torch::autograd::grad({(fast * weight).sum()}, {x})[0];
  const torch::Tensor g_direct = torch::autograd::grad({(direct * weight.to(torch::kDouble)).sum()}, {x64})[0];
  EXPECT_LT(((g_fast.to(torch::kDouble) - g_direct).norm() / g_direct.norm()).item<double>(), 1e-5);
  // bfloat16 in, bfloat16 out (computed in float32).
  EXPECT_EQ(lowpass_same(x.detach().to(torch::kBFloat16), taps).scalar_type(), torch::kBFloat16);
}

// The identity-free joint step (ts-rirgan-train with --identity-weight=0) runs each generator on
// its own batch instead of [own; other]: valid because an RIR's output and its gradient do not
// depend on the rest of its batch (no batch statistics anywhere in the generator). Asserted for
// the default generator (residual, 500 Hz correction, light decoder): outputs within float32
// rounding, and the weights' gradient of a loss on the first half alone is the same whether the
// second half was in the pass or not (its contribution is exactly zero).
TEST(GanNetworks, OutputAndGradientOfARirDoNotDependOnTheRestOfItsBatch) {
  torch::manual_seed(21);
  Generator g(spec_of(4, GanDecoder::kLight, GanGenerator::kResidual, 500.0), GanInit::kHe);
  for (auto& p : g->parameters()) {
    torch::NoGradGuard no_grad;
    p.mul_(3.0);  // a correction well above the initial 10 %, so the test sees the network
  }
  torch::Tensor own = torch::randn({4, 1, 16384}) * 0.05, other = torch::randn({4, 1, 16384}) * 0.05;
  own.narrow(2, 100, 1).fill_(1.0), other.narrow(2, 900, 1).fill_(-1.0);
  const torch::Tensor target = torch::randn({4, 1, 16384}) * 0.05;
  auto loss_and_grads = [&](const torch::Tensor& batch) {
    const torch::Tensor y = g->forward(batch).narrow(0, 0, 4);
    const torch::Tensor loss = (y - target).abs().mean();
    std::vector<torch::Tensor> params = g->parameters();
    return std::make_pair(y.detach(), torch::autograd::grad({loss}, params));
  };
  const auto [y_alone, grad_alone] = loss_and_grads(own);
  const auto [y_both, grad_both] = loss_and_grads(torch::cat({own, other}, 0));
  EXPECT_LT(((y_alone - y_both).norm() / y_alone.norm()).item<double>(), 1e-6);
  for (size_t i = 0; i < grad_alone.size(); ++i) {
    const double scale = grad_both[i].norm().item<double>();
    EXPECT_LE((grad_alone[i] - grad_both[i]).norm().item<double>(), 1e-4 * scale + 1e-12) << "parameter " << i;
  }
}

// He-uniform: limit sqrt(6/fan) with fan = inputs summed per output (in*k for a conv, in*k/stride
// for the transposed conv), variance 2/fan; biases zero.
TEST(GanNetworks, HeUniformInitialisation) {
  torch::manual_seed(5);
  SameConv1d conv(64, 128, 25, 4, GanInit::kHe);
  const torch::Tensor w = conv->named_parameters()["conv.weight"];
  const double limit = std::sqrt(6.0 / (64.0 * 25));
  EXPECT_LE(w.abs().max().item<double>(), limit);
  EXPECT_NEAR(w.var().item<double>(), 2.0 / (64.0 * 25), 0.02 * 2.0 / (64.0 * 25));
  SameConvTranspose1d up(128, 64, 25, 4, GanInit::kHe);
  const double up_limit = std::sqrt(6.0 / (128.0 * 25 / 4));
  EXPECT_LE(up->weight.abs().max().item<double>(), up_limit);
  EXPECT_NEAR(up->weight.var().item<double>(), up_limit * up_limit / 3.0, 0.02 * up_limit * up_limit / 3.0);
  EXPECT_EQ(up->bias.abs().max().item<double>(), 0.0);
}

// gas-to-real --precision=bfloat16: bfloat16 operands (8 significant bits, rounding 2^-9 = 0.2%)
// with float32 accumulation; over 13 layers the errors add roughly in quadrature, ~1%. Bound:
// 2% relative RMS (-34 dB), far below the changes the GAN itself makes to an RIR. Where the probe
// (gan_bfloat16.h) says this CPU's LibTorch sums in bfloat16, the same forward pass must miss that
// bound (8.7% on AMD Zen 3, LibTorch 1.13): the probe's verdict, checked on the generator itself,
// so the programs refuse bfloat16 exactly where it would break its promise.
TEST(GanNetworks, Bfloat16ForwardMatchesFloat32) {
  torch::manual_seed(7);
  Generator g(spec_of(8), GanInit::kHe);
  torch::Tensor x = torch::zeros({2, 1, 16384});
  for (int b = 0; b < 2; ++b) {
    x[b][0][300 + 500 * b] = 1.0;
    x[b][0].narrow(0, 301 + 500 * b, 6000).copy_(0.1 * torch::randn({6000}) * torch::exp(-torch::arange(6000) / 1500.0));
  }
  torch::NoGradGuard no_grad;
  const torch::Tensor y32 = g->forward(x);
  g->to(torch::kBFloat16);
  const torch::Tensor y16 = g->forward(x.to(torch::kBFloat16)).to(torch::kFloat32);
  const double relative_rms = ((y16 - y32).norm() / y32.norm()).item<double>();
  std::cerr << "bfloat16 vs float32 relative RMS difference " << relative_rms << "\n";
  EXPECT_GT(y32.norm().item<double>(), 0.0);
  if (bfloat16_convolutions_sum_in_float32()) {
    EXPECT_LT(relative_rms, 0.02);
  } else {
    EXPECT_GT(relative_rms, 0.02) << "the probe refuses bfloat16 on a CPU where it keeps its 2% bound";
  }
}

// The refusal follows the probe, and its message says what the probe saw and what to use.
TEST(GanNetworks, Bfloat16RefusalFollowsTheProbe) {
  if (bfloat16_convolutions_sum_in_float32()) {
    EXPECT_NO_THROW(require_float32_sums_for_bfloat16("gas-to-real"));
    return;
  }
  try {
    require_float32_sums_for_bfloat16("gas-to-real");
    FAIL() << "no refusal where the probe saw bfloat16 sums";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("gas-to-real --precision=bfloat16"), std::string::npos) << what;
    EXPECT_NE(what.find("not 1600"), std::string::npos) << what;
    EXPECT_NE(what.find("use --precision=float32"), std::string::npos) << what;
  }
}

// RMSProp with the mean square starting at 0 (torch/Keras): the first step is lr*g/sqrt(0.1 g^2).
TEST(GanOptimiser, ZeroInitialMeanSquare) {
  torch::Tensor p = torch::tensor({1.0, -2.0}, torch::kDouble).requires_grad_(true);
  TfRmsProp opt({p}, 0.1, 0.9, 1e-10, 0.0);
  opt.step({torch::tensor({0.5, -3.0}, torch::kDouble)});
  EXPECT_NEAR(p[0].item<double>(), 1.0 - 0.1 / std::sqrt(0.1 + 1e-10 / 0.25), 1e-9);
  EXPECT_NEAR(p[1].item<double>(), -2.0 + 0.1 / std::sqrt(0.1 + 1e-10 / 9.0), 1e-9);
}

// TF RMSProp (rms starts at 1, eps inside the sqrt), two steps by hand.
TEST(GanOptimiser, MatchesTensorFlowRmsProp) {
  torch::Tensor p = torch::tensor({1.0, -2.0}, torch::kDouble).requires_grad_(true);
  TfRmsProp opt({p}, 0.1, 0.9, 1e-10);
  double ms[2] = {1.0, 1.0}, v[2] = {1.0, -2.0};
  const double grads[2][2] = {{0.5, -3.0}, {2.0, 0.25}};
  for (const auto& g : grads) {
    opt.step({torch::tensor({g[0], g[1]}, torch::kDouble)});
    for (int i = 0; i < 2; ++i) {
      ms[i] = 0.9 * ms[i] + 0.1 * g[i] * g[i];
      v[i] -= 0.1 * g[i] / std::sqrt(ms[i] + 1e-10);
    }
  }
  EXPECT_NEAR(p[0].item<double>(), v[0], 1e-12);
  EXPECT_NEAR(p[1].item<double>(), v[1], 1e-12);
}

void expect_equal_parameters(torch::nn::Module& x, torch::nn::Module& y) {
  const auto px = x.parameters(), py = y.parameters();
  ASSERT_EQ(px.size(), py.size());
  for (size_t i = 0; i < px.size(); ++i) EXPECT_TRUE(torch::equal(px[i], py[i])) << "parameter " << i;
}

// `a` saved at `step` to `path` and loaded into a model of other initial weights.
std::unique_ptr<CycleGan> reloaded(const CycleGan& a, const std::string& path, long long step) {
  save_checkpoint(path, a, step);
  torch::manual_seed(6);
  auto b = std::make_unique<CycleGan>(a.settings, torch::kCPU);
  EXPECT_EQ(load_checkpoint(path, *b), step);
  return b;
}

// The averaged weights after t steps are the weighted mean of the live weights at steps 1..t with
// weights decay^(t-s), written out as that sum (not the recursion the code runs), whatever the
// average held before step 1; a decay of 0 keeps the last step's weights.
TEST(GanWeightAverage, IsTheDecayWeightedMeanOfTheStepsWeights) {
  EXPECT_EQ(weight_average_rate(0.999, 1), 1.0);
  EXPECT_EQ(weight_average_rate(0.0, 7), 1.0);
  EXPECT_NEAR(weight_average_rate(0.5, 2), 0.5 / 0.75, 1e-15);
  EXPECT_THROW(weight_average_rate(0.5, 0), Error);
  torch::manual_seed(11);
  Generator live = make_generator([] { GanSettings s; s.width = 2; return s; }(), GanInit::kHe);
  Generator average = make_generator([] { GanSettings s; s.width = 2; return s; }(), GanInit::kHe);
  // The average starts away from every live value, to show the start does not count.
  { torch::NoGradGuard no_grad; for (auto& p : average->parameters()) p.fill_(1e3); }
  for (double decay : {0.0, 0.5, 0.9, 0.995}) {
    const int steps = 40;
    std::vector<std::vector<torch::Tensor>> history;
    torch::manual_seed(12);
    for (long long t = 1; t <= steps; ++t) {
      std::vector<torch::Tensor> values;
      {
        torch::NoGradGuard no_grad;
        for (auto& p : live->parameters()) p.copy_(torch::randn_like(p) + double(t) / steps);
      }
      for (auto& p : live->parameters()) values.push_back(p.detach().to(torch::kDouble).clone());
      history.push_back(values);
      update_weight_average(*average, *live, decay, t);
    }
    const auto averaged = average->parameters();
    for (size_t i = 0; i < averaged.size(); ++i) {
      torch::Tensor sum = torch::zeros_like(history[0][i]);
      double norm = 0.0;
      for (int s = 1; s <= steps; ++s) {
        const double w = std::pow(decay, steps - s);  // pow(0, 0) = 1: the last step alone
        sum += w * history[s - 1][i];
        norm += w;
      }
      const torch::Tensor expected = sum / norm;
      EXPECT_LT((averaged[i].to(torch::kDouble) - expected).abs().max().item<double>(), 1e-5)
          << "decay " << decay << ", parameter " << i;
    }
  }
}

// The averages are built after the four networks, so a model that keeps them starts from the same
// weights as one that does not (its training is that model's), and they start as the generators.
TEST(GanWeightAverage, KeepingAnAverageLeavesTheModelsInitialWeights) {
  GanSettings s;
  s.width = 2;
  torch::manual_seed(5);
  CycleGan plain(s, torch::kCPU);
  s.generator_average_decay = 0.99;
  torch::manual_seed(5);
  CycleGan averaged(s, torch::kCPU);
  ASSERT_FALSE(plain.g_real_average);
  ASSERT_TRUE(averaged.g_real_average && averaged.g_synthetic_average);
  expect_equal_parameters(*plain.g_real, *averaged.g_real);
  expect_equal_parameters(*plain.g_synthetic, *averaged.g_synthetic);
  expect_equal_parameters(*plain.d_real, *averaged.d_real);
  expect_equal_parameters(*plain.d_synthetic, *averaged.d_synthetic);
  expect_equal_parameters(*averaged.g_synthetic, *averaged.g_synthetic_average);
  // No optimiser, no gradient: only the update moves it.
  for (const auto& p : averaged.g_synthetic_average->parameters()) EXPECT_FALSE(p.requires_grad());
}

// A checkpoint keeps the averages; a generator loads from them or from the last weights as asked,
// and a model without an average gives its last weights either way.
TEST(GanWeightAverage, CheckpointKeepsTheAveragesAndLoadsEitherWeights) {
  const std::string dir = (fs::temp_directory_path() / ("tsrir_gan_avg_" + std::to_string(::getpid()))).string();
  fs::create_directories(dir);
  GanSettings s;
  s.width = 2;
  s.generator_average_decay = 0.9;
  torch::manual_seed(5);
  CycleGan a(s, torch::kCPU);
  update_generator_averages(a, 1);
  {
    torch::NoGradGuard no_grad;
    for (auto& p : a.g_real->parameters()) p.add_(1.0);  // the live weights move on
  }
  update_generator_averages(a, 2);  // g_real's average now lies between its two steps' weights
  const std::string path = dir + "/checkpoint.pt";
  std::unique_ptr<CycleGan> b = reloaded(a, path, 2);
  expect_equal_parameters(*a.g_real_average, *b->g_real_average);
  expect_equal_parameters(*a.g_synthetic_average, *b->g_synthetic_average);
  const auto pa = a.g_real_average->parameters();
  GanSettings loaded;
  long long step = 0;
  const auto first = [&](GeneratorWeights w) { return load_generator(path, "g_real", w, &loaded, &step)->parameters()[0]; };
  EXPECT_TRUE(torch::equal(first(GeneratorWeights::kAverageWhereKept), pa[0]));
  EXPECT_TRUE(torch::equal(first(GeneratorWeights::kLast), a.g_real->parameters()[0]));
  EXPECT_FALSE(torch::equal(pa[0], a.g_real->parameters()[0]));
  // Without an average in the model: the last weights, and a checkpoint without the average's
  // tensors is refused by a model that expects them.
  GanSettings plain = s;
  plain.generator_average_decay = 0;
  CycleGan c(plain, torch::kCPU);
  save_checkpoint(dir + "/plain.pt", c, 1);
  EXPECT_TRUE(torch::equal(load_generator(dir + "/plain.pt", "g_real", GeneratorWeights::kAverageWhereKept, &loaded, &step)
                               ->parameters()[0],
                           c.g_real->parameters()[0]));
  try {
    load_checkpoint(dir + "/plain.pt", *b);
    FAIL() << "a checkpoint without the averages loaded into a model that keeps them";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("g_real_average"), std::string::npos) << e.what();
  }
  remove_tree(dir);
}

TEST(GanCheckpoint, RoundTripAndErrors) {
  const std::string dir = temp_dir("ckpt");
  GanSettings s;
  s.width = 2;
  s.batch_size = 2;
  torch::manual_seed(5);
  CycleGan a(s, torch::kCPU);
  a.optimizers[1].mean_square()[0].fill_(0.25);
  const std::string path = dir + "/checkpoint.pt";
  std::unique_ptr<CycleGan> reloaded_a = reloaded(a, path, 17);
  CycleGan& b = *reloaded_a;
  expect_equal_parameters(*a.g_synthetic, *b.g_synthetic);
  const auto pa = a.g_synthetic->parameters();
  EXPECT_TRUE(torch::equal(a.optimizers[1].mean_square()[0], b.optimizers[1].mean_square()[0]));
  GanSettings loaded;
  long long step = 0;
  Generator g = load_generator(path, "g_synthetic", GeneratorWeights::kLast, &loaded, &step);
  EXPECT_EQ(loaded.width, 2);
  EXPECT_EQ(step, 17);
  EXPECT_TRUE(torch::equal(g->parameters()[0], pa[0]));

  // Another width: a clear error naming the widths, nothing silently reshaped.
  GanSettings wide = s;
  wide.width = 3;
  CycleGan c(wide, torch::kCPU);
  try {
    load_checkpoint(path, c);
    FAIL() << "width mismatch accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("width 2"), std::string::npos) << e.what();
  }
  // Corrupt / foreign files.
  { std::ofstream(dir + "/bad.pt") << "not a checkpoint"; }
  EXPECT_THROW(load_checkpoint(dir + "/bad.pt", b), Error);
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  { std::ofstream(dir + "/truncated.pt", std::ios::binary) << bytes.substr(0, bytes.size() / 2); }
  EXPECT_THROW(load_checkpoint(dir + "/truncated.pt", b), Error);
  remove_tree(dir);
}

// tune_memory_for_torch(): blocks of >= 1 MiB come from the reusing allocator, 2 MiB aligned, and a
// freed block is handed out again for the next request of its rounded size; smaller tensors and the
// raw interface keep working; the arithmetic is unchanged; drop_kept_tensor_memory() unmaps what is
// kept. (Whether the kernel backs the blocks with huge pages is its choice, not asserted.)
TEST(GanAllocator, ReusesLargeBlocksAndKeepsResults) {
  tune_memory_for_torch();
  tune_memory_for_torch();  // idempotent
  const TensorAllocatorStats before = tensor_allocator_stats();
  const void* first = nullptr;
  {
    torch::Tensor big = torch::empty({1 << 20});  // 4 MiB
    first = big.data_ptr();
    EXPECT_EQ(reinterpret_cast<uintptr_t>(first) % (2u << 20), 0u);
    big.fill_(2.0f);
    EXPECT_EQ(big.sum().item<double>(), 2.0 * (1 << 20));
  }
  {
    torch::Tensor again = torch::empty({(1 << 20) - 1000});  // same rounded size
    EXPECT_EQ(again.data_ptr(), first);
  }
  const TensorAllocatorStats after = tensor_allocator_stats();
  EXPECT_GE(after.blocks_reused, before.blocks_reused + 1);
  EXPECT_GT(after.bytes_kept_free, 0u);
  torch::manual_seed(33);
  const torch::Tensor a = torch::randn({700, 600}, torch::kDouble), b = torch::randn({600, 500}, torch::kDouble);
  const torch::Tensor small = torch::ones({10});  // below 1 MiB: LibTorch's own allocator
  EXPECT_EQ(small.sum().item<double>(), 10.0);
  const torch::Tensor product = torch::matmul(a, b);  // 2.8 MB result
  double want = 0.0;
  for (int64_t k = 0; k < 600; ++k) want += a[3][k].item<double>() * b[k][7].item<double>();
  EXPECT_NEAR(product[3][7].item<double>(), want, 1e-9 * std::max(1.0, std::abs(want)));
  c10::Allocator* allocator = c10::GetCPUAllocator();
  for (size_t bytes : {size_t(100), size_t(3) << 20}) {
    void* raw = allocator->raw_allocate(bytes);
    std::memset(raw, 1, bytes);
    allocator->raw_deallocate(raw);
  }
  drop_kept_tensor_memory();
  EXPECT_EQ(tensor_allocator_stats().bytes_kept_free, 0u);
}

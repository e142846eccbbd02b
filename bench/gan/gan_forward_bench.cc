// Generator forward throughput (the cost of gas-to-real without file I/O): RIRs/s, ms per batch
// and achieved GFLOP/s for a width, decoder, batch size, thread count and precision, so that a
// translation rate can be compared with what the machine's arithmetic allows.
//   gan_forward_bench [--width=64] [--decoder=original|light] [--batch=16] [--threads=2]
//                     [--precision=float32|bfloat16] [--reps=5]
//                     [--generator=original|residual|band-gain] [--correction-max-hz=0|500] [--lowpass-compare=1]
//                     [--conv=auto|direct] [--allocator=reusing|libtorch] [--bins=parallel|serial]
//                     [--band-gain-profile=1]
// (--generator=residual --correction-max-hz=500 --decoder=light: ts-rirgan-train's defaults, the
// model gas-to-real runs by default; --generator=band-gain is the opt-in whole-band generator; the GFLOP column counts the convolution layers only.)
#include <c10/core/InferenceMode.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "gan/gan_binwise_product.h"
#include "gan/gan_networks.h"
#include "gan/gan_runtime.h"
#include "gan/gan_tensor_allocator.h"
#include "gan/gan_settings.h"

namespace {

// Multiply-adds x 2 of one generator pass on 16384 samples (direct convolution count; the
// transposed convs' phase decomposition adds 28/25 of theirs).
double generator_gflop(int w, tsrir::GanDecoder decoder, int k) {
  int m[3];
  tsrir::decoder_multipliers(decoder, m);
  double macs = 0.0;
  long long length = 16384;
  const int down[9][2] = {{1, w}, {w, 2 * w}, {2 * w, 4 * w}, {4 * w, 8 * w}, {8 * w, 8 * w},
                          {8 * w, 8 * w}, {8 * w, 8 * w}, {8 * w, 8 * w}, {8 * w, 8 * w}};
  for (int i = 0; i < 9; ++i) {
    if (i < 4) length /= 4;
    macs += double(length) * down[i][0] * down[i][1] * k;
  }
  const int up[4][2] = {{8 * w, m[0] * w}, {m[0] * w, m[1] * w}, {m[1] * w, m[2] * w}, {m[2] * w, 1}};
  for (int i = 0; i < 4; ++i) {
    macs += double(length) * up[i][0] * up[i][1] * k;  // input length x taps
    length *= 4;
  }
  return 2.0 * macs / 1e9;
}

std::string arg(int argc, char** argv, const std::string& name, const std::string& fallback) {
  const std::string prefix = "--" + name + "=";
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], prefix.c_str(), prefix.size()) == 0) return argv[i] + prefix.size();
  }
  return fallback;
}

// Median over `reps` runs of f() in ms, after one unmeasured run.
template <typename F>
double median_run_ms(int reps, F&& f) {
  std::vector<double> t;
  f();
  for (int r = 0; r < reps; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(1000.0 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int width = std::atoi(arg(argc, argv, "width", "64").c_str());
  const std::string decoder_name = arg(argc, argv, "decoder", "original");
  const tsrir::GanDecoder decoder = tsrir::parse_choice(tsrir::kGanDecoderNames, decoder_name, "--decoder");
  const int batch = std::atoi(arg(argc, argv, "batch", "16").c_str());
  const int threads = std::atoi(arg(argc, argv, "threads", "2").c_str());
  const int reps = std::atoi(arg(argc, argv, "reps", "5").c_str());
  const std::string precision = arg(argc, argv, "precision", "float32");
  if (arg(argc, argv, "allocator", "reusing") == "reusing") tsrir::tune_memory_for_torch();
  // --bins=serial: the FFT form's per-bin products one after another (torch::matmul), as before
  // they were shared among the threads (gan_binwise_product.h).
  const bool serial_bins = arg(argc, argv, "bins", "parallel") == "serial";
  tsrir::gan::allow_parallel_binwise_product(!serial_bins);
  tsrir::set_openblas_threads(1);
  tsrir::gan::set_torch_threads(threads);
  torch::manual_seed(1);
  const std::string kind_name = arg(argc, argv, "generator", "original");
  tsrir::gan::GeneratorSpec spec;
  spec.width = width;
  spec.decoder = decoder;
  spec.kind = tsrir::parse_choice(tsrir::kGanGeneratorNames, kind_name, "--generator");
  spec.correction_max_hz = std::atof(arg(argc, argv, "correction-max-hz", "0").c_str());
  const double correction_max_hz = spec.correction_max_hz;
  tsrir::gan::Generator g(spec, tsrir::GanInit::kHe);
  g->eval();
  const auto dtype = precision == "bfloat16" ? torch::kBFloat16 : torch::kFloat32;
  g->to(dtype);
  // --conv=direct: every layer's direct form (what training computes), by running under
  // NoGradGuard instead of InferenceMode (the FFT form of the stride-1 layers is inference-only).
  const bool direct = arg(argc, argv, "conv", "auto") == "direct";
  std::optional<c10::InferenceMode> inference;
  std::optional<torch::NoGradGuard> no_grad;
  if (direct) {
    no_grad.emplace();
  } else {
    inference.emplace();
  }
  const torch::Tensor x = (torch::rand({batch, 1, 16384}) * 2 - 1).to(dtype);
  g->forward(x);  // warm-up: oneDNN primitive creation
  std::vector<double> seconds;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    g->forward(x);
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  if (spec.kind != tsrir::GanGenerator::kOriginal && correction_max_hz > 0 && arg(argc, argv, "lowpass-compare", "0") == "1") {
    // The correction's low-pass alone on one batch: the direct conv1d it used to be against the
    // FFT form the generator now uses (median of reps), printed as a comment line.
    const torch::Tensor taps = torch::tensor(tsrir::gan::correction_lowpass_taps(correction_max_hz)).view({1, 1, -1}).to(dtype);
    const int64_t half = taps.size(2) / 2;
    auto median_ms = [&](auto&& f) { return median_run_ms(reps, f); };
    const double direct = median_ms([&] { torch::conv1d(torch::constant_pad_nd(x, {half, half}, 0.0), taps); });
    const double fft = median_ms([&] { tsrir::gan::lowpass_same(x, taps); });
    std::printf("# correction low-pass (%lld taps), batch %d: direct conv1d %.2f ms, FFT %.2f ms\n",
                static_cast<long long>(taps.size(2)), batch, direct, fft);
  }
  if (spec.kind == tsrir::GanGenerator::kBandGain && arg(argc, argv, "band-gain-profile", "0") == "1") {
    // The band-gain stage's parts alone on one batch (median of reps, ms), printed as a comment
    // line: the band split (one real FFT, six inverse ones), the knots' interpolation and the whole
    // stage with random features of the bottleneck's shape.
    tsrir::gan::BandGain stage(8 * width);
    for (auto& p : stage->parameters()) {
      torch::NoGradGuard no_grad;
      p.normal_(0, 0.01);
    }
    stage->to(dtype);
    const torch::Tensor features = torch::rand({batch, 8 * width, 64}).to(dtype);
    const torch::Tensor onset = torch::full({batch, 1, 1}, 300, torch::kLong);
    auto median_ms = [&](auto&& f) { return median_run_ms(reps, f); };
    const double split = median_ms([&] { stage->band_signals(x); });
    const double knots = median_ms([&] {
      tsrir::gan::interpolate_knots(stage->knot_log_gains(features), tsrir::gan::knot_positions(onset, 16384, 16000.0));
    });
    const double whole = median_ms([&] { stage->forward(x, features, onset); });
    std::printf("# band-gain stage, batch %d: band split %.2f ms, knot gains %.2f ms, whole stage %.2f ms\n", batch,
                split, knots, whole);
  }
  std::sort(seconds.begin(), seconds.end());
  const double s = seconds[seconds.size() / 2];
  const double gflop = generator_gflop(width, decoder, 25);
  const std::string model = spec.kind != tsrir::GanGenerator::kOriginal
                                ? decoder_name + ", " + kind_name +
                                      (correction_max_hz > 0 ? " <= " + std::to_string(int(correction_max_hz)) + " Hz" : "")
                                : decoder_name;
  std::string variant = model;
  if (direct) variant += ", direct conv";
  if (serial_bins && !direct) variant += ", serial bins";
  if (arg(argc, argv, "allocator", "reusing") != "reusing") variant += ", LibTorch allocator";
  std::printf("| %d | %s | %d | %d | %s | %.1f | %.2f | %.1f | %.2f | %.0f |\n", width, variant.c_str(), batch,
              threads, precision.c_str(), tsrir::gan::count_parameters(*g) / 1e6, gflop, 1000.0 * s,
              batch / s, gflop * batch / s);
  return 0;
}

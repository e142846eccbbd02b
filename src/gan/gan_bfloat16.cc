#include "gan/gan_bfloat16.h"

#include <torch/torch.h>

#include <cmath>

#include "util/error.h"

namespace tsrir {

namespace {

constexpr int kProbeChannels = 64, kProbeTaps = 25;  // the width-16 generator's first wide layer
constexpr double kProbeSum = kProbeChannels * kProbeTaps;
constexpr double kBfloat16StepAtProbeSum = 8.0;  // 1600 lies in [1024, 2048): steps of 2^(10-7)

double probe_sum() {
  torch::NoGradGuard no_grad;
  const torch::Tensor ones = torch::ones({1, kProbeChannels, kProbeTaps}, torch::kBFloat16);
  return torch::conv1d(ones, ones).to(torch::kFloat64).item<double>();
}

}  // namespace

bool bfloat16_convolutions_sum_in_float32() {
  static const bool in_float32 = std::abs(probe_sum() - kProbeSum) <= kBfloat16StepAtProbeSum;
  return in_float32;
}

void require_float32_sums_for_bfloat16(const std::string& program) {
  if (bfloat16_convolutions_sum_in_float32()) return;
  throw Error(program + " --precision=bfloat16: this CPU's LibTorch sums bfloat16 convolution products in bfloat16 (a " +
              std::to_string(kProbeChannels) + "-channel " + std::to_string(kProbeTaps) + "-tap sum of ones gives " +
              std::to_string(int(probe_sum())) + ", not " + std::to_string(int(kProbeSum)) +
              "), which puts ~5% RMS of error in each wide layer (~9% in a generator's output) and is slower than float32 here; use --precision=float32 "
              "(bfloat16 needs a CPU where oneDNN runs it: AVX512 or AMX)");
}

}  // namespace tsrir

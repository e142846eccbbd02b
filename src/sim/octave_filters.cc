#include "sim/octave_filters.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include "dsp/fft.h"
#include "util/error.h"

namespace tsrir::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

// FFT plan and the 8 gain curves for one (rate, size): built once, shared by all threads.
struct CombinePlan {
  std::unique_ptr<RealFft> fft;
  std::array<std::vector<float>, kNumOctaveBands> gain;  // per bin, already scaled by 1/N
  std::array<size_t, kNumOctaveBands> bin_begin{}, bin_end{};  // non-zero range per band
};

const CombinePlan& combine_plan(double sample_rate_hz, size_t fft_size) {
  static std::mutex mutex;
  static std::map<std::pair<double, size_t>, std::unique_ptr<CombinePlan>> plans;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = plans[{sample_rate_hz, fft_size}];
  if (!slot) {
    auto plan = std::make_unique<CombinePlan>();
    plan->fft = std::make_unique<RealFft>(fft_size);
    const size_t bins = fft_size / 2 + 1;
    for (int b = 0; b < kNumOctaveBands; ++b) {
      plan->gain[b].resize(bins);
      plan->bin_begin[b] = bins;
      plan->bin_end[b] = 0;
      for (size_t k = 0; k < bins; ++k) {
        const double g = octave_crossover_gain(b, k * sample_rate_hz / fft_size);
        plan->gain[b][k] = static_cast<float>(g / fft_size);
        if (g > 0.0) {
          plan->bin_begin[b] = std::min(plan->bin_begin[b], k);
          plan->bin_end[b] = k + 1;
        }
      }
    }
    slot = std::move(plan);
  }
  return *slot;
}

}  // namespace

double octave_crossover_gain(int band, double f_hz) {
  if (band < 0 || band >= kNumOctaveBands) throw Error("octave band index out of range");
  // Position between two neighbouring centres in octaves (0..1) -> upper band's share.
  auto upper_share = [](double x) {
    const double u = std::clamp((x - 0.5 * (1.0 - kCrossoverWidthOctaves)) / kCrossoverWidthOctaves, 0.0, 1.0);
    const double s = std::sin(0.5 * kPi * u);
    return s * s;
  };
  const double centre = kOctaveCentersHz[band];
  if (f_hz <= centre) {
    if (band == 0) return 1.0;
    const double below = kOctaveCentersHz[band - 1];
    if (f_hz <= below) return 0.0;
    return upper_share(std::log2(f_hz / below));
  }
  if (band == kNumOctaveBands - 1) return 1.0;
  const double above = kOctaveCentersHz[band + 1];
  if (f_hz >= above) return 0.0;
  return 1.0 - upper_share(std::log2(f_hz / centre));
}

std::vector<float> combine_octave_bands(const BandSignals& bands, double sample_rate_hz) {
  const size_t n = bands.band[0].size();
  for (const auto& b : bands.band) {
    if (b.size() != n) throw Error("combine_octave_bands: band signals differ in length");
  }
  if (n == 0) return {};
  const size_t pad = static_cast<size_t>(std::ceil(0.15 * sample_rate_hz));
  const size_t fft_size = next_fast_fft_size(n + pad);
  const CombinePlan& plan = combine_plan(sample_rate_hz, fft_size);
  const size_t bins = fft_size / 2 + 1;
  std::vector<float> buffer(fft_size, 0.0f);
  std::vector<std::complex<float>> spectrum(bins), sum(bins, {0.0f, 0.0f});
  for (int b = 0; b < kNumOctaveBands; ++b) {
    if (plan.bin_begin[b] >= plan.bin_end[b]) continue;  // band entirely above Nyquist
    bool silent = true;
    for (float x : bands.band[b]) {
      if (x != 0.0f) { silent = false; break; }
    }
    if (silent) continue;
    // The padding after n stays zero: the forward transform leaves its input as it was.
    std::copy(bands.band[b].begin(), bands.band[b].end(), buffer.begin());
    plan.fft->forward(buffer.data(), spectrum.data());
    const float* g = plan.gain[b].data();
    for (size_t k = plan.bin_begin[b]; k < plan.bin_end[b]; ++k) sum[k] += g[k] * spectrum[k];
  }
  plan.fft->inverse(sum.data(), buffer.data());
  buffer.resize(n);
  return buffer;
}

}  // namespace tsrir::sim

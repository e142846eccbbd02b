#include "sim/onset_shift.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "dsp/fft.h"
#include "util/error.h"

namespace tsrir::sim {

std::vector<float> fractional_shift(const std::vector<float>& x, double shift_samples) {
  const size_t n = x.size();
  if (n == 0 || shift_samples == 0.0) return x;
  // Zero padding on both sides so that neither the shifted start nor the end wraps around.
  const size_t margin = static_cast<size_t>(std::ceil(std::abs(shift_samples))) + 64;
  const size_t size = next_fast_fft_size(n + 2 * margin);
  std::vector<float> buffer(size, 0.0f);
  std::copy(x.begin(), x.end(), buffer.begin() + margin);
  RealFft fft(size);
  std::vector<std::complex<float>> spectrum(fft.num_bins());
  fft.forward(buffer.data(), spectrum.data());
  constexpr double kPi = 3.14159265358979323846;
  for (size_t k = 0; k < spectrum.size(); ++k) {
    const double phase = -2.0 * kPi * static_cast<double>(k) * shift_samples / static_cast<double>(size);
    spectrum[k] *= std::complex<float>(static_cast<float>(std::cos(phase) / size), static_cast<float>(std::sin(phase) / size));
  }
  // The Nyquist bin of an even size must stay real.
  if (size % 2 == 0) spectrum.back() = std::complex<float>(spectrum.back().real(), 0.0f);
  fft.inverse(spectrum.data(), buffer.data());
  return std::vector<float>(buffer.begin() + margin, buffer.begin() + margin + n);
}

OnsetShiftComponent::OnsetShiftComponent(ComponentParams& params)
    : latency_s_(params.number("latency_ms", 0.0) / 1000.0), align_s_(params.number("align_ms", 0.0) / 1000.0) {
  if (!(std::abs(latency_s_) <= 1.0)) throw Error("model component onset_shift: latency_ms must be within +-1000");
  if (!(align_s_ >= 0.0 && align_s_ <= 1.0)) throw Error("model component onset_shift: align_ms must be in [0, 1000]");
}

double OnsetShiftComponent::max_decay_time_s(const RoomSpec&) const { return std::max(0.0, latency_s_) + align_s_; }

void OnsetShiftComponent::process_rir(const RenderContext& ctx, std::vector<float>& samples) const {
  double shift_s = latency_s_;
  if (align_s_ > 0.0) shift_s += align_s_ - ctx.facts.direct_delay_s;
  samples = fractional_shift(samples, shift_s * ctx.sample_rate_hz);
}

}  // namespace tsrir::sim

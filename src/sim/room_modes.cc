#include "sim/room_modes.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "sim/spectral_shaping.h"
#include "util/error.h"

namespace tsrir::sim {
namespace {
constexpr double kPi = 3.14159265358979323846;
}

std::vector<RoomMode> shoebox_modes(const Vec3& size_m, double c, double min_hz, double max_hz) {
  std::vector<RoomMode> modes;
  const int nx_max = static_cast<int>(2.0 * max_hz * size_m[0] / c);
  const int ny_max = static_cast<int>(2.0 * max_hz * size_m[1] / c);
  const int nz_max = static_cast<int>(2.0 * max_hz * size_m[2] / c);
  for (int nx = 0; nx <= nx_max; ++nx) {
    for (int ny = 0; ny <= ny_max; ++ny) {
      for (int nz = 0; nz <= nz_max; ++nz) {
        const double kx = nx / size_m[0], ky = ny / size_m[1], kz = nz / size_m[2];
        const double f = 0.5 * c * std::sqrt(kx * kx + ky * ky + kz * kz);
        if (f >= min_hz && f <= max_hz) modes.push_back({nx, ny, nz, f});
      }
    }
  }
  std::sort(modes.begin(), modes.end(), [](const RoomMode& a, const RoomMode& b) { return a.freq_hz < b.freq_hz; });
  return modes;
}

double schroeder_frequency_hz(const RoomSpec& room) {
  const double t60 = eyring_t60_s(room)[1];
  return 2000.0 * std::sqrt(std::max(t60, 0.05) / room.volume_m3());
}

double modal_crossover_lowpass(double f_hz, double crossover_hz) {
  if (f_hz <= crossover_hz / std::sqrt(2.0)) return 1.0;
  if (f_hz >= crossover_hz * std::sqrt(2.0)) return 0.0;
  const double x = std::log2(f_hz / crossover_hz) + 0.5;  // 0..1 across the octave
  const double c = std::cos(0.5 * kPi * x);
  return c * c;
}

RoomModesComponent::RoomModesComponent(ComponentParams& params)
    : crossover_hz_(params.number("crossover_hz", 0.0)),
      decay_scale_(params.number("decay_scale", 1.0)),
      level_db_(params.number("level_db", 0.0)) {
  if (!(crossover_hz_ == 0.0 || (crossover_hz_ >= 30.0 && crossover_hz_ <= 1000.0))) {
    throw Error("model component modes: crossover_hz must be 0 (auto) or in [30, 1000]");
  }
  if (!(decay_scale_ >= 0.1 && decay_scale_ <= 10.0)) throw Error("model component modes: decay_scale must be in [0.1, 10]");
  if (!(std::abs(level_db_) <= 40.0)) throw Error("model component modes: level_db must be within +-40");
}

double RoomModesComponent::crossover_hz(const RoomSpec& room) const {
  return crossover_hz_ > 0.0 ? crossover_hz_ : std::clamp(schroeder_frequency_hz(room), 40.0, 1000.0);
}

std::vector<double> RoomModesComponent::modal_response(const RoomSpec& room, double fs, size_t n,
                                                       double direct_delay_s) const {
  const double fc = crossover_hz(room);
  const double c = room.speed_of_sound_m_s;
  const std::vector<RoomMode> modes = shoebox_modes(room.size_m, c, 15.0, std::min(fc * std::sqrt(2.0), 0.45 * fs));
  const BandValues rate = eyring_decay_rate_per_s(room);
  BandValues log_rate{};
  for (int b = 0; b < kNumOctaveBands; ++b) log_rate[b] = std::log(std::isfinite(rate[b]) ? rate[b] : 1e3);
  const double gain = c * c / (room.volume_m3() * fs) * std::pow(10.0, level_db_ / 20.0);
  std::vector<double> h(n, 0.0);
  for (const RoomMode& m : modes) {
    double shape = 1.0;
    const int idx[3] = {m.nx, m.ny, m.nz};
    for (int i = 0; i < 3; ++i) {
      shape *= std::cos(idx[i] * kPi * room.source_m[i] / room.size_m[i]) *
               std::cos(idx[i] * kPi * room.mic_m[i] / room.size_m[i]);
      if (idx[i] > 0) shape *= 2.0;  // 1 / Lambda
    }
    const double w = 2.0 * kPi * m.freq_hz;
    const double damping = 0.5 * std::exp(interpolate_band_db(log_rate, m.freq_hz)) / decay_scale_;
    const double amp = gain * shape / w;
    // exp((-d + i w) t) advanced by one complex multiply per sample; sin = imaginary part.
    const std::complex<double> step = std::exp(std::complex<double>(-damping, w) / fs);
    std::complex<double> z(1.0, 0.0);
    for (size_t i = 0; i < n; ++i) {
      h[i] += amp * z.imag();
      z *= step;
    }
  }
  // The truncated mode sum is not exactly zero before the direct sound: fade it in over one
  // period of the crossover frequency centred on the direct delay.
  const double ramp_s = 1.0 / fc;
  for (size_t i = 0; i < n; ++i) {
    const double t = i / fs - (direct_delay_s - 0.5 * ramp_s);
    if (t >= ramp_s) break;
    h[i] *= t <= 0.0 ? 0.0 : 0.5 * (1.0 - std::cos(kPi * t / ramp_s));
  }
  return h;
}

void RoomModesComponent::process_rir(const RenderContext& ctx, std::vector<float>& samples) const {
  const double fc = crossover_hz(ctx.room);
  const size_t pad = static_cast<size_t>(std::ceil(0.15 * ctx.sample_rate_hz));
  const std::vector<double> modal = modal_response(ctx.room, ctx.sample_rate_hz, samples.size(), ctx.facts.direct_delay_s);
  std::vector<float> modal_f(modal.begin(), modal.end());
  const auto high = zero_phase_filter(samples, ctx.sample_rate_hz, pad,
                                      [](double f, const void* a) {
                                        return 1.0 - modal_crossover_lowpass(f, *static_cast<const double*>(a));
                                      },
                                      &fc);
  const auto low = zero_phase_filter(modal_f, ctx.sample_rate_hz, pad,
                                     [](double f, const void* a) {
                                       return modal_crossover_lowpass(f, *static_cast<const double*>(a));
                                     },
                                     &fc);
  for (size_t i = 0; i < samples.size(); ++i) samples[i] = high[i] + low[i];
}

}  // namespace tsrir::sim

#include "sim/image_sources.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"

namespace tsrir::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kHalfTaps = 8;             // kernel taps j in (-8, 8] around the arrival
constexpr int kFractionSteps = 1024;     // timing quantised to 1/1024 sample

// Windowed-sinc kernels tabulated per fractional offset: the table costs 64 KiB once and turns
// per-image kernel evaluation (16 sin/cos) into a lookup.
struct KernelTable {
  float taps[kFractionSteps + 1][2 * kHalfTaps];
  KernelTable() {
    for (int f = 0; f <= kFractionSteps; ++f) {
      const double frac = static_cast<double>(f) / kFractionSteps;
      for (int k = 0; k < 2 * kHalfTaps; ++k) {
        const double x = (k - kHalfTaps + 1) - frac;  // tap time minus arrival time, samples
        const double sinc = std::abs(x) < 1e-12 ? 1.0 : std::sin(kPi * x) / (kPi * x);
        const double window = std::abs(x) >= kHalfTaps ? 0.0 : 0.5 * (1.0 + std::cos(kPi * x / kHalfTaps));
        taps[f][k] = static_cast<float>(sinc * window);
      }
    }
  }
};

const KernelTable& kernel_table() {
  static const KernelTable table;
  return table;
}

// One axis of the image lattice: coordinate offset to the mic and the per-band reflection factor.
struct AxisImage {
  double offset_sq;
  int reflections;
  BandValues factor;          // sqrt(1-a) products of the two walls of this axis
};

std::vector<AxisImage> axis_images(double length, double src, double mic, const BandValues& a_low,
                                   const BandValues& a_high, double reach) {
  std::vector<AxisImage> out;
  const long n_max = static_cast<long>(std::ceil((reach + length) / (2.0 * length))) + 1;
  BandValues r_low{}, r_high{};
  for (int b = 0; b < kNumOctaveBands; ++b) {
    r_low[b] = std::sqrt(1.0 - a_low[b]);
    r_high[b] = std::sqrt(1.0 - a_high[b]);
  }
  for (long n = -n_max; n <= n_max; ++n) {
    for (int q = 0; q <= 1; ++q) {
      // Image at 2nL + (1-2q) src: |n - q| reflections on the wall at 0, |n| on the wall at L.
      const double offset = 2.0 * n * length + (1 - 2 * q) * src - mic;
      if (std::abs(offset) > reach) continue;
      const int hits_low = static_cast<int>(std::labs(n - q));
      const int hits_high = static_cast<int>(std::labs(n));
      AxisImage img;
      img.offset_sq = offset * offset;
      img.reflections = hits_low + hits_high;
      for (int b = 0; b < kNumOctaveBands; ++b) {
        img.factor[b] = std::pow(r_low[b], hits_low) * std::pow(r_high[b], hits_high);
      }
      out.push_back(img);
    }
  }
  std::sort(out.begin(), out.end(), [](const AxisImage& x, const AxisImage& y) {
    if (x.offset_sq != y.offset_sq) return x.offset_sq < y.offset_sq;
    return x.reflections < y.reflections;
  });
  return out;
}

}  // namespace

std::vector<ImageArrival> image_arrivals(const RoomSpec& room, double max_delay_s) {
  const double c = room.speed_of_sound_m_s;
  const double reach = max_delay_s * c;
  const double reach_sq = reach * reach;
  std::vector<AxisImage> axes[3];
  for (int i = 0; i < 3; ++i) {
    axes[i] = axis_images(room.size_m[i], room.source_m[i], room.mic_m[i], room.absorption[2 * i],
                          room.absorption[2 * i + 1], reach);
  }
  BandValues scatter_amp{};
  for (int b = 0; b < kNumOctaveBands; ++b) scatter_amp[b] = std::sqrt(1.0 - room.scattering[b]);
  std::vector<ImageArrival> out;
  for (const AxisImage& x : axes[0]) {
    if (x.offset_sq >= reach_sq) break;
    for (const AxisImage& y : axes[1]) {
      const double xy = x.offset_sq + y.offset_sq;
      if (xy >= reach_sq) break;
      for (const AxisImage& z : axes[2]) {
        const double d_sq = xy + z.offset_sq;
        if (d_sq >= reach_sq) break;
        ImageArrival arr;
        arr.distance_m = std::sqrt(d_sq);
        arr.delay_s = arr.distance_m / c;
        arr.reflections = x.reflections + y.reflections + z.reflections;
        const double spread = 1.0 / (4.0 * kPi * arr.distance_m);
        for (int b = 0; b < kNumOctaveBands; ++b) {
          arr.unscattered_amplitude[b] = spread * x.factor[b] * y.factor[b] * z.factor[b];
          arr.amplitude[b] = arr.unscattered_amplitude[b] * std::pow(scatter_amp[b], arr.reflections);
        }
        out.push_back(arr);
      }
    }
  }
  return out;
}

double image_transition_time_s(const RoomSpec& room, double num_images) {
  const double radius_m = std::cbrt(3.0 * room.volume_m3() * num_images / (4.0 * kPi));
  const double direct_s = room.source_mic_distance_m() / room.speed_of_sound_m_s;
  return std::max(radius_m / room.speed_of_sound_m_s, direct_s + 1e-3);
}

void add_fractional_impulse(double position, const BandValues& gain, BandSignals& bands) {
  const KernelTable& table = kernel_table();
  const long base = static_cast<long>(std::floor(position));
  const int f = static_cast<int>(std::lround((position - base) * kFractionSteps));
  const float* taps = table.taps[f];
  const long n = static_cast<long>(bands.band[0].size());
  const long first = base - kHalfTaps + 1;
  const int k_begin = static_cast<int>(std::max(0L, -first));
  const int k_end = static_cast<int>(std::min<long>(2 * kHalfTaps, n - first));
  for (int b = 0; b < kNumOctaveBands; ++b) {
    const float g = static_cast<float>(gain[b]);
    if (g == 0.0f) continue;
    float* out = bands.band[b].data() + first;
    for (int k = k_begin; k < k_end; ++k) out[k] += g * taps[k];
  }
}

ImageSourceComponent::ImageSourceComponent(ComponentParams& params)
    : max_images_(params.number("max_images", 2000.0)),
      transition_s_(params.number("transition_ms", 0.0) / 1000.0) {
  if (!(max_images_ >= 1.0 && max_images_ <= 1e7)) {
    throw Error("model component ism: max_images must be in [1, 1e7]");
  }
  if (!(transition_s_ >= 0.0 && transition_s_ <= 10.0)) {
    throw Error("model component ism: transition_ms must be in [0, 10000]");
  }
}

double ImageSourceComponent::transition_time_s(const RoomSpec& room) const {
  return transition_s_ > 0.0 ? transition_s_ : image_transition_time_s(room, max_images_);
}

double ImageSourceComponent::max_decay_time_s(const RoomSpec& room) const {
  return transition_time_s(room);
}

void ImageSourceComponent::render_bands(const RenderContext& ctx, BandSignals& bands) const {
  const RoomSpec& room = ctx.room;
  const double fs = ctx.sample_rate_hz;
  const double t_tr = std::min(transition_time_s(room), ctx.num_samples / fs);
  const double window_start = 0.5 * t_tr;
  BandValues window_energy{};
  for (const ImageArrival& arr : image_arrivals(room, t_tr)) {
    add_fractional_impulse(arr.delay_s * fs, arr.amplitude, bands);
    if (arr.delay_s >= window_start && arr.reflections > 0) {
      for (int b = 0; b < kNumOctaveBands; ++b) {
        window_energy[b] += arr.unscattered_amplitude[b] * arr.unscattered_amplitude[b];
      }
    }
  }
  // What a diffuse field with Eyring decay puts into the same window: the image count grows as
  // 4 pi c^3 t^2 dt / V and each carries 1 / (4 pi c t)^2, so the energy density is
  // c / (4 pi V) exp(-rate t).
  const BandValues rate = eyring_decay_rate_per_s(room);
  const double density = room.speed_of_sound_m_s / (4.0 * kPi * room.volume_m3());
  const double start = std::max(window_start, ctx.facts.direct_delay_s);
  for (int b = 0; b < kNumOctaveBands; ++b) {
    double expected = 0.0;
    if (t_tr > start) {
      expected = std::isinf(rate[b]) ? 0.0
                                     : density * (std::exp(-rate[b] * start) - std::exp(-rate[b] * t_tr)) / rate[b];
    }
    ctx.facts.window_diffuse_energy[b] = expected;
  }
  ctx.facts.transition_time_s = t_tr;
  ctx.facts.window_start_s = start;
  ctx.facts.window_image_energy = window_energy;
}

}  // namespace tsrir::sim

#include "sim/image_sources.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "util/cpu_clones.h"
#include "util/error.h"

namespace tsrir::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kHalfTaps = 8;             // kernel taps j in (-8, 8] around the arrival
constexpr int kFractionSteps = 1024;     // timing quantised to 1/1024 sample

// Windowed-sinc kernels tabulated per fractional offset: the table costs 64 KiB once and turns
// per-image kernel evaluation (16 sin/cos) into a lookup.
struct alignas(64) KernelTable {
  alignas(64) float taps[kFractionSteps + 1][2 * kHalfTaps];
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

// base[b]^k per band for k = 0..max_exponent: the std::pow values a per-image evaluation gives (so
// outputs are unchanged), looked up instead of recomputed for every image and band (pow was an
// eighth of a render's CPU time).
std::vector<BandValues> band_powers(const BandValues& base, int max_exponent) {
  std::vector<BandValues> table(static_cast<size_t>(max_exponent) + 1);
  for (int k = 0; k <= max_exponent; ++k) {
    for (int b = 0; b < kNumOctaveBands; ++b) table[k][b] = std::pow(base[b], k);
  }
  return table;
}

}  // namespace

std::vector<AxisImage> axis_images(double length, double src, double centre, const BandValues& a_low,
                                   const BandValues& a_high, double reach) {
  std::vector<AxisImage> out;
  const long n_max = static_cast<long>(std::ceil((reach + length) / (2.0 * length))) + 1;
  BandValues r_low{}, r_high{};
  for (int b = 0; b < kNumOctaveBands; ++b) {
    r_low[b] = std::sqrt(1.0 - a_low[b]);
    r_high[b] = std::sqrt(1.0 - a_high[b]);
  }
  // For every hit count an image of this axis can have (|n - q| <= n_max + 1).
  const std::vector<BandValues> pow_low = band_powers(r_low, static_cast<int>(n_max) + 1);
  const std::vector<BandValues> pow_high = band_powers(r_high, static_cast<int>(n_max) + 1);
  for (long n = -n_max; n <= n_max; ++n) {
    for (int q = 0; q <= 1; ++q) {
      // Image at 2nL + (1-2q) src: |n - q| reflections on the wall at 0, |n| on the wall at L.
      const double position = 2.0 * n * length + (1 - 2 * q) * src;
      const double offset = position - centre;
      if (std::abs(offset) > reach) continue;
      const int hits_low = static_cast<int>(std::labs(n - q));
      const int hits_high = static_cast<int>(std::labs(n));
      AxisImage img;
      img.position = position;
      img.offset_sq = offset * offset;
      img.mirror = 1 - 2 * q;
      img.reflections = hits_low + hits_high;
      for (int b = 0; b < kNumOctaveBands; ++b) {
        img.factor[b] = pow_low[hits_low][b] * pow_high[hits_high][b];
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

ImageLattice image_lattice(const RoomSpec& room, const Vec3& centre, double reach_m) {
  ImageLattice lattice;
  lattice.centre = centre;
  lattice.reach_m = reach_m;
  for (int i = 0; i < 3; ++i) {
    lattice.axes[i] = axis_images(room.size_m[i], room.source_m[i], centre[i], room.absorption[2 * i],
                                  room.absorption[2 * i + 1], reach_m);
  }
  return lattice;
}

namespace {

// The polar patterns' gain for one image: the microphone's for the direction the sound arrives
// from, the source's for the direction it left the real source in (the image's direction to the
// microphone, mirrored back on every axis where the image is a mirror image).
// Per band, as a loudspeaker's pattern may differ by band (RoomSpec::source_band_patterns).
BandValues pattern_gains(const RoomSpec& room, const AxisImage* xyz[3], const double offset[3], double distance_m) {
  Vec3 arrival{}, departure{};
  for (int i = 0; i < 3; ++i) {
    arrival[i] = offset[i] / distance_m;  // from the microphone towards the image
    departure[i] = -xyz[i]->mirror * arrival[i];
  }
  const double mic = polar_gain(room.mic_pattern.value_or(PolarPattern::kOmni), room.mic_axis, arrival);
  BandValues gains = source_pattern_gains(room, departure);
  for (double& g : gains) g *= mic;
  return gains;
}

// sqrt(1 - s)^k per band for every reflection count k the lattice holds.
std::vector<BandValues> scattering_loss_table(const RoomSpec& room, const ImageLattice& lattice) {
  int max_reflections = 0;
  for (const auto& axis : lattice.axes) {
    int axis_max = 0;
    for (const AxisImage& img : axis) axis_max = std::max(axis_max, img.reflections);
    max_reflections += axis_max;
  }
  BandValues scatter_amp{};
  for (int b = 0; b < kNumOctaveBands; ++b) scatter_amp[b] = std::sqrt(1.0 - room.scattering[b]);
  return band_powers(scatter_amp, max_reflections);
}

}  // namespace

std::vector<ImageArrival> image_arrivals(const ImageLattice& lattice, const RoomSpec& room, double max_delay_s) {
  const double c = room.speed_of_sound_m_s;
  const double reach = max_delay_s * c;
  const double reach_sq = reach * reach;
  // The lattice is sorted by distance from its centre; a microphone `spread` from it sees every
  // image within reach among those within reach + spread of the centre.
  double spread_sq = 0.0;
  for (int i = 0; i < 3; ++i) spread_sq += (room.mic_m[i] - lattice.centre[i]) * (room.mic_m[i] - lattice.centre[i]);
  const double outer = std::min(lattice.reach_m, reach + std::sqrt(spread_sq));
  const double outer_sq = spread_sq == 0.0 ? reach_sq : outer * outer;
  const bool directional = has_directional_transducers(room);
  const std::vector<BandValues> scatter_loss = scattering_loss_table(room, lattice);
  std::vector<ImageArrival> out;
  // A shoebox holds about (4 pi / 3) reach^3 / V images within reach.
  out.reserve(static_cast<size_t>(std::min(1e7, 4.5 * reach_sq * reach / room.volume_m3())) + 16);
  for (const AxisImage& x : lattice.axes[0]) {
    if (x.offset_sq >= outer_sq) break;
    const double dx = x.position - room.mic_m[0];
    for (const AxisImage& y : lattice.axes[1]) {
      if (x.offset_sq + y.offset_sq >= outer_sq) break;
      const double dy = y.position - room.mic_m[1];
      for (const AxisImage& z : lattice.axes[2]) {
        if (x.offset_sq + y.offset_sq + z.offset_sq >= outer_sq) break;
        const double dz = z.position - room.mic_m[2];
        const double d_sq = dx * dx + dy * dy + dz * dz;
        if (d_sq >= reach_sq) continue;
        // Filled in place: a local copied in afterwards was read back before its stores had
        // landed (a store-forwarding stall that was half of this function's time).
        ImageArrival& arr = out.emplace_back(ImageArrival::Unset{});
        arr.distance_m = std::sqrt(d_sq);
        arr.delay_s = arr.distance_m / c;
        arr.reflections = x.reflections + y.reflections + z.reflections;
        double spread = 1.0 / (4.0 * kPi * arr.distance_m);
        for (int b = 0; b < kNumOctaveBands; ++b) {
          arr.unscattered_amplitude[b] = spread * x.factor[b] * y.factor[b] * z.factor[b];
          arr.amplitude[b] = arr.unscattered_amplitude[b] * scatter_loss[arr.reflections][b];
        }
        if (directional) {
          const AxisImage* xyz[3] = {&x, &y, &z};
          const double offset[3] = {dx, dy, dz};
          const BandValues gains = pattern_gains(room, xyz, offset, arr.distance_m);
          for (int b = 0; b < kNumOctaveBands; ++b) arr.amplitude[b] *= gains[b];
        }
      }
    }
  }
  return out;
}

std::vector<ImageArrival> image_arrivals(const RoomSpec& room, double max_delay_s) {
  return image_arrivals(image_lattice(room, room.mic_m, max_delay_s * room.speed_of_sound_m_s), room, max_delay_s);
}

double image_transition_time_s(const RoomSpec& room, double num_images) {
  const double radius_m = std::cbrt(3.0 * room.volume_m3() * num_images / (4.0 * kPi));
  const double direct_s = room.source_mic_distance_m() / room.speed_of_sound_m_s;
  return std::max(radius_m / room.speed_of_sound_m_s, direct_s + 1e-3);
}

namespace {

typedef float Floats8 __attribute__((vector_size(32)));
static_assert(2 * kHalfTaps == 16, "a kernel is two vectors of eight taps");

// Where an arrival at `position` (samples) lands: its kernel's first sample and the table row of
// the nearest 1/1024 sample, halves rounded up. That is std::lround's rounding, which costs a libm
// call per image; the fraction `scaled - whole` is exact, so its comparison with 0.5 decides as
// lround does.
struct KernelPlace {
  long first;
  int row;
};
inline KernelPlace kernel_place(double position) {
  const double base = std::floor(position);
  const double scaled = (position - base) * kFractionSteps;
  const double whole = std::floor(scaled);
  return {static_cast<long>(base) - kHalfTaps + 1, static_cast<int>(whole) + (scaled - whole >= 0.5 ? 1 : 0)};
}

// rows[b][first + k] += gain[b] * taps[k] for the taps inside [0, n): one multiplication and one
// addition per tap, in this order, in every clone (the avx2 target has no FMA), so the sums are
// those of the scalar loop.
inline void add_impulse_body(const KernelTable& table, double position, const double* gain, float* const* rows, long n) {
  const KernelPlace at = kernel_place(position);
  const float* taps = table.taps[at.row];
  // The taps as two vectors of eight, loaded once for all bands (GCC vector types: whole vectors in
  // every clone, and no store into a band can be taken to change a tap).
  Floats8 tap_vec[2];
  std::memcpy(tap_vec, __builtin_assume_aligned(taps, 64), sizeof tap_vec);  // rows are 64 bytes
  const int k_begin = static_cast<int>(std::max(0L, -at.first));
  const int k_end = static_cast<int>(std::min<long>(2 * kHalfTaps, n - at.first));
  for (int b = 0; b < kNumOctaveBands; ++b) {
    const float g = static_cast<float>(gain[b]);
    if (g == 0.0f) continue;
    float* out = rows[b] + at.first;
    if (k_begin == 0 && k_end == 2 * kHalfTaps) {  // every tap inside: the usual case
      for (int h = 0; h < 2; ++h) {
        Floats8 o;
        std::memcpy(&o, out + 8 * h, sizeof o);
        o += g * tap_vec[h];
        std::memcpy(out + 8 * h, &o, sizeof o);
      }
    } else {
      for (int k = k_begin; k < k_end; ++k) out[k] += g * taps[k];
    }
  }
}

std::array<float*, kNumOctaveBands> band_rows(BandSignals& bands) {
  std::array<float*, kNumOctaveBands> rows{};
  for (int b = 0; b < kNumOctaveBands; ++b) rows[b] = bands.band[b].data();
  return rows;
}

// Every arrival's impulse, in one function compiled per instruction set: dispatched once per
// microphone rather than once per image and band (the per-call dispatch and a scalar copy of the
// taps cost more than the additions themselves; issue 35's profile).
TSRIR_AVX2_CLONES
void add_arrival_impulses(const ImageArrival* arrivals, size_t count, double fs, float* const* rows, long n) {
  const KernelTable& table = kernel_table();
  for (size_t i = 0; i < count; ++i) add_impulse_body(table, arrivals[i].delay_s * fs, arrivals[i].amplitude.data(), rows, n);
}

}  // namespace

void add_fractional_impulse(double position, const BandValues& gain, BandSignals& bands) {
  const std::array<float*, kNumOctaveBands> rows = band_rows(bands);
  add_impulse_body(kernel_table(), position, gain.data(), rows.data(), static_cast<long>(bands.band[0].size()));
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
  render_array_bands({&ctx}, {&bands});
}

void ImageSourceComponent::render_array_bands(const std::vector<const RenderContext*>& ctxs,
                                              const std::vector<BandSignals*>& bands) const {
  Vec3 centre{};
  for (const RenderContext* ctx : ctxs) {
    for (int i = 0; i < 3; ++i) centre[i] += ctx->room.mic_m[i] / ctxs.size();
  }
  if (ctxs.size() == 1) centre = ctxs[0]->room.mic_m;  // exactly the microphone
  std::vector<double> transitions_s;
  double reach_m = 0.0;
  for (const RenderContext* ctx : ctxs) {
    const RoomSpec& room = ctx->room;
    transitions_s.push_back(std::min(transition_time_s(room), ctx->num_samples / ctx->sample_rate_hz));
    double spread_sq = 0.0;
    for (int i = 0; i < 3; ++i) spread_sq += (room.mic_m[i] - centre[i]) * (room.mic_m[i] - centre[i]);
    reach_m = std::max(reach_m, transitions_s.back() * room.speed_of_sound_m_s + std::sqrt(spread_sq));
  }
  const ImageLattice lattice = image_lattice(ctxs[0]->room, centre, reach_m);
  for (size_t m = 0; m < ctxs.size(); ++m) render_microphone(*ctxs[m], lattice, transitions_s[m], *bands[m]);
}

void ImageSourceComponent::render_microphone(const RenderContext& ctx, const ImageLattice& lattice,
                                             double t_tr, BandSignals& bands) const {
  const RoomSpec& room = ctx.room;
  const double fs = ctx.sample_rate_hz;
  const double window_start = 0.5 * t_tr;
  BandValues window_energy{};
  const std::vector<ImageArrival> arrivals = image_arrivals(lattice, room, t_tr);
  const std::array<float*, kNumOctaveBands> rows = band_rows(bands);
  add_arrival_impulses(arrivals.data(), arrivals.size(), fs, rows.data(), static_cast<long>(bands.band[0].size()));
  for (const ImageArrival& arr : arrivals) {
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

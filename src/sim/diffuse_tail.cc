#include "sim/diffuse_tail.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstring>
#include <vector>

#include "dsp/fft.h"
#include "util/cpu_clones.h"
#include "util/error.h"

namespace tsrir::sim {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kCoherenceLoading = 1e-6;
constexpr size_t kCoherenceStepBins = 8;

// The lower Cholesky factor l (row-major, m x m) of the diffuse coherence matrix at wavenumber k,
// given the microphones' distances d (row-major); only the lower triangle is read or written.
void coherence_cholesky(const std::vector<double>& d, size_t m, double k, std::vector<double>* a,
                        std::vector<double>* l) {
  for (size_t i = 0; i < m; ++i) {
    for (size_t j = 0; j <= i; ++j) {
      const double kd = k * d[i * m + j];
      (*a)[i * m + j] = (kd < 1e-9 ? 1.0 : std::sin(kd) / kd) + (i == j ? kCoherenceLoading : 0.0);
    }
  }
  for (size_t j = 0; j < m; ++j) {
    double diag = (*a)[j * m + j];
    for (size_t p = 0; p < j; ++p) diag -= (*l)[j * m + p] * (*l)[j * m + p];
    (*l)[j * m + j] = std::sqrt(std::max(diag, kCoherenceLoading));
    for (size_t i = j + 1; i < m; ++i) {
      double v = (*a)[i * m + j];
      for (size_t p = 0; p < j; ++p) v -= (*l)[i * m + p] * (*l)[j * m + p];
      (*l)[i * m + j] = v / (*l)[j * m + j];
    }
  }
}

}  // namespace

std::vector<std::vector<float>> diffuse_coherent_noise(const std::vector<std::vector<float>>& white,
                                                       const std::vector<Vec3>& mics_m, double speed_of_sound_m_s,
                                                       double sample_rate_hz) {
  const size_t m = white.size(), n = white.at(0).size();
  if (mics_m.size() != m) throw Error("diffuse_coherent_noise: one position per noise needed");
  // Padding takes the wrap-around of the (short, zero-phase) mixing filters.
  const RealFft fft(next_fast_fft_size(n + 256));
  const size_t bins = fft.num_bins();
  std::vector<std::vector<std::complex<float>>> spectra(m, std::vector<std::complex<float>>(bins));
  std::vector<float> padded(fft.size());
  for (size_t c = 0; c < m; ++c) {
    if (white[c].size() != n) throw Error("diffuse_coherent_noise: noises of different lengths");
    std::fill(std::copy(white[c].begin(), white[c].end(), padded.begin()), padded.end(), 0.0f);
    fft.forward(padded.data(), spectra[c].data());
  }
  std::vector<double> distance(m * m), a(m * m), l(m * m, 0.0);
  for (size_t i = 0; i < m; ++i) {
    for (size_t j = 0; j < m; ++j) {
      const double dx = mics_m[i][0] - mics_m[j][0], dy = mics_m[i][1] - mics_m[j][1], dz = mics_m[i][2] - mics_m[j][2];
      distance[i * m + j] = std::sqrt(dx * dx + dy * dy + dz * dz);
    }
  }
  // The factor is computed every kCoherenceStepBins bins and interpolated linearly between: the
  // coherence changes on the scale c / d (>= 343 Hz for d <= 1 m), the bins are ~1 Hz apart, and
  // the interpolation's error, (step k)^2 d^2 / 8, stays below 3e-3 for d <= 1 m.
  std::vector<double> l_next(m * m, 0.0);
  std::vector<std::complex<double>> spectrum_bin(m);
  const auto wavenumber = [&](size_t bin) {
    return 2.0 * kPi * (bin * sample_rate_hz / fft.size()) / speed_of_sound_m_s;
  };
  coherence_cholesky(distance, m, wavenumber(0), &a, &l_next);
  std::vector<std::complex<float>> mixed(m);
  for (size_t bin = 0; bin < bins; ++bin) {
    const size_t offset = bin % kCoherenceStepBins;
    if (offset == 0) {
      l.swap(l_next);
      coherence_cholesky(distance, m, wavenumber(bin + kCoherenceStepBins), &a, &l_next);
    }
    const double w = static_cast<double>(offset) / kCoherenceStepBins;
    for (size_t j = 0; j < m; ++j) spectrum_bin[j] = spectra[j][bin];
    for (size_t i = 0; i < m; ++i) {  // the factor is lower triangular: j <= i only
      std::complex<double> v = 0.0;
      for (size_t j = 0; j <= i; ++j) {
        const size_t ij = i * m + j;
        v += ((1.0 - w) * l[ij] + w * l_next[ij]) * spectrum_bin[j];
      }
      mixed[i] = std::complex<float>(v);
    }
    for (size_t i = 0; i < m; ++i) spectra[i][bin] = mixed[i];
  }
  std::vector<std::vector<float>> out(m, std::vector<float>(n));
  const float scale = 1.0f / static_cast<float>(fft.size());
  for (size_t c = 0; c < m; ++c) {
    fft.inverse(spectra[c].data(), padded.data());
    for (size_t i = 0; i < n; ++i) out[c][i] = padded[i] * scale;
  }
  return out;
}

DiffuseTailComponent::DiffuseTailComponent(ComponentParams&) {}

double DiffuseTailComponent::max_decay_time_s(const RoomSpec& room) const {
  const BandValues t60 = eyring_t60_s(room);
  return *std::max_element(t60.begin(), t60.end());
}

namespace {

size_t tail_start(const RenderContext& ctx) {
  return std::min(ctx.num_samples, static_cast<size_t>(std::ceil(ctx.facts.direct_delay_s * ctx.sample_rate_hz)));
}

// Uniform noise on [-sqrt(3), sqrt(3)): variance 1, and an order of magnitude cheaper than
// Gaussian draws; after band filtering it is Gaussian anyway.
std::vector<float> white_noise(Rng& rng, size_t n) {
  std::vector<float> noise(n);
  const double half_width = std::sqrt(3.0);
  rng.fill_uniform(-half_width, half_width, noise.data(), n);
  return noise;
}

typedef double Doubles4 __attribute__((vector_size(32)));
typedef float Floats4 __attribute__((vector_size(16)));
typedef int Ints4 __attribute__((vector_size(16)));

// The bands' envelopes advanced together, sample by sample: each band's recurrence is a chain of
// dependent multiplications, and interleaving the bands' chains lets them overlap (the tail took
// an eighth of a render's CPU time waiting on them). The bands are the lanes of two vectors of
// four; each lane's arithmetic is what a band-by-band loop does (IEEE operations, no FMA in either
// clone), so the samples are the same.
// TailEnvelopes::render's loops: the bands' envelopes as two vectors of four lanes; unused lanes
// run with zeros into a scratch row (no test of the count). Four samples at a time, the lanes are
// transposed into each band's four consecutive samples, added to its row as one vector: one
// addition per sample and band as before, without eight scalar stores a sample.
struct TailLanes {
  Doubles4 amp[2], step[2], spec[2], spec_step[2];

  // One sample's eight band values: before the transition the scattered share sqrt(1 - specular).
  template <bool kScatteredShare>
  void sample(double w, Floats4 out[2]) {
    const Doubles4 one = {1, 1, 1, 1};
    for (int g = 0; g < 2; ++g) {
      Doubles4 a = amp[g];
      if (kScatteredShare) {
        const Doubles4 rest = one - spec[g];
        const Doubles4 sq = {std::sqrt(rest[0]), std::sqrt(rest[1]), std::sqrt(rest[2]), std::sqrt(rest[3])};
        a = a * sq;
        spec[g] *= spec_step[g];
      }
      out[g] = __builtin_convertvector(a * w, Floats4);
      amp[g] *= step[g];
    }
  }

  template <bool kScatteredShare>
  void run(const float* white, size_t i, size_t end, float* const* rows) {
    for (; i + 4 <= end; i += 4) {
      Floats4 v[4][2];
      for (int j = 0; j < 4; ++j) sample<kScatteredShare>(white[i + j], v[j]);
      for (int g = 0; g < 2; ++g) add_transposed(v[0][g], v[1][g], v[2][g], v[3][g], rows + 4 * g, i);
    }
    for (; i < end; ++i) {
      Floats4 v[2];
      sample<kScatteredShare>(white[i], v);
      for (int b = 0; b < 8; ++b) rows[b][i] += v[b / 4][b % 4];
    }
  }

  // Lanes i0..i3 of the eight of x then y (GCC >= 12 and Clang spell it __builtin_shufflevector).
  template <int i0, int i1, int i2, int i3>
  static Floats4 pick(Floats4 x, Floats4 y) {
#if defined(__clang__) || (defined(__GNUC__) && __GNUC__ >= 12)
    return __builtin_shufflevector(x, y, i0, i1, i2, i3);
#else
    return __builtin_shuffle(x, y, Ints4{i0, i1, i2, i3});
#endif
  }

  // Samples i..i+3 as rows a..d (lanes: four bands) -> each band's four samples, added to rows[0..3].
  static void add_transposed(Floats4 a, Floats4 b, Floats4 c, Floats4 d, float* const* rows, size_t i) {
    const Floats4 ab_lo = pick<0, 4, 1, 5>(a, b), ab_hi = pick<2, 6, 3, 7>(a, b);
    const Floats4 cd_lo = pick<0, 4, 1, 5>(c, d), cd_hi = pick<2, 6, 3, 7>(c, d);
    const Floats4 band[4] = {pick<0, 1, 4, 5>(ab_lo, cd_lo), pick<2, 3, 6, 7>(ab_lo, cd_lo),
                             pick<0, 1, 4, 5>(ab_hi, cd_hi), pick<2, 3, 6, 7>(ab_hi, cd_hi)};
    for (int k = 0; k < 4; ++k) {
      Floats4 r;
      std::memcpy(&r, rows[k] + i, sizeof r);
      r += band[k];
      std::memcpy(rows[k] + i, &r, sizeof r);
    }
  }
};

TSRIR_AVX2_CLONES
void render_tail_lanes(const float* white, size_t first, size_t transition, size_t n,
                       const double* amp0, const double* amp_step0, const double* spec0,
                       const double* spec_step0, float* const* rows) {
  TailLanes lanes;
  std::memcpy(lanes.amp, amp0, sizeof lanes.amp);
  std::memcpy(lanes.step, amp_step0, sizeof lanes.step);
  std::memcpy(lanes.spec, spec0, sizeof lanes.spec);
  std::memcpy(lanes.spec_step, spec_step0, sizeof lanes.spec_step);
  const size_t scattered_end = std::max(first, transition);
  lanes.run<true>(white, first, scattered_end, rows);
  lanes.run<false>(white, scattered_end, std::max(scattered_end, n), rows);
}

struct TailEnvelopes {
  int count = 0;
  std::array<float*, kNumOctaveBands> out{};
  std::array<double, kNumOctaveBands> amp{}, amp_step{}, specular{}, specular_step{};

  void add_band(float* band_out, double amp0, double amp_step0, double specular0, double specular_step0) {
    out[count] = band_out;
    amp[count] = amp0;
    amp_step[count] = amp_step0;
    specular[count] = specular0;
    specular_step[count] = specular_step0;
    ++count;
  }

  // Before `transition` the tail carries the scattered share 1 - specular; from it on, everything.
  void render(const float* white, size_t first, size_t transition, size_t n) {
    static_assert(kNumOctaveBands == 8, "two vectors of four bands");
    std::vector<float> scratch(count < kNumOctaveBands ? n : 0);
    float* rows[kNumOctaveBands];
    for (int b = 0; b < kNumOctaveBands; ++b) rows[b] = b < count ? out[b] : scratch.data();
    render_tail_lanes(white, first, transition, n, amp.data(), amp_step.data(), specular.data(), specular_step.data(),
                      rows);
  }
};

}  // namespace

void DiffuseTailComponent::render_bands(const RenderContext& ctx, BandSignals& bands) const {
  const size_t first = tail_start(ctx);
  if (first >= ctx.num_samples) return;
  Rng rng = ctx.rng_for(name());
  const std::vector<float> noise = white_noise(rng, ctx.num_samples - first);
  add_tail(ctx, noise.data() - first, bands);
}

void DiffuseTailComponent::render_array_bands(const std::vector<const RenderContext*>& ctxs,
                                              const std::vector<BandSignals*>& bands) const {
  if (ctxs.size() == 1) return render_bands(*ctxs[0], *bands[0]);
  std::vector<std::vector<float>> white;
  std::vector<Vec3> mics_m;
  for (const RenderContext* ctx : ctxs) {
    Rng rng = ctx->rng_for(name());
    white.push_back(white_noise(rng, ctx->num_samples));
    mics_m.push_back(ctx->room.mic_m);
  }
  const RenderContext& ctx0 = *ctxs[0];
  const std::vector<std::vector<float>> coherent =
      diffuse_coherent_noise(white, mics_m, ctx0.room.speed_of_sound_m_s, ctx0.sample_rate_hz);
  for (size_t m = 0; m < ctxs.size(); ++m) {
    if (tail_start(*ctxs[m]) < ctxs[m]->num_samples) add_tail(*ctxs[m], coherent[m].data(), *bands[m]);
  }
}

void DiffuseTailComponent::add_tail(const RenderContext& ctx, const float* white, BandSignals& bands) const {
  const RoomSpec& room = ctx.room;
  const double fs = ctx.sample_rate_hz;
  const size_t n = ctx.num_samples;
  const RenderFacts& facts = ctx.facts;
  const size_t first = tail_start(ctx);
  // The share of the diffuse energy the polar patterns pass (1 for omni, exactly).
  const double mic_energy = polar_diffuse_energy(room.mic_pattern.value_or(PolarPattern::kOmni));
  const BandValues source_energy = source_diffuse_energy(room);

  const BandValues rate = eyring_decay_rate_per_s(room);
  const double density_per_sample = room.speed_of_sound_m_s / (4.0 * kPi * room.volume_m3() * fs);
  const double reflections_per_s = room.speed_of_sound_m_s * room.surface_area_m2() / (4.0 * room.volume_m3());
  const size_t transition = std::min(n, static_cast<size_t>(std::ceil(facts.transition_time_s * fs)));

  // Per band: the amplitude envelope sqrt(level * density * exp(-rate t)) and the specular share
  // (1 - s)^k(t) = exp(ln(1 - s) * reflections_per_s * t), both advanced multiplicatively.
  TailEnvelopes env;
  for (int b = 0; b < kNumOctaveBands; ++b) {
    if (std::isinf(rate[b])) continue;  // a = 1: no reverberation in this band
    double level = 1.0;
    if (facts.transition_time_s > 0.0 && facts.window_diffuse_energy[b] > 0.0) {
      level = std::clamp(facts.window_image_energy[b] / facts.window_diffuse_energy[b], 0.25, 4.0);
    }
    const double t0 = first / fs;
    double amp = std::sqrt(level * density_per_sample) * std::exp(-0.5 * rate[b] * t0);
    const double pattern_energy = mic_energy * source_energy[b];
    if (pattern_energy != 1.0) amp *= std::sqrt(pattern_energy);
    const double s = room.scattering[b];
    const double log_specular_rate = s >= 1.0 ? -INFINITY : std::log1p(-s) * reflections_per_s;
    env.add_band(bands.band[b].data(), amp, std::exp(-0.5 * rate[b] / fs), std::exp(log_specular_rate * t0),
                 std::exp(log_specular_rate / fs));
  }
  env.render(white, first, transition, n);
}

}  // namespace tsrir::sim

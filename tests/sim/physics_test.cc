// Physical correctness of the default model ("gas"), measured on rendered RIRs. Reference values
// come from geometry and closed-form acoustics computed here (independently of src/sim), and
// reverberation times are measured with the toolkit's metrics library (ISO 3382 T30).
#include <gtest/gtest.h>

#include <cmath>

#include "metrics/rir_metrics.h"
#include "sim/image_sources.h"
#include "sim/octave_filters.h"
#include "sim_test_util.h"

namespace tsrir::sim {
namespace {

using test::energy;
using test::peak_index;
using test::simulate;

constexpr double kPi = 3.14159265358979323846;
constexpr double kFs = 16000.0;

// Eyring T60 written out independently: 0.1611 s/m * V / (-S ln(1 - a)) at c = 343 m/s
// (24 ln 10 / 343 = 0.16111).
double eyring_reference_s(double lx, double ly, double lz, double a) {
  const double v = lx * ly * lz, s = 2.0 * (lx * ly + ly * lz + lx * lz);
  return 24.0 * std::log(10.0) / 343.0 * v / (-s * std::log(1.0 - a));
}

TEST(SimPhysics, DirectSoundArrivesAtDistanceOverCWithAmplitudeOneOverR) {
  // Distances that are whole numbers of samples at 16 kHz (c = 343: 343/16000 m per sample), so
  // the band-limited impulse peaks exactly on a sample with its full amplitude.
  const double step_m = 343.0 / kFs;
  double previous_peak_times_r = 0.0;
  for (int samples : {40, 80, 160}) {
    const double r = samples * step_m;
    const std::string line = "d room=10,8,4 src=2,4,2 mic=" + std::to_string(2.0 + r) +
                             ",4,2 absorption=0.9 scattering=0";
    const Signal rir = simulate(line, "gas", kFs, 0.3);
    const size_t peak = peak_index(rir.samples);
    EXPECT_NEAR(static_cast<double>(peak), samples, 1.0) << "r=" << r;
    // 1/(4 pi r): reflections (absorption 0.9, >= 2 m farther) add < 1% at the direct sample.
    const double expected = 1.0 / (4.0 * kPi * r);
    EXPECT_NEAR(rir.samples[peak], expected, 0.02 * expected) << "r=" << r;
    if (previous_peak_times_r > 0.0) {
      EXPECT_NEAR(rir.samples[peak] * r, previous_peak_times_r, 0.02 * previous_peak_times_r);
    }
    previous_peak_times_r = rir.samples[peak] * r;
  }
}

// Reference early response, written independently of src/sim: every lattice image within the
// time limit, its reflections counted by unfolding (each plane k*L crossed between the microphone
// and the image is one reflection, on the wall at 0 for even k and at L for odd k), rendered with
// an exactly evaluated Hann-windowed sinc of half-width 8 samples (the arrival shape documented in
// sim/image_sources.h).
std::vector<double> reference_early_rir(const double l[3], const double s[3], const double m[3],
                                        const double absorption[6], double max_delay_s, size_t n) {
  std::vector<double> out(n, 0.0);
  const int n_max = 12;
  for (int nx = -n_max; nx <= n_max; ++nx)
    for (int ny = -n_max; ny <= n_max; ++ny)
      for (int nz = -n_max; nz <= n_max; ++nz)
        for (int q = 0; q < 8; ++q) {
          const int idx[3] = {nx, ny, nz};
          double d2 = 0.0, gain = 1.0;
          for (int ax = 0; ax < 3; ++ax) {
            const double sign = (q >> ax) & 1 ? -1.0 : 1.0;
            const double x = 2.0 * idx[ax] * l[ax] + sign * s[ax];
            d2 += (x - m[ax]) * (x - m[ax]);
            const double lo = std::min(x, m[ax]), hi = std::max(x, m[ax]);
            for (long k = static_cast<long>(std::floor(lo / l[ax])) - 1; k * l[ax] < hi + l[ax]; ++k) {
              if (k * l[ax] > lo && k * l[ax] < hi) {
                const int wall = 2 * ax + static_cast<int>(std::labs(k) % 2);
                gain *= std::sqrt(1.0 - absorption[wall]);
              }
            }
          }
          const double d = std::sqrt(d2), delay = d / 343.0;
          if (delay >= max_delay_s) continue;
          const double pos = delay * kFs, amp = gain / (4.0 * kPi * d);
          for (long i = static_cast<long>(std::floor(pos)) - 8; i <= static_cast<long>(pos) + 9; ++i) {
            const double x = i - pos;
            if (i < 0 || i >= static_cast<long>(n) || std::abs(x) >= 8.0) continue;
            const double sinc = std::abs(x) < 1e-12 ? 1.0 : std::sin(kPi * x) / (kPi * x);
            out[i] += amp * sinc * 0.5 * (1.0 + std::cos(kPi * x / 8.0));
          }
        }
  return out;
}

TEST(SimPhysics, ImageSourcesMatchIndependentReference) {
  // Different absorption on every surface (flat in frequency, so band filtering is transparent)
  // and no scattering: the "ism" component alone must reproduce the reference sample by sample.
  const double l[3] = {6.0, 4.5, 3.0}, s[3] = {2.0, 1.5, 1.6}, m[3] = {4.0, 3.0, 1.2};
  const double absorption[6] = {0.1, 0.3, 0.2, 0.5, 0.05, 0.4};
  const double limit_s = 0.06;
  const Signal rir = simulate("i room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 absorption.x0=0.1 absorption.x1=0.3 "
                              "absorption.y0=0.2 absorption.y1=0.5 absorption.floor=0.05 absorption.ceiling=0.4 "
                              "scattering=0",
                              "ism:transition_ms=60", kFs, 0.1);
  const std::vector<double> ref = reference_early_rir(l, s, m, absorption, limit_s, rir.samples.size());
  double peak = 0.0;
  for (double x : ref) peak = std::max(peak, std::abs(x));
  // Arrivals within 8 samples of the cut-off are half-rendered by either side: compare before it.
  // Tolerance: arrival times are tabulated to 1/1024 sample (error < 0.3% of an arrival's slope)
  // plus float accumulation.
  const size_t end = static_cast<size_t>(limit_s * kFs) - 8;
  for (size_t i = 0; i < end; ++i) ASSERT_NEAR(rir.samples[i], ref[i], 2e-3 * peak) << "sample " << i;
  EXPECT_GT(energy(rir.samples, static_cast<size_t>(0.02 * kFs), end), 0.0);
}

TEST(SimPhysics, OctaveCrossoversSumToUnity) {
  for (double f = 0.0; f < 24000.0; f += 7.3) {
    double sum = 0.0;
    for (int b = 0; b < kNumOctaveBands; ++b) sum += octave_crossover_gain(b, f);
    ASSERT_NEAR(sum, 1.0, 1e-12) << f;
  }
  // The same signal in every band comes back unfiltered (a flat response).
  BandSignals bands;
  for (auto& b : bands.band) {
    b.assign(4000, 0.0f);
    b[1000] = 1.0f;
    b[2500] = -0.5f;
  }
  const std::vector<float> out = combine_octave_bands(bands, kFs);
  for (size_t i = 0; i < out.size(); ++i) {
    const float expected = i == 1000 ? 1.0f : i == 2500 ? -0.5f : 0.0f;
    ASSERT_NEAR(out[i], expected, 1e-5) << i;
  }
}

// Mean ISO T30 per band over several seeds: a single stochastic tail scatters T30 by a standard
// deviation of ~11% at 62.5 Hz, ~6-11% at 125 Hz and <= 4% from 500 Hz up (measured over 10
// seeds; exponentially decaying white noise measured by the same code scatters alike), so one RIR
// cannot be held to 10% in the low octaves but the mean of 6 can (SD of the mean <= 4.6%).
std::vector<double> mean_band_t30(const RoomSpec& room, int seeds) {
  const Model model = Model::parse("gas");
  const size_t n = static_cast<size_t>(model.auto_length_s(room) * kFs);
  std::vector<double> sum(kNumOctaveBands, 0.0);
  for (int seed = 0; seed < seeds; ++seed) {
    const RirMetrics metrics = measure_rir(model.render(room, kFs, n, 100 + seed));
    for (const BandMetrics& band : metrics.bands) sum[octave_band_index(band.center_hz)] += band.t30_s / seeds;
  }
  return sum;
}

TEST(SimPhysics, BandT30MatchesEyringAcrossT60) {
  // A diffuse room (scattering 0.5, uniform absorption). The mean T30 per band must be within
  // 10% of Eyring's T60 (the acceptance criterion); 62.5 Hz gets 15% (B*T is only 9 at
  // 0.2 s, so the octave filter itself shapes the decay).
  for (double t60 : {0.2, 0.4, 0.6, 1.0, 1.5}) {
    const std::string line = "e room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 scattering=0.5 t60=" + std::to_string(t60);
    const RoomSpec room = test::room_from_line(line);
    const double expected = eyring_reference_s(6, 4.5, 3, room.absorption[0][0]);
    ASSERT_NEAR(expected, t60, 1e-3 * t60);  // the t60 key inverts Eyring exactly
    const std::vector<double> t30 = mean_band_t30(room, 6);
    for (int b = 0; b < 7; ++b) {  // 8 kHz is not measurable at 16 kHz
      const double tolerance = b == 0 ? 0.15 : 0.10;
      EXPECT_NEAR(t30[b], expected, tolerance * expected) << "T60 " << t60 << " band " << kOctaveCentersHz[b];
    }
  }
}

TEST(SimPhysics, PerBandAbsorptionGivesPerBandDecay) {
  // Absorption rising with frequency (a typical furnished room): each band follows its own
  // Eyring T60. Neighbouring bands differ by up to 1.6x, and the measuring octave filter itself
  // mixes in some of the neighbours' decays, hence 12% instead of 10%.
  const std::string line =
      "b room=8,6,3.5 src=2,2,1.5 mic=5.5,4,1.3 scattering=0.5 absorption=0.08,0.1,0.12,0.15,0.2,0.25,0.3,0.35";
  const RoomSpec room = test::room_from_line(line);
  const BandValues t60 = eyring_t60_s(room);
  const std::vector<double> t30 = mean_band_t30(room, 4);
  for (int b = 1; b < 7; ++b) {
    EXPECT_NEAR(t30[b], t60[b], 0.12 * t60[b]) << kOctaveCentersHz[b];
  }
}

TEST(SimPhysics, DecayIsRightAtOtherRatesRoomsAndScattering) {
  // The band filters and the noise must not depend on 16 kHz (bands above Nyquist are dropped at
  // 8 kHz, reach up to 24 kHz at 48 kHz), and the energy matching must hold for a large hall and
  // for the scattering extremes. Mean of 3 seeds, 250 Hz up (SD of the mean < 4%), 10%.
  struct Case { const char* line; double fs; };
  const Case cases[] = {
      {"x room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.6 scattering=0.5", 8000.0},
      {"x room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.6 scattering=0.5", 48000.0},
      {"x room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.6 scattering=1", 16000.0},
      {"x room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.6 scattering=0", 16000.0},
      {"x room=24,16,9 src=5,4,1.7 mic=15,9,1.5 t60=1.5 scattering=0.3", 16000.0},
  };
  for (const Case& c : cases) {
    const RoomSpec room = test::room_from_line(c.line);
    const Model model = Model::parse("gas");
    const size_t n = static_cast<size_t>(model.auto_length_s(room) * c.fs);
    std::vector<double> t30(kNumOctaveBands, 0.0);
    int measured = 0;
    for (int seed = 0; seed < 3; ++seed) {
      const RirMetrics m = measure_rir(model.render(room, c.fs, n, seed));
      measured = static_cast<int>(m.bands.size());
      for (const BandMetrics& b : m.bands) t30[octave_band_index(b.center_hz)] += b.t30_s / 3;
    }
    const double expected = eyring_t60_s(room)[0];
    for (int b = 2; b < 2 + measured - 2; ++b) {
      EXPECT_NEAR(t30[b], expected, 0.10 * expected) << c.line << " fs " << c.fs << " band " << kOctaveCentersHz[b];
    }
  }
}

TEST(SimPhysics, DrrFallsWithDistance) {
  // The direct energy falls as 1/r^2 while the diffuse energy is position-independent, so DRR
  // drops by ~6 dB per doubling of distance. Stochastic tails and early reflections move each
  // value by ~1 dB: compare 0.75 m -> 3 m (two doublings, 12 dB) with a 3 dB tolerance.
  auto drr_at = [](double r) {
    const std::string line = "r room=9,7,3 src=2,3.5,1.5 mic=" + std::to_string(2.0 + r) +
                             ",3.5,1.5 t60=0.6 scattering=0.3";
    return measure_rir(simulate(line, "gas", kFs, 0.8, 5)).drr_db;
  };
  const double near_db = drr_at(0.75), mid_db = drr_at(1.5), far_db = drr_at(3.0);
  EXPECT_GT(near_db, mid_db);
  EXPECT_GT(mid_db, far_db);
  EXPECT_NEAR(near_db - far_db, 12.0, 3.0);
}

TEST(SimPhysics, MirrorSymmetricSetupsGiveIdenticalRirs) {
  // Mirror x -> Lx - x for source and microphone with symmetric absorption (x0 = x1); the same
  // rir id keeps the stochastic stream the same.
  const Signal a = simulate("m room=6,4,3 src=1.5,1.2,1.4 mic=4.1,2.9,1.6 absorption.x0=0.3 absorption.x1=0.3 "
                            "absorption.y0=0.1 absorption.y1=0.2 absorption.floor=0.05 absorption.ceiling=0.4");
  const Signal b = simulate("m room=6,4,3 src=4.5,1.2,1.4 mic=1.9,2.9,1.6 absorption.x0=0.3 absorption.x1=0.3 "
                            "absorption.y0=0.1 absorption.y1=0.2 absorption.floor=0.05 absorption.ceiling=0.4");
  // And the same in y, with y0/y1 swapped along with the geometry.
  const Signal c = simulate("m room=6,4,3 src=1.5,2.8,1.4 mic=4.1,1.1,1.6 absorption.x0=0.3 absorption.x1=0.3 "
                            "absorption.y0=0.2 absorption.y1=0.1 absorption.floor=0.05 absorption.ceiling=0.4");
  ASSERT_EQ(a.samples.size(), b.samples.size());
  const double peak = std::abs(a.samples[peak_index(a.samples)]);
  for (size_t i = 0; i < a.samples.size(); ++i) {
    // Only float rounding may differ (images are summed in another order).
    ASSERT_NEAR(a.samples[i], b.samples[i], 1e-5 * peak) << i;
    ASSERT_NEAR(a.samples[i], c.samples[i], 1e-5 * peak) << i;
  }
}

TEST(SimPhysics, EnergyDecreasesMonotonicallyWithAbsorption) {
  double previous = INFINITY;
  for (double a : {0.05, 0.1, 0.2, 0.35, 0.5, 0.7, 0.9, 1.0}) {
    const std::string line = "a room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 absorption=" + std::to_string(a);
    const double e = energy(simulate(line, "gas", kFs, 1.5).samples);
    EXPECT_LT(e, previous) << "absorption " << a;
    previous = e;
  }
}

TEST(SimPhysics, EnergyIsContinuousAtTheTransition) {
  // Energy in 10 ms before and after the image-source transition, averaged over seeds, in a room
  // where the model's diffuse assumption holds (uniform absorption, scattering 0.3). A jump at the
  // transition would show as a ratio far from exp(-rate * 10 ms).
  const RoomSpec room = test::room_from_line("t room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.6 scattering=0.3");
  const Model model = Model::parse("gas");
  const double t_tr = image_transition_time_s(room, 2000);
  const size_t tr = static_cast<size_t>(t_tr * kFs), w = static_cast<size_t>(0.01 * kFs);
  double before = 0.0, after = 0.0;
  for (uint64_t seed = 0; seed < 8; ++seed) {
    const Signal rir = model.render(room, kFs, 16000, seed);
    before += energy(rir.samples, tr - w, tr);
    after += energy(rir.samples, tr, tr + w);
  }
  const double decay = std::exp(-eyring_decay_rate_per_s(room)[4] * 0.01);
  // +-1.5 dB: 8 seeds x 160 samples of band-limited noise plus the discrete images before t_tr.
  EXPECT_NEAR(10.0 * std::log10(after / before), 10.0 * std::log10(decay), 1.5);
}

TEST(SimPhysics, DeterministicPerSeedAndId) {
  const std::string line = "s room=5,4,3 src=1,1,1 mic=3,3,1.5 t60=0.5";
  const Signal a = simulate(line, "gas", kFs, 0.5, 7), b = simulate(line, "gas", kFs, 0.5, 7);
  const Signal c = simulate(line, "gas", kFs, 0.5, 8);
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_NE(a.samples, c.samples);
}

}  // namespace
}  // namespace tsrir::sim

// The model extensions (src/sim), each against a reference computed another way (the independent
// generators of tests/diagnose among them).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "dsp/fft.h"
#include "hidden_effects.h"
#include "measured_rir_generator.h"
#include "sim/air_absorption.h"
#include "sim/extension_components.h"
#include "sim/model.h"
#include "sim/onset_shift.h"
#include "sim/room_modes.h"
#include "sim/source_directivity.h"
#include "sim/transducer.h"
#include "util/error.h"

namespace tsrir {
namespace {

constexpr double kPi = 3.14159265358979323846;

sim::RoomSpec test_room() { return testdata::make_test_rooms(1, 5)[0]; }

TEST(AirAbsorption, MatchesIsoTableAndTheIndependentImplementation) {
  // ISO 9613-1 Table 1 at 20 C, 50 % RH (dB/km), 125 Hz - 2 kHz; above, the table uses the exact
  // one-third-octave mid-band frequencies, not the nominal ones.
  const double f[] = {125, 250, 500, 1000, 2000};
  const double table[] = {0.443, 1.32, 2.73, 4.66, 9.66};
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(sim::air_attenuation_db_per_m(f[i], 20.0, 50.0) * 1000.0, table[i], 0.03 * table[i]) << f[i];
    EXPECT_NEAR(sim::air_attenuation_db_per_m(f[i], 12.0, 23.0), testdata::test_air_attenuation_db_per_m(f[i], 12.0, 23.0),
                1e-9);
  }
}

TEST(AirAbsorption, BandDecayIncreaseIsBetweenTheBandEdgeRates) {
  // The fitted band rate lies between the attenuation at the band's lower and upper edges.
  const double c = 343.0, base = 20.0;
  for (double fc : {1000.0, 4000.0}) {
    const double lo = sim::air_attenuation_db_per_m(fc / std::sqrt(2.0), 20, 30) / 4.342945 * c;
    const double hi = sim::air_attenuation_db_per_m(fc * std::sqrt(2.0), 20, 30) / 4.342945 * c;
    const double inc = sim::air_band_decay_increase_per_s(fc, 20, 30, c, base);
    EXPECT_GT(inc, lo);
    EXPECT_LT(inc, hi);
  }
}

// A directional source of the same power: the direct sound, and nothing else, is raised by the
// directivity index (its amplitude by 10^(DI/20)); where the index differs by band, so does the rise.
TEST(SourceDirectivity, RaisesTheDirectSoundAloneByTheDirectivityIndex) {
  sim::register_extension_components();
  sim::RoomSpec room = test_room();
  room.source_m = {3.0, 2.4, 1.5};
  room.mic_m = {4.0, 2.4, 1.5};  // 1 m; the first reflection arrives 6 ms after the direct sound
  const double fs = 16000.0;
  const size_t n = 8000;
  const Signal omni = sim::Model::parse("gas").render(room, fs, n, 3);
  const Signal flat = sim::Model::parse("gas+directivity:di62.5=6,di125=6,di250=6,di500=6,di1000=6,di2000=6,di4000=6,"
                                        "di8000=6").render(room, fs, n, 3);
  // The omni direct sound alone: the image sources without the diffuse tail (which starts at the
  // direct sound), up to the first reflection.
  const Signal images = sim::Model::parse("ism").render(room, fs, n, 3);
  const long direct = std::lround(1.0 / room.speed_of_sound_m_s * fs);
  const long half = static_cast<long>(0.001 * fs);
  double inside = 0.0, outside = 0.0, projection = 0.0, omni_energy = 0.0;
  for (long i = 0; i < static_cast<long>(n); ++i) {
    const double diff = flat.samples[i] - omni.samples[i];
    if (std::labs(i - direct) <= half) {
      inside += diff * diff;
      projection += diff * images.samples[i];
      omni_energy += double(images.samples[i]) * images.samples[i];
    } else {
      outside += diff * diff;
    }
  }
  // Only the direct sound moves, and by 10^(6/20) - 1 of itself.
  EXPECT_LT(outside, 1e-9 * inside);
  EXPECT_NEAR(projection / omni_energy, std::pow(10.0, 6.0 / 20.0) - 1.0, 2e-3);

  // A directivity index in the 4 kHz band only: the added sound lies in that band.
  const Signal high = sim::Model::parse("gas+directivity:di4000=6").render(room, fs, n, 3);
  std::vector<float> added(n);
  for (size_t i = 0; i < n; ++i) added[i] = high.samples[i] - omni.samples[i];
  const size_t nfft = 1 << 14;
  const auto spec = rfft(added, nfft);
  double in_band = 0.0, total = 0.0;
  for (size_t k = 0; k < spec.size(); ++k) {
    const double f = k * fs / nfft, e = std::norm(spec[k]);
    total += e;
    if (f >= 4000.0 / std::sqrt(2.0) && f <= 4000.0 * std::sqrt(2.0)) in_band += e;
  }
  EXPECT_GT(in_band, 0.8 * total);
  EXPECT_THROW(sim::Model::parse("gas+directivity:di1000=25"), Error);
}

TEST(Transducer, FilterIsMinimumPhaseWithTheRequestedBandGains) {
  const double fs = 16000.0;
  sim::BandValues g = {3.0, -2.0, 6.0, 0.0, -4.0, 5.0, -6.0, 2.0};
  const std::vector<float> h = sim::transducer_filter(g, fs);
  const size_t n = 1 << 15;
  const auto spec = rfft(h, n);
  for (int b = 0; b < kNumOctaveBands; ++b) {
    const size_t k = static_cast<size_t>(std::lround(kOctaveCentersHz[b] * n / fs));
    if (k >= spec.size()) continue;
    // The cosine interpolation reaches each band's value exactly at its centre; the 64 ms FIR's
    // truncation costs a fraction of a dB.
    EXPECT_NEAR(20.0 * std::log10(std::abs(spec[k])), g[b], 0.5) << kOctaveCentersHz[b];
  }
  // Minimum phase: the energy is at the start (99 % within the first 5 ms for octave-smooth
  // responses; a linear-phase design would centre it at 32 ms).
  double total = 0.0, early = 0.0;
  for (size_t i = 0; i < h.size(); ++i) {
    total += double(h[i]) * h[i];
    if (i < 0.005 * fs) early += double(h[i]) * h[i];
  }
  EXPECT_GT(early / total, 0.99);
}

TEST(OnsetShift, FractionalShiftMatchesTheBandLimitedImpulse) {
  std::vector<float> x(512, 0.0f);
  x[100] = 1.0f;
  const double shift = 10.3;
  const std::vector<float> y = sim::fractional_shift(x, shift);
  for (int i = 90; i < 130; ++i) {
    const double t = i - 100 - shift;
    EXPECT_NEAR(y[i], std::sin(kPi * t) / (kPi * t), 0.02) << i;
  }
}

TEST(Extensions, BandAbsorptionScalesTheEyringRate) {
  sim::register_extension_components();
  const sim::RoomSpec room = test_room();
  const sim::Model m = sim::Model::parse("gas+band_absorption:s500=1.5,s2000=0.7");
  const sim::BandValues before = sim::eyring_decay_rate_per_s(room);
  const sim::BandValues after = sim::eyring_decay_rate_per_s(m.prepare_room(room));
  EXPECT_NEAR(after[3] / before[3], 1.5, 1e-9);  // uniform absorption: exact
  EXPECT_NEAR(after[5] / before[5], 0.7, 1e-9);
  EXPECT_NEAR(after[4] / before[4], 1.0, 1e-12);
}

TEST(Extensions, NoiseFloorLevelIsRelativeToTheRirEnergy) {
  sim::register_extension_components();
  const sim::RoomSpec room = test_room();
  const double fs = 16000.0;
  const Signal clean = sim::Model::parse("gas").render(room, fs, 16000, 3);
  const Signal noisy = sim::Model::parse("gas+noise_floor:level_db=-50").render(room, fs, 16000, 3);
  double e = 0.0, late = 0.0;
  for (float v : clean.samples) e += double(v) * v;
  for (size_t i = 14000; i < 16000; ++i) late += double(noisy.samples[i]) * noisy.samples[i];
  // 2000 Gaussian samples: the power estimate is within ~10 % (3 sigma).
  EXPECT_NEAR(10.0 * std::log10(late / 2000.0 / e), -50.0, 0.5);
}

TEST(Extensions, OnsetShiftAlignsOrDelays) {
  sim::register_extension_components();
  const sim::RoomSpec room = test_room();
  const double fs = 16000.0;
  auto peak_at = [](const Signal& s) {
    size_t best = 0;
    for (size_t i = 0; i < s.size(); ++i) {
      if (std::abs(s.samples[i]) > std::abs(s.samples[best])) best = i;
    }
    return best / 16000.0;
  };
  const double direct = room.source_mic_distance_m() / room.speed_of_sound_m_s;
  const Signal aligned = sim::Model::parse("gas+onset_shift:align_ms=10").render(room, fs, 8000, 1);
  const Signal delayed = sim::Model::parse("gas+onset_shift:latency_ms=4").render(room, fs, 8000, 1);
  EXPECT_NEAR(peak_at(aligned), 0.010, 1.0 / fs);
  EXPECT_NEAR(peak_at(delayed), direct + 0.004, 1.0 / fs);
}

TEST(RoomModes, ModeFrequenciesAndModalEnergyAgreeWithTheImageSources) {
  sim::register_extension_components();
  const sim::RoomSpec room = test_room();
  const auto modes = sim::shoebox_modes(room.size_m, 343.0, 20.0, 60.0);
  ASSERT_FALSE(modes.empty());
  EXPECT_NEAR(modes[0].freq_hz, 343.0 / (2.0 * 6.2), 1e-9);  // the (1,0,0) axial mode
  // The synthesised modal response carries, per mode, the energy of the damped sinusoid of the
  // modal expansion: sum over modes of (c^2 / (V fs) psi psi / Lambda / w)^2 fs / (4 d). Compared
  // in 20-100 Hz (modes' spectral leakage across the band edges: 1.5 dB).
  const double fs = 8000.0, c = room.speed_of_sound_m_s, v = room.volume_m3();
  sim::ComponentParams params("modes", {});
  const sim::RoomModesComponent component(params);
  const std::vector<double> h = component.modal_response(room, fs, 8000, room.source_mic_distance_m() / c);
  const std::vector<float> hf(h.begin(), h.end());
  const size_t nfft = 16384;
  const auto p = power_spectrum(hf, nfft);
  double measured = 0.0;
  for (size_t k = 0; k < p.size(); ++k) {
    if (k * fs / nfft >= 20.0 && k * fs / nfft < 100.0) measured += 2.0 * p[k] / nfft;
  }
  const sim::BandValues rate = sim::eyring_decay_rate_per_s(room);
  double expected = 0.0;
  for (const auto& m : sim::shoebox_modes(room.size_m, c, 20.0, 100.0)) {
    double shape = 1.0;
    const int idx[3] = {m.nx, m.ny, m.nz};
    for (int i = 0; i < 3; ++i) {
      shape *= std::cos(idx[i] * kPi * room.source_m[i] / room.size_m[i]) * std::cos(idx[i] * kPi * room.mic_m[i] / room.size_m[i]);
      if (idx[i]) shape *= 2.0;
    }
    const double w = 2.0 * kPi * m.freq_hz;
    const double d = 0.5 * (m.freq_hz < 62.5 ? rate[0] : rate[0] + (rate[1] - rate[0]) * std::log2(m.freq_hz / 62.5));
    expected += std::pow(c * c / (v * fs) * shape / w, 2) * fs / (4.0 * d);
  }
  EXPECT_NEAR(10.0 * std::log10(measured / expected), 0.0, 1.5);
}

}  // namespace
}  // namespace tsrir

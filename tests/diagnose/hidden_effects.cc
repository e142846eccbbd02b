#include "hidden_effects.h"

#include <cmath>
#include <complex>

#include "dsp/fft.h"
#include "sim/model.h"
#include "util/rng.h"

namespace tsrir::testing {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Forward FFT of a real signal and back, through the dsp library's RealFft (the FFT is not what
// is under test).
std::vector<std::complex<float>> spectrum_of(const std::vector<float>& x, size_t n) { return rfft(x, n); }
std::vector<float> inverse_of(std::vector<std::complex<float>> spec, size_t n) {
  RealFft fft(n);
  std::vector<float> out(n);
  fft.inverse(spec.data(), out.data());
  for (float& v : out) v /= static_cast<float>(n);
  return out;
}

void add_room_modes(const sim::RoomSpec& room, Signal& s, Rng& rng, double gain_db, double decay_factor) {
  const double fs = s.sample_rate_hz, c = room.speed_of_sound_m_s;
  const double lx = room.size_m[0], ly = room.size_m[1], lz = room.size_m[2];
  const double t60_low = sim::eyring_t60_s(room)[1] * decay_factor;
  const double onset = room.source_mic_distance_m() / c;
  const double scale = std::pow(10.0, gain_db / 20.0) * c * c / (room.volume_m3() * fs);
  for (int p = 0; p < 12; ++p) {
    for (int q = 0; q < 12; ++q) {
      for (int r = 0; r < 8; ++r) {
        const double f = 0.5 * c * std::sqrt(std::pow(p / lx, 2) + std::pow(q / ly, 2) + std::pow(r / lz, 2));
        if (f < 20.0 || f > 180.0) continue;
        auto shape = [&](const sim::Vec3& x) {
          return std::cos(p * kPi * x[0] / lx) * std::cos(q * kPi * x[1] / ly) * std::cos(r * kPi * x[2] / lz);
        };
        const double norm = (p ? 2.0 : 1.0) * (q ? 2.0 : 1.0) * (r ? 2.0 : 1.0);
        const double jitter = std::pow(10.0, rng.normal(0.0, 3.0) / 20.0);
        const double amp = scale * norm * shape(room.source_m) * shape(room.mic_m) * jitter / (2.0 * kPi * f);
        const double t60 = t60_low * rng.uniform(0.85, 1.15);
        const double delta = 6.907755 / t60;  // amplitude decay for 60 dB in t60
        for (size_t i = static_cast<size_t>(std::ceil(onset * fs)); i < s.size(); ++i) {
          const double t = i / fs;
          s.samples[i] += static_cast<float>(amp * std::sin(2.0 * kPi * f * t) * std::exp(-delta * t));
        }
      }
    }
  }
}

void apply_air(Signal& s, double temperature_c, double humidity, double c) {
  // STFT, sqrt-Hann analysis and synthesis windows at 75 % overlap (the squared windows sum to 2).
  const size_t frame = 512, hop = 128;
  const double fs = s.sample_rate_hz;
  const size_t n = s.size();
  std::vector<float> padded(n + 2 * frame, 0.0f);
  std::copy(s.samples.begin(), s.samples.end(), padded.begin() + frame);
  std::vector<double> out(padded.size(), 0.0);
  std::vector<double> win(frame);
  for (size_t i = 0; i < frame; ++i) win[i] = std::sqrt(0.5 - 0.5 * std::cos(2.0 * kPi * i / frame));
  std::vector<double> alpha(frame / 2 + 1);
  for (size_t k = 0; k < alpha.size(); ++k) alpha[k] = test_air_attenuation_db_per_m(k * fs / frame, temperature_c, humidity);
  for (size_t start = 0; start + frame <= padded.size(); start += hop) {
    std::vector<float> x(frame);
    for (size_t i = 0; i < frame; ++i) x[i] = static_cast<float>(padded[start + i] * win[i]);
    auto spec = spectrum_of(x, frame);
    const double t_centre = (static_cast<double>(start) + frame / 2.0 - frame) / fs;
    const double distance = std::max(0.0, t_centre) * c;
    for (size_t k = 0; k < spec.size(); ++k) spec[k] *= static_cast<float>(std::pow(10.0, -alpha[k] * distance / 20.0));
    const std::vector<float> y = inverse_of(spec, frame);
    for (size_t i = 0; i < frame; ++i) out[start + i] += y[i] * win[i] / 2.0;
  }
  for (size_t i = 0; i < n; ++i) s.samples[i] = static_cast<float>(out[frame + i]);
}

struct TestBiquad { double b0, b1, b2, a1, a2; };

// RBJ audio-EQ cookbook peaking filter.
TestBiquad peaking(double f0, double gain_db, double q, double fs) {
  const double a = std::pow(10.0, gain_db / 40.0), w = 2.0 * kPi * f0 / fs, alpha = std::sin(w) / (2.0 * q);
  const double a0 = 1.0 + alpha / a;
  return {(1.0 + alpha * a) / a0, -2.0 * std::cos(w) / a0, (1.0 - alpha * a) / a0, -2.0 * std::cos(w) / a0,
          (1.0 - alpha / a) / a0};
}
// RBJ high shelf (shelf slope 1).
TestBiquad high_shelf(double f0, double gain_db, double fs) {
  const double a = std::pow(10.0, gain_db / 40.0), w = 2.0 * kPi * f0 / fs;
  const double alpha = std::sin(w) / 2.0 * std::sqrt(2.0), cw = std::cos(w), sa = 2.0 * std::sqrt(a) * alpha;
  const double a0 = (a + 1) - (a - 1) * cw + sa;
  return {a * ((a + 1) + (a - 1) * cw + sa) / a0, -2 * a * ((a - 1) + (a + 1) * cw) / a0,
          a * ((a + 1) + (a - 1) * cw - sa) / a0, 2 * ((a - 1) - (a + 1) * cw) / a0, ((a + 1) - (a - 1) * cw - sa) / a0};
}

void apply_biquad(const TestBiquad& f, std::vector<float>& x) {
  double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
  for (float& v : x) {
    const double y = f.b0 * v + f.b1 * x1 + f.b2 * x2 - f.a1 * y1 - f.a2 * y2;
    x2 = x1; x1 = v; y2 = y1; y1 = y;
    v = static_cast<float>(y);
  }
}

}  // namespace

double test_air_attenuation_db_per_m(double f, double temperature_c, double humidity) {
  // ISO 9613-1:1993, equations (3)-(5) and (B.1)-(B.3), at the reference pressure.
  const double T = temperature_c + 273.15, Tr = 293.15, T01 = 273.16;
  const double csat = -6.8346 * std::pow(T01 / T, 1.261) + 4.6151;
  const double h = humidity * std::pow(10.0, csat);
  const double frO = 24.0 + 4.04e4 * h * (0.02 + h) / (0.391 + h);
  const double frN = std::pow(T / Tr, -0.5) * (9.0 + 280.0 * h * std::exp(-4.170 * (std::pow(T / Tr, -1.0 / 3.0) - 1.0)));
  const double oxygen = 0.01275 * std::exp(-2239.1 / T) / (frO + f * f / frO);
  const double nitrogen = 0.1068 * std::exp(-3352.0 / T) / (frN + f * f / frN);
  return 8.686 * f * f * (1.84e-11 * std::pow(T / Tr, 0.5) + std::pow(T / Tr, -2.5) * (oxygen + nitrogen));
}

std::vector<sim::RoomSpec> make_test_rooms(size_t count, uint64_t seed) {
  Rng rng(seed);
  std::vector<sim::RoomSpec> rooms;
  const sim::BandValues absorption = {0.12, 0.14, 0.16, 0.18, 0.20, 0.22, 0.25, 0.30};
  while (rooms.size() < count) {
    sim::RoomSpec r;
    r.rir_id = "pos" + std::to_string(100 + rooms.size());
    r.size_m = {6.2, 4.8, 3.0};
    for (auto& s : r.absorption) s = absorption;
    r.scattering.fill(0.1);
    r.source_m = {rng.uniform(0.6, 5.6), rng.uniform(0.6, 4.2), rng.uniform(1.2, 1.8)};
    r.mic_m = {rng.uniform(0.6, 5.6), rng.uniform(0.6, 4.2), rng.uniform(1.0, 1.6)};
    if (r.source_mic_distance_m() < 1.0) continue;
    r.where = "test room " + r.rir_id;
    rooms.push_back(r);
  }
  return rooms;
}

HiddenSet make_hidden_set(const std::vector<sim::RoomSpec>& rooms, const std::set<std::string>& effects, uint64_t seed,
                          double fs, double length_s) {
  Rng rng(seed);
  HiddenSet set;
  set.stated = rooms;
  const size_t n = static_cast<size_t>(std::llround(length_s * fs));
  const sim::Model truth = sim::Model::parse("gas");

  // Set-level hidden parameters (a measurement campaign has one chain, one air, one room).
  sim::BandValues absorption_factor;
  for (double& f : absorption_factor) f = std::exp((rng.uniform() < 0.5 ? -1 : 1) * rng.uniform(std::log(1.35), std::log(1.8)));
  const double scattering = rng.uniform(0.45, 0.85);
  const double mode_gain_db = rng.uniform(0.0, 6.0), mode_decay = rng.uniform(1.5, 2.5);
  const double air_t = rng.uniform(16.0, 26.0), air_rh = rng.uniform(10.0, 40.0);
  // A colouration a measurement would show: redrawn until its octave-band levels (500 Hz-4 kHz)
  // span at least 3 dB (peaks that cancel within octaves are no colouration at that resolution).
  std::vector<TestBiquad> chain;
  for (int attempt = 0; attempt < 100; ++attempt) {
    chain.clear();
    for (int k = 0; k < 3; ++k) {
      const double g = (rng.uniform() < 0.5 ? -1 : 1) * rng.uniform(4.0, 9.0);
      chain.push_back(peaking(std::exp(rng.uniform(std::log(400.0), std::log(5000.0))), g, rng.uniform(0.7, 1.5), fs));
    }
    chain.push_back(high_shelf(rng.uniform(2000.0, 5000.0), (rng.uniform() < 0.5 ? -1 : 1) * rng.uniform(3.0, 6.0), fs));
    double lo = INFINITY, hi = -INFINITY;
    for (double fc : {500.0, 1000.0, 2000.0, 4000.0}) {
      double e = 0.0;
      for (int j = 0; j < 32; ++j) {
        const double f = fc * std::pow(2.0, (j + 0.5) / 32.0 - 0.5);
        const std::complex<double> z = std::exp(std::complex<double>(0.0, -2.0 * kPi * f / fs));
        std::complex<double> h = 1.0;
        for (const TestBiquad& q : chain) h *= (q.b0 + q.b1 * z + q.b2 * z * z) / (1.0 + q.a1 * z + q.a2 * z * z);
        e += std::norm(h) / 32.0;
      }
      lo = std::min(lo, 10.0 * std::log10(e));
      hi = std::max(hi, 10.0 * std::log10(e));
    }
    if (hi - lo >= 3.0) break;
  }
  const double peak_to_noise_db = rng.uniform(35.0, 55.0);
  const bool pink = rng.uniform() < 0.5;
  const double latency_ms = rng.uniform(2.0, 12.0);
  const uint64_t render_seed = 1000 + seed;

  if (effects.count("band_absorption")) {
    for (int b = 0; b < kNumOctaveBands; ++b) set.truth["absorption_factor_" + std::to_string(b)] = absorption_factor[b];
  }
  if (effects.count("diffuse_scattering")) set.truth["scattering"] = scattering;
  if (effects.count("air_absorption")) { set.truth["temperature_c"] = air_t; set.truth["humidity_percent"] = air_rh; }
  if (effects.count("noise_floor")) set.truth["peak_to_noise_db"] = peak_to_noise_db;
  if (effects.count("time_offset")) set.truth["latency_ms"] = std::round(latency_ms * 1e-3 * fs) / fs * 1e3;

  for (const sim::RoomSpec& stated : rooms) {
    sim::RoomSpec real = stated;
    if (effects.count("band_absorption")) {
      for (auto& s : real.absorption) {
        for (int b = 0; b < kNumOctaveBands; ++b) s[b] = std::min(0.9, s[b] * absorption_factor[b]);
      }
    }
    if (effects.count("diffuse_scattering")) real.scattering.fill(scattering);
    Signal s = truth.render(real, fs, n, render_seed);
    Rng item = Rng::for_item(seed, stated.rir_id);
    if (effects.count("room_modes")) add_room_modes(stated, s, item, mode_gain_db, mode_decay);
    if (effects.count("air_absorption")) apply_air(s, air_t, air_rh, stated.speed_of_sound_m_s);
    if (effects.count("transducer_response")) {
      for (const TestBiquad& f : chain) apply_biquad(f, s.samples);
    }
    if (effects.count("time_offset")) {
      const size_t shift = static_cast<size_t>(std::llround(latency_ms * 1e-3 * fs));
      s.samples.insert(s.samples.begin(), shift, 0.0f);
      s.samples.resize(n);
    }
    if (effects.count("noise_floor")) {
      float peak = 0.0f;
      for (float v : s.samples) peak = std::max(peak, std::abs(v));
      std::vector<float> noise(n);
      for (float& v : noise) v = static_cast<float>(item.normal());
      if (pink) {
        // 1/f power: amplitude ~ f^-1/2 above 20 Hz.
        const size_t size = next_fast_fft_size(2 * n);
        auto spec = spectrum_of(noise, size);
        for (size_t k = 0; k < spec.size(); ++k) spec[k] *= static_cast<float>(1.0 / std::sqrt(std::max(20.0, k * fs / size) / 1000.0));
        noise = inverse_of(spec, size);
        noise.resize(n);
      }
      double p = 0.0;
      for (float v : noise) p += double(v) * v;
      const double rms = std::sqrt(p / n);
      const double target = peak * std::pow(10.0, -peak_to_noise_db / 20.0);
      for (size_t i = 0; i < n; ++i) s.samples[i] += static_cast<float>(noise[i] * target / rms);
    }
    s.id = stated.rir_id;
    set.measured.push_back(std::move(s));
  }
  return set;
}

}  // namespace tsrir::testing

#include "hidden_effects.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "dsp/fft.h"
#include "measured_rir_generator.h"
#include "util/rng.h"

namespace tsrir::testdata {
namespace {

// Draws `name` from [lo, hi) unless the options fix it; the draw is made either way, so fixing
// one parameter does not change the others.
double drawn(Rng& rng, const HiddenOptions& o, const std::string& name, double lo, double hi) {
  const double v = rng.uniform(lo, hi);
  auto it = o.fixed.find(name);
  return it == o.fixed.end() ? v : it->second;
}

}  // namespace

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
                          double fs, double length_s, const HiddenOptions& options) {
  Rng rng(seed);
  HiddenSet set;
  set.stated = rooms;
  const size_t n = static_cast<size_t>(std::llround(length_s * fs));

  // Set-level hidden parameters (a measurement campaign has one chain, one air, one room).
  sim::BandValues absorption_factor;
  for (int b = 0; b < kNumOctaveBands; ++b) {
    const double sign = rng.uniform() < 0.5 ? -1 : 1;
    const double mag = rng.uniform(std::log(1.35), std::log(1.8));
    const auto fixed = options.fixed.find("absorption_factor_" + std::to_string(b));
    absorption_factor[b] = fixed == options.fixed.end() ? std::exp(sign * mag) : fixed->second;
  }
  const double scattering = drawn(rng, options, "scattering", 0.8, 0.95);
  const double mode_gain_db = drawn(rng, options, "mode_gain_db", 0.0, 6.0);
  const double mode_decay = drawn(rng, options, "mode_decay_factor", 1.5, 2.5);
  const double air_t = drawn(rng, options, "temperature_c", 16.0, 26.0);
  const double air_rh = drawn(rng, options, "humidity_percent", 10.0, 40.0);
  // The true room's size differs slightly from the stated one (its modes are the true room's).
  sim::Vec3 mode_room_scale;
  for (double& s : mode_room_scale) s = 1.0 + rng.uniform(-0.015, 0.015);
  // A colouration a measurement would show: redrawn until its octave-band levels (500 Hz-4 kHz)
  // span at least 3 dB (peaks that cancel within octaves are no colouration at that resolution).
  const double transducer_scale = options.fixed.count("transducer_scale") ? options.fixed.at("transducer_scale") : 1.0;
  std::vector<TestBiquad> chain;
  for (int attempt = 0; attempt < 100; ++attempt) {
    chain.clear();
    for (int k = 0; k < 3; ++k) {
      const double g = (rng.uniform() < 0.5 ? -1 : 1) * rng.uniform(4.0, 9.0) * transducer_scale;
      chain.push_back(test_peaking(std::exp(rng.uniform(std::log(400.0), std::log(5000.0))), g, rng.uniform(0.7, 1.5), fs));
    }
    chain.push_back(
        test_high_shelf(rng.uniform(2000.0, 5000.0), (rng.uniform() < 0.5 ? -1 : 1) * rng.uniform(3.0, 6.0) * transducer_scale, fs));
    double lo = INFINITY, hi = -INFINITY;
    for (double fc : {500.0, 1000.0, 2000.0, 4000.0}) {
      const double e = test_cascade_octave_gain_db(chain, fc, fs);
      lo = std::min(lo, e);
      hi = std::max(hi, e);
    }
    if (hi - lo >= 3.0 * transducer_scale) break;
  }
  if (options.fixed.count("transducer_peak_db")) {
    chain = {test_peaking(1000.0, options.fixed.at("transducer_peak_db"), 1.4, fs)};
  }
  const double peak_to_noise_db = drawn(rng, options, "peak_to_noise_db", 35.0, 55.0);
  bool pink = rng.uniform() < 0.5;
  if (options.fixed.count("noise_re_tail") || options.fixed.count("noise_late_decay_db")) pink = false;  // sweeps: white
  const double latency_ms = drawn(rng, options, "latency_ms", 2.0, 12.0);
  // A small measurement loudspeaker's directivity index: ~0 at 125 Hz and below, rising over four
  // octaves to its high-frequency value at 2 kHz and above (drawn last: adding it changed no other
  // draw of the sets above).
  const double directivity_db = drawn(rng, options, "directivity_db", 4.0, 8.0);
  sim::BandValues directivity{};
  for (int b = 0; b < kNumOctaveBands; ++b) {
    directivity[b] = options.fixed.count("directivity_flat_db")
                         ? options.fixed.at("directivity_flat_db")
                         : directivity_db * std::clamp(std::log2(kOctaveCentersHz[b] / 125.0) / 4.0, 0.0, 1.0);
  }
  const double size_factor = 1.0 + options.size_error;
  // The dense modal field (drawn after everything above: the other draws stay as they were). Its
  // level re the modal Green's function and the divisor of every mode's Morse damping (1: the
  // walls' damping, which already leaves axial modes decaying ~1.6x slower than the tail), and a
  // true room within +-5 % of the stated one per dimension.
  const double modal_gain_db = drawn(rng, options, "modal_gain_db", -3.0, 3.0);
  const double modal_decay = drawn(rng, options, "modal_decay_factor", 1.0, 2.0);
  sim::Vec3 modal_room_scale;
  const double modal_size_error = options.fixed.count("modal_size_error") ? options.fixed.at("modal_size_error") : 0.05;
  for (double& s : modal_room_scale) s = 1.0 + modal_size_error * rng.uniform(-1.0, 1.0);
  const bool dense = options.dense_modes && effects.count("room_modes");
  // Outside the catalog (drawn last: nothing above changes).
  const double coupled_level_db = drawn(rng, options, "coupled_level_db", -14.0, -8.0);
  const double coupled_decay = drawn(rng, options, "coupled_decay_factor", 2.5, 4.0);
  const double flutter_level_db = drawn(rng, options, "flutter_level_db", -12.0, -6.0);
  const double flutter_loss_db = drawn(rng, options, "flutter_trip_loss_db", 0.5, 1.5);
  const double splay_m = drawn(rng, options, "splay_m", 0.6, 1.2);
  if (options.coupled_room) { set.truth["coupled_level_db"] = coupled_level_db; set.truth["coupled_decay_factor"] = coupled_decay; }
  if (options.flutter) { set.truth["flutter_level_db"] = flutter_level_db; set.truth["flutter_trip_loss_db"] = flutter_loss_db; }
  if (options.non_shoebox) set.truth["splay_m"] = splay_m;

  if (effects.count("band_absorption")) {
    for (int b = 0; b < kNumOctaveBands; ++b) set.truth["absorption_factor_" + std::to_string(b)] = absorption_factor[b];
  }
  if (effects.count("diffuse_scattering")) set.truth["scattering"] = scattering;
  if (effects.count("air_absorption")) { set.truth["temperature_c"] = air_t; set.truth["humidity_percent"] = air_rh; }
  if (effects.count("noise_floor")) {
    set.truth["peak_to_noise_db"] = peak_to_noise_db;
    set.truth["pink"] = pink;
  }
  if (effects.count("time_offset")) set.truth["latency_ms"] = latency_ms;
  if (effects.count("source_directivity")) {
    for (int b = 0; b < kNumOctaveBands; ++b) set.truth["directivity_db_" + std::to_string(b)] = directivity[b];
  }
  if (effects.count("room_modes") && !dense) { set.truth["mode_gain_db"] = mode_gain_db; set.truth["mode_decay_factor"] = mode_decay; }
  if (dense) {
    set.truth["modal_gain_db"] = modal_gain_db;
    set.truth["modal_decay_factor"] = modal_decay;
    for (int a = 0; a < 3; ++a) set.truth["modal_room_scale_" + std::to_string(a)] = modal_room_scale[a];
  }
  if (effects.count("transducer_response") || options.highpass_hz > 0.0) {
    std::vector<TestBiquad> full = effects.count("transducer_response") ? chain : std::vector<TestBiquad>{};
    if (options.highpass_hz > 0.0) full.push_back(test_high_pass(options.highpass_hz, std::sqrt(0.5), fs));
    for (int b = 0; b < kNumOctaveBands; ++b) {
      if (kOctaveCentersHz[b] * std::sqrt(2.0) < fs / 2) {
        set.truth["transducer_db_" + std::to_string(b)] = test_cascade_octave_gain_db(full, kOctaveCentersHz[b], fs);
      }
    }
  }

  std::vector<double> noise_level_db;
  // The decay-rate factor per band that the absorption factors make (by the generator's own
  // Eyring formula at the band centres), averaged in log over the set: the factor multiplies the
  // surfaces' absorption a, while what a measured decay shows (and the simulator's band refit is,
  // by its definition: (1 - a') = (1 - a)^s) is the change of the decay rate -ln(1 - a), which
  // is larger than the factor on a for a > 0 (a = 0.35 x 1.7: rate x 2.1).
  sim::BandValues log_rate_factor_sum{};
  for (const sim::RoomSpec& stated : rooms) {
    Rng item = Rng::for_item(seed, stated.rir_id);
    TrueRoom real = true_room_from(stated);
    for (int a = 0; a < 3; ++a) {
      real.size_m[a] *= size_factor;
      real.source_m[a] = real.source_m[a] * size_factor + item.uniform(-1.0, 1.0) * options.position_error_m;
      real.mic_m[a] = real.mic_m[a] * size_factor + item.uniform(-1.0, 1.0) * options.position_error_m;
      real.source_m[a] = std::clamp(real.source_m[a], 0.1, real.size_m[a] - 0.1);
      real.mic_m[a] = std::clamp(real.mic_m[a], 0.1, real.size_m[a] - 0.1);
    }
    if (effects.count("band_absorption")) {
      const sim::BandValues rate_before = test_eyring_rate_per_s(real);
      for (auto& s : real.absorption) {
        for (int b = 0; b < kNumOctaveBands; ++b) s[b] = std::min(0.9, s[b] * absorption_factor[b]);
      }
      const sim::BandValues rate_after = test_eyring_rate_per_s(real);
      for (int b = 0; b < kNumOctaveBands; ++b) log_rate_factor_sum[b] += std::log(rate_after[b] / rate_before[b]);
    }
    if (effects.count("diffuse_scattering")) real.scattering.fill(scattering);
    if (effects.count("air_absorption")) {
      real.air = true;
      real.air_temperature_c = air_t;
      real.air_humidity_percent = air_rh;
      if (options.fixed.count("air_scale")) real.air_scale = options.fixed.at("air_scale");
    }
    if (effects.count("time_offset")) real.latency_s = latency_ms * 1e-3;
    if (options.coupled_room) {
      real.coupled_level_db = coupled_level_db;
      real.coupled_decay_factor = coupled_decay;
    }
    if (options.flutter) {
      real.flutter_level_db = flutter_level_db;
      real.flutter_trip_loss_db = flutter_loss_db;
    }
    if (options.non_shoebox) {
      const double lx = real.size_m[0], ly = real.size_m[1];
      real.floor_polygon = {{0.0, 0.0}, {lx, 0.0}, {lx + splay_m, ly}, {-splay_m, ly}};
    }
    if (effects.count("source_directivity")) real.directivity_db = directivity;
    if (dense) {
      // Positions stay where they were measured (from the room's origin corner), inside the room.
      for (int a = 0; a < 3; ++a) {
        real.size_m[a] *= modal_room_scale[a];
        real.source_m[a] = std::clamp(real.source_m[a], 0.1, real.size_m[a] - 0.1);
        real.mic_m[a] = std::clamp(real.mic_m[a], 0.1, real.size_m[a] - 0.1);
      }
      real.modal_gain_db = modal_gain_db;
      real.modal_decay_factor = modal_decay;
      if (options.fixed.count("modal_max_factor")) real.modal_max_factor = options.fixed.at("modal_max_factor");
    } else if (effects.count("room_modes")) {
      for (int a = 0; a < 3; ++a) real.size_m[a] *= mode_room_scale[a];
      real.mode_gain_db = mode_gain_db;
      real.mode_decay_factor = mode_decay;
    }
    Signal s = generate_measured_rir(real, fs, n, item);
    if (options.pre_align_ms > 0.0) {
      double d2 = 0.0;
      for (int a = 0; a < 3; ++a) d2 += std::pow(real.source_m[a] - real.mic_m[a], 2);
      const double arrival_s = std::sqrt(d2) / real.speed_of_sound_m_s + real.latency_s;
      const long shift = std::lround((options.pre_align_ms * 1e-3 - arrival_s) * fs);
      std::vector<float> moved(n, 0.0f);
      for (long i = 0; i < static_cast<long>(n); ++i) {
        const long j = i - shift;
        if (j >= 0 && j < static_cast<long>(n)) moved[i] = s.samples[j];
      }
      s.samples = std::move(moved);
    }
    if (effects.count("transducer_response")) {
      for (const TestBiquad& f : chain) apply_test_biquad(f, s.samples);
    }
    if (options.highpass_hz > 0.0) apply_test_biquad(test_high_pass(options.highpass_hz, std::sqrt(0.5), fs), s.samples);
    if (effects.count("noise_floor")) {
      float peak = 0.0f;
      for (float v : s.samples) peak = std::max(peak, std::abs(v));
      std::vector<float> noise(n);
      for (float& v : noise) v = static_cast<float>(item.normal());
      if (pink) {
        // 1/f power: amplitude ~ f^-1/2 above 20 Hz.
        const size_t size = next_fast_fft_size(2 * n);
        auto spec = rfft(noise, size);
        for (size_t k = 0; k < spec.size(); ++k) spec[k] *= static_cast<float>(1.0 / std::sqrt(std::max(20.0, k * fs / size) / 1000.0));
        RealFft fft(size);
        std::vector<float> back(size);
        fft.inverse(spec.data(), back.data());
        back.resize(n);
        noise = back;
      }
      double p = 0.0;
      for (float v : noise) p += double(v) * v;
      const double rms = std::sqrt(p / n);
      double target = peak * std::pow(10.0, -peak_to_noise_db / 20.0);
      double energy = 0.0;
      for (float v : s.samples) energy += double(v) * v;
      if (options.fixed.count("noise_re_tail")) {
        double tail = 0.0;
        for (size_t i = n - n / 10; i < n; ++i) tail += double(s.samples[i]) * s.samples[i];
        target = std::sqrt(options.fixed.at("noise_re_tail") * tail / (n / 10));
      }
      if (options.fixed.count("noise_late_decay_db")) {
        // White noise of the power that leaves the noisy RIR decaying by this much between 70-80 %
        // and 90-100 % of the file, as the median over the 500 Hz-4 kHz octaves (the detector's
        // statistic): per octave (P7 + N_b) / (P9 + N_b), N_b the noise's share of the octave,
        // solved for the noise power by bisection in dB.
        auto band_powers = [&](size_t a, size_t b) {
          std::vector<float> seg(s.samples.begin() + a, s.samples.begin() + b);
          const size_t size = next_fast_fft_size(seg.size());
          const auto spec = rfft(seg, size);
          std::vector<double> out;
          for (double fc : {500.0, 1000.0, 2000.0, 4000.0}) {
            double e = 0.0;
            for (size_t k = 0; k < spec.size(); ++k) {
              const double f = k * fs / size;
              if (f >= fc / std::sqrt(2.0) && f < fc * std::sqrt(2.0)) e += std::norm(spec[k]);
            }
            out.push_back(2.0 * e / (double(size) * (b - a)));  // per-sample power in the octave
          }
          return out;
        };
        const std::vector<double> p7 = band_powers(7 * n / 10, 8 * n / 10), p9 = band_powers(9 * n / 10, n);
        const double want = options.fixed.at("noise_late_decay_db");
        auto late_decay = [&](double noise_power) {
          std::vector<double> d;
          for (size_t k = 0; k < p7.size(); ++k) {
            // White noise's share of the octave: its bandwidth over the Nyquist band.
            const double share = noise_power * (std::sqrt(2.0) - 1.0 / std::sqrt(2.0)) * (500.0 * (1 << k)) / (0.5 * fs);
            d.push_back(10.0 * std::log10((p7[k] + share) / (p9[k] + share)));
          }
          std::sort(d.begin(), d.end());
          return 0.5 * (d[1] + d[2]);
        };
        double lo = -200.0, hi = 100.0;  // noise power, dB re 1
        for (int it = 0; it < 100; ++it) {
          const double mid = 0.5 * (lo + hi);
          (late_decay(std::pow(10.0, mid / 10.0)) > want ? lo : hi) = mid;
        }
        target = std::sqrt(std::pow(10.0, 0.5 * (lo + hi) / 10.0));
      }
      for (size_t i = 0; i < n; ++i) s.samples[i] += static_cast<float>(noise[i] * target / rms);
      // The noise's power per sample at its 1 kHz spectral density, re the clean RIR's energy
      // (the noise_floor extension's level_db): white noise has its mean density there; pink
      // noise's 1 kHz density is 1 / mean(1000 / max(20, f)) of its mean.
      double density_at_1k = 1.0;
      if (pink) {
        double mean_gain = 0.0;
        const size_t bins = 4096;
        for (size_t k = 0; k <= bins; ++k) mean_gain += 1000.0 / std::max(20.0, k * 0.5 * fs / bins) / (bins + 1);
        density_at_1k = 1.0 / mean_gain;
      }
      noise_level_db.push_back(10.0 * std::log10(target * target * density_at_1k / energy));
    }
    if (options.silent_tail_s > 0.0) {
      const size_t cut = n - std::min(n, static_cast<size_t>(std::lround(options.silent_tail_s * fs)));
      std::fill(s.samples.begin() + cut, s.samples.end(), 0.0f);
    }
    s.id = stated.rir_id;
    set.measured.push_back(std::move(s));
  }
  if (!noise_level_db.empty()) {
    std::sort(noise_level_db.begin(), noise_level_db.end());
    set.truth["noise_level_db"] = noise_level_db[noise_level_db.size() / 2];
  }
  if (effects.count("band_absorption") && !rooms.empty()) {
    for (int b = 0; b < kNumOctaveBands; ++b) {
      set.truth["decay_rate_factor_" + std::to_string(b)] = std::exp(log_rate_factor_sum[b] / rooms.size());
    }
  }
  return set;
}

}  // namespace tsrir::testdata

#include "diagnose/extension_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>

#include "diagnose/set_statistics.h"
#include "dsp/octave_filter.h"
#include "sim/extension_components.h"
#include "sim/model.h"
#include "sim/noise_floor.h"
#include "sim/room_modes.h"
#include "sim/room_refits.h"
#include "sim/transducer.h"
#include "util/parallel.h"
#include "util/strings.h"

namespace tsrir::diagnose {
namespace {

std::string num(double v) { return format_double(v, 5); }

Finding* find(std::vector<Finding>* findings, const std::string& effect) {
  for (Finding& f : *findings) {
    if (f.effect == effect) return &f;
  }
  return nullptr;
}

// Noise power fraction an octave filter passes of tilted white noise (relative to the noise's
// per-sample power at the 1 kHz density): integral of |H|^2 g(f) df / (fs / 2).
double band_noise_fraction(int band, double tilt, double fs, double lo_hz, double hi_hz) {
  const SosFilter filter = ansi_octave_filter(kOctaveCentersHz[band], fs, 3);
  constexpr int kGrid = 4096;
  double s = 0.0;
  for (int k = 1; k < kGrid; ++k) {
    const double f = 0.5 * fs * k / kGrid;
    s += std::norm(sos_response(filter, f, fs)) * sim::noise_tilt_power_gain(f, tilt, lo_hz, hi_hz);
  }
  return s / kGrid;
}

}  // namespace

Signal render_rir(const std::string& model_spec, const sim::RoomSpec& room, double fs, size_t n, uint64_t seed) {
  sim::register_extension_components();
  return sim::Model::parse(model_spec).render(room, fs, n, seed);
}

sim::BandValues band_absorption_scales(const SetObservations& obs, const std::vector<size_t>& idx, const AirFit& air_fit,
                                       double keep_below_hz) {
  const double temp = obs.rooms[0].temperature_c, c = obs.rooms[0].speed_of_sound_m_s;
  sim::BandValues scale;
  scale.fill(NAN);
  for (int b = 0; b < kNumOctaveBands; ++b) {
    if (kOctaveCentersHz[b] < keep_below_hz) { scale[b] = 1.0; continue; }
    std::vector<double> q, r;
    for (size_t i : idx) {
      q.push_back(std::log(obs.meas[i].decay_rate_per_s[b] / obs.sim_a[i].decay_rate_per_s[b]));
      r.push_back(obs.sim_a[i].decay_rate_per_s[b]);
    }
    if (finite_values(q).size() >= std::max<size_t>(1, idx.size() / 2)) {
      const double air_share = air_fit.scale > 0.0 ? air_log_ratio(b, air_fit, median_of(r), temp, c) : 0.0;
      scale[b] = std::clamp(std::exp(median_of(q) - air_share), 0.1, 10.0);
    }
  }
  // Bands without a measurement (e.g. above Nyquist) take their nearest measured neighbour.
  for (int b = 0; b < kNumOctaveBands; ++b) {
    if (std::isfinite(scale[b])) continue;
    for (int d = 1; d < kNumOctaveBands && !std::isfinite(scale[b]); ++d) {
      if (b - d >= 0 && std::isfinite(scale[b - d])) scale[b] = scale[b - d];
      else if (b + d < kNumOctaveBands && std::isfinite(scale[b + d])) scale[b] = scale[b + d];
    }
    if (!std::isfinite(scale[b])) scale[b] = 1.0;
  }
  return scale;
}

std::string band_absorption_spec(const sim::BandValues& scale) {
  std::string spec = "band_absorption:";
  for (int b = 0; b < kNumOctaveBands; ++b) spec += (b ? "," : "") + sim::band_absorption_key(b) + "=" + num(scale[b]);
  return spec;
}

sim::BandValues refine_band_scales(const SetObservations& obs, const std::vector<size_t>& idx, sim::BandValues scale,
                                   const std::string& model_prefix, const DiagnoseOptions& options, int iterations,
                                   double keep_below_hz) {
  std::array<bool, kNumOctaveBands> measured{};
  for (int it = 0; it < iterations; ++it) {
    const std::string spec = model_prefix + "+" + band_absorption_spec(scale);
    std::vector<sim::BandValues> rates(idx.size()), early(idx.size());
    parallel_for(idx.size(), options.num_threads, [&](size_t k) {
      const size_t i = idx[k];
      const Signal s = render_rir(spec, obs.rooms[i], options.sample_rate_hz, obs.measured[i].size(), options.seed);
      const RirFeatures f = compute_features(s, {}, obs.schroeder_hz[i], obs.t60_low_s[i]);
      rates[k] = f.decay_rate_per_s;
      early[k] = f.early_decay_rate_per_s;
    });
    for (int b = 0; b < kNumOctaveBands; ++b) {
      if (kOctaveCentersHz[b] < keep_below_hz) continue;
      // Late (T30) and early (EDT) decay residuals, averaged: the early one keeps moving a band
      // whose T30 is dominated by a neighbour's leakage.
      std::vector<double> q, qe;
      for (size_t k = 0; k < idx.size(); ++k) {
        q.push_back(std::log(obs.meas[idx[k]].decay_rate_per_s[b] / rates[k][b]));
        qe.push_back(std::log(obs.meas[idx[k]].early_decay_rate_per_s[b] / early[k][b]));
      }
      if (finite_values(q).size() >= std::max<size_t>(1, idx.size() / 2)) {
        const double late = median_of(q), first = median_of(qe);
        const double step = std::isfinite(first) ? 0.5 * (late + first) : late;
        scale[b] = std::clamp(scale[b] * std::exp(step), 0.1, 10.0);
        measured[b] = true;
      }
    }
  }
  // Bands without a measurement (above Nyquist) follow their nearest refined neighbour.
  for (int b = 0; b < kNumOctaveBands; ++b) {
    if (measured[b] || kOctaveCentersHz[b] < keep_below_hz) continue;
    for (int d = 1; d < kNumOctaveBands; ++d) {
      if (b - d >= 0 && measured[b - d]) { scale[b] = scale[b - d]; break; }
      if (b + d < kNumOctaveBands && measured[b + d]) { scale[b] = scale[b + d]; break; }
    }
  }
  return scale;
}

std::map<std::string, std::string> fit_extensions(const SetObservations& obs, const std::vector<size_t>& fit_index,
                                                  const DiagnoseOptions& options, std::vector<Finding>* findings) {
  const double fs = options.sample_rate_hz;
  auto detected = [&](const std::string& e) {
    const Finding* f = find(findings, e);
    return f && f->detected;
  };
  std::map<std::string, std::vector<size_t>> fit_by_room;
  for (size_t i : fit_index) fit_by_room[room_group(obs.rooms[i])].push_back(i);
  std::map<std::string, std::string> component_by_room;  // band_absorption per room
  std::string common;                                    // the other components

  // air_absorption: humidity and scale refitted on the fit part only.
  AirFit air_fit;
  const double temp = obs.rooms[0].temperature_c, c = obs.rooms[0].speed_of_sound_m_s;
  if (detected("air_absorption")) {
    std::vector<RateObservation> observations;
    for (const auto& [room, idx] : fit_by_room) {
      for (int b = 0; b < kNumOctaveBands; ++b) {
        std::vector<double> q, r;
        for (size_t i : idx) {
          q.push_back(std::log(obs.meas[i].decay_rate_per_s[b] / obs.sim_a[i].decay_rate_per_s[b]));
          r.push_back(obs.sim_a[i].decay_rate_per_s[b]);
        }
        const OneSampleTest t = t_test(q);
        if (t.n >= 3 && t.n >= 0.8 * idx.size()) {
          observations.push_back({b, t.mean, std::max(t.standard_error, 1e-4), median_of(r)});
        }
      }
    }
    const AirFit fit = fit_air(observations, temp, c);
    air_fit = fit;
    find(findings, "air_absorption")->parameters = {{"humidity_percent", fit.humidity_percent}, {"scale", fit.scale}};
    common += "+air:humidity=" + num(fit.humidity_percent) + ",scale=" + num(fit.scale);
  }

  // band_absorption: per room, the factor on -ln(1 - a) that matches the measured decay rate
  // (Eyring: the rate is proportional to -ln(1 - a)), air's share removed.
  const double schroeder = median_of(obs.schroeder_hz);
  if (detected("band_absorption")) {
    Finding* f = find(findings, "band_absorption");
    f->parameters.clear();
    for (const auto& [room, idx] : fit_by_room) {
      const double keep_below = detected("room_modes") ? 2.0 * schroeder : 0.0;
      const std::string air_spec = air_fit.scale > 0.0 ? "+air:humidity=" + num(air_fit.humidity_percent) +
                                                             ",scale=" + num(air_fit.scale)
                                                       : std::string();
      const sim::BandValues scale =
          refine_band_scales(obs, idx, band_absorption_scales(obs, idx, air_fit, keep_below),
                             options.baseline_model + air_spec, options, 3, keep_below);
      const std::string spec = "+" + band_absorption_spec(scale);
      for (int b = 0; b < kNumOctaveBands; ++b) {
        f->parameters.push_back({(fit_by_room.size() > 1 ? room + "." : std::string()) + sim::band_absorption_key(b), scale[b]});
      }
      component_by_room[room] = spec;
    }
  }

  // room_modes: modal decay relative to the stated low-band decay, and level.
  if (detected("room_modes")) {
    std::vector<double> ratio;
    for (size_t i : fit_index) {
      for (int b = 0; b < kNumOctaveBands && kOctaveCentersHz[b] < 2.0 * schroeder; ++b) {
        ratio.push_back(obs.meas[i].t30_s[b] / obs.sim_a[i].t30_s[b]);
      }
    }
    const double decay_scale = std::clamp(std::isfinite(median_of(ratio)) ? median_of(ratio) : 1.0, 0.5, 4.0);
    // Level: one trial render of the fit part with the modes at 0 dB.
    const std::string trial = options.baseline_model + "+modes:decay_scale=" + num(decay_scale);
    std::vector<double> trial_ratio(fit_index.size()), meas_ratio(fit_index.size());
    parallel_for(fit_index.size(), options.num_threads, [&](size_t k) {
      const size_t i = fit_index[k];
      const Signal s = render_rir(trial, obs.rooms[i], fs, obs.measured[i].size(), options.seed);
      // The share of energy below the Schroeder frequency, as in the features.
      trial_ratio[k] = compute_features(s, {}, obs.schroeder_hz[i], obs.t60_low_s[i]).lf_energy_ratio;
      meas_ratio[k] = obs.meas[i].lf_energy_ratio;
    });
    const double level_db =
        std::clamp(10.0 * std::log10(median_of(meas_ratio) / median_of(trial_ratio)), -20.0, 20.0);
    find(findings, "room_modes")->parameters = {{"decay_scale", decay_scale}, {"level_db", level_db},
                                                {"crossover_hz", schroeder}};
    common += "+modes:decay_scale=" + num(decay_scale) + ",level_db=" + num(std::isfinite(level_db) ? level_db : 0.0);
  }

  // diffuse_scattering: the scattering value whose simulated early echo density matches.
  if (detected("diffuse_scattering")) {
    std::vector<size_t> idx = fit_index;
    if (idx.size() > options.max_scattering_fit_rirs) idx.resize(options.max_scattering_fit_rirs);
    // For each grid value: mean over the fit RIRs of the cross-equalised density difference
    // (measured - simulated); the refit value is where it crosses zero.
    const double want = 0.0;
    const std::vector<double> grid = {0.0, 0.05, 0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0};
    std::vector<double> got(grid.size());
    // Two render seeds per grid value (the statistic's seed noise is ~0.02, the effect a few
    // hundredths), then an increasing fit (pool-adjacent-violators): a noisy grid point must not
    // move the crossing to the other end of the grid.
    for (size_t g = 0; g < grid.size(); ++g) {
      std::vector<double> ed(2 * idx.size());
      const std::string spec = options.baseline_model + "+scattering:value=" + num(grid[g]);
      parallel_for(2 * idx.size(), options.num_threads, [&](size_t k) {
        const size_t i = idx[k % idx.size()];
        const Signal s = render_rir(spec, obs.rooms[i], fs, obs.measured[i].size(), options.seed + k / idx.size());
        const double onset = compute_features(s, {}, obs.schroeder_hz[i], obs.t60_low_s[i]).onset_s;
        const auto pair = cross_equalised_echo_density(obs.measured[i], obs.meas[i].onset_s, s, onset);
        ed[k] = pair.first - pair.second;
      });
      got[g] = -mean_of(ed);  // increases with scattering, like the simulated density
    }
    {
      std::vector<double> value(got), weight(got.size(), 1.0);
      std::vector<size_t> start(got.size());
      size_t blocks = 0;
      for (size_t g = 0; g < got.size(); ++g) {
        value[blocks] = got[g];
        weight[blocks] = 1.0;
        start[blocks] = g;
        ++blocks;
        while (blocks > 1 && value[blocks - 2] > value[blocks - 1]) {
          const double w = weight[blocks - 2] + weight[blocks - 1];
          value[blocks - 2] = (value[blocks - 2] * weight[blocks - 2] + value[blocks - 1] * weight[blocks - 1]) / w;
          weight[blocks - 2] = w;
          --blocks;
        }
      }
      for (size_t b = 0; b < blocks; ++b) {
        const size_t end = b + 1 < blocks ? start[b + 1] : got.size();
        for (size_t g = start[b]; g < end; ++g) got[g] = value[b];
      }
    }
    double value = got.front() >= want ? grid.front() : grid.back();
    for (size_t g = 0; g + 1 < grid.size(); ++g) {
      if (got[g] <= want && got[g + 1] > want) {
        value = grid[g] + (grid[g + 1] - grid[g]) * (want - got[g]) / (got[g + 1] - got[g]);
        break;
      }
    }
    find(findings, "diffuse_scattering")->parameters = {{"scattering", value}};
    common += "+scattering:value=" + num(value);
  }

  // transducer_response: median direct-sound band level difference (absolute, so the calibration
  // gain of the measurement chain is part of the filter).
  if (detected("transducer_response")) {
    sim::BandValues gain;
    gain.fill(NAN);
    for (int b = 0; b < kNumOctaveBands; ++b) {
      if (!direct_band_reliable(b, fs)) continue;
      std::vector<double> d;
      for (size_t i : fit_index) d.push_back(obs.meas[i].direct_band_db[b] - obs.sim_a[i].direct_band_db[b]);
      gain[b] = median_of(d);
    }
    // Bands the short direct window cannot resolve (below 500 Hz) take the tail's level
    // difference, aligned to the direct-sound estimate over the bands both resolve (the tail
    // carries the same colouration plus the overall reverberant level).
    sim::BandValues tail_delta;
    tail_delta.fill(NAN);
    for (int b = 0; b < kNumOctaveBands; ++b) {
      std::vector<double> d;
      for (size_t i : fit_index) d.push_back(obs.meas[i].tail_band_db[b] - obs.sim_a[i].tail_band_db[b]);
      tail_delta[b] = median_of(d);
    }
    std::vector<double> offset;
    for (int b = 0; b < kNumOctaveBands; ++b) {
      if (std::isfinite(gain[b]) && std::isfinite(tail_delta[b])) offset.push_back(tail_delta[b] - gain[b]);
    }
    const double tail_offset = offset.empty() ? 0.0 : mean_of(offset);
    for (int b = 0; b < kNumOctaveBands; ++b) {
      if (!std::isfinite(gain[b]) && std::isfinite(tail_delta[b]) && kOctaveCentersHz[b] < 500.0) {
        gain[b] = tail_delta[b] - tail_offset;
      }
    }
    for (int b = 0; b < kNumOctaveBands; ++b) {
      if (std::isfinite(gain[b])) continue;
      for (int d = 1; d < kNumOctaveBands && !std::isfinite(gain[b]); ++d) {
        if (b - d >= 0 && std::isfinite(gain[b - d])) gain[b] = gain[b - d];
        else if (b + d < kNumOctaveBands && std::isfinite(gain[b + d])) gain[b] = gain[b + d];
      }
      if (!std::isfinite(gain[b])) gain[b] = 0.0;
    }
    std::string spec = "+transducer:";
    Finding* f = find(findings, "transducer_response");
    f->parameters.clear();
    for (int b = 0; b < kNumOctaveBands; ++b) {
      const double g = std::clamp(gain[b], -60.0, 60.0);
      spec += (b ? "," : "") + sim::transducer_gain_key(b) + "=" + num(g);
      f->parameters.push_back({sim::transducer_gain_key(b) + "_db", g});
    }
    common += spec;
  }

  // time_offset: constant latency or pre-alignment, whichever the onsets follow.
  if (detected("time_offset")) {
    std::vector<double> x, y, latency, sim_extra;
    for (size_t i : fit_index) {
      const double flight = obs.rooms[i].source_mic_distance_m() / obs.rooms[i].speed_of_sound_m_s;
      x.push_back(flight);
      y.push_back(obs.meas[i].onset_s);
      latency.push_back(obs.meas[i].onset_s - obs.sim_a[i].onset_s);
      sim_extra.push_back(obs.sim_a[i].onset_s - flight);
    }
    const double mx = mean_of(x), my = mean_of(y);
    double sxy = 0.0, sxx = 0.0;
    for (size_t k = 0; k < x.size(); ++k) { sxy += (x[k] - mx) * (y[k] - my); sxx += (x[k] - mx) * (x[k] - mx); }
    const double slope = sxx > 0 ? sxy / sxx : 1.0;
    Finding* f = find(findings, "time_offset");
    if (slope < 0.5) {
      const double align_ms = 1e3 * (median_of(y) - median_of(sim_extra));
      f->parameters = {{"onset_vs_flight_slope", slope}, {"align_ms", align_ms}};
      common += "+onset_shift:align_ms=" + num(std::max(0.0, align_ms));
    } else {
      const double latency_ms = 1e3 * median_of(latency);
      f->parameters = {{"onset_vs_flight_slope", slope}, {"latency_ms", latency_ms}};
      common += "+onset_shift:latency_ms=" + num(latency_ms);
    }
  }

  // noise_floor: per-band late power of the measurements (where it exceeds the simulation's
  // decay by 6 dB, i.e. is noise), fitted by a tilted white noise.
  if (detected("noise_floor")) {
    std::vector<int> bands;
    sim::BandValues observed{};
    for (int b = 0; b < kNumOctaveBands; ++b) {
      // Only bands whose end is noise: flat (< 3 dB decay over the last 30 %) in most RIRs; a
      // band still decaying there (long low-frequency reverberation) says nothing about noise.
      std::vector<double> l, flatness;
      for (size_t i : fit_index) {
        const double pm = obs.meas[i].late_power[b] / obs.meas[i].energy;
        const double ps = obs.sim_a[i].late_power[b] / obs.sim_a[i].energy;
        flatness.push_back(obs.meas[i].late_decay_band_db[b]);
        if (std::isfinite(pm) && pm > 4.0 * ps) l.push_back(10.0 * std::log10(pm - ps));
      }
      if (l.size() >= std::max<size_t>(1, fit_index.size() / 2) && median_of(flatness) < 3.0) {
        bands.push_back(b);
        observed[b] = median_of(l);
      }
    }
    // The slope holds between the outer edges of the bands it was fitted on.
    const double lo_hz = bands.empty() ? 20.0 : octave_lower_edge_hz(kOctaveCentersHz[bands.front()]);
    const double hi_hz = bands.empty() ? 0.5 * fs : std::min(0.5 * fs, octave_upper_edge_hz(kOctaveCentersHz[bands.back()]));
    double best_tilt = 0.0, best_level = -100.0, best_err = INFINITY;
    for (double tilt = -6.0; tilt <= 3.0001; tilt += 0.25) {
      std::vector<double> offs;
      for (int b : bands) offs.push_back(observed[b] - 10.0 * std::log10(band_noise_fraction(b, tilt, fs, lo_hz, hi_hz)));
      if (offs.empty()) break;
      const double level = mean_of(offs);
      double err = 0.0;
      for (double o : offs) err += (o - level) * (o - level);
      if (err < best_err) { best_err = err; best_level = level; best_tilt = tilt; }
    }
    best_level = std::clamp(best_level, -300.0, 0.0);
    find(findings, "noise_floor")->parameters = {{"level_db", best_level}, {"tilt_db_per_octave", best_tilt},
                                                 {"min_hz", lo_hz}, {"max_hz", hi_hz}};
    common += "+noise_floor:level_db=" + num(best_level) + ",tilt_db_per_octave=" + num(best_tilt) + ",min_hz=" + num(lo_hz) +
              ",max_hz=" + num(hi_hz);
  }

  std::map<std::string, std::string> out;
  for (const sim::RoomSpec& r : obs.rooms) {
    const std::string room = room_group(r);
    auto it = component_by_room.find(room);
    out[room] = options.baseline_model + (it != component_by_room.end() ? it->second : std::string()) + common;
  }
  return out;
}

}  // namespace tsrir::diagnose

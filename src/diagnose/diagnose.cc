#include "diagnose/diagnose.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>

#include "diagnose/decision_rules.h"
#include "diagnose/extension_fit.h"
#include "diagnose/report_html.h"
#include "diagnose/set_statistics.h"
#include "io/atomic_output.h"
#include "io/owned_output.h"
#include "io/audio_io.h"
#include "sim/extension_components.h"
#include "sim/model.h"
#include "sim/room_modes.h"
#include "util/cli.h"
#include "util/error.h"
#include "util/json.h"
#include "util/parallel.h"
#include "util/strings.h"

namespace tsrir::diagnose {
namespace {

// Per-RIR absolute errors of one simulated RIR against its measurement, per gain metric.
struct MetricDef {
  const char* name;
  const char* unit;
  double (*error)(const RirFeatures& meas, const RirFeatures& sim);
};

double band_mean_abs(const BandValues& a, const BandValues& b) {
  double s = 0.0;
  int c = 0;
  for (int k = 0; k < kNumOctaveBands; ++k) {
    if (std::isfinite(a[k]) && std::isfinite(b[k])) { s += std::abs(a[k] - b[k]); ++c; }
  }
  return c ? s / c : NAN;
}

const std::vector<MetricDef>& metric_defs() {
  static const std::vector<MetricDef> kDefs = {
      {"t30_per_band", "s", [](const RirFeatures& m, const RirFeatures& s) { return band_mean_abs(m.t30_s, s.t30_s); }},
      {"level_per_band", "dB", [](const RirFeatures& m, const RirFeatures& s) { return band_mean_abs(m.level_db, s.level_db); }},
      {"drr", "dB", [](const RirFeatures& m, const RirFeatures& s) { return std::abs(m.metrics.drr_db - s.metrics.drr_db); }},
      {"c50", "dB", [](const RirFeatures& m, const RirFeatures& s) { return std::abs(m.metrics.c50_db - s.metrics.c50_db); }},
      {"lf_spectral_distance", "dB",
       [](const RirFeatures& m, const RirFeatures& s) { return lf_spectral_distance_db(m.lf_spectrum_db, s.lf_spectrum_db, 30.0); }},
      {"onset", "ms", [](const RirFeatures& m, const RirFeatures& s) { return 1e3 * std::abs(m.onset_s - s.onset_s); }},
      {"tail_level", "dB", [](const RirFeatures& m, const RirFeatures& s) { return std::abs(m.tail_level_db - s.tail_level_db); }},
      // Cross-equalised early echo density (computed per pair, see diagnose_set).
      {"echo_density", "", nullptr},
  };
  return kDefs;
}

// Fit/eval split: ids sorted by (room, id) alternate fit, eval, fit, ... so both halves cover the
// same rooms and a spread of positions.
void split_ids(const std::vector<sim::RoomSpec>& rooms, std::vector<size_t>* fit, std::vector<size_t>* eval) {
  std::vector<size_t> idx(rooms.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](size_t a, size_t b) {
    if (room_group(rooms[a]) != room_group(rooms[b])) {
      return room_group(rooms[a]) < room_group(rooms[b]);
    }
    return rooms[a].rir_id < rooms[b].rir_id;
  });
  for (size_t k = 0; k < idx.size(); ++k) (k % 2 == 0 ? fit : eval)->push_back(idx[k]);
  std::sort(fit->begin(), fit->end());
  std::sort(eval->begin(), eval->end());
}

// The observations of the RIRs `idx` (in that order).
SetObservations subset(const SetObservations& all, const std::vector<size_t>& idx) {
  SetObservations s;
  for (size_t i : idx) {
    s.rooms.push_back(all.rooms[i]);
    s.measured.push_back(all.measured[i]);
    s.simulated.push_back(all.simulated[i]);
    s.meas.push_back(all.meas[i]);
    s.sim_a.push_back(all.sim_a[i]);
    s.sim_b.push_back(all.sim_b[i]);
    s.mode_freqs_hz.push_back(all.mode_freqs_hz[i]);
    s.schroeder_hz.push_back(all.schroeder_hz[i]);
    s.t60_low_s.push_back(all.t60_low_s[i]);
    s.echo_density_meas_a.push_back(all.echo_density_meas_a[i]);
    s.echo_density_b_a.push_back(all.echo_density_b_a[i]);
  }
  return s;
}

}  // namespace

Diagnosis diagnose_set(const std::vector<sim::RoomSpec>& rooms, const std::vector<Signal>& measured_in,
                       const DiagnoseOptions& options, const std::vector<std::string>& measured_where,
                       const EffectRegistry& registry) {
  const auto start = std::chrono::steady_clock::now();
  sim::register_extension_components();
  const sim::Model baseline = sim::Model::parse(options.baseline_model);
  if (measured_in.size() < 6) throw Error("rir-diagnose needs at least 6 measured RIRs (decisions are over the set)");
  std::map<std::string, const sim::RoomSpec*> room_of;
  for (const sim::RoomSpec& r : rooms) room_of[r.rir_id] = &r;

  SetObservations obs;
  const size_t n = measured_in.size();
  for (const Signal& m : measured_in) {
    auto it = room_of.find(m.id);
    if (it == room_of.end()) throw Error("measured RIR '" + m.id + "' has no line in the room list");
    obs.rooms.push_back(*it->second);
  }
  obs.measured.resize(n);
  obs.simulated.resize(n);
  obs.meas.resize(n);
  obs.sim_a.resize(n);
  obs.sim_b.resize(n);
  obs.mode_freqs_hz.resize(n);
  obs.schroeder_hz.resize(n);
  obs.t60_low_s.resize(n);
  obs.echo_density_meas_a.resize(n);
  obs.echo_density_b_a.resize(n);
  log_info("simulating and analysing " + std::to_string(n) + " RIRs (baseline '" + options.baseline_model +
           "', 2 seeds)");
  parallel_for(n, options.num_threads, [&](size_t i) {
    // Errors of the measured RIR's analysis name it by id only; the user needs the list line
    // and the file.
    auto about_measured = [&](const Error& e) {
      return i < measured_where.size() ? Error(measured_where[i] + ": " + e.what()) : e;
    };
    Signal m;
    try {
      m = resample(measured_in[i], options.sample_rate_hz);
    } catch (const Error& e) {
      throw about_measured(e);
    }
    m.id = measured_in[i].id;
    const sim::RoomSpec& room = obs.rooms[i];
    const sim::RoomSpec prepared = baseline.prepare_room(room);
    obs.schroeder_hz[i] = sim::schroeder_frequency_hz(prepared);
    obs.t60_low_s[i] = sim::eyring_t60_s(prepared)[1];
    for (const sim::RoomMode& mode : sim::shoebox_modes(room.size_m, room.speed_of_sound_m_s, 20.0, obs.schroeder_hz[i])) {
      obs.mode_freqs_hz[i].push_back(mode.freq_hz);
    }
    const Signal a = baseline.render(room, options.sample_rate_hz, m.size(), options.seed);
    const Signal b = baseline.render(room, options.sample_rate_hz, m.size(), options.seed + 1);
    try {
      obs.meas[i] = compute_features(m, obs.mode_freqs_hz[i], obs.schroeder_hz[i], obs.t60_low_s[i]);
    } catch (const Error& e) {
      throw about_measured(e);
    }
    obs.sim_a[i] = compute_features(a, obs.mode_freqs_hz[i], obs.schroeder_hz[i], obs.t60_low_s[i]);
    obs.sim_b[i] = compute_features(b, obs.mode_freqs_hz[i], obs.schroeder_hz[i], obs.t60_low_s[i]);
    obs.echo_density_meas_a[i] = cross_equalised_echo_density(m, obs.meas[i].onset_s, a, obs.sim_a[i].onset_s);
    obs.echo_density_b_a[i] = cross_equalised_echo_density(b, obs.sim_b[i].onset_s, a, obs.sim_a[i].onset_s);
    obs.measured[i] = std::move(m);
    obs.simulated[i] = a;
  });

  Diagnosis d;
  d.registry = &registry;
  d.sample_rate_hz = options.sample_rate_hz;
  d.num_rirs = n;
  d.baseline_model = options.baseline_model;
  // Decide on one half, judge on the other: detection and fitting see the fit RIRs only; the
  // gain table is computed on the held-out RIRs.
  std::vector<size_t> fit, eval;
  split_ids(obs.rooms, &fit, &eval);
  for (size_t i : fit) d.fit_ids.push_back(obs.rooms[i].rir_id);
  for (size_t i : eval) d.eval_ids.push_back(obs.rooms[i].rir_id);
  d.findings = decide_effects(registry, subset(obs, fit), options);
  for (size_t i = 0; i < n; ++i) {
    d.flight_ms.push_back(1e3 * obs.rooms[i].source_mic_distance_m() / obs.rooms[i].speed_of_sound_m_s);
    d.onset_meas_ms.push_back(1e3 * obs.meas[i].onset_s);
    d.onset_sim_ms.push_back(1e3 * obs.sim_a[i].onset_s);
  }
  log_info("fitting the extensions of the detected effects on " + std::to_string(fit.size()) + " RIRs");
  d.extended_model_by_room = fit_extensions(registry, obs, fit, options, &d.findings);

  // Gain on the eval part: baseline and extended rendered with a seed no fit has seen.
  log_info("evaluating baseline and extended models on " + std::to_string(eval.size()) + " held-out RIRs");
  const uint64_t eval_seed = options.seed + 2;
  std::vector<RirFeatures> base_f(eval.size()), ext_f(eval.size());
  std::vector<Signal> base_s(eval.size()), ext_s(eval.size());
  std::vector<double> ed_err_base(eval.size()), ed_err_ext(eval.size());
  parallel_for(eval.size(), options.num_threads, [&](size_t k) {
    const size_t i = eval[k];
    const std::string& ext_spec = d.extended_model_by_room.at(room_group(obs.rooms[i]));
    base_s[k] = render_rir(options.baseline_model, obs.rooms[i], options.sample_rate_hz, obs.measured[i].size(), eval_seed);
    ext_s[k] = render_rir(ext_spec, obs.rooms[i], options.sample_rate_hz, obs.measured[i].size(), eval_seed);
    base_f[k] = compute_features(base_s[k], obs.mode_freqs_hz[i], obs.schroeder_hz[i], obs.t60_low_s[i]);
    ext_f[k] = compute_features(ext_s[k], obs.mode_freqs_hz[i], obs.schroeder_hz[i], obs.t60_low_s[i]);
    // The early echo density of one render carries its own random diffuse field: the per-RIR
    // error is taken against the mean of two renders (the eval seed and the next), which halves
    // that part of its variance, so a fit that matches the set's density shows as a gain.
    auto density_error = [&](const Signal& render, double render_onset_s) {
      const auto pair = cross_equalised_echo_density(obs.measured[i], obs.meas[i].onset_s, render, render_onset_s);
      return pair.first - pair.second;
    };
    auto second_render_error = [&](const std::string& spec) {
      const Signal render = render_rir(spec, obs.rooms[i], options.sample_rate_hz, obs.measured[i].size(), eval_seed + 1);
      return density_error(render, onset_time_s(render));
    };
    ed_err_base[k] = std::abs(0.5 * density_error(base_s[k], base_f[k].onset_s) +
                              0.5 * second_render_error(options.baseline_model));
    ed_err_ext[k] = std::abs(0.5 * density_error(ext_s[k], ext_f[k].onset_s) + 0.5 * second_render_error(ext_spec));
  });
  for (const MetricDef& def : metric_defs()) {
    std::vector<double> eb, ee, diff;
    for (size_t k = 0; k < eval.size(); ++k) {
      const double b = def.error ? def.error(obs.meas[eval[k]], base_f[k]) : ed_err_base[k];
      const double e = def.error ? def.error(obs.meas[eval[k]], ext_f[k]) : ed_err_ext[k];
      if (!std::isfinite(b) || !std::isfinite(e)) continue;
      eb.push_back(b);
      ee.push_back(e);
      diff.push_back(b - e);
    }
    MetricGain g;
    g.name = def.name;
    g.unit = def.unit;
    g.n = diff.size();
    g.baseline = mean_of(eb);
    g.extended = mean_of(ee);
    g.gain = mean_of(diff);
    g.gain_se = diff.size() >= 2 ? stddev_of(diff) / std::sqrt(static_cast<double>(diff.size())) : NAN;
    // Paired t-test of the per-RIR error reduction (two-sided); a gain counts at p < kGainAlpha.
    g.t = g.gain_se > 0.0 ? g.gain / g.gain_se : (g.gain == 0.0 ? 0.0 : std::copysign(INFINITY, g.gain));
    g.p = diff.size() >= 2 && std::isfinite(g.t) ? student_t_two_sided_p(g.t, diff.size() - 1.0) : (g.gain != 0.0 && diff.size() >= 2 ? 0.0 : 1.0);
    d.gains.push_back(g);
  }

  // Example curves for the report: the first eval RIR of up to three rooms.
  std::map<std::string, int> shown;
  for (size_t k = 0; k < eval.size() && d.examples.size() < 3; ++k) {
    const size_t i = eval[k];
    if (shown[room_group(obs.rooms[i])]++ > 0) continue;
    ExampleCurves ex;
    ex.id = obs.rooms[i].rir_id;
    const double len = std::min(obs.measured[i].duration_s() - obs.meas[i].onset_s, 1.0);
    ex.edc_meas_db = edc_db_curve(obs.measured[i], obs.meas[i].onset_s, 0.005, len);
    ex.edc_base_db = edc_db_curve(base_s[k], base_f[k].onset_s, 0.005, len);
    ex.edc_ext_db = edc_db_curve(ext_s[k], ext_f[k].onset_s, 0.005, len);
    ex.lf_meas_db = obs.meas[i].lf_spectrum_db;
    ex.lf_base_db = base_f[k].lf_spectrum_db;
    ex.lf_ext_db = ext_f[k].lf_spectrum_db;
    ex.mode_freqs_hz = obs.mode_freqs_hz[i];
    ex.measured = obs.measured[i];
    ex.baseline = base_s[k];
    ex.extended = ext_s[k];
    d.examples.push_back(std::move(ex));
  }
  d.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return d;
}

void write_findings_json(const Diagnosis& d, std::ostream& out) {
  JsonWriter w(out);
  w.begin_object();
  w.key("findings").begin_array();
  for (const Finding& f : d.findings) {
    w.begin_object();
    w.field("effect", f.effect);
    w.field("detected", f.detected);
    w.field("confidence", f.confidence);
    w.field("evidence", f.evidence);
    w.key("parameters").begin_object();
    for (const auto& [k, v] : f.parameters) w.field(k, v);
    w.end_object();
    w.key("statistic").begin_object();
    w.field("value", f.statistic).field("null_value", f.null_statistic).field("threshold", f.threshold);
    w.field("unit", f.statistic_unit);
    w.end_object();
    w.key("thresholds").begin_object();
    for (const Threshold& t : f.thresholds) w.field(t.name, t.value);
    w.end_object();
    w.end_object();
  }
  w.end_array();
  w.key("gain").begin_object();
  w.field("baseline_model", d.baseline_model);
  std::string ext_summary;
  std::map<std::string, int> distinct;
  for (const auto& [room, spec] : d.extended_model_by_room) distinct[spec]++;
  if (distinct.size() == 1) ext_summary = distinct.begin()->first;
  // One string always (per-room specs joined when the refit differs by room), and the per-room
  // specs as an object.
  if (distinct.size() != 1) {
    for (const auto& [room, spec] : d.extended_model_by_room) {
      ext_summary += (ext_summary.empty() ? "" : "; ") + room + ": " + spec;
    }
  }
  w.field("extended_model", ext_summary);
  w.key("extended_model_by_room").begin_object();
  for (const auto& [room, spec] : d.extended_model_by_room) w.field(room, spec);
  w.end_object();
  w.key("metric").begin_object();
  for (const MetricGain& g : d.gains) {
    w.key(g.name).begin_object();
    w.field("baseline", g.baseline).field("extended", g.extended).field("unit", g.unit);
    w.field("gain", g.gain).field("gain_standard_error", g.gain_se).field("t", g.t).field("p", g.p);
    w.field("significant", g.gain > 0.0 && g.p < kGainAlpha).field("n", g.n);
    w.end_object();
  }
  w.end_object();
  w.key("fit_ids").begin_array();
  for (const std::string& id : d.fit_ids) w.value(id);
  w.end_array();
  w.key("eval_ids").begin_array();
  for (const std::string& id : d.eval_ids) w.value(id);
  w.end_array();
  w.end_object();
  // The thresholds every decision shares (each effect's own are in its finding).
  w.key("thresholds").begin_object();
  w.field("alpha", kDecision.alpha).field("gain_alpha", kDecision.gain_alpha);
  w.end_object();
  w.key("set").begin_object();
  w.field("num_rirs", d.num_rirs).field("sample_rate_hz", d.sample_rate_hz).field("seconds", d.seconds);
  w.end_object();
  w.end_object();
  out << "\n";
}

std::string diagnosis_summary(const Diagnosis& d) {
  std::ostringstream s;
  s << "rir-diagnose: " << d.num_rirs << " RIRs at " << num(d.sample_rate_hz, 6) << " Hz, baseline '" << d.baseline_model
    << "', " << d.fit_ids.size() << " fit / " << d.eval_ids.size() << " eval, " << num(d.seconds, 3) << " s\n";
  for (const Finding& f : d.findings) {
    s << "  " << (f.detected ? "DETECTED " : "absent   ") << f.effect << " (confidence " << num(f.confidence, 2) << ")";
    if (f.detected && !f.parameters.empty()) {
      s << ":";
      int k = 0;
      for (const auto& [name, v] : f.parameters) {
        if (k++ == 6) { s << " ..."; break; }
        s << " " << name << "=" << num(v);
      }
    }
    s << "\n";
  }
  s << "  gain on held-out RIRs (mean absolute error, baseline -> extended, gain +- s.e., paired t, p):\n";
  for (const MetricGain& g : d.gains) {
    s << "    " << g.name << ": " << num(g.baseline) << " -> " << num(g.extended) << " " << g.unit << " (" << num(g.gain)
      << " +- " << num(g.gain_se, 2) << ", t = " << num(g.t, 3) << ", p = " << num(g.p, 2)
      << (g.gain > 0.0 && g.p < kGainAlpha ? ", gain" : "") << ")\n";
  }
  return s.str();
}

std::string write_diagnosis(const Diagnosis& d, const std::string& out_dir, const std::string& command_line) {
  OwnedOutputDir dir(out_dir);
  {
    std::ofstream json(dir.path() + "/findings.json");
    write_findings_json(d, json);
    if (!json) throw Error("cannot write " + out_dir + "/findings.json");
  }
  {
    std::ofstream html(dir.path() + "/report.html");
    write_report_html(d, command_line, html);
    if (!html) throw Error("cannot write " + out_dir + "/report.html");
  }
  {
    std::ofstream models(dir.path() + "/extended_models");
    for (const auto& [room, spec] : d.extended_model_by_room) models << room << " " << spec << "\n";
    if (!models) throw Error("cannot write " + out_dir + "/extended_models");
  }
  dir.commit();
  return diagnosis_summary(d);
}

}  // namespace tsrir::diagnose

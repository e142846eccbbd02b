#include "diagnose/diagnose.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>

#include "diagnose/decay_rate_effects.h"
#include "diagnose/decision_rules.h"
#include "diagnose/extension_fit.h"
#include "diagnose/report_html.h"
#include "diagnose/set_statistics.h"
#include "diagnose/unexplained.h"
#include "io/atomic_output.h"
#include "io/owned_output.h"
#include "io/audio_io.h"
#include "sim/extension_components.h"
#include "sim/model.h"
#include "sim/room_modes.h"
#include "util/cli.h"
#include "util/error.h"
#include "util/json.h"
#include "util/log.h"
#include "util/parallel.h"
#include "util/strings.h"

namespace tsrir::diagnose {
namespace {

// ---- observe: every stated set-up simulated with two seeds and analysed with its measurement.

// Fills one RIR's observation: the measurement resampled, the stated room's analysis grid, the
// baseline's renders with seeds A and B, and the features of all three.
void observe_one(const Signal& measured_in, const std::string& where, const sim::Model& baseline,
                 const DiagnoseOptions& options, RirObservation* r) {
  // Errors of the measured RIR's analysis name it by id only; the user needs the list line and the
  // file.
  auto about_measured = [&](const Error& e) { return where.empty() ? e : Error(where + ": " + e.what()); };
  try {
    r->measured = resample(measured_in, options.sample_rate_hz);
  } catch (const Error& e) {
    throw about_measured(e);
  }
  r->measured.id = measured_in.id;
  const sim::RoomSpec prepared = baseline.prepare_room(r->room);
  r->schroeder_hz = sim::schroeder_frequency_hz(prepared);
  for (const sim::RoomMode& mode : sim::shoebox_modes(r->room.size_m, r->room.speed_of_sound_m_s, 20.0, r->schroeder_hz)) {
    r->mode_freqs_hz.push_back(mode.freq_hz);
  }
  const Signal a = baseline.render(r->room, options.sample_rate_hz, r->measured.size(), options.seed);
  const Signal b = baseline.render(r->room, options.sample_rate_hz, r->measured.size(), options.seed + 1);
  try {
    r->meas = r->features_of(r->measured);
  } catch (const Error& e) {
    throw about_measured(e);
  }
  r->sim_a = r->features_of(a);
  r->sim_b = r->features_of(b);
  r->echo_density_meas_a = cross_equalised_echo_density(r->measured, r->meas.onset_s, a, r->sim_a.onset_s);
  r->echo_density_b_a = cross_equalised_echo_density(b, r->sim_b.onset_s, a, r->sim_a.onset_s);
  r->simulated = a;
}

SetObservations observe(const std::vector<sim::RoomSpec>& rooms, const std::vector<Signal>& measured,
                        const DiagnoseOptions& options, const std::vector<std::string>& measured_where) {
  const sim::Model baseline = sim::Model::parse(options.baseline_model);
  std::map<std::string, const sim::RoomSpec*> room_of;
  for (const sim::RoomSpec& r : rooms) room_of[r.rir_id] = &r;
  SetObservations obs;
  obs.rirs.resize(measured.size());
  for (size_t i = 0; i < measured.size(); ++i) {
    auto it = room_of.find(measured[i].id);
    if (it == room_of.end()) throw Error("measured RIR '" + measured[i].id + "' has no line in the room list");
    obs[i].room = *it->second;
  }
  log_info("simulating and analysing " + std::to_string(measured.size()) + " RIRs (baseline '" +
           options.baseline_model + "', 2 seeds)");
  parallel_for(measured.size(), options.num_threads, [&](size_t i) {
    observe_one(measured[i], i < measured_where.size() ? measured_where[i] : std::string(), baseline, options, &obs[i]);
  });
  return obs;
}

// Fit/eval split: ids sorted by (room, id) alternate fit, eval, fit, ... so both halves cover the
// same rooms and a spread of positions.
void split_ids(const SetObservations& obs, std::vector<size_t>* fit, std::vector<size_t>* eval) {
  std::vector<size_t> idx(obs.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](size_t a, size_t b) {
    const std::string ga = room_group(obs[a].room), gb = room_group(obs[b].room);
    if (ga != gb) return ga < gb;
    return obs[a].room.rir_id < obs[b].room.rir_id;
  });
  for (size_t k = 0; k < idx.size(); ++k) (k % 2 == 0 ? fit : eval)->push_back(idx[k]);
  std::sort(fit->begin(), fit->end());
  std::sort(eval->begin(), eval->end());
}

// ---- evaluate: models rendered for the held-out RIRs with a seed no fit has seen, and their
// per-RIR errors per gain metric.

using ModelOf = std::function<std::string(const RirObservation&)>;

struct ModelEvaluation {
  std::vector<std::vector<double>> errors;  // [gain metric][eval RIR]
  std::vector<Signal> renders;              // the eval renders (kept only when asked: report examples)
  std::vector<RirFeatures> features;
  double mean(size_t metric) const { return mean_of(errors[metric]); }
};

// The early echo density of one render carries its own random diffuse field: the per-RIR error is
// taken against the mean of two renders (the eval seed and the next), which halves that part of
// its variance, so a fit that matches the set's density shows as a gain.
double echo_density_error(const RirObservation& r, const Signal& render, double render_onset_s, const std::string& spec,
                          const DiagnoseOptions& options, uint64_t seed) {
  auto density_error = [&](const Signal& s, double onset_s) {
    const auto pair = cross_equalised_echo_density(r.measured, r.meas.onset_s, s, onset_s);
    return pair.first - pair.second;
  };
  const Signal second = render_rir(spec, r.room, options.sample_rate_hz, r.measured.size(), seed + 1);
  return std::abs(0.5 * density_error(render, render_onset_s) + 0.5 * density_error(second, onset_time_s(second)));
}

ModelEvaluation evaluate_model(const SetObservations& obs, const std::vector<size_t>& eval, const ModelOf& model,
                               const DiagnoseOptions& options, bool keep_renders) {
  const uint64_t seed = options.seed + 2;
  const std::vector<GainMetric>& metrics = gain_metrics();
  ModelEvaluation ev;
  ev.errors.assign(metrics.size(), std::vector<double>(eval.size(), NAN));
  if (keep_renders) {
    ev.renders.resize(eval.size());
    ev.features.resize(eval.size());
  }
  parallel_for(eval.size(), options.num_threads, [&](size_t k) {
    const RirObservation& r = obs[eval[k]];
    const std::string spec = model(r);
    Signal s = render_rir(spec, r.room, options.sample_rate_hz, r.measured.size(), seed);
    RirFeatures f = r.features_of(s);
    for (size_t m = 0; m < metrics.size(); ++m) {
      ev.errors[m][k] = metrics[m].error ? metrics[m].error(r.meas, f) : echo_density_error(r, s, f.onset_s, spec, options, seed);
    }
    if (keep_renders) {
      ev.renders[k] = std::move(s);
      ev.features[k] = std::move(f);
    }
  });
  return ev;
}

// Paired comparison of per-RIR errors: gain = mean(first - second) over the RIRs where both are
// finite; a paired t-test (two-sided).
PairedGain paired_gain(const std::vector<double>& first, const std::vector<double>& second) {
  std::vector<double> diff;
  for (size_t k = 0; k < first.size() && k < second.size(); ++k) {
    if (std::isfinite(first[k]) && std::isfinite(second[k])) diff.push_back(first[k] - second[k]);
  }
  PairedGain g;
  g.n = diff.size();
  g.gain = mean_of(diff);
  g.gain_se = diff.size() >= 2 ? stddev_of(diff) / std::sqrt(static_cast<double>(diff.size())) : NAN;
  g.t = g.gain_se > 0.0 ? g.gain / g.gain_se : (g.gain == 0.0 ? 0.0 : std::copysign(INFINITY, g.gain));
  g.p = diff.size() >= 2 && std::isfinite(g.t) ? student_t_two_sided_p(g.t, diff.size() - 1.0)
                                               : (g.gain != 0.0 && diff.size() >= 2 ? 0.0 : 1.0);
  if (diff.empty()) g.gain = 0.0;
  return g;
}

// The gain table: per metric the three models' errors and the extended model's paired gains.
std::vector<MetricGain> gain_table(const ModelEvaluation& base, const ModelEvaluation& refitted,
                                   const ModelEvaluation& ext) {
  std::vector<MetricGain> out;
  const std::vector<GainMetric>& metrics = gain_metrics();
  for (size_t m = 0; m < metrics.size(); ++m) {
    MetricGain g;
    g.name = metrics[m].name;
    g.unit = metrics[m].unit;
    const PairedGain vs_base = paired_gain(base.errors[m], ext.errors[m]);
    g.baseline = base.mean(m);
    g.refitted = refitted.mean(m);
    g.extended = ext.mean(m);
    g.gain = vs_base.gain;
    g.gain_se = vs_base.gain_se;
    g.t = vs_base.t;
    g.p = vs_base.p;
    g.n = vs_base.n;
    g.vs_refitted = paired_gain(refitted.errors[m], ext.errors[m]);
    out.push_back(g);
  }
  return out;
}

// The held-out check of each detected effect: its extension left out of the extended model (the
// baseline when it is the only one) must be worse on the effect's gain metric; a metric the
// extended model makes worse than the baseline (significantly, and by more than the metric's
// just-noticeable difference) is traced to the effects without which it is significantly better.
// The verdict goes into the finding: confirmed, a trade-off (its own metric better, another worse),
// contested (another worse, its own not better) or unconfirmed (no gain); an effect whose own metric
// does not improve keeps its detection (made on the fit half) but its confidence drops to 0.5, the
// least a detection has.
void check_held_out(const EffectRegistry& registry, const SetObservations& obs, const std::vector<size_t>& eval,
                    const std::vector<Extension>& extensions, const ModelEvaluation& base, const ModelEvaluation& ext,
                    const DiagnoseOptions& options, Diagnosis* d) {
  const auto& effects = registry.effects();
  const std::vector<GainMetric>& metrics = gain_metrics();
  std::vector<size_t> detected;
  for (size_t k = 0; k < effects.size(); ++k) {
    if (d->findings[k].detected) detected.push_back(k);
  }
  std::map<size_t, ModelEvaluation> without;
  for (size_t k : detected) {
    if (detected.size() == 1) break;
    without[k] = evaluate_model(obs, eval, [&](const RirObservation& r) {
      return model_spec(options.baseline_model, extensions, room_group(r.room), [&](size_t j) {
        return j != k && d->findings[j].detected;
      });
    }, options, false);
  }
  auto left_out = [&](size_t k) -> const ModelEvaluation& { return detected.size() == 1 ? base : without.at(k); };
  for (size_t m = 0; m < metrics.size(); ++m) {
    const PairedGain vs_base = paired_gain(base.errors[m], ext.errors[m]);
    if (!vs_base.worse() || -vs_base.gain <= metrics[m].jnd) continue;
    Regression reg{metrics[m].name, metrics[m].unit, base.mean(m), ext.mean(m), vs_base, {}};
    for (size_t k : detected) {
      if (paired_gain(ext.errors[m], left_out(k).errors[m]).better()) reg.caused_by.push_back(effects[k]->name());
    }
    d->regressions.push_back(reg);
  }
  for (size_t k : detected) {
    Finding& f = d->findings[k];
    const size_t own = effects[k]->gain_metric().index();
    const PairedGain gain = paired_gain(left_out(k).errors[own], ext.errors[own]);
    std::string worse;
    for (const Regression& reg : d->regressions) {
      if (std::find(reg.caused_by.begin(), reg.caused_by.end(), f.effect) == reg.caused_by.end()) continue;
      worse += (worse.empty() ? "" : ", ") + reg.metric + " (p = " + num(reg.vs_baseline.p, 2) + ")";
    }
    const std::string own_text = metrics[own].name + " (" + num(gain.gain) + " +- " + num(gain.gain_se, 2) +
                                 ", p = " + num(gain.p, 2) + ")";
    if (gain.better() && worse.empty()) f.held_out = "confirmed: improves " + own_text;
    else if (gain.better()) f.held_out = "trade-off: improves " + own_text + " but makes worse " + worse;
    else if (!worse.empty()) f.held_out = "contested: makes worse " + worse + " and does not improve " + own_text;
    else f.held_out = "unconfirmed: does not improve " + own_text;
    if (!gain.better()) f.confidence = std::min(f.confidence, 0.5);
  }
}

// What each detected effect adds beyond the band refit: the refitted baseline plus its extension
// alone (effects whose extension is a decay change are the refit's own: skipped).
void gains_beyond_refit(const EffectRegistry& registry, const SetObservations& obs, const std::vector<size_t>& eval,
                        const std::vector<Extension>& extensions, const ModelEvaluation& refitted,
                        const DiagnoseOptions& options, Diagnosis* d) {
  const auto& effects = registry.effects();
  const std::vector<GainMetric>& metrics = gain_metrics();
  for (size_t k = 0; k < effects.size(); ++k) {
    if (!d->findings[k].detected || effects[k]->within_band_refit()) continue;
    const ModelEvaluation with = evaluate_model(obs, eval, [&](const RirObservation& r) {
      const std::string room = room_group(r.room);
      return model_spec(d->refitted_model_by_room.at(room), extensions, room, [&](size_t j) { return j == k; });
    }, options, false);
    const size_t own = effects[k]->gain_metric().index();
    EffectGain g{effects[k]->name(), metrics[own].name, metrics[own].unit, refitted.mean(own), with.mean(own),
                 paired_gain(refitted.errors[own], with.errors[own]), {}};
    for (size_t m = 0; m < metrics.size(); ++m) {
      const PairedGain w = paired_gain(refitted.errors[m], with.errors[m]);
      if (w.worse() && -w.gain > metrics[m].jnd) g.worse.push_back(metrics[m].name);
    }
    d->effect_gains.push_back(g);
  }
}

// Example curves for the report: the first eval RIR of up to three rooms.
void add_examples(const SetObservations& obs, const std::vector<size_t>& eval, const ModelEvaluation& base,
                  const ModelEvaluation& ext, Diagnosis* d) {
  std::map<std::string, int> shown;
  for (size_t k = 0; k < eval.size() && d->examples.size() < 3; ++k) {
    const RirObservation& r = obs[eval[k]];
    if (shown[room_group(r.room)]++ > 0) continue;
    ExampleCurves ex;
    ex.id = r.room.rir_id;
    const double len = std::min(r.measured.duration_s() - r.meas.onset_s, 1.0);
    ex.edc_meas_db = edc_db_curve(r.measured, r.meas.onset_s, 0.005, len);
    ex.edc_base_db = edc_db_curve(base.renders[k], base.features[k].onset_s, 0.005, len);
    ex.edc_ext_db = edc_db_curve(ext.renders[k], ext.features[k].onset_s, 0.005, len);
    ex.lf_meas_db = r.meas.lf_spectrum_db;
    ex.lf_base_db = base.features[k].lf_spectrum_db;
    ex.lf_ext_db = ext.features[k].lf_spectrum_db;
    ex.mode_freqs_hz = r.mode_freqs_hz;
    ex.measured = r.measured;
    ex.baseline = base.renders[k];
    ex.extended = ext.renders[k];
    d->examples.push_back(std::move(ex));
  }
}

// The band refit is per room, from the fit half's RIRs of that room; a held-out RIR whose room has
// none there (every RIR its own room, or rooms split apart) gets the refit pooled over the fit half.
void add_pooled_refit_for_unfitted_rooms(const SetObservations& obs, const std::vector<size_t>& eval,
                                         const SetObservations& fit_obs, const DiagnoseOptions& options,
                                         std::map<std::string, std::string>* by_room) {
  std::string pooled;
  for (size_t i : eval) {
    const std::string room = room_group(obs[i].room);
    if (by_room->count(room)) continue;
    if (pooled.empty()) pooled = band_refit_pooled_model(fit_obs, options);
    (*by_room)[room] = pooled;
  }
}

// Decides every effect on the fit half (`withdrawn` set not detected) and fits the detected ones'
// extensions; the findings and the extended model per room go into *d.
std::vector<Extension> decide_and_fit(const EffectRegistry& registry, const SetObservations& obs,
                                      const std::vector<size_t>& fit, const SetObservations& fit_obs,
                                      const DiagnoseOptions& options, const std::map<std::string, std::string>& withdrawn,
                                      ReferenceCache* references, Diagnosis* d) {
  d->findings = decide_effects(registry, fit_obs, options, references, withdrawn);
  log_info("fitting the extensions of the detected effects on " + std::to_string(fit.size()) + " RIRs");
  const std::vector<Extension> extensions = fit_effect_extensions(registry, obs, fit, options, &d->findings);
  d->extended_model_by_room.clear();
  for (const RirObservation& r : obs) {
    const std::string room = room_group(r.room);
    d->extended_model_by_room[room] =
        model_spec(options.baseline_model, extensions, room, [&](size_t k) { return d->findings[k].detected; });
  }
  return extensions;
}

Finding unexplained_finding(const UnexplainedCheck& check) {
  Finding f;
  f.effect = "unexplained";
  f.detected = !check.departing.empty();
  f.confidence = f.detected ? 1.0 : 0.0;
  f.statistic = check.statistic;
  f.threshold = 1.0;
  f.statistic_unit = "x threshold";
  f.parameters = check.parameters;
  f.evidence = (f.detected ? std::string("The extended model leaves departures no catalog effect explains. ")
                           : std::string("Nothing departs from the extended model beyond its thresholds. ")) +
               check.evidence;
  const UnexplainedThresholds& t = kUnexplainedThresholds;
  f.thresholds = {{"min_bend_db", t.min_bend_db, "decay shape: the bend of a band's decay curve beyond the model's"},
                  {"min_early_late_log_ratio", t.min_early_late_log_ratio,
                   "two slopes: ln of how much faster the early decay (EDT) is re the model's than the late (T30)"},
                  {"min_periodicity", t.min_periodicity, "late periodicity: envelope autocorrelation beyond the model's"},
                  {"min_pattern_loss_db", t.min_pattern_loss_db,
                   "early pattern: reflections less prominent where the model has them than where the measurement does"}};
  return f;
}

// Baseline, band-refitted baseline and extended model on the held-out RIRs: the gain table, the
// held-out check of each detected effect, what each adds beyond the refit, the report's examples.
void evaluate(const EffectRegistry& registry, const SetObservations& obs, const std::vector<size_t>& eval,
              const std::vector<Extension>& extensions, const DiagnoseOptions& options, Diagnosis* d) {
  log_info("evaluating baseline, band-refitted baseline and extended model on " + std::to_string(eval.size()) +
           " held-out RIRs");
  auto model_by_room = [](const std::map<std::string, std::string>& by_room) {
    return [&by_room](const RirObservation& r) { return by_room.at(room_group(r.room)); };
  };
  const ModelEvaluation base =
      evaluate_model(obs, eval, [&](const RirObservation&) { return options.baseline_model; }, options, true);
  const ModelEvaluation refitted = evaluate_model(obs, eval, model_by_room(d->refitted_model_by_room), options, false);
  const ModelEvaluation ext = evaluate_model(obs, eval, model_by_room(d->extended_model_by_room), options, true);
  d->gains = gain_table(base, refitted, ext);
  check_held_out(registry, obs, eval, extensions, base, ext, options, d);
  gains_beyond_refit(registry, obs, eval, extensions, refitted, options, d);
  add_examples(obs, eval, base, ext, d);
}

}  // namespace

Diagnosis diagnose_set(const std::vector<sim::RoomSpec>& rooms, const std::vector<Signal>& measured,
                       const DiagnoseOptions& options, const std::vector<std::string>& measured_where,
                       const EffectRegistry& registry) {
  const auto start = std::chrono::steady_clock::now();
  sim::register_extension_components();
  if (measured.size() < 6) throw Error("rir-diagnose needs at least 6 measured RIRs (decisions are over the set)");
  const SetObservations obs = observe(rooms, measured, options, measured_where);
  Diagnosis d;
  d.registry = &registry;
  d.sample_rate_hz = options.sample_rate_hz;
  d.num_rirs = obs.size();
  d.baseline_model = options.baseline_model;
  // Decide on one half, judge on the other: detection and fitting see the fit RIRs only; the
  // gain table is computed on the held-out RIRs.
  std::vector<size_t> fit, eval;
  split_ids(obs, &fit, &eval);
  for (size_t i : fit) d.fit_ids.push_back(obs[i].room.rir_id);
  for (size_t i : eval) d.eval_ids.push_back(obs[i].room.rir_id);
  const SetObservations fit_obs = obs.subset(fit);
  ReferenceCache references;
  std::vector<Extension> extensions = decide_and_fit(registry, obs, fit, fit_obs, options, {}, &references, &d);
  // What the extended model leaves unexplained; the effects whose extension should have removed it
  // are withdrawn, and the rest decided and fitted again.
  log_info("checking what the extended model leaves unexplained on " + std::to_string(fit.size()) + " RIRs");
  const UnexplainedCheck check = check_unexplained(fit_obs, d.extended_model_by_room, options);
  std::map<std::string, std::string> withdrawn;
  for (size_t k = 0; k < registry.effects().size(); ++k) {
    if (!d.findings[k].detected) continue;
    for (ResidualView view : registry.effects()[k]->residual_views()) {
      if (std::find(check.departing.begin(), check.departing.end(), view) == check.departing.end()) continue;
      withdrawn[d.findings[k].effect] = "with its extension fitted the measurements still depart from the model in " +
                                        residual_view_name(view) + " (the unexplained finding): the cause may be "
                                        "outside the catalog.";
    }
  }
  if (!withdrawn.empty()) extensions = decide_and_fit(registry, obs, fit, fit_obs, options, withdrawn, &references, &d);
  d.unexplained = unexplained_finding(check);
  for (const RirObservation& r : obs) {
    d.flight_ms.push_back(1e3 * r.room.source_mic_distance_m() / r.room.speed_of_sound_m_s);
    d.onset_meas_ms.push_back(1e3 * r.meas.onset_s);
    d.onset_sim_ms.push_back(1e3 * r.sim_a.onset_s);
  }
  if (options.held_out_evaluation) {
    // The second baseline (the cheap fix): the decisions' band refit when they rendered one.
    const auto refit = references.find(kBandRefittedReference);
    d.refitted_model_by_room = refit != references.end() ? refit->second.model_by_room : band_refit_models(fit_obs, options);
    add_pooled_refit_for_unfitted_rooms(obs, eval, fit_obs, options, &d.refitted_model_by_room);
    evaluate(registry, obs, eval, extensions, options, &d);
  }
  d.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return d;
}

namespace {
void write_strings(JsonWriter& w, const std::string& key, const std::vector<std::string>& values) {
  w.key(key).begin_array();
  for (const std::string& v : values) w.value(v);
  w.end_array();
}

void write_paired(JsonWriter& w, const PairedGain& g) {
  w.field("gain", g.gain).field("gain_standard_error", g.gain_se).field("t", g.t).field("p", g.p);
  w.field("significant", g.better()).field("worse", g.worse()).field("n", g.n);
}
}  // namespace

void write_findings_json(const Diagnosis& d, std::ostream& out) {
  JsonWriter w(out);
  w.begin_object();
  w.key("findings").begin_array();
  auto write_finding = [&](const Finding& f) {
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
    w.field("held_out", f.held_out);
    w.end_object();
  };
  for (const Finding& f : d.findings) write_finding(f);
  write_finding(d.unexplained);
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
  w.key("refitted_model_by_room").begin_object();
  for (const auto& [room, spec] : d.refitted_model_by_room) w.field(room, spec);
  w.end_object();
  w.key("metric").begin_object();
  for (const MetricGain& g : d.gains) {
    w.key(g.name).begin_object();
    w.field("baseline", g.baseline).field("refitted", g.refitted).field("extended", g.extended).field("unit", g.unit);
    w.field("gain", g.gain).field("gain_standard_error", g.gain_se).field("t", g.t).field("p", g.p);
    w.field("significant", g.gain > 0.0 && g.p < kGainAlpha).field("worse", g.gain < 0.0 && g.p < kGainAlpha).field("n", g.n);
    w.key("vs_refitted").begin_object();
    write_paired(w, g.vs_refitted);
    w.end_object();
    w.end_object();
  }
  w.end_object();
  w.key("regressions").begin_array();
  for (const Regression& r : d.regressions) {
    w.begin_object();
    w.field("metric", r.metric).field("unit", r.unit).field("baseline", r.baseline).field("extended", r.extended);
    write_paired(w, r.vs_baseline);
    write_strings(w, "caused_by", r.caused_by);
    w.end_object();
  }
  w.end_array();
  w.key("beyond_refit").begin_array();
  for (const EffectGain& g : d.effect_gains) {
    w.begin_object();
    w.field("effect", g.effect).field("metric", g.metric).field("unit", g.unit);
    w.field("refitted", g.refitted).field("with_effect", g.with_effect);
    write_paired(w, g.gain);
    write_strings(w, "worse", g.worse);
    w.end_object();
  }
  w.end_array();
  write_strings(w, "fit_ids", d.fit_ids);
  write_strings(w, "eval_ids", d.eval_ids);
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
  std::vector<Finding> all = d.findings;
  all.push_back(d.unexplained);
  for (const Finding& f : all) {
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
    if (f.detected && !f.held_out.empty()) s << "      held out: " << f.held_out << "\n";
  }
  s << "  gain on held-out RIRs (mean absolute error, baseline -> extended, gain +- s.e., paired t, p; band-refitted "
       "baseline, p of the gain over it):\n";
  for (const MetricGain& g : d.gains) {
    s << "    " << g.name << ": " << num(g.baseline) << " -> " << num(g.extended) << " " << g.unit << " (" << num(g.gain)
      << " +- " << num(g.gain_se, 2) << ", t = " << num(g.t, 3) << ", p = " << num(g.p, 2)
      << (g.gain > 0.0 && g.p < kGainAlpha ? ", gain" : g.gain < 0.0 && g.p < kGainAlpha ? ", WORSE" : "")
      << "; refitted " << num(g.refitted) << ", p = " << num(g.vs_refitted.p, 2) << ")\n";
  }
  for (const Regression& r : d.regressions) {
    s << "  worse than the baseline: " << r.metric << " (" << num(r.baseline) << " -> " << num(r.extended) << " " << r.unit
      << ", p = " << num(r.vs_baseline.p, 2) << ")";
    for (size_t k = 0; k < r.caused_by.size(); ++k) s << (k ? ", " : ", caused by ") << r.caused_by[k];
    s << "\n";
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

// The registry and the dispatch of the effects (effect.h): decisions, revisions, fits, --help.
#include <algorithm>
#include <cstdio>
#include <set>
#include <sstream>

#include "diagnose/decision_rules.h"
#include "diagnose/effect.h"
#include "util/error.h"
#include "util/rng.h"
#include "util/strings.h"

namespace tsrir::diagnose {
namespace {

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

[[noreturn]] void undeclared(const std::string& reader, const std::string& effect) {
  throw Error("rir-diagnose: effect " + reader + " reads the finding of " + effect +
              " without declaring it (Effect::depends_on or revised_after)");
}

std::string join(const std::vector<std::string>& names, const std::string& sep) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : sep) + n;
  return out;
}

// Greedy word wrap of `text` at `width` columns: the first line prefixed by `first`, the others
// by `rest`.
std::string wrap(const std::string& text, const std::string& first, const std::string& rest, size_t width) {
  std::istringstream words(text);
  std::string word, line, out;
  const std::string* indent = &first;
  while (words >> word) {
    if (!line.empty() && indent->size() + line.size() + 1 + word.size() > width) {
      out += *indent + line + "\n";
      line.clear();
      indent = &rest;
    }
    line += (line.empty() ? "" : " ") + word;
  }
  if (!line.empty()) out += *indent + line + "\n";
  return out;
}

}  // namespace

// ---- contexts

DecisionContext::DecisionContext(const SetObservations& obs, const DiagnoseOptions& options,
                                 const std::map<std::string, Finding>& decided, std::vector<std::string> readable,
                                 ReferenceCache* references)
    : obs_(obs), options_(options), decided_(decided), readable_(std::move(readable)), references_(references) {}

const Finding& DecisionContext::finding(const std::string& effect) const {
  if (!contains(readable_, effect)) undeclared(readable_.empty() ? "?" : readable_.front(), effect);
  const auto it = decided_.find(effect);
  if (it == decided_.end()) throw Error("rir-diagnose: effect " + effect + " is read before it was decided");
  return it->second;
}

const SetObservations& DecisionContext::reference(const std::string& name, const ReferenceRenderer& render) const {
  auto it = references_->find(name);
  if (it == references_->end()) it = references_->emplace(name, render(obs_, options_)).first;
  return it->second;
}

FitContext::FitContext(const SetObservations& obs, const std::vector<size_t>& fit_index, const DiagnoseOptions& options,
                       const std::vector<Finding>& findings, std::vector<std::string> readable)
    : obs_(obs), fit_index_(fit_index), options_(options), findings_(findings), readable_(std::move(readable)) {
  for (size_t i : fit_index_) fit_by_room_[room_group(obs_[i].room)].push_back(i);
}

const Finding& FitContext::finding(const std::string& effect) const {
  if (!contains(readable_, effect)) undeclared(readable_.empty() ? "?" : readable_.front(), effect);
  for (const Finding& f : findings_) {
    if (f.effect == effect) return f;
  }
  throw Error("rir-diagnose: no finding of effect " + effect);
}

// ---- Effect defaults

void Effect::revise(const DecisionContext&, Finding*) const {}
void Effect::report_set(const Finding&, const Diagnosis&, std::ostream&) const {}
void Effect::report_example(const ExampleCurves&, std::ostream&) const {}

// ---- registry

void EffectRegistry::add(std::unique_ptr<Effect> effect) {
  const std::string name = effect->name();
  if (find(name)) throw Error("rir-diagnose: effect " + name + " registered twice");
  for (const std::string& d : effect->depends_on()) {
    if (!find(d)) throw Error("rir-diagnose: effect " + name + " depends on " + d + ", which is not registered before it");
  }
  try {
    gain_metric(effect->gain_metric());
  } catch (const std::exception& e) {
    throw Error("rir-diagnose: effect " + name + " names no gain metric of gain_metrics.h: " + e.what());
  }
  effects_.push_back(std::move(effect));
}

const Effect* EffectRegistry::find(const std::string& name) const {
  for (const auto& e : effects_) {
    if (e->name() == name) return e.get();
  }
  return nullptr;
}

std::vector<std::string> EffectRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& e : effects_) out.push_back(e->name());
  return out;
}

std::vector<std::string> effect_catalog() { return effect_registry().names(); }

std::string effects_help(const EffectRegistry& registry) {
  std::string out = wrap("Effects (catalog order; each decided over the fit half at p < " + num(kDecision.alpha) +
                             " and calibrated on seed-vs-seed differences; thresholds as name = value: why):",
                         "", "", 100);
  for (const auto& e : registry.effects()) {
    out += "  " + e->name() + "\n" + wrap(e->description(), "      ", "      ", 100);
    for (const Threshold& t : e->thresholds()) {
      out += wrap(t.name + " = " + num(t.value, 6) + ": " + t.why, "    - ", "      ", 100);
    }
    std::string rules;
    if (!e->depends_on().empty()) rules += "decided and fitted after " + join(e->depends_on(), ", ") + ". ";
    if (!e->revised_after().empty()) rules += "revised once " + join(e->revised_after(), ", ") + " is decided.";
    if (!rules.empty()) out += wrap(rules, "      ", "      ", 100);
  }
  return out;
}

// ---- dispatch

std::vector<Finding> decide_effects(const EffectRegistry& registry, const SetObservations& obs,
                                    const DiagnoseOptions& options, ReferenceCache* references,
                                    const std::map<std::string, std::string>& withdrawn) {
  std::map<std::string, Finding> decided;
  ReferenceCache local;
  ReferenceCache* cache = references ? references : &local;
  auto readable = [](const Effect& e, bool revising) {
    std::vector<std::string> r = {e.name()};
    for (const std::string& d : e.depends_on()) r.push_back(d);
    if (revising) {
      for (const std::string& d : e.revised_after()) r.push_back(d);
    }
    return r;
  };
  auto decide = [&](const Effect& e) {
    const DecisionContext ctx(obs, options, decided, readable(e, false), cache);
    Finding f = e.detect(ctx);
    f.effect = e.name();
    const auto w = withdrawn.find(e.name());
    if (w != withdrawn.end() && f.detected) {
      f.detected = false;
      f.confidence = std::min(f.confidence, 0.49);
      f.evidence += " Withdrawn: " + w->second;
    }
    decided[e.name()] = std::move(f);
  };
  for (const auto& e : registry.effects()) decide(*e);
  for (const auto& e : registry.effects()) {
    if (e->revised_after().empty()) continue;
    const DecisionContext ctx(obs, options, decided, readable(*e, true), cache);
    Finding revised = decided.at(e->name());
    const bool before = revised.detected;
    e->revise(ctx, &revised);
    decided[e->name()] = std::move(revised);
    if (decided[e->name()].detected == before) continue;
    // A changed verdict: whatever was decided on it is decided again, in registry order.
    std::set<std::string> changed = {e->name()};
    for (const auto& d : registry.effects()) {
      const std::vector<std::string> deps = d->depends_on();
      if (std::none_of(deps.begin(), deps.end(), [&](const std::string& x) { return changed.count(x) > 0; })) continue;
      decide(*d);
      changed.insert(d->name());
    }
  }
  std::vector<Finding> out;
  for (const auto& e : registry.effects()) {
    out.push_back(decided.at(e->name()));
    out.back().thresholds = e->thresholds();
  }
  return out;
}

std::vector<Extension> fit_effect_extensions(const EffectRegistry& registry, const SetObservations& obs,
                                             const std::vector<size_t>& fit_index, const DiagnoseOptions& options,
                                             std::vector<Finding>* findings) {
  const auto& effects = registry.effects();
  if (findings->size() != effects.size()) throw Error("rir-diagnose: findings do not match the effect registry");
  std::vector<Extension> extensions(effects.size());
  for (size_t k = 0; k < effects.size(); ++k) {
    if (!(*findings)[k].detected) continue;
    std::vector<std::string> readable = {effects[k]->name()};
    for (const std::string& d : effects[k]->depends_on()) readable.push_back(d);
    const FitContext ctx(obs, fit_index, options, *findings, readable);
    extensions[k] = effects[k]->fit(ctx, &(*findings)[k]);
  }
  return extensions;
}

std::string model_spec(const std::string& base, const std::vector<Extension>& extensions, const std::string& room,
                       const std::function<bool(size_t)>& use) {
  std::string spec = base;
  for (size_t k = 0; k < extensions.size(); ++k) {
    if (!use(k)) continue;
    const auto it = extensions[k].by_room.find(room);
    spec += it != extensions[k].by_room.end() ? it->second : extensions[k].common;
  }
  return spec;
}

std::map<std::string, std::string> fit_extensions(const EffectRegistry& registry, const SetObservations& obs,
                                                  const std::vector<size_t>& fit_index, const DiagnoseOptions& options,
                                                  std::vector<Finding>* findings) {
  const std::vector<Extension> extensions = fit_effect_extensions(registry, obs, fit_index, options, findings);
  std::map<std::string, std::string> out;
  for (const RirObservation& r : obs) {
    const std::string room = room_group(r.room);
    out[room] = model_spec(options.baseline_model, extensions, room, [&](size_t k) { return (*findings)[k].detected; });
  }
  return out;
}

}  // namespace tsrir::diagnose

// The catalog of causes rir-diagnose looks for, as a registry of effects (like sim's component
// registry, sim/model.h). One file per effect, src/diagnose/effect_<name>.cc, holds everything
// about it:
//   - its detector: a decision over the whole set (never one RIR) on the fit half, with its
//     thresholds as a named struct whose list() documents each value once (rir-diagnose --help
//     prints it, findings.json carries it);
//   - its extension: the sim::ModelComponent the extended model adds and how its parameters are
//     fitted on the fit half;
//   - its report section (plots over the set, and per held-out example).
// The catalog (findings.json order), the decisions, the fits, the JSON, the stdout summary and the
// HTML report iterate the registry; none of them names an effect.
//
// Every decision is over the whole set. The null hypothesis is "measured = the baseline model
// with another seed" (the baseline is random: diffuse-tail noise). Each statistic is a per-RIR
// paired difference d_i = f(measured_i) - f(simulated_i, seed A); the same statistic between
// seed B and seed A, e_i = f(sim_B_i) - f(sim_A_i), is the null calibration: the decision rule
// applied to e must not fire (reported as null_statistic; if it fires, the statistic is not
// trusted and the effect is not reported as detected). Each rule has two conditions: a test that
// the set's differences are not chance at p < alpha (Bonferroni-corrected over bands and rooms
// inside the decision), AND an effect size a listener or a metric would notice.
//
// Cross-effect rules have one place: what an effect reads of another is declared.
//   depends_on()     effects whose findings detect() and fit() read. They are registered (so
//                    decided and fitted) earlier; DecisionContext/FitContext refuse to hand out
//                    any other effect's finding. E.g. band_absorption leaves the low bands to
//                    room_modes when room_modes is detected, and removes air's share.
//   revised_after()  effects decided later whose findings revise() reads: after every effect is
//                    decided, revise() runs in registry order; when it changes an effect's
//                    verdict, every effect that depends on it (transitively) is decided again.
//                    E.g. room_modes is decided again against band-refitted simulations when
//                    band_absorption is detected too; if that rules the modes out, air and band
//                    absorption are decided again without leaving the low bands to room_modes.
//
// How to add an effect (e.g. "source_directivity"):
//   1. A new file src/diagnose/effect_<name>.cc with a class derived from Effect (name,
//      description, thresholds, depends_on, detect, fit, gain_metric, report hooks) and a factory
//      `std::unique_ptr<Effect> make_<name>_effect()`.
//   2. In builtin_effects.cc, its factory's declaration and one r.add() line, in catalog order (an
//      effect comes after those it depends on). (No static-initialiser self-registration: the
//      linker drops unreferenced objects of static libraries.)
//   When it interacts with effects already there (it changes their statistic, or theirs changes
//   its), declare it: depends_on() in the effect that reads the other's finding, and the rule in
//   both files' header comments (source_directivity: transducer_response and diffuse_scattering).
//   3. Its test: hide it with the independent generator in tests/diagnose and require finding it.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "diagnose/diagnose_options.h"
#include "diagnose/gain_metrics.h"
#include "diagnose/observations.h"
#include "diagnose/rir_features.h"
#include "diagnose/unexplained.h"
#include "io/signal.h"
#include "sim/room.h"

namespace tsrir::diagnose {

// The thresholds every decision shares.
struct DecisionThresholds {
  double alpha = 1e-3;       // per-decision p (Bonferroni over bands/rooms inside a decision)
  double gain_alpha = 0.01;  // a held-out gain counts when its paired test gives p below this
};
inline constexpr DecisionThresholds kDecision{};
constexpr double kAlpha = kDecision.alpha;

// One named threshold of a decision, with why it has its value (the one place that says so).
struct Threshold {
  std::string name;
  double value;
  std::string why;
};

struct Finding {
  std::string effect;
  bool detected = false;
  double confidence = 0.0;
  std::string evidence;
  std::vector<std::pair<std::string, double>> parameters;  // fitted values (when detected)
  double statistic = 0.0;        // the effect-size statistic on measured vs simulated
  double null_statistic = 0.0;   // the same on seed B vs seed A
  double threshold = 0.0;
  std::string statistic_unit;
  std::vector<Threshold> thresholds;  // the effect's (Effect::thresholds), for findings.json
  // The held-out check of a detected effect's extension (diagnose.cc): "confirmed" (it improves its
  // gain metric and makes none worse), or what it does instead; empty when not detected.
  std::string held_out;
  // What the effect's report section plots (per-band curves, ...), by name; not in findings.json.
  std::map<std::string, std::vector<double>> curves;
};

// Alternative references the decisions of one pass share (e.g. the same set-ups re-rendered with
// another model), by name, each rendered once from the fit half (DecisionContext::reference).
using ReferenceCache = std::map<std::string, SetObservations>;
using ReferenceRenderer = std::function<SetObservations(const SetObservations& obs, const DiagnoseOptions& options)>;

// What detect() and revise() see: the fit half and the findings of the declared effects.
class DecisionContext {
 public:
  DecisionContext(const SetObservations& obs, const DiagnoseOptions& options, const std::map<std::string, Finding>& decided,
                  std::vector<std::string> readable, ReferenceCache* references);
  const SetObservations& obs() const { return obs_; }
  const DiagnoseOptions& options() const { return options_; }
  // The finding of a declared effect (depends_on, or revised_after in revise()); throws Error for
  // any other, so that every cross-effect rule is declared.
  const Finding& finding(const std::string& effect) const;
  bool detected(const std::string& effect) const { return finding(effect).detected; }
  // The reference called `name`: render(obs(), options()) on first use in the pass, shared by
  // every effect after it. The effect that owns a reference names and renders it (e.g.
  // decay_rate_effects.h: band_refitted); the framework names none.
  const SetObservations& reference(const std::string& name, const ReferenceRenderer& render) const;

 private:
  const SetObservations& obs_;
  const DiagnoseOptions& options_;
  const std::map<std::string, Finding>& decided_;
  std::vector<std::string> readable_;
  ReferenceCache* references_;
};

// The extension of a detected effect: model components ("+name:key=value,...") for every room, or
// per room (room_group) where the fit differs by room.
struct Extension {
  std::string common;
  std::map<std::string, std::string> by_room;
};

// What fit() sees: all RIRs, which of them are the fit half, and the declared effects' findings
// (fitted before this one, parameters included).
class FitContext {
 public:
  FitContext(const SetObservations& obs, const std::vector<size_t>& fit_index, const DiagnoseOptions& options,
             const std::vector<Finding>& findings, std::vector<std::string> readable);
  const SetObservations& obs() const { return obs_; }
  const std::vector<size_t>& fit_index() const { return fit_index_; }
  const DiagnoseOptions& options() const { return options_; }
  // The fit RIRs of each room (room_group), in set order.
  const std::map<std::string, std::vector<size_t>>& fit_by_room() const { return fit_by_room_; }
  const Finding& finding(const std::string& effect) const;  // declared effects only (as above)
  bool detected(const std::string& effect) const { return finding(effect).detected; }

 private:
  const SetObservations& obs_;
  const std::vector<size_t>& fit_index_;
  const DiagnoseOptions& options_;
  const std::vector<Finding>& findings_;
  std::vector<std::string> readable_;
  std::map<std::string, std::vector<size_t>> fit_by_room_;
};

struct Diagnosis;
struct ExampleCurves;

class Effect {
 public:
  virtual ~Effect() = default;
  virtual std::string name() const = 0;
  // The physical cause and the statistic that decides it, one or two lines (--help).
  virtual std::string description() const = 0;
  // Its decision's thresholds (--help, findings.json).
  virtual std::vector<Threshold> thresholds() const = 0;
  // The held-out metric (gain_metrics.h) its extension acts on.
  virtual GainMetricId gain_metric() const = 0;
  virtual std::vector<std::string> depends_on() const { return {}; }
  // True for an effect whose extension only changes per-band decay rates: the gain table's second
  // baseline (every band's absorption refitted to the measured decay) already does what it does,
  // so it has no gain of its own beyond that baseline.
  virtual bool within_band_refit() const { return false; }
  // The views of the `unexplained` check (unexplained.h) in which this effect's extension must leave
  // no departure: when one departs after the fit, the effect is withdrawn (its statistic may have
  // read a cause outside the catalog).
  virtual std::vector<ResidualView> residual_views() const { return {}; }
  // The decision on the fit half (ctx.obs()).
  virtual Finding detect(const DecisionContext& ctx) const = 0;
  virtual std::vector<std::string> revised_after() const { return {}; }
  // Called after every effect was decided when revised_after() is not empty; may replace *finding.
  virtual void revise(const DecisionContext& ctx, Finding* finding) const;
  // Fits the extension on ctx.fit_index() (only called when detected); writes the fitted values
  // into finding->parameters.
  virtual Extension fit(const FitContext& ctx, Finding* finding) const = 0;
  // Report: plots over the set (inside the report's "per-band departures" section) and plots per
  // held-out example (after the spectrograms and the energy decay curve).
  virtual void report_set(const Finding& finding, const Diagnosis& diagnosis, std::ostream& html) const;
  virtual void report_example(const ExampleCurves& example, std::ostream& html) const;
};

class EffectRegistry {
 public:
  // Appends an effect (catalog order). Throws Error for a name given twice, a dependency that is
  // not registered before it, or a gain metric that does not exist.
  void add(std::unique_ptr<Effect> effect);
  const std::vector<std::unique_ptr<Effect>>& effects() const { return effects_; }
  const Effect* find(const std::string& name) const;  // nullptr if unknown
  std::vector<std::string> names() const;

 private:
  std::vector<std::unique_ptr<Effect>> effects_;
};

// The built-in catalog (builtin_effects.cc).
const EffectRegistry& effect_registry();
// Catalog order (the order of findings.json) of the built-in registry.
std::vector<std::string> effect_catalog();

// "name: description" and "  threshold = value  why" lines of every effect, for --help.
std::string effects_help(const EffectRegistry& registry);

// Decides every effect of the registry on `fit_obs` (detect in registry order, then the
// revisions and the dependents' re-decisions); findings in registry order.
// `references` (optional) keeps the pass's references (DecisionContext::reference) for the caller.
// `withdrawn`: effects decided as usual and then set not detected (with `why` in their evidence),
// before the effects after them are decided.
std::vector<Finding> decide_effects(const EffectRegistry& registry, const SetObservations& fit_obs,
                                    const DiagnoseOptions& options, ReferenceCache* references = nullptr,
                                    const std::map<std::string, std::string>& withdrawn = {});

// Fits the extensions of the detected effects (registry order) on the fit RIRs of `obs` and writes
// their parameters into the findings; one Extension per effect of the registry (empty when not
// detected).
std::vector<Extension> fit_effect_extensions(const EffectRegistry& registry, const SetObservations& obs,
                                             const std::vector<size_t>& fit_index, const DiagnoseOptions& options,
                                             std::vector<Finding>* findings);

// `base` + the components of the extensions whose index `use` accepts, in registry order, for one
// room (room_group): its own fit where the extension has one, else the common one.
std::string model_spec(const std::string& base, const std::vector<Extension>& extensions, const std::string& room,
                       const std::function<bool(size_t)>& use);

// fit_effect_extensions, assembled: the extended model spec per room (room_group) of `obs`:
// baseline + each detected effect's components in registry order.
std::map<std::string, std::string> fit_extensions(const EffectRegistry& registry, const SetObservations& obs,
                                                  const std::vector<size_t>& fit_index, const DiagnoseOptions& options,
                                                  std::vector<Finding>* findings);

}  // namespace tsrir::diagnose

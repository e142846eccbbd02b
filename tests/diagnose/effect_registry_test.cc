// The effect registry's dispatch (effect.h), with small effects whose decisions are known: declared
// dependencies are decided first and are the only findings an effect can read; a revision that
// changes a verdict re-decides the effects that depend on it; extensions are assembled per room in
// registry order. And the built-in catalog: every effect documented and its thresholds in
// findings.json.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "diagnose/diagnose.h"
#include "diagnose/effect.h"
#include "hidden_effects.h"
#include "metrics/metric_columns.h"
#include "util/error.h"

namespace tsrir::diagnose {
namespace {

// A configurable effect: detect() returns `rule(ctx)` and counts its calls.
struct TestEffect : Effect {
  std::string id;
  std::vector<std::string> deps, revised;
  std::function<bool(const DecisionContext&)> rule = [](const DecisionContext&) { return true; };
  std::function<void(const DecisionContext&, Finding*)> reviser;
  Extension extension;
  int* detect_calls = nullptr;

  std::string name() const override { return id; }
  std::string description() const override { return "test effect " + id; }
  std::vector<Threshold> thresholds() const override { return {{"min", 1.0, "for the test"}}; }
  GainMetricId gain_metric() const override { return GainMetricId::own(OwnMetric::kOnset); }
  std::vector<std::string> depends_on() const override { return deps; }
  std::vector<std::string> revised_after() const override { return revised; }
  Finding detect(const DecisionContext& ctx) const override {
    if (detect_calls) ++*detect_calls;
    Finding f;
    f.detected = rule(ctx);
    return f;
  }
  void revise(const DecisionContext& ctx, Finding* f) const override {
    if (reviser) reviser(ctx, f);
  }
  Extension fit(const FitContext& ctx, Finding* f) const override {
    for (const std::string& d : deps) ctx.finding(d);  // declared: readable
    f->parameters = {{"fitted", 1.0}};
    return extension;
  }
};

std::unique_ptr<TestEffect> effect(const std::string& id, std::vector<std::string> deps = {}) {
  auto e = std::make_unique<TestEffect>();
  e->id = id;
  e->deps = std::move(deps);
  return e;
}

bool detected(const std::vector<Finding>& findings, const std::string& id) {
  for (const Finding& f : findings) {
    if (f.effect == id) return f.detected;
  }
  ADD_FAILURE() << "no finding " << id;
  return false;
}

TEST(EffectRegistry, DependenciesAreDecidedFirstAndARevisedVerdictRedecidesItsDependents) {
  EffectRegistry r;
  int calls_d = 0, calls_b = 0;
  auto c = effect("c");
  c->revised = {"b"};
  c->reviser = [](const DecisionContext& ctx, Finding* f) {
    if (ctx.detected("b")) f->detected = false;  // b explains c away
  };
  r.add(std::move(c));
  r.add(effect("a"));
  auto b = effect("b", {"a"});
  b->rule = [](const DecisionContext& ctx) { return ctx.detected("a"); };
  b->detect_calls = &calls_b;
  r.add(std::move(b));
  auto d = effect("d", {"c"});
  d->rule = [](const DecisionContext& ctx) { return ctx.detected("c"); };
  d->detect_calls = &calls_d;
  r.add(std::move(d));

  const std::vector<Finding> f = decide_effects(r, SetObservations{}, DiagnoseOptions{});
  ASSERT_EQ(f.size(), 4u);
  EXPECT_EQ(f[0].effect, "c");  // registry order
  EXPECT_EQ(f[3].effect, "d");
  EXPECT_TRUE(detected(f, "a"));
  EXPECT_TRUE(detected(f, "b"));
  EXPECT_FALSE(detected(f, "c"));  // revised
  EXPECT_FALSE(detected(f, "d"));  // decided again on the revised c
  EXPECT_EQ(calls_d, 2);
  EXPECT_EQ(calls_b, 1);           // b does not depend on c
  EXPECT_EQ(f[2].thresholds.size(), 1u);
}

TEST(EffectRegistry, AnUndeclaredReadIsAnError) {
  EffectRegistry r;
  r.add(effect("a"));
  auto b = effect("b");
  b->rule = [](const DecisionContext& ctx) { return ctx.detected("a"); };  // not in depends_on
  r.add(std::move(b));
  EXPECT_THROW(decide_effects(r, SetObservations{}, DiagnoseOptions{}), Error);
}

TEST(EffectRegistry, RegistrationChecksNamesAndOrder) {
  EffectRegistry r;
  r.add(effect("a"));
  EXPECT_THROW(r.add(effect("a")), Error);
  EXPECT_THROW(r.add(effect("b", {"later"})), Error);  // dependencies come first
  r.add(effect("b", {"a"}));
  EXPECT_EQ(r.names(), (std::vector<std::string>{"a", "b"}));
}

TEST(EffectRegistry, ExtensionsAreAssembledPerRoomInRegistryOrder) {
  EffectRegistry r;
  auto a = effect("a");
  a->extension.common = "+x:v=1";
  r.add(std::move(a));
  auto b = effect("b", {"a"});
  b->extension.by_room = {{"room1", "+y:v=2"}};  // room2 has no fit RIR of its own: nothing
  r.add(std::move(b));
  auto c = effect("c");
  c->extension.common = "+z:v=3";
  r.add(std::move(c));

  SetObservations obs;
  for (const char* room : {"room1", "room1", "room2"}) {
    RirObservation r;
    r.room.room_id = room;
    obs.rirs.push_back(r);
  }
  std::vector<Finding> findings(3);
  findings[0].effect = "a";
  findings[1].effect = "b";
  findings[2].effect = "c";
  findings[0].detected = findings[1].detected = true;  // c not detected: not fitted, not in the model
  DiagnoseOptions options;
  options.baseline_model = "base";
  const auto models = fit_extensions(r, obs, {0, 1, 2}, options, &findings);
  EXPECT_EQ(models.at("room1"), "base+x:v=1+y:v=2");
  EXPECT_EQ(models.at("room2"), "base+x:v=1");
  EXPECT_EQ(findings[1].parameters.size(), 1u);
  EXPECT_TRUE(findings[2].parameters.empty());
}

TEST(EffectRegistry, AnUnknownGainMetricIsRefusedAtRegistration) {
  struct BadMetric : TestEffect {
    GainMetricId gain_metric() const override { return GainMetricId::column("C99"); }
  };
  EffectRegistry r;
  auto e = std::make_unique<BadMetric>();
  e->id = "bad";
  EXPECT_THROW(r.add(std::move(e)), Error);
  EXPECT_THROW(GainMetricId::named("no_such_metric"), Error);
}

// Every parameter of the metric table (src/metrics/metric_columns.cc) is a gain metric, by the
// table's own name and unit, with no list of its own here.
TEST(GainMetrics, EveryMetricTableColumnIsAGainMetric) {
  for (const MetricColumn& c : metric_columns()) {
    const GainMetric& g = gain_metric(GainMetricId::column(c.name));
    EXPECT_EQ(g.unit, c.unit) << c.name;
    EXPECT_EQ(GainMetricId::named(g.name), GainMetricId::column(c.name)) << c.name;
    RirFeatures m, s;
    m.metrics.*(c.value) = 3.0;
    s.metrics.*(c.value) = 1.25;
    EXPECT_DOUBLE_EQ(g.error(m, s), 1.75) << c.name;  // |measured - simulated| of that column
  }
}

// A fit that makes a metric worse on the held-out RIRs: an effect always "detected" whose extension
// adds a 3 ms latency to a set that has none (data from the tests' independent generator). The gain
// table must show onset worse, the regression must name this effect, and its held-out verdict must
// say that it does not improve its own metric: contested, confidence down to 0.5.
TEST(HeldOutCheck, AFitThatMakesAMetricWorseIsReportedAndTakenIntoAccount) {
  struct WrongLatency : TestEffect {
    Extension fit(const FitContext&, Finding* f) const override {
      f->parameters = {{"latency_ms", 3.0}};
      return {"+onset_shift:latency_ms=3", {}};
    }
  };
  EffectRegistry r;
  auto e = std::make_unique<WrongLatency>();
  e->id = "wrong_latency";
  r.add(std::move(e));
  const auto rooms = testdata::make_test_rooms(16, 81);
  const testdata::HiddenSet set = testdata::make_hidden_set(rooms, {}, 4);
  DiagnoseOptions options;
  const Diagnosis d = diagnose_set(set.stated, set.measured, options, {}, r);
  ASSERT_EQ(d.findings.size(), 1u);
  EXPECT_TRUE(d.findings[0].detected);
  EXPECT_EQ(d.findings[0].held_out.rfind("contested: makes worse onset", 0), 0u) << d.findings[0].held_out;
  EXPECT_LE(d.findings[0].confidence, 0.5);
  bool onset_reported = false;
  for (const Regression& reg : d.regressions) {
    if (reg.metric != "onset") continue;
    onset_reported = true;
    EXPECT_NEAR(reg.extended - reg.baseline, 3.0, 0.3);
    EXPECT_EQ(reg.caused_by, std::vector<std::string>{"wrong_latency"});
  }
  EXPECT_TRUE(onset_reported);
  std::ostringstream json;
  write_findings_json(d, json);
  const std::string text = json.str();
  const size_t regressions = text.find("\"regressions\": [");
  ASSERT_NE(regressions, std::string::npos);
  EXPECT_EQ(text.find("\"metric\": \"onset\"", regressions), text.find("\"metric\"", regressions)) << text;
}

TEST(EffectRegistry, BuiltInCatalogIsDocumented) {
  const EffectRegistry& r = effect_registry();
  EXPECT_GE(r.effects().size(), 7u);
  for (const auto& e : r.effects()) {
    EXPECT_FALSE(e->description().empty()) << e->name();
    EXPECT_FALSE(e->thresholds().empty()) << e->name();
    for (const Threshold& t : e->thresholds()) EXPECT_GT(t.why.size(), 10u) << e->name() << "." << t.name;
    EXPECT_LT(e->gain_metric().index(), gain_metrics().size()) << e->name();
  }
  const std::string help = effects_help(r);
  for (const auto& e : r.effects()) EXPECT_NE(help.find("  " + e->name() + "\n"), std::string::npos) << e->name();
}

}  // namespace
}  // namespace tsrir::diagnose

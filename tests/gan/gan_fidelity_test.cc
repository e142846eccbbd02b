// The TS-RIRGAN translation-fidelity suite (issues 17 and 34). First the measures themselves are
// shown to tell translation from its failure modes without any training, for every hidden-effect
// kind: the identity keeps every RIR's acoustics but moves no effect; the oracle translation
// (each input with its own hidden effect added, from the data generator) passes; the same effects
// put in the wrong band (a 300-450 Hz crossover instead of 2-3 kHz) fail on the parameters the
// kind leaves alone; one pasted template (a real RIR for every input) loses the inputs'
// acoustics and fine structure; one low-frequency addition pasted onto every input keeps them but
// is caught by the additions' similarity. Then small models are trained through the real programs
// with the program's defaults on two fixed seeds of two kinds (below);
// bench/gan/fidelity_trajectory.sh runs five seeds per kind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <unistd.h>

#include "fidelity_domains.h"
#include "fidelity_measures.h"
#include "fidelity_suite.h"

namespace fs = std::filesystem;
using namespace tsrir_test;

namespace {

using P = FidelityParameter;

const HiddenEffect kKinds[] = {HiddenEffect::kLowFrequency, HiddenEffect::kDecay, HiddenEffect::kDirect,
                               HiddenEffect::kEarly};

bool failed_on(const FidelityReport& r, const std::string& parameter) {
  for (const auto& f : r.failures) {
    if (f.rfind(parameter + " ", 0) == 0) return true;
  }
  return false;
}

}  // namespace

TEST(FidelityDomains, DomainsShareAcousticsAndDifferByTheEffect) {
  for (HiddenEffect kind : kKinds) {
    SCOPED_TRACE(hidden_effect_name(kind));
    const FidelityDomainSpec syn, real = real_domain_spec(kind);
    const auto a = make_fidelity_domain(syn, "x", 60, 5), b = make_fidelity_domain(real, "x", 60, 5);
    int low_kinds[kNumLowFrequencyKinds + 1] = {};
    std::vector<double> mid_error;
    for (size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].t60_s, b[i].t60_s);
      EXPECT_EQ(a[i].onset_s, b[i].onset_s);
      ++low_kinds[int(b[i].effect)];
      // The measures read back the drawn acoustics (the measure is not the generator's formula):
      // the synthetic RIR's decay is the drawn T60 in both bands, its onset the drawn one. The
      // 500-1000 Hz band's estimate is the noisier (half an octave of noise, the early
      // reflections in its fit range): most within 15 %, all within 40 %.
      const RirFidelityMeasures m = measure_fidelity_rir(a[i].signal);
      EXPECT_NEAR(m.onset_ms, 1000 * a[i].onset_s, 0.1);
      EXPECT_NEAR(m[P::kT60High], a[i].t60_s, 0.15 * a[i].t60_s) << a[i].signal.id;
      EXPECT_NEAR(m[P::kT60Mid], a[i].t60_s, 0.4 * a[i].t60_s) << a[i].signal.id;
      mid_error.push_back(std::abs(m[P::kT60Mid] / a[i].t60_s - 1.0));
    }
    std::sort(mid_error.begin(), mid_error.end());
    EXPECT_LT(mid_error[mid_error.size() * 9 / 10], 0.15);
    if (kind == HiddenEffect::kLowFrequency) {
      EXPECT_EQ(low_kinds[0], 0);
      for (int k = 1; k <= kNumLowFrequencyKinds; ++k) EXPECT_GE(low_kinds[k], 8) << effect_name(LowFrequencyEffect(k));
    } else {
      EXPECT_EQ(low_kinds[0], 60);
    }
  }
}

// Per kind, without training: the identity fails only the moved check; the oracle passes with
// every moved parameter near 1 of the gap; the effect in the wrong band fails a kept parameter.
TEST(FidelityMeasures, IdentityOracleAndWrongBandPerKind) {
  for (HiddenEffect kind : kKinds) {
    SCOPED_TRACE(hidden_effect_name(kind));
    const HeldOutSets h = held_out_sets(real_domain_spec(kind), 101);
    const FidelityReport identity = evaluate_fidelity(kind, h.synthetic, h.synthetic, h.reference);
    const FidelityReport oracle = evaluate_fidelity(kind, h.synthetic, h.oracle, h.reference);
    std::cerr << "identity: " << identity.summary() << "\noracle: " << oracle.summary() << "\n";
    const FidelityPlan plan = fidelity_plan(kind);
    EXPECT_EQ(identity.failures.size(), plan.moved.size());
    for (P p : plan.moved) {
      EXPECT_TRUE(failed_on(identity, parameter_name(p)));
      EXPECT_NEAR(identity[p].moved, 0.0, 1e-9);
      EXPECT_NEAR(oracle[p].moved, 1.0, 0.25) << parameter_name(p);
    }
    EXPECT_TRUE(oracle.passed()) << oracle.summary();
    EXPECT_GT(identity.own_correlation - identity.other_correlation, 0.8);

    FidelityDomainSpec wrong = real_domain_spec(kind);
    wrong.crossover_min_hz = 300.0, wrong.crossover_max_hz = 450.0;
    if (kind == HiddenEffect::kLowFrequency) continue;  // no crossover; its wrong band is below
    const FidelityReport misplaced = evaluate_fidelity(kind, h.synthetic, held_out_sets(wrong, 101, 48, 0).oracle,
                                                       h.reference);
    std::cerr << "wrong band: " << misplaced.summary() << "\n";
    EXPECT_FALSE(misplaced.passed());
    bool kept_failed = false;
    for (P p : plan.kept) kept_failed = kept_failed || failed_on(misplaced, parameter_name(p));
    EXPECT_TRUE(kept_failed) << misplaced.summary();
  }
}

// The low-frequency kind's translation that also changes the bands above 500 Hz (its oracle plus
// what the decay kind's oracle changes above 2-3 kHz) fails on the high band's kept parameters.
TEST(FidelityMeasures, LowFrequencyEffectWithHighBandChangesFails) {
  const HeldOutSets low = held_out_sets(real_domain_spec(HiddenEffect::kLowFrequency), 202);
  const HeldOutSets decay = held_out_sets(real_domain_spec(HiddenEffect::kDecay), 202, 48, 0);
  std::vector<tsrir::Signal> both = low.oracle;
  for (size_t i = 0; i < both.size(); ++i) {
    for (size_t k = 0; k < both[i].samples.size(); ++k) {
      both[i].samples[k] += decay.oracle[i].samples[k] - decay.synthetic[i].samples[k];
    }
  }
  const FidelityReport r = evaluate_fidelity(HiddenEffect::kLowFrequency, low.synthetic, both, low.reference);
  std::cerr << r.summary() << "\n";
  EXPECT_NEAR(r[P::kLowFrequency].moved, 1.0, 0.25);
  EXPECT_TRUE(failed_on(r, "t60_high_s"));
  EXPECT_TRUE(failed_on(r, "early_high_db"));
}

TEST(FidelityMeasures, OneTemplateForEveryInputFails) {
  for (HiddenEffect kind : {HiddenEffect::kLowFrequency, HiddenEffect::kDirect}) {
    SCOPED_TRACE(hidden_effect_name(kind));
    const HeldOutSets h = held_out_sets(real_domain_spec(kind), 303);
    const std::vector<tsrir::Signal> pasted(h.synthetic.size(), h.reference.real[0]);
    const FidelityReport r = evaluate_fidelity(kind, h.synthetic, pasted, h.reference);
    std::cerr << r.summary() << "\n";
    EXPECT_FALSE(r.passed());
    EXPECT_LT(r.own_correlation - r.other_correlation, 0.1);
    EXPECT_LT(r[P::kT60Mid].spearman, 0.5);
    EXPECT_LT(r.onset_fraction_within, 0.5);
  }
}

// The failure a generator that adds a low-frequency waveform can still have: every input keeps its
// own acoustics above 500 Hz and gains the SAME low-frequency addition at its onset: here one
// oracle RIR's hidden effect, pasted onto every input. Only the measure of the additions'
// similarity across RIRs can tell this from a translation.
TEST(FidelityMeasures, OneLowFrequencyTemplateAddedToEveryInputFails) {
  const HeldOutSets h = held_out_sets(real_domain_spec(HiddenEffect::kLowFrequency), 404);
  auto onset_sample = [](const tsrir::Signal& x) {
    return long(std::lround(measure_fidelity_rir(x).onset_ms * x.sample_rate_hz / 1000.0));
  };
  const size_t j = 0;
  const long onset_j = onset_sample(h.synthetic[j]);
  std::vector<tsrir::Signal> pasted = h.synthetic;
  for (size_t i = 0; i < pasted.size(); ++i) {
    const long shift = onset_sample(h.synthetic[i]) - onset_j;
    auto& out = pasted[i].samples;
    for (long k = 0; k < long(out.size()); ++k) {
      const long from = k - shift;
      if (from >= 0 && from < long(h.oracle[j].samples.size())) {
        out[size_t(k)] += h.oracle[j].samples[size_t(from)] - h.synthetic[j].samples[size_t(from)];
      }
    }
  }
  const FidelityReport r = evaluate_fidelity(HiddenEffect::kLowFrequency, h.synthetic, pasted, h.reference);
  std::cerr << r.summary() << "\n";
  EXPECT_FALSE(r.passed());
  EXPECT_GT(r.added_correlation, 0.9);
  EXPECT_GT(r.own_correlation - r.other_correlation, 0.8);  // the other measures cannot tell
  EXPECT_GT(r[P::kT60High].spearman, 0.95);
}

// A level change is not an addition: the inputs scaled by 0.5 (as gas-to-real rescales an output
// whose peak grew) add nothing below 200 Hz, so they cannot read as a pasted template.
TEST(FidelityMeasures, ALevelChangeAddsNothing) {
  const HeldOutSets h = held_out_sets(real_domain_spec(HiddenEffect::kDirect), 505, 24, 32);
  std::vector<tsrir::Signal> halved = h.synthetic;
  for (auto& s : halved) {
    for (auto& v : s.samples) v *= 0.5f;
  }
  const long start = long(std::lround(measure_fidelity_rir(h.synthetic[0]).onset_ms * 16.0));
  for (double v : low_band_addition(h.synthetic[0], halved[0], start)) EXPECT_NEAR(v, 0.0, 1e-6);
}

// Program defaults at the width the issue names (issue 17: "only --width, --batch-size, --steps and
// --seed given"), on two fixed seeds, each with its own hidden-effect kind: the low-frequency kind
// (modes below 200 Hz) and the direct sound above 2-3 kHz (the broadband difference R3VIVAL shows).
// The seeds are two the bench run passed (bench/RESULTS.md, "Five seeds per kind of (m) with the
// averaged weights": low-frequency seed 2 moved 0.76 of the gap, direct seed 3 0.78, every kept
// parameter within its bound by at least 0.38 of it); training is not bit-reproducible across
// machines, so these are checks of the configuration, not of one run. ~25 minutes of one core each.
// bench/gan/fidelity_trajectory.sh runs five seeds per kind.
// TSRIR_GAN_FIDELITY_ARGS replaces the options, TSRIR_GAN_FIDELITY_SEED both seeds (e.g. the seed
// of the day: the date as YYYYMMDD), TSRIR_GAN_FIDELITY_KEEP=1 keeps the work dirs.
constexpr const char* kTrainArgs = "--width=16 --batch-size=4 --steps=2000";

void expect_fidelity(uint64_t seed, HiddenEffect effect) {
  FidelitySuiteOptions o;
  o.bin_dir = TSRIR_BIN_DIR;
  o.work_dir = (fs::temp_directory_path() /
                ("tsrir_gan_fidelity_" + std::to_string(::getpid()) + "_" + std::to_string(seed))).string();
  const char* fixed = std::getenv("TSRIR_GAN_FIDELITY_SEED");
  o.seed = fixed ? std::strtoull(fixed, nullptr, 10) : seed;
  o.effect = effect;
  const char* args = std::getenv("TSRIR_GAN_FIDELITY_ARGS");
  o.train_args = args ? args : kTrainArgs;
  o.keep = std::getenv("TSRIR_GAN_FIDELITY_KEEP") != nullptr;
  const FidelitySuiteResult r = run_fidelity_suite(o);
  ASSERT_TRUE(r.error.empty()) << r.error;
  std::cerr << "seed " << o.seed << " (" << o.train_args << "), train " << r.train_s << " s: " << r.report.summary()
            << "\n";
  EXPECT_TRUE(r.report.passed()) << "seed " << o.seed << ": " << r.report.summary() << "; work dir " << o.work_dir;
}

TEST(GanFidelity, TranslatesEachInputWithProgramDefaultsLowFrequencySeed2) {
  expect_fidelity(2, HiddenEffect::kLowFrequency);
}
TEST(GanFidelity, TranslatesEachInputWithProgramDefaultsDirectSeed3) { expect_fidelity(3, HiddenEffect::kDirect); }

// gan-fidelity-suite: runs the TS-RIRGAN translation-fidelity suite (tests/gan/fidelity_suite.h)
// for one seed and one hidden-effect kind and prints one line with every measure; exit 0 if it
// passed, 1 if it failed, 2 if a program failed. Used by bench/gan/fidelity_seeds.sh (a test
// helper, not installed).
// Usage: gan-fidelity-suite [--effect=KIND] <bin-dir> <work-dir> <seed> "<ts-rirgan-train options>" [num-threads] [keep]
//        gan-fidelity-suite [--effect=KIND] --measure <input-scp> <translated-scp> <synthetic-ref-scp> <real-ref-scp>
//   (the measures alone, on any sets: translated RIRs are matched to inputs by id)
//        gan-fidelity-suite [--effect=KIND] --remeasure <work-dir> <seed>
//   (the measures alone, again, of a work dir a run kept: its sr/ against the seed's held-out sets)
//        gan-fidelity-suite --calibrate <first-seed> <count>
//   (no training: per kind, over held-out draws of `count` seeds, what the kept parameters' bounds
//   must tell apart: the oracle translation's measurement noise against translations that put the
//   effect in the wrong band; bench/RESULTS.md records the output the bounds were set from)
// KIND: low-frequency (the default), decay, direct or early (fidelity_domains.h).
// TSRIR_GAN_FIDELITY_DETAILS=1 adds one line per RIR.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>

#include "fidelity_suite.h"
#include "io/rir_set.h"

namespace {
std::vector<tsrir::Signal> load_scp(const std::string& scp) {
  std::vector<tsrir::Signal> rirs;
  tsrir::AudioReadOptions options;
  options.target_rate_hz = 16000.0;
  for (const auto& ref : tsrir::read_rir_refs(scp, nullptr)) rirs.push_back(tsrir::load_rir(ref, options));
  return rirs;
}
}  // namespace

// Worst (lowest) rank correlation and worst (highest) median error of the kept parameters.
struct Extremes {
  double min_rho = 1e9, max_rho = -1e9, min_error = 1e9, max_error = -1e9, min_moved = 1e9, max_moved = -1e9;
  void add(const tsrir_test::ParameterReport& p) {
    if (std::isfinite(p.spearman)) min_rho = std::min(min_rho, p.spearman), max_rho = std::max(max_rho, p.spearman);
    min_error = std::min(min_error, p.median_error), max_error = std::max(max_error, p.median_error);
    min_moved = std::min(min_moved, p.moved), max_moved = std::max(max_moved, p.moved);
  }
};

// Translations that change what the kind leaves alone: for the kinds above 500 Hz, each RIR's
// own effect with a crossover of 300-450 Hz instead of 2-3 kHz (so the mid band changes too); for
// the low-frequency kind, its oracle plus what the decay kind's oracle changes above 2-3 kHz.
std::vector<tsrir::Signal> wrong_band(tsrir_test::HiddenEffect kind, uint64_t seed) {
  using namespace tsrir_test;
  if (kind == HiddenEffect::kLowFrequency) {
    const HeldOutSets low = held_out_sets(real_domain_spec(kind), seed, 48, 0);
    const HeldOutSets decay = held_out_sets(real_domain_spec(HiddenEffect::kDecay), seed, 48, 0);
    std::vector<tsrir::Signal> out = low.oracle;
    for (size_t i = 0; i < out.size(); ++i) {
      for (size_t k = 0; k < out[i].samples.size(); ++k) {
        out[i].samples[k] += decay.oracle[i].samples[k] - decay.synthetic[i].samples[k];
      }
    }
    return out;
  }
  FidelityDomainSpec s = real_domain_spec(kind);
  s.crossover_min_hz = 300.0, s.crossover_max_hz = 450.0;
  return held_out_sets(s, seed, 48, 0).oracle;
}

int calibrate(uint64_t first_seed, int count) {
  using namespace tsrir_test;
  for (int k = 0; k < kNumHiddenEffects; ++k) {
    const HiddenEffect kind = HiddenEffect(k);
    Extremes oracle[kNumFidelityParameters], wrong[kNumFidelityParameters], identity[kNumFidelityParameters];
    int oracle_failed = 0, wrong_passed = 0;
    double min_own = 1e9, max_added = -1e9;
    for (int i = 0; i < count; ++i) {
      const uint64_t seed = first_seed + 16 * uint64_t(i);
      const HeldOutSets h = held_out_sets(real_domain_spec(kind), seed);
      const std::vector<tsrir::Signal> w = wrong_band(kind, seed);
      const FidelityReport o = evaluate_fidelity(kind, h.synthetic, h.oracle, h.reference);
      const FidelityReport x = evaluate_fidelity(kind, h.synthetic, w, h.reference);
      const FidelityReport id = evaluate_fidelity(kind, h.synthetic, h.synthetic, h.reference);
      oracle_failed += !o.passed(), wrong_passed += x.passed();
      min_own = std::min(min_own, o.own_correlation - o.other_correlation);
      max_added = std::max(max_added, o.added_correlation);
      for (int p = 0; p < kNumFidelityParameters; ++p) {
        oracle[p].add(o.parameters[p]), wrong[p].add(x.parameters[p]), identity[p].add(id.parameters[p]);
      }
      if (!o.passed()) std::cout << "  oracle failed, seed " << seed << ": " << o.summary() << "\n";
    }
    const FidelityPlan plan = fidelity_plan(kind);
    std::cout << "kind " << hidden_effect_name(kind) << " (" << count << " draws of 48 held-out RIRs): oracle failed " << oracle_failed
              << ", wrong-band passed " << wrong_passed << "; oracle envelope own - other >= " << min_own
              << ", added corr. <= " << max_added << "\n";
    for (auto p : plan.moved) {
      const int i = int(p);
      std::cout << "  moved " << parameter_name(p) << ": oracle " << oracle[i].min_moved << " .. " << oracle[i].max_moved
                << ", identity " << identity[i].min_moved << " .. " << identity[i].max_moved << "\n";
    }
    for (auto p : plan.kept) {
      const int i = int(p);
      std::cout << "  kept " << parameter_name(p) << ": oracle rho >= " << oracle[i].min_rho << ", error <= "
                << oracle[i].max_error << "; wrong band rho " << wrong[i].min_rho << " .. " << wrong[i].max_rho
                << ", error " << wrong[i].min_error << " .. " << wrong[i].max_error << "\n";
    }
  }
  return 0;
}

int main(int argc, char** argv) {
  if (argc == 4 && std::string(argv[1]) == "--calibrate") {
    return calibrate(std::strtoull(argv[2], nullptr, 10), std::atoi(argv[3]));
  }
  const bool details = std::getenv("TSRIR_GAN_FIDELITY_DETAILS") != nullptr;
  tsrir_test::HiddenEffect effect = tsrir_test::HiddenEffect::kLowFrequency;
  if (argc > 1 && std::string(argv[1]).rfind("--effect=", 0) == 0) {
    if (!tsrir_test::parse_hidden_effect(std::string(argv[1]).substr(9), &effect)) {
      std::cerr << "unknown hidden effect " << argv[1] << " (low-frequency, decay, direct, early)\n";
      return 2;
    }
    ++argv, --argc;
  }
  if (argc == 6 && std::string(argv[1]) == "--measure") {
    std::vector<tsrir::Signal> inputs = load_scp(argv[2]), outputs;
    std::map<std::string, tsrir::Signal> by_id;
    for (auto& s : load_scp(argv[3])) by_id[s.id] = std::move(s);
    std::vector<tsrir::Signal> matched;
    for (const auto& in : inputs) {
      auto it = by_id.find(in.id);
      if (it == by_id.end()) {
        std::cerr << "no translated RIR with id " << in.id << " in " << argv[3] << "\n";
        return 2;
      }
      // Compare over the common length (a translation may keep fewer samples).
      tsrir::Signal a = in, b = it->second;
      const size_t n = std::min(a.samples.size(), b.samples.size());
      a.samples.resize(n), b.samples.resize(n);
      matched.push_back(a), outputs.push_back(b);
    }
    const tsrir_test::FidelityReport r = tsrir_test::evaluate_fidelity(effect, matched, outputs, {load_scp(argv[4]), load_scp(argv[5])});
    if (details) std::cout << r.per_rir;
    std::cout << r.summary() << std::endl;
    return r.passed() ? 0 : 1;
  }
  if (argc == 4 && std::string(argv[1]) == "--remeasure") {
    tsrir_test::FidelitySuiteOptions o;
    o.work_dir = argv[2];
    o.seed = std::strtoull(argv[3], nullptr, 10);
    o.effect = effect;
    const tsrir_test::FidelitySuiteResult r = tsrir_test::measure_fidelity_work_dir(o);
    if (!r.error.empty()) {
      std::cout << "seed " << o.seed << ": ERROR " << r.error << std::endl;
      return 2;
    }
    if (details) std::cout << r.report.per_rir;
    std::cout << "seed " << o.seed << " (remeasured " << o.work_dir << "): " << r.report.summary() << std::endl;
    return r.passed() ? 0 : 1;
  }
  if (argc < 5) {
    std::cerr << "Usage: gan-fidelity-suite [--effect=KIND] <bin-dir> <work-dir> <seed> \"<ts-rirgan-train options>\" "
                 "[num-threads] [keep]\n";
    return 2;
  }
  tsrir_test::FidelitySuiteOptions o;
  o.bin_dir = argv[1];
  o.work_dir = argv[2];
  o.seed = std::strtoull(argv[3], nullptr, 10);
  o.train_args = argv[4];
  o.effect = effect;
  if (argc > 5) o.num_threads = std::atoi(argv[5]);
  o.keep = argc > 6 && std::string(argv[6]) == "keep";
  const tsrir_test::FidelitySuiteResult r = tsrir_test::run_fidelity_suite(o);
  if (!r.error.empty()) {
    std::cout << "seed " << o.seed << ": ERROR " << r.error << std::endl;
    return 2;
  }
  if (details) std::cout << r.report.per_rir;
  std::cout << "seed " << o.seed << ": train " << int(r.train_s) << " s; " << r.report.summary() << std::endl;
  return r.passed() ? 0 : 1;
}

// The TS-RIRGAN translation-fidelity suite end to end (issues 17, 34): generates the two domains
// (fidelity_domains.h) for a seed and a hidden-effect kind, trains through the real ts-rirgan-train with the given
// options, translates held-out synthetic RIRs with gas-to-real and measures them
// (fidelity_measures.h). Shared by tests/gan/gan_fidelity_test and bench/gan/fidelity_seeds.sh
// (through the gan-fidelity-suite program).
#pragma once
#include <cstdint>
#include <string>

#include "fidelity_domains.h"
#include "fidelity_measures.h"

namespace tsrir_test {

struct FidelitySuiteOptions {
  std::string bin_dir;       // where ts-rirgan-train and gas-to-real are
  std::string work_dir;      // created; removed afterwards unless keep
  uint64_t seed = 1;         // data and training seed
  HiddenEffect effect = HiddenEffect::kLowFrequency;  // the real domain's hidden effect
  std::string train_args;    // ts-rirgan-train options, without --seed
  int num_threads = 1;
  int train_count = 64;      // RIRs per training domain
  int test_count = 48;       // held-out synthetic RIRs translated and measured
  int reference_count = 256; // held-out RIRs per domain whose means define the gap
  bool keep = false;
};

struct FidelitySuiteResult {
  std::string error;         // a program failed (its exit status and log tail); empty if all ran
  FidelityReport report;
  double train_s = 0;
  bool passed() const { return error.empty() && report.passed(); }
};

FidelitySuiteResult run_fidelity_suite(const FidelitySuiteOptions& options);
// The measures alone, again, of a work dir the suite kept (its sr/ translations against the held-out
// sets `options`' seed and effect regenerate): for a suite whose measures changed after training.
FidelitySuiteResult measure_fidelity_work_dir(const FidelitySuiteOptions& options);

// Held-out sets without training, for the measures' own tests and their calibration: `count`
// synthetic RIRs (name "test_syn", `seed`), their oracle translation (the same names and seed
// under `real_spec`: each input with its own hidden effect added) and the reference sets
// (`reference_count` per domain, seeds seed + 1 and seed + 2).
struct HeldOutSets {
  std::vector<tsrir::Signal> synthetic, oracle;
  FidelityReference reference;
};
HeldOutSets held_out_sets(const FidelityDomainSpec& real_spec, uint64_t seed, int count = 48, int reference_count = 256);
// The real domain's spec of a hidden-effect kind.
FidelityDomainSpec real_domain_spec(HiddenEffect effect);

}  // namespace tsrir_test

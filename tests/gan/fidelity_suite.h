// The TS-RIRGAN translation-fidelity suite end to end (issue 17): generates the two domains
// (fidelity_domains.h) for a seed, trains through the real ts-rirgan-train with the given
// options, translates held-out synthetic RIRs with gas-to-real and measures them
// (fidelity_measures.h). Shared by tests/gan/gan_fidelity_test and bench/gan/fidelity_seeds.sh
// (through the gan-fidelity-suite program).
#pragma once
#include <cstdint>
#include <string>

#include "fidelity_measures.h"

namespace tsrir_test {

struct FidelitySuiteOptions {
  std::string bin_dir;       // where ts-rirgan-train and gas-to-real are
  std::string work_dir;      // created; removed afterwards unless keep
  uint64_t seed = 1;         // data and training seed
  std::string train_args;    // ts-rirgan-train options, without --seed
  int num_threads = 1;
  int train_count = 64;      // RIRs per training domain
  int test_count = 24;       // held-out RIRs per domain
  bool keep = false;
};

struct FidelitySuiteResult {
  std::string error;         // a program failed (its exit status and log tail); empty if all ran
  FidelityReport report;
  double train_s = 0;
  bool passed() const { return error.empty() && report.passed(); }
};

FidelitySuiteResult run_fidelity_suite(const FidelitySuiteOptions& options);

}  // namespace tsrir_test

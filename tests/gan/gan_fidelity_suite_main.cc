// gan-fidelity-suite: runs the TS-RIRGAN translation-fidelity suite (tests/gan/fidelity_suite.h)
// for one seed and prints one line with every measure; exit 0 if it passed, 1 if it failed, 2 if
// a program failed. Used by bench/gan/fidelity_seeds.sh (a test helper, not installed).
// Usage: gan-fidelity-suite <bin-dir> <work-dir> <seed> "<ts-rirgan-train options>" [num-threads] [keep]
//        gan-fidelity-suite --measure <input-scp> <translated-scp> <real-scp>
//   (the measures alone, on any sets: translated RIRs are matched to inputs by id)
// TSRIR_GAN_FIDELITY_DETAILS=1 adds one line per RIR.
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

int main(int argc, char** argv) {
  const bool details = std::getenv("TSRIR_GAN_FIDELITY_DETAILS") != nullptr;
  if (argc == 5 && std::string(argv[1]) == "--measure") {
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
    const tsrir_test::FidelityReport r = tsrir_test::evaluate_fidelity(matched, outputs, load_scp(argv[4]));
    if (details) std::cout << r.per_rir;
    std::cout << r.summary() << std::endl;
    return r.passed() ? 0 : 1;
  }
  if (argc < 5) {
    std::cerr << "Usage: gan-fidelity-suite <bin-dir> <work-dir> <seed> \"<ts-rirgan-train options>\" "
                 "[num-threads] [keep]\n";
    return 2;
  }
  tsrir_test::FidelitySuiteOptions o;
  o.bin_dir = argv[1];
  o.work_dir = argv[2];
  o.seed = std::strtoull(argv[3], nullptr, 10);
  o.train_args = argv[4];
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

#include "fidelity_suite.h"

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "fidelity_domains.h"
#include "io/rir_set.h"
#include "util/remove_tree.h"

namespace fs = std::filesystem;

namespace tsrir_test {
namespace {

std::string tail_of(const std::string& path, size_t chars) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string s = ss.str();
  return s.size() > chars ? s.substr(s.size() - chars) : s;
}

std::string run_logged(const std::string& command, const std::string& log) {
  const int raw = std::system((command + " > " + log + " 2>&1").c_str());
  const int status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  if (status == 0) return "";
  return "exit status " + std::to_string(status) + " of: " + command + "\n" + tail_of(log, 1500);
}

std::vector<tsrir::Signal> load_scp(const std::string& scp) {
  std::vector<tsrir::Signal> rirs;
  for (const auto& ref : tsrir::read_rir_refs(scp, nullptr)) rirs.push_back(tsrir::load_rir(ref));
  return rirs;
}

std::vector<tsrir::Signal> signals_of(const std::vector<FidelityRir>& rirs) {
  std::vector<tsrir::Signal> out;
  for (const auto& r : rirs) out.push_back(r.signal);
  return out;
}

}  // namespace

namespace {
// The held-out sets of a seed: what run_fidelity_suite translates and measures against.
struct HeldOutOfSeed {
  std::vector<FidelityRir> test_syn;
  FidelityReference reference;
};
HeldOutOfSeed held_out_of_seed(const FidelitySuiteOptions& o) {
  const FidelityDomainSpec synthetic_spec, real_spec = real_domain_spec(o.effect);
  const uint64_t base = o.seed * 16;
  HeldOutOfSeed h;
  h.test_syn = make_fidelity_domain(synthetic_spec, "test_syn", o.test_count, base + 3);
  h.reference.synthetic = signals_of(make_fidelity_domain(synthetic_spec, "ref_syn", o.reference_count, base + 4));
  h.reference.real = signals_of(make_fidelity_domain(real_spec, "ref_real", o.reference_count, base + 5));
  return h;
}
}  // namespace

FidelitySuiteResult measure_fidelity_work_dir(const FidelitySuiteOptions& o) {
  FidelitySuiteResult result;
  const HeldOutOfSeed h = held_out_of_seed(o);
  std::map<std::string, tsrir::Signal> by_id;
  for (auto& s : load_scp(o.work_dir + "/sr/rir.scp")) by_id[s.id] = std::move(s);
  std::vector<tsrir::Signal> inputs = signals_of(h.test_syn), outputs;
  for (const auto& in : inputs) {
    auto it = by_id.find(in.id);
    if (it == by_id.end()) {
      result.error = "gas-to-real wrote no output for " + in.id;
      return result;
    }
    outputs.push_back(it->second);
  }
  result.report = evaluate_fidelity(o.effect, inputs, outputs, h.reference);
  return result;
}

FidelitySuiteResult run_fidelity_suite(const FidelitySuiteOptions& o) {
  FidelitySuiteResult result;
  const std::string d = o.work_dir;
  tsrir::remove_tree(d);
  fs::create_directories(d);
  const FidelityDomainSpec synthetic_spec, real_spec = real_domain_spec(o.effect);
  // Independent draws (seeds base + 1 ... base + 5): no RIR is in two sets, held-out sets are not
  // trained on.
  const uint64_t base = o.seed * 16;
  const auto train_syn = make_fidelity_domain(synthetic_spec, "syn", o.train_count, base + 1);
  const auto train_real = make_fidelity_domain(real_spec, "real", o.train_count, base + 2);
  const std::string train_syn_scp = write_fidelity_domain(train_syn, d + "/train_syn");
  const std::string train_real_scp = write_fidelity_domain(train_real, d + "/train_real");
  const std::string test_syn_scp = write_fidelity_domain(held_out_of_seed(o).test_syn, d + "/test_syn");

  const auto t0 = std::chrono::steady_clock::now();
  result.error = run_logged(o.bin_dir + "/ts-rirgan-train --real=" + train_real_scp + " --synthetic=" + train_syn_scp +
                                " --num-threads=" + std::to_string(o.num_threads) + " --progress-interval=30 " +
                                o.train_args + " --seed=" + std::to_string(o.seed) + " " + d + "/model",
                            d + "/train.log");
  const double train_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (result.error.empty()) {
    result.error = run_logged(o.bin_dir + "/gas-to-real --model=" + d + "/model --keep-length=input --num-threads=" +
                                  std::to_string(o.num_threads) + " " + test_syn_scp + " " + d + "/sr",
                              d + "/translate.log");
  }
  if (result.error.empty()) result = measure_fidelity_work_dir(o);
  result.train_s = train_s;
  if (!o.keep && result.passed()) tsrir::remove_tree(d);
  return result;
}

FidelityDomainSpec real_domain_spec(HiddenEffect effect) {
  FidelityDomainSpec s;
  s.hidden_effect = true;
  s.effect = effect;
  return s;
}

HeldOutSets held_out_sets(const FidelityDomainSpec& real_spec, uint64_t seed, int count, int reference_count) {
  const FidelityDomainSpec synthetic_spec;
  HeldOutSets h;
  h.synthetic = signals_of(make_fidelity_domain(synthetic_spec, "test_syn", count, seed));
  h.reference.synthetic = signals_of(make_fidelity_domain(synthetic_spec, "ref_syn", reference_count, seed + 1));
  h.reference.real = signals_of(make_fidelity_domain(real_spec, "ref_real", reference_count, seed + 2));
  // Same ids and seed with the effect on: the generator draws the acoustics first, so these are
  // the synthetic inputs with each one's own hidden effect added (a perfect translation).
  h.oracle = signals_of(make_fidelity_domain(real_spec, "test_syn", count, seed));
  return h;
}

}  // namespace tsrir_test

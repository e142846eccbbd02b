// Runs rir-diagnose on "measured" sets from the tests' independent generator and prints one line
// per set: which effects were detected, with their statistics (for sweeps; see power_sweep.sh).
//   diagnose_probe --effects=a,b --seed=N [--count=24] [--fix=name=value,...] [--highpass-hz=F]
//                  [--position-error-m=E] [--size-error=E] [--pre-align-ms=T] [--verbose]
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <set>
#include <sstream>
#include <string>

#include "diagnose/diagnose.h"
#include "hidden_effects.h"
#include "util/strings.h"

using namespace tsrir;

int main(int argc, char** argv) {
  std::set<std::string> effects;
  uint64_t seed = 1;
  size_t count = 24;
  bool verbose = false;
  testing::HiddenOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const std::string& key) { return a.rfind(key, 0) == 0 ? a.substr(key.size()) : std::string(); };
    if (!value("--effects=").empty()) {
      std::stringstream s(value("--effects="));
      std::string e;
      while (std::getline(s, e, ',')) if (!e.empty()) effects.insert(e);
    } else if (!value("--seed=").empty()) {
      seed = std::strtoull(value("--seed=").c_str(), nullptr, 10);
    } else if (!value("--count=").empty()) {
      count = std::strtoul(value("--count=").c_str(), nullptr, 10);
    } else if (!value("--fix=").empty()) {
      std::stringstream s(value("--fix="));
      std::string kv;
      while (std::getline(s, kv, ',')) {
        const size_t eq = kv.find('=');
        if (eq == std::string::npos) { std::cerr << "bad --fix entry " << kv << "\n"; return 2; }
        options.fixed[kv.substr(0, eq)] = std::stod(kv.substr(eq + 1));
      }
    } else if (!value("--highpass-hz=").empty()) {
      options.highpass_hz = std::stod(value("--highpass-hz="));
    } else if (!value("--position-error-m=").empty()) {
      options.position_error_m = std::stod(value("--position-error-m="));
    } else if (!value("--size-error=").empty()) {
      options.size_error = std::stod(value("--size-error="));
    } else if (!value("--pre-align-ms=").empty()) {
      options.pre_align_ms = std::stod(value("--pre-align-ms="));
    } else if (a == "--verbose") {
      verbose = true;
    } else {
      std::cerr << "unknown argument " << a << "\n";
      return 2;
    }
  }
  const auto rooms = testing::make_test_rooms(count, 77 + seed);
  const auto set = testing::make_hidden_set(rooms, effects, seed, 16000.0, 1.0, options);
  if (verbose) {
    // Energy envelope of the first "measured" RIR (dB per 50 ms window) against the baseline.
    const Signal& m = set.measured[0];
    std::cout << "envelope dB/50ms:";
    for (size_t i = 0; i + 800 <= m.size(); i += 800) {
      double e = 0;
      for (size_t k = i; k < i + 800; ++k) e += double(m.samples[k]) * m.samples[k];
      std::cout << " " << format_double(10 * std::log10(e + 1e-30), 3);
    }
    std::cout << "\n";
  }
  diagnose::DiagnoseOptions dopt;
  dopt.num_threads = 2;
  const diagnose::Diagnosis d = diagnose::diagnose_set(set.stated, set.measured, dopt);
  std::cout << "seed " << seed << " detected:";
  for (const auto& f : d.findings) if (f.detected) std::cout << " " << f.effect;
  std::cout << "\n";
  if (verbose) {
    std::cout << diagnose::diagnosis_summary(d);
    for (const auto& f : d.findings) std::cout << "  " << f.effect << ": " << f.evidence << "\n";
    for (const auto& [k, v] : set.truth) std::cout << "  truth " << k << " = " << v << "\n";
  }
  for (const auto& f : d.findings) {
    std::cout << "stat " << f.effect << " " << f.detected << " " << f.statistic << " " << f.null_statistic << " "
              << f.threshold;
    for (const auto& [k, v] : f.parameters) std::cout << " " << k << "=" << v;
    std::cout << "\n";
  }
  return 0;
}

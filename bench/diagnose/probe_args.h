// The arguments that choose a "measured" set of the tests' independent generator, shared by
// bench/diagnose's programs (diagnose_probe, modes_statistics):
//   --effects=a,b --seed=N --count=K --fix=name=value,... --highpass-hz=F --position-error-m=E
//   --size-error=E --pre-align-ms=T --dense-modes --coupled-room --flutter --non-shoebox
// (tests/diagnose/hidden_effects.h says what each hides).
#pragma once
#include <cstdint>
#include <cstdlib>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include "hidden_effects.h"

namespace tsrir::bench {

struct SetArgs {
  std::set<std::string> effects;
  uint64_t seed = 1;
  size_t count = 24;
  testdata::HiddenOptions options;
};

// Reads `arg` into *a when it is one of the set's arguments (returns false otherwise); throws
// std::invalid_argument for a malformed --fix entry.
inline bool parse_set_arg(const std::string& arg, SetArgs* a) {
  auto value = [&](const std::string& key) { return arg.rfind(key, 0) == 0 ? arg.substr(key.size()) : std::string(); };
  if (!value("--effects=").empty()) {
    std::stringstream s(value("--effects="));
    std::string e;
    while (std::getline(s, e, ',')) if (!e.empty()) a->effects.insert(e);
  } else if (!value("--seed=").empty()) {
    a->seed = std::strtoull(value("--seed=").c_str(), nullptr, 10);
  } else if (!value("--count=").empty()) {
    a->count = std::strtoul(value("--count=").c_str(), nullptr, 10);
  } else if (!value("--fix=").empty()) {
    std::stringstream s(value("--fix="));
    std::string kv;
    while (std::getline(s, kv, ',')) {
      const size_t eq = kv.find('=');
      if (eq == std::string::npos) throw std::invalid_argument("bad --fix entry " + kv);
      a->options.fixed[kv.substr(0, eq)] = std::stod(kv.substr(eq + 1));
    }
  } else if (!value("--highpass-hz=").empty()) {
    a->options.highpass_hz = std::stod(value("--highpass-hz="));
  } else if (!value("--position-error-m=").empty()) {
    a->options.position_error_m = std::stod(value("--position-error-m="));
  } else if (!value("--size-error=").empty()) {
    a->options.size_error = std::stod(value("--size-error="));
  } else if (!value("--pre-align-ms=").empty()) {
    a->options.pre_align_ms = std::stod(value("--pre-align-ms="));
  } else if (arg == "--dense-modes") {
    a->options.dense_modes = true;
  } else if (arg == "--coupled-room") {
    a->options.coupled_room = true;
  } else if (arg == "--flutter") {
    a->options.flutter = true;
  } else if (arg == "--non-shoebox") {
    a->options.non_shoebox = true;
  } else {
    return false;
  }
  return true;
}

}  // namespace tsrir::bench

// Runs rir-diagnose on "measured" sets from the tests' independent generator and prints one line
// per set: which effects were detected, with their statistics (for sweeps; see power_sweep.sh).
//   diagnose_probe --effects=a,b --seed=N [--count=24] [--fix=name=value,...] [--highpass-hz=F]
//                  [--position-error-m=E] [--size-error=E] [--pre-align-ms=T] [--verbose]
//                  [--dense-modes]   (room_modes hidden as the true room's whole modal field)
//                  [--coupled-room] [--flutter] [--non-shoebox]  (outside the catalog: hidden_effects.h)
//                  [--decisions-only] (no held-out evaluation: the sweeps count detections only)
//                  [--gas-scattering=S]  (the self-consistency check of the scattering fit:
//                                    "measured" = the baseline simulator itself with scattering S)
//                  [--strength=K]   (one effect: its hidden parameter set so that its nominal
//                                    effect size is K x the detector's threshold, see below)
//                  [--write-set=DIR] (write the set as rir-diagnose's inputs, DIR/rooms.txt,
//                                    DIR/rir.scp and float WAVs, instead of diagnosing it: for
//                                    running the program itself on a test set)
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "diagnose/diagnose.h"
#include "diagnose/rir_features.h"
#include "io/wav_writer.h"
#include "sim/room_list.h"
#include "sim/model.h"
#include "measured_rir_generator.h"
#include "hidden_effects.h"
#include "probe_args.h"
#include "util/strings.h"

using namespace tsrir;

// The hidden parameter whose statistic is `want`, interpolated linearly in a measured table of the
// statistic (increasing) against the parameter; clamped to the table's ends.
double parameter_for_statistic(const std::vector<double>& stat, const std::vector<double>& parameter, double want) {
  if (want <= stat.front()) return parameter.front();
  for (size_t i = 0; i + 1 < stat.size(); ++i) {
    if (want <= stat[i + 1]) return parameter[i] + (parameter[i + 1] - parameter[i]) * (want - stat[i]) / (stat[i + 1] - stat[i]);
  }
  return parameter.back();
}

// A measured strength table: the statistic (increasing) at each level of the hidden parameter.
struct StrengthTable {
  std::vector<double> stat, level;
};
// room_modes, the generator's few extra modes decaying 2x the room's low-band T60 (2026-11-27,
// docs/results/diagnose_power.md; 2 cores, load 9-15):
//   bench/diagnose/strength_table.sh <build> room_modes
//     "--decisions-only --effects=room_modes --fix=mode_gain_db=%G,mode_decay_factor=2"
//     "-24 -18 -12 -9 -6 -3 0 3 6"
const StrengthTable kModesTable = {{0.0295, 0.0711, 0.1479, 0.1917, 0.2334, 0.2714, 0.3029, 0.3274, 0.3457},
                                   {-24, -18, -12, -9, -6, -3, 0, 3, 6}};
// Dense modal field, decay factor 1 (2026-11-27, docs/results/diagnose_power.md):
//   bench/diagnose/strength_table.sh <build> room_modes
//     "--decisions-only --effects=room_modes --dense-modes --fix=modal_gain_db=%G,modal_decay_factor=1"
//     "-30 -24 -18 -15 -12 -9 -6 -3 0"
const StrengthTable kDenseTable = {{0.0236, 0.0260, 0.0396, 0.0591, 0.0921, 0.1405, 0.1989, 0.2593, 0.3124},
                                   {-30, -24, -18, -15, -12, -9, -6, -3, 0}};

int main(int argc, char** argv) {
  bench::SetArgs set_args;
  set_args.count = 24;
  bool verbose = false;
  bool decisions_only = false;
  double strength = -1.0;
  double gas_scattering = -1.0;
  std::string write_set;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const std::string& key) { return a.rfind(key, 0) == 0 ? a.substr(key.size()) : std::string(); };
    try {
      if (bench::parse_set_arg(a, &set_args)) continue;
    } catch (const std::exception& e) {
      std::cerr << e.what() << "\n";
      return 2;
    }
    if (!value("--gas-scattering=").empty()) {
      gas_scattering = std::stod(value("--gas-scattering="));
    } else if (!value("--strength=").empty()) {
      strength = std::stod(value("--strength="));
    } else if (!value("--write-set=").empty()) {
      write_set = value("--write-set=");
    } else if (a == "--decisions-only") {
      decisions_only = true;
    } else if (a == "--verbose") {
      verbose = true;
    } else {
      std::cerr << "unknown argument " << a << "\n";
      return 2;
    }
  }
  const std::set<std::string>& effects = set_args.effects;
  const uint64_t seed = set_args.seed;
  testdata::HiddenOptions& options = set_args.options;
  const auto rooms = testdata::make_test_rooms(set_args.count, 77 + seed);
  if (strength >= 0.0) {
    if (effects.size() != 1) { std::cerr << "--strength needs exactly one effect\n"; return 2; }
    const std::string e = *effects.begin();
    const double k = strength;
    const testdata::TrueRoom stated = testdata::true_room_from(rooms.front());
    if (e == "time_offset") {
      options.fixed["latency_ms"] = 0.6 * k;                     // threshold 0.6 ms
    } else if (e == "band_absorption") {
      // The 1 kHz band's Eyring decay rate 1.08^k times the stated one (threshold 8 %).
      const double a = rooms.front().absorption[0][4];
      for (int b = 0; b < kNumOctaveBands; ++b) options.fixed["absorption_factor_" + std::to_string(b)] = 1.0;
      options.fixed["absorption_factor_4"] = (1.0 - std::pow(1.0 - a, std::pow(1.08, k))) / a;
    } else if (e == "air_absorption") {
      // 20 C, 30 % RH, attenuation scaled so that the 4 kHz decay rate rises by 1.05^k (threshold 5 %).
      options.fixed["temperature_c"] = 20.0;
      options.fixed["humidity_percent"] = 30.0;
      const double base = testdata::test_eyring_rate_per_s(stated)[6];
      const double per_unit = testdata::test_air_attenuation_db_per_m(4000.0, 20.0, 30.0) * std::log(10.0) / 10.0 *
                              stated.speed_of_sound_m_s;
      options.fixed["air_scale"] = (std::pow(1.05, k) - 1.0) * base / per_unit;
    } else if (e == "transducer_response") {
      // One peaking filter at 1 kHz whose octave level departs k dB from the mean over the
      // direct-sound bands the detector uses (threshold 1 dB).
      auto shape = [&](double g) {
        const std::vector<testdata::TestBiquad> chain = {testdata::test_peaking(1000.0, g, 1.4, 16000.0)};
        double sum = 0.0;
        int m = 0;
        for (int b = 0; b < kNumOctaveBands; ++b) {
          if (!diagnose::direct_band_reliable(b, 16000.0)) continue;
          sum += testdata::test_cascade_octave_gain_db(chain, kOctaveCentersHz[b], 16000.0);
          ++m;
        }
        return testdata::test_cascade_octave_gain_db(chain, 1000.0, 16000.0) - sum / m;
      };
      double lo = 0.0, hi = 40.0;
      for (int i = 0; i < 60; ++i) ((shape(0.5 * (lo + hi)) < k) ? lo : hi) = 0.5 * (lo + hi);
      options.fixed["transducer_peak_db"] = 0.5 * (lo + hi);
    } else if (e == "noise_floor") {
      // White noise at the level that leaves the noisy RIR decaying by 3 / k dB over its last 30 %
      // (broadband): the binding condition of the decision is the measured late decay being flat
      // below 3 dB (the paired difference, < -6 dB, is met long before).
      options.fixed["noise_late_decay_db"] = 3.0 / std::max(k, 1e-3);
    } else if (e == "room_modes" && options.dense_modes) {
      // The dense modal field decaying as its walls damp it (decay factor 1), at the level whose
      // persistence statistic is k x 0.07 (the threshold), interpolated in this table of the
      // statistic against the level (dB re the modal Green's function), the mean over seeds 1-4:
      //   bench/diagnose/strength_table.sh build room_modes "--effects=room_modes --dense-modes --fix=modal_gain_db=%G,modal_decay_factor=1" "<levels>"
      options.fixed["modal_gain_db"] = parameter_for_statistic(kDenseTable.stat, kDenseTable.level, 0.07 * k);
      options.fixed["modal_decay_factor"] = 1.0;
    } else if (e == "room_modes") {
      // Modes decaying 2x the room's low-band T60 at the level whose persistence statistic is
      // k x 0.07 (the threshold), interpolated in this table of the statistic against the level
      // (dB re the generator's nominal modal level), the mean over seeds 1-4, 48 RIRs each:
      //   bench/diagnose/strength_table.sh build room_modes "--effects=room_modes --fix=mode_gain_db=%G,mode_decay_factor=2" "<levels>"
      options.fixed["mode_gain_db"] = parameter_for_statistic(kModesTable.stat, kModesTable.level, 0.07 * k);
      options.fixed["mode_decay_factor"] = 2.0;
    } else if (e == "source_directivity") {
      // The same directivity index in every band, k dB (threshold 1 dB).
      options.fixed["directivity_flat_db"] = 1.0 * k;
    } else if (e == "diffuse_scattering") {
      // The scattering (stated 0.1) whose echo-density statistic is k x 0.05 (the threshold),
      // interpolated in this table of the statistic against the generator's scattering, the mean
      // over seeds 1-4, 48 RIRs each (2026-11-26, the 2-20 ms / 1-7 kHz statistic):
      //   diagnose_probe --count=48 --seed=S --effects=diffuse_scattering --fix=scattering=X
      // The statistic saturates at ~0.13 (2.6x) at scattering 0.95, the largest value swept: 3x
      // is out of reach and runs at 0.95.
      options.fixed["scattering"] =
          parameter_for_statistic({-0.0020, 0.0118, 0.0264, 0.0466, 0.0763, 0.0941, 0.1056, 0.1209, 0.1299},
                                  {0.17, 0.24, 0.31, 0.38, 0.5, 0.6, 0.7, 0.8, 0.95}, 0.05 * k);
    }
    for (const auto& [name, v] : options.fixed) std::cout << "fixed " << name << " = " << v << "\n";
  }
  auto set = testdata::make_hidden_set(rooms, effects, seed, 16000.0, 1.0, options);
  if (gas_scattering >= 0.0) {
    const sim::Model gas = sim::Model::parse("gas");
    for (size_t i = 0; i < rooms.size(); ++i) {
      sim::RoomSpec real = rooms[i];
      real.scattering.fill(gas_scattering);
      set.measured[i] = gas.render(real, 16000.0, 16000, 1000 + seed);
      set.measured[i].id = rooms[i].rir_id;
    }
    set.truth = {{"scattering", gas_scattering}};
  }
  if (!write_set.empty()) {
    std::filesystem::create_directories(write_set);
    std::ofstream list(write_set + "/rooms.txt"), scp(write_set + "/rir.scp");
    AudioWriteOptions wav;
    wav.format = SampleFormat::kFloat32;
    for (size_t i = 0; i < set.stated.size(); ++i) {
      const std::string file = write_set + "/" + set.stated[i].rir_id + ".wav";
      write_wav(file, set.measured[i], wav);
      list << sim::format_room_list_line(set.stated[i]) << "\n";
      scp << set.stated[i].rir_id << " " << std::filesystem::absolute(file).string() << "\n";
    }
    if (!list || !scp) { std::cerr << "cannot write " << write_set << "\n"; return 1; }
    return 0;
  }
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
  dopt.held_out_evaluation = !decisions_only;
  const diagnose::Diagnosis d = diagnose::diagnose_set(set.stated, set.measured, dopt);
  std::cout << "seed " << seed << " detected:";
  for (const auto& f : d.findings) if (f.detected) std::cout << " " << f.effect;
  if (d.unexplained.detected) std::cout << " unexplained";
  std::cout << "\n";
  if (verbose) {
    std::cout << diagnose::diagnosis_summary(d);
    for (const auto& f : d.findings) std::cout << "  " << f.effect << ": " << f.evidence << "\n";
    std::cout << "  unexplained: " << d.unexplained.evidence << "\n";
    for (const auto& [k, v] : set.truth) std::cout << "  truth " << k << " = " << v << "\n";
  }
  std::vector<diagnose::Finding> all = d.findings;
  all.push_back(d.unexplained);
  for (const auto& f : all) {
    std::cout << "stat " << f.effect << " " << f.detected << " " << f.statistic << " " << f.null_statistic << " "
              << f.threshold;
    for (const auto& [k, v] : f.parameters) std::cout << " " << k << "=" << v;
    std::cout << "\n";
  }
  return 0;
}

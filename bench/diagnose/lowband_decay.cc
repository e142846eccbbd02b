// Whether a low-band absorption change can be told from a slowly decaying modal field by decay
// rates (issue 36: band_absorption in the low bands when room_modes is detected): for one set of
// the tests' generator (the fit half, the first count/2 RIRs), per octave band 62.5-500 Hz, the
// set median of ln(measured / baseline seed A) of the early (EDT) and the late (T30, T20 where
// T30 is not measurable; NaN where neither is) decay rate. Negative: the measurement decays
// more slowly. docs/results/diagnose_power.md quotes it.
//   lowband_decay --seed=N [--count=48] [--effects=a,b] [--dense-modes] [--fix=name=value,...]
#include <cmath>
#include <iostream>
#include <vector>

#include "diagnose/rir_features.h"
#include "diagnose/set_statistics.h"
#include "hidden_effects.h"
#include "probe_args.h"
#include "sim/model.h"
#include "sim/room_modes.h"
#include "util/parallel.h"
#include "util/strings.h"

using namespace tsrir;

int main(int argc, char** argv) {
  bench::SetArgs args;
  args.count = 48;
  for (int i = 1; i < argc; ++i) {
    if (!bench::parse_set_arg(argv[i], &args)) { std::cerr << "unknown " << argv[i] << "\n"; return 2; }
  }
  const auto rooms = testdata::make_test_rooms(args.count, 77 + args.seed);
  const testdata::HiddenSet set = testdata::make_hidden_set(rooms, args.effects, args.seed, 16000.0, 1.0, args.options);
  const sim::Model gas = sim::Model::parse("gas");
  const double schroeder = sim::schroeder_frequency_hz(gas.prepare_room(rooms.front()));
  const size_t n = args.count / 2;
  std::vector<std::vector<double>> qe(4, std::vector<double>(n)), ql = qe;
  parallel_for(n, 2, [&](size_t i) {
    const Signal a = gas.render(rooms[i], 16000.0, set.measured[i].size(), 1);
    const diagnose::RirFeatures fm = diagnose::compute_features(set.measured[i], schroeder);
    const diagnose::RirFeatures fa = diagnose::compute_features(a, schroeder);
    for (int b = 0; b < 4; ++b) {
      qe[b][i] = std::log(fm.early_decay_rate_per_s[b] / fa.early_decay_rate_per_s[b]);
      ql[b][i] = std::log(fm.decay_rate_per_s[b] / fa.decay_rate_per_s[b]);
    }
  });
  std::cout << "seed " << args.seed << ", stated Schroeder frequency " << format_double(schroeder, 4) << " Hz";
  for (int b = 0; b < 4; ++b) {
    std::cout << " | " << kOctaveCentersHz[b] << " Hz: EDT " << format_double(diagnose::median_of(qe[b]), 2) << " T30 "
              << format_double(diagnose::median_of(ql[b]), 2);
  }
  std::cout << "\n";
}

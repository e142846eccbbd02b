// Why room_modes' former statistic barely moved on a dense modal field, measured per frequency
// band (docs/results/diagnose_power.md, issue 36): on one "measured" set of the tests' independent
// generator and the baseline's render (seed A) of its fit half (the first 24 RIRs), per band of the
// stated room's predicted modes:
//   prominence   the former statistic (rir_features.cc up to commit 7a99820, re-implemented here
//                for the record): the late spectrum (from 150 ms) at each predicted mode (window
//                maximum within +-1.1 / T60 Hz) minus the mean over a grid of windows one
//                half-bandwidth apart over the modes' range, each re the local mean level over
//                +-10 Hz; measured - simulated, dB;
//   persistence  today's statistic (rir_features.h) restricted to the band; measured - simulated;
// with the predicted modes' count and mean spacing against the window width.
//   modes_statistics --seed=N [--count=48] [the set arguments of probe_args.h]
#include <algorithm>
#include <cmath>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "diagnose/rir_features.h"
#include "diagnose/set_statistics.h"
#include "dsp/fft.h"
#include "hidden_effects.h"
#include "probe_args.h"
#include "sim/model.h"
#include "sim/room_modes.h"
#include "util/parallel.h"
#include "util/strings.h"

using namespace tsrir;

namespace {

double db(double p) { return p > 0.0 ? 10.0 * std::log10(p) : -300.0; }

// The former prominence statistic over the predicted modes in [lo, hi).
double prominence_db(const Signal& s, const std::vector<double>& modes, double lo, double hi, double tol_hz) {
  const double fs = s.sample_rate_hz;
  const size_t begin = static_cast<size_t>((diagnose::onset_time_s(s) + 0.15) * fs);
  const std::vector<float> late(s.samples.begin() + std::min(begin, s.size()), s.samples.end());
  const size_t nfft = next_fast_fft_size(static_cast<size_t>(4.0 * fs));
  const std::vector<double> p = power_spectrum(late, nfft);
  const double df = fs / nfft;
  auto window_max = [&](double c) {
    double best = -300.0;
    for (size_t k = static_cast<size_t>(std::max(0.0, (c - tol_hz) / df)); k * df <= c + tol_hz && k < p.size(); ++k) {
      best = std::max(best, db(p[k]));
    }
    return best;
  };
  auto local_level = [&](double c) {
    double sum = 0.0;
    int count = 0;
    for (size_t k = static_cast<size_t>(std::max(0.0, (c - 10.0) / df)); k * df <= c + 10.0 && k < p.size(); ++k) {
      sum += db(p[k]);
      ++count;
    }
    return count ? sum / count : 0.0;
  };
  std::vector<double> in;
  for (double f : modes) {
    if (f >= lo && f < hi) in.push_back(f);
  }
  if (in.size() < 2) return NAN;
  double peaks = 0.0, grid = 0.0;
  int np = 0, ng = 0;
  for (double f : in) { peaks += window_max(f) - local_level(f); ++np; }
  for (double c = in.front(); c <= in.back(); c += tol_hz) { grid += window_max(c) - local_level(c); ++ng; }
  return peaks / np - grid / ng;
}

// Today's persistence restricted to [lo, hi): the feature pass with its range's top at hi and its
// bottom at lo.
double persistence(const Signal& s, double lo, double hi) {
  diagnose::FeatureOptions o;
  o.lf_min_hz = lo;
  o.persistence_schroeder_factor = 1.0;
  const diagnose::RirFeatures f = diagnose::compute_features(s, hi, o);
  return diagnose::mean_persistence(f, diagnose::persistence_pairs_in_span(f, o));
}

}  // namespace

int main(int argc, char** argv) {
  bench::SetArgs args;
  args.count = 48;
  for (int i = 1; i < argc; ++i) {
    try {
      if (bench::parse_set_arg(argv[i], &args)) continue;
    } catch (const std::exception& e) {
      std::cerr << e.what() << "\n";
      return 2;
    }
    std::cerr << "unknown argument " << argv[i] << "\n";
    return 2;
  }
  const uint64_t seed = args.seed;
  const size_t count = args.count;
  const auto rooms = testdata::make_test_rooms(count, 77 + seed);
  const testdata::HiddenSet set = testdata::make_hidden_set(rooms, args.effects, seed, 16000.0, 1.0, args.options);
  const sim::Model gas = sim::Model::parse("gas");
  const sim::RoomSpec prepared = gas.prepare_room(rooms.front());
  const double schroeder = sim::schroeder_frequency_hz(prepared);
  const double tol_hz = std::max(0.75, 1.1 / std::max(sim::eyring_t60_s(prepared)[1], 0.1));
  const std::vector<double> edges = {30.0, 60.0, 100.0, 140.0, schroeder, 250.0};
  const size_t n = count / 2;
  std::vector<std::vector<double>> d_prom(edges.size() - 1, std::vector<double>(n)), d_pers = d_prom;
  std::vector<double> d_prom_all(n);
  parallel_for(n, 2, [&](size_t i) {
    std::vector<double> modes;
    for (const sim::RoomMode& m : sim::shoebox_modes(rooms[i].size_m, rooms[i].speed_of_sound_m_s, 20.0, 400.0)) {
      modes.push_back(m.freq_hz);
    }
    const Signal a = gas.render(rooms[i], 16000.0, set.measured[i].size(), 1);
    for (size_t b = 0; b + 1 < edges.size(); ++b) {
      d_prom[b][i] = prominence_db(set.measured[i], modes, edges[b], edges[b + 1], tol_hz) -
                     prominence_db(a, modes, edges[b], edges[b + 1], tol_hz);
      d_pers[b][i] = persistence(set.measured[i], edges[b], edges[b + 1]) - persistence(a, edges[b], edges[b + 1]);
    }
    d_prom_all[i] = prominence_db(set.measured[i], modes, 30.0, schroeder, tol_hz) - prominence_db(a, modes, 30.0, schroeder, tol_hz);
  });
  std::cout << "seed " << seed << ", " << n << " fit RIRs; stated room's Schroeder frequency " << format_double(schroeder, 4)
            << " Hz, prominence window +-" << format_double(tol_hz, 3) << " Hz\n";
  std::cout << "| band, Hz | predicted modes | mean spacing, Hz | prominence, dB (measured - simulated) | persistence (measured - simulated) |\n";
  std::cout << "|---|---|---|---|---|\n";
  const std::vector<sim::RoomMode> modes = sim::shoebox_modes(rooms.front().size_m, rooms.front().speed_of_sound_m_s, 20.0, 400.0);
  for (size_t b = 0; b + 1 < edges.size(); ++b) {
    const double count_b = static_cast<double>(std::count_if(modes.begin(), modes.end(), [&](const sim::RoomMode& m) {
      return m.freq_hz >= edges[b] && m.freq_hz < edges[b + 1];
    }));
    const diagnose::OneSampleTest p = diagnose::t_test(d_prom[b]), q = diagnose::t_test(d_pers[b]);
    std::cout << "| " << format_double(edges[b], 4) << "-" << format_double(edges[b + 1], 4) << " | " << count_b << " | "
              << format_double(count_b > 0 ? (edges[b + 1] - edges[b]) / count_b : NAN, 3) << " | "
              << format_double(p.mean, 3) << " +- " << format_double(p.standard_error, 2) << " | " << format_double(q.mean, 3)
              << " +- " << format_double(q.standard_error, 2) << " |\n";
  }
  const diagnose::OneSampleTest all = diagnose::t_test(d_prom_all);
  std::cout << "prominence over all modes 30 Hz - Schroeder (the former statistic): " << format_double(all.mean, 3) << " +- "
            << format_double(all.standard_error, 2) << " dB (t = " << format_double(all.t, 3) << ")\n";
  return 0;
}

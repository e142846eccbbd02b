// What rir-diagnose knows of each RIR of a set once it has simulated and analysed it: one struct per
// RIR (the measured response, its stated set-up, the baseline's renders with two seeds, their
// features), so that a subset of the set (the fit half, a room) is one line.
#pragma once
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "diagnose/rir_features.h"
#include "io/signal.h"
#include "sim/room.h"

namespace tsrir::diagnose {

struct RirObservation {
  sim::RoomSpec room;        // the stated set-up
  Signal measured;           // at the analysis rate
  Signal simulated;          // the baseline model, seed A
  RirFeatures meas, sim_a, sim_b;  // of the measurement, seed A and seed B (the null calibration)
  std::vector<double> mode_freqs_hz;  // the stated room's modes up to its Schroeder frequency (report)
  double schroeder_hz = 0.0;          // of the stated room under the baseline model
  // Cross-equalised early echo densities: {measured, sim A} and {sim B, sim A}.
  std::pair<double, double> echo_density_meas_a{NAN, NAN}, echo_density_b_a{NAN, NAN};

  // The features of another rendering of this set-up, on the same analysis grid (the stated
  // Schroeder frequency) as meas, sim_a and sim_b.
  RirFeatures features_of(const Signal& rir) const;
};

struct SetObservations {
  std::vector<RirObservation> rirs;  // set order
  // The model sim_a and sim_b were rendered with, per room (room_group); empty: the baseline.
  std::map<std::string, std::string> model_by_room;

  size_t size() const { return rirs.size(); }
  bool empty() const { return rirs.empty(); }
  const RirObservation& operator[](size_t i) const { return rirs[i]; }
  RirObservation& operator[](size_t i) { return rirs[i]; }
  std::vector<RirObservation>::const_iterator begin() const { return rirs.begin(); }
  std::vector<RirObservation>::const_iterator end() const { return rirs.end(); }

  // The observations of the RIRs `idx`, in that order.
  SetObservations subset(const std::vector<size_t>& idx) const;
  // f(rir) for every RIR, in set order.
  template <typename F>
  std::vector<double> each(F f) const {
    std::vector<double> out;
    out.reserve(rirs.size());
    for (const RirObservation& r : rirs) out.push_back(f(r));
    return out;
  }
  // The analysis rate (16 kHz for an empty set).
  double sample_rate_hz() const { return rirs.empty() ? 16000.0 : rirs.front().measured.sample_rate_hz; }
};

// The room a set-up belongs to for per-room refits: its room id when the list gives one, else its
// dimensions and stated absorption (lines that differ only in positions share a room).
std::string room_group(const sim::RoomSpec& room);

}  // namespace tsrir::diagnose

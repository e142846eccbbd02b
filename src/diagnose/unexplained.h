// What the catalog does not explain: the `unexplained` finding. Every catalog effect names one
// physical cause; a real room also has causes no entry names (a coupled volume with a double-slope
// decay, flutter between parallel walls, a room that is not the stated shoebox). Their data can
// move a catalog effect's statistic (a double slope slows the measured T30, so band_absorption
// fires), and a wrong name would send a user to fix the wrong thing. So after the detected effects'
// extensions are fitted, the measurements of the fit half are compared with the extended model's
// renders in four views that no catalog extension changes as such:
//   decay shape       per octave band (500 Hz-4 kHz), how the energy decay curve bends: the
//                     departure D(t) (measured - model, dB) of the energy decay curve at 50-600 ms
//                     after the onset, and how far it sags below its chord (a wrong decay rate makes
//                     D a straight line; a double slope or a late floor make it sag); a band next
//                     to a much more slowly decaying one is left out (its filter's leakage alone
//                     makes a double slope);
//   two slopes        the same bands, whether the early decay (EDT, the first 10 dB) departs from the
//                     model's more than the late decay (T30) does: ln(EDT rate ratio) - ln(T30 rate
//                     ratio), measured re the model. A wrong absorption changes both rates alike; a
//                     coupled volume's double slope leaves the early decay fast where the model's
//                     single exponential was refitted to the slow late decay (band_absorption),
//                     also when the sag from 50 ms on stays under its threshold;
//   late periodicity  the largest autocorrelation, at lags of 10-60 ms, of the 1-6 kHz energy
//                     envelope between 80 and 600 ms after the onset, detrended (flutter echo);
//   early pattern     whether the measured reflections arrive where the model's do: the broadband
//                     energy envelope 3-40 ms after the onset (0.5 ms bins), its prominence over the
//                     local median at its own 8 strongest peaks minus that at the model's 8 strongest
//                     (dB), measured minus the model's second seed (a room of another shape moves
//                     the reflections; heavy scattering only weakens them, at both alike).
// Each view is decided like a catalog effect (paired over the fit half, p < alpha with Bonferroni
// over its cells, a minimum size, and the same statistic between two seeds of the model must not
// fire). A view that departs is the `unexplained` finding (which view, where in time and
// frequency, how far), and every detected effect whose extension should have removed it
// (Effect::residual_views) is withdrawn: its statistic may have read a cause outside the catalog.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "diagnose/diagnose_options.h"
#include "diagnose/observations.h"

namespace tsrir::diagnose {

enum class ResidualView { kDecayShape, kTwoSlopes, kLatePeriodicity, kEarlyPattern };
std::string residual_view_name(ResidualView view);  // "decay shape", ...

// Set above what the catalog's own cases leave after their extensions (docs/results/diagnose_power.md).
struct UnexplainedThresholds {
  double min_bend_db = 4.0;        // decay shape, dB
  double min_early_late_log_ratio = 0.25;  // two slopes, ln of the early rate's ratio over the late rate's (1.28x)
  double min_periodicity = 0.15;   // late periodicity, autocorrelation
  double min_pattern_loss_db = 1.5;  // early pattern, dB
};
inline constexpr UnexplainedThresholds kUnexplainedThresholds{};

struct UnexplainedCheck {
  std::vector<ResidualView> departing;
  std::string evidence;                // every view's result, departing or not
  double statistic = 0.0;              // the largest departure re its threshold
  std::vector<std::pair<std::string, double>> parameters;  // where and how far
};

// The four views on `fit_obs` against renders of `model_by_room` (room_group -> model spec) with
// seeds A and B.
UnexplainedCheck check_unexplained(const SetObservations& fit_obs, const std::map<std::string, std::string>& model_by_room,
                                   const DiagnoseOptions& options);

}  // namespace tsrir::diagnose

// The fitted distribution of real-room relative gains, and its small versioned text file.
//
// File format (one keyword line each, '#' starts a comment, blank lines ignored):
//   tsrir-eq-model 1
//   sample_rate_hz 16000
//   gain_method octave
//   points_hz 62.5 125 250 500 2000 4000 8000
//   reference_hz 1000
//   fitted_rirs 102
//   covariance diag|full
//   components K
//   then K times:  component <k> / weight <w> / mean <7 values> /
//                  variance <7 values> (diag) or 7 lines covariance_row <7 values> (full)
//   end
// The trailing `end` line makes a truncated file an error instead of a smaller model.
#pragma once
#include <iosfwd>
#include <string>
#include <vector>

#include "eq/gaussian_mixture.h"
#include "eq/relative_gain.h"

namespace tsrir {

constexpr int kEqModelVersion = 1;

struct EqModel {
  double sample_rate_hz = 16000.0;
  GainMethod gain_method = GainMethod::kOctave;
  long fitted_rirs = 0;
  GaussianMixture mixture;   // over the 7 relative gains, in kEqPointsHz order

  // Moments of the mixture per point (for reports).
  RelativeGainsDb mean_db() const;
  RelativeGainsDb std_db() const;
};

// Fits the distribution of `gains` (one vector per real RIR). Errors as fit_gaussian_mixture
// (in particular: fewer RIRs than free parameters).
EqModel fit_eq_model(const std::vector<RelativeGainsDb>& gains, double sample_rate_hz, GainMethod method,
                     const GmmFitOptions& options);

// One target gain vector.
RelativeGainsDb draw_target_gains(const EqModel& model, Rng& rng);

void write_eq_model(const EqModel& model, std::ostream& out);
void save_eq_model(const EqModel& model, const std::string& path);  // atomic (temp + rename)
// Errors name source:line.
EqModel parse_eq_model(const std::string& text, const std::string& source);
EqModel load_eq_model(const std::string& path);

}  // namespace tsrir

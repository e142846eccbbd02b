// Gaussian mixture over d-dimensional vectors (here: 7-D relative-gain vectors), fitted by EM.
// One component with diagonal covariance is the paper's reading (an independent Gaussian per
// sample point); more components and full covariance keep the cross-band structure of real rooms.
#pragma once
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "util/options.h"
#include "util/rng.h"

namespace tsrir {

enum class CovarianceType { kDiagonal, kFull };
const Choices<CovarianceType>& covariance_type_choices();  // "diag" | "full"
CovarianceType parse_covariance_type(const std::string& name);
std::string covariance_type_name(CovarianceType type);

struct GaussianComponent {
  double weight = 1.0;
  Eigen::VectorXd mean;
  Eigen::MatrixXd covariance;  // diagonal models keep off-diagonal entries at exactly 0
};

struct GaussianMixture {
  CovarianceType covariance_type = CovarianceType::kDiagonal;
  std::vector<GaussianComponent> components;

  int dimension() const { return components.empty() ? 0 : static_cast<int>(components[0].mean.size()); }
  // Free parameters: (K-1) weights + K*d means + K*d (diag) or K*d(d+1)/2 (full) covariances.
  static long num_parameters(int num_components, int dimension, CovarianceType type);
  long num_parameters() const {
    return num_parameters(static_cast<int>(components.size()), dimension(), covariance_type);
  }
  // Mean log-likelihood per vector.
  double mean_log_likelihood(const Eigen::MatrixXd& data) const;
  // One draw (the component by weight, then mean + L z with L the Cholesky factor).
  Eigen::VectorXd sample(Rng& rng) const;
  // Throws Error (with `what`) unless weights sum to 1, covariances are symmetric positive definite
  // and all dimensions agree.
  void validate(const std::string& what) const;
};

struct GmmFitOptions {
  int num_components = 1;
  CovarianceType covariance_type = CovarianceType::kDiagonal;
  uint64_t seed = 0;
  int restarts = 4;            // EM runs from different k-means++ seeds; the best likelihood wins
  int max_iterations = 500;
  double tolerance = 1e-7;     // stop when the mean log-likelihood improves by less
  // Added to every variance. A component sitting on a few nearly identical vectors would
  // otherwise collapse to a singular covariance with unbounded likelihood; 0.01 dB^2 (0.1 dB)
  // is far below the spread of measured relative gains.
  double variance_floor = 1e-2;
};

// Fits the mixture to the rows of `data` (n x d). With one component the estimate is closed form
// (sample mean, unbiased sample covariance). Throws Error if there are fewer vectors than free
// parameters, or if every restart collapses.
GaussianMixture fit_gaussian_mixture(const Eigen::MatrixXd& data, const GmmFitOptions& options);

}  // namespace tsrir

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "eq/eq_model.h"
#include "eq_test_util.h"
#include "util/error.h"
#include "util/rng.h"

using namespace tsrir;

namespace {

// Draws n vectors from a known mixture with the test's own Cholesky sampling.
Eigen::MatrixXd draw(const std::vector<double>& weights, const std::vector<Eigen::VectorXd>& means,
                     const std::vector<Eigen::MatrixXd>& covs, int n, uint64_t seed, std::vector<int>* labels) {
  Rng rng(seed);
  const int d = static_cast<int>(means[0].size());
  Eigen::MatrixXd x(n, d);
  for (int i = 0; i < n; ++i) {
    double u = rng.uniform(), acc = 0;
    int k = 0;
    for (; k + 1 < static_cast<int>(weights.size()); ++k) {
      acc += weights[k];
      if (u < acc) break;
    }
    Eigen::VectorXd z(d);
    for (int j = 0; j < d; ++j) z(j) = rng.normal();
    const Eigen::MatrixXd l = covs[k].llt().matrixL();
    x.row(i) = (means[k] + l * z).transpose();
    if (labels) labels->push_back(k);
  }
  return x;
}

Eigen::MatrixXd random_spd(int d, double scale, uint64_t seed) {
  Rng rng(seed);
  Eigen::MatrixXd a(d, d);
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j) a(i, j) = rng.normal();
  return scale * (a * a.transpose() / d + 0.3 * Eigen::MatrixXd::Identity(d, d));
}

}  // namespace

TEST(GaussianMixture, OneDiagonalComponentIsPerPointMeanAndStd) {
  Eigen::VectorXd mu(7);
  mu << 6, 3, 1, 0.5, -1, -4, -9;
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(7, 7);
  cov.diagonal() << 4, 2.25, 1, 1, 0.64, 2.25, 6.25;
  const int n = 4000;
  const Eigen::MatrixXd x = draw({1.0}, {mu}, {cov}, n, 11, nullptr);
  GmmFitOptions o;
  const GaussianMixture g = fit_gaussian_mixture(x, o);
  ASSERT_EQ(g.components.size(), 1u);
  for (int j = 0; j < 7; ++j) {
    const double sigma = std::sqrt(cov(j, j));
    EXPECT_NEAR(g.components[0].mean(j), mu(j), 4 * sigma / std::sqrt(n));  // 4 standard errors
    // Sample std has relative standard error 1/sqrt(2n) = 1.1%; allow 5% (+ the 0.01 dB^2 floor).
    EXPECT_NEAR(std::sqrt(g.components[0].covariance(j, j)), sigma, 0.05 * sigma);
    for (int i = 0; i < 7; ++i) {
      if (i != j) {
        EXPECT_EQ(g.components[0].covariance(i, j), 0.0);
      }
    }
  }
  EXPECT_EQ(g.num_parameters(), 14);
}

TEST(GaussianMixture, EmRecoversTwoCorrelatedComponents) {
  Eigen::VectorXd m1(7), m2(7);
  m1 << 8, 5, 2, 1, -1, -3, -6;
  m2 << 0, -1, -2, 0, 1, -6, -14;
  const Eigen::MatrixXd c1 = random_spd(7, 1.5, 21), c2 = random_spd(7, 2.0, 22);
  const int n = 3000;
  const Eigen::MatrixXd x = draw({0.3, 0.7}, {m1, m2}, {c1, c2}, n, 23, nullptr);
  GmmFitOptions o;
  o.num_components = 2;
  o.covariance_type = CovarianceType::kFull;
  o.seed = 1;
  const GaussianMixture g = fit_gaussian_mixture(x, o);
  ASSERT_EQ(g.components.size(), 2u);
  // Match fitted components to true ones by the first coordinate (8 vs 0: well separated).
  const int a = g.components[0].mean(0) > g.components[1].mean(0) ? 0 : 1;
  const GaussianComponent& f1 = g.components[a];
  const GaussianComponent& f2 = g.components[1 - a];
  // Weight: binomial standard error sqrt(0.21 / 3000) = 0.008; allow 0.03.
  EXPECT_NEAR(f1.weight, 0.3, 0.03);
  EXPECT_NEAR(f2.weight, 0.7, 0.03);
  for (int j = 0; j < 7; ++j) {
    // Means: standard error sigma / sqrt(n_k) <= sqrt(5) / sqrt(900) = 0.075 dB; allow 0.3.
    EXPECT_NEAR(f1.mean(j), m1(j), 0.3) << j;
    EXPECT_NEAR(f2.mean(j), m2(j), 0.3) << j;
    for (int i = 0; i < 7; ++i) {
      // Covariance entries: standard error ~ sqrt((s_ii s_jj + s_ij^2) / n_k) <= ~0.25; allow 4x.
      const double tol1 = 4 * std::sqrt((c1(i, i) * c1(j, j) + c1(i, j) * c1(i, j)) / 900);
      const double tol2 = 4 * std::sqrt((c2(i, i) * c2(j, j) + c2(i, j) * c2(i, j)) / 2100);
      EXPECT_NEAR(f1.covariance(i, j), c1(i, j), tol1) << i << "," << j;
      EXPECT_NEAR(f2.covariance(i, j), c2(i, j), tol2) << i << "," << j;
    }
  }
  EXPECT_EQ(g.num_parameters(), 2 - 1 + 2 * 7 + 2 * 28);
}

TEST(GaussianMixture, SamplesHaveTheModelsMoments) {
  GaussianMixture g;
  g.covariance_type = CovarianceType::kFull;
  Eigen::VectorXd m(7);
  m << 3, 2, 1, 0, -1, -2, -3;
  const Eigen::MatrixXd c = random_spd(7, 1.0, 31);
  g.components.push_back({1.0, m, c});
  Rng rng(32);
  const int n = 20000;
  Eigen::MatrixXd x(n, 7);
  for (int i = 0; i < n; ++i) x.row(i) = g.sample(rng).transpose();
  const Eigen::VectorXd mean = x.colwise().mean().transpose();
  const Eigen::MatrixXd centered = x.rowwise() - mean.transpose();
  const Eigen::MatrixXd cov = centered.transpose() * centered / (n - 1);
  for (int i = 0; i < 7; ++i) {
    EXPECT_NEAR(mean(i), m(i), 4 * std::sqrt(c(i, i) / n));
    for (int j = 0; j < 7; ++j) EXPECT_NEAR(cov(i, j), c(i, j), 4 * std::sqrt((c(i, i) * c(j, j) + c(i, j) * c(i, j)) / n));
  }
}

TEST(GaussianMixture, RefusesFewerVectorsThanParameters) {
  Eigen::MatrixXd x = draw({1.0}, {Eigen::VectorXd::Zero(7)}, {Eigen::MatrixXd::Identity(7, 7)}, 13, 41, nullptr);
  GmmFitOptions o;  // 1 diagonal component: 14 parameters
  try {
    fit_gaussian_mixture(x, o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("13 < 14"), std::string::npos) << e.what();
  }
  x.conservativeResize(14, 7);
  x.row(13) = x.row(0);
  EXPECT_NO_THROW(fit_gaussian_mixture(x, o));
  o.num_components = 2;
  o.covariance_type = CovarianceType::kFull;
  EXPECT_THROW(fit_gaussian_mixture(x, o), Error);  // 71 parameters
}

TEST(EqModelFile, RoundTripIsExact) {
  tsrir_test::ScratchDir dir;
  EqModel m;
  m.sample_rate_hz = 16000;
  m.gain_method = GainMethod::kSmooth;
  m.fitted_rirs = 102;
  m.mixture.covariance_type = CovarianceType::kFull;
  Eigen::VectorXd mu(7);
  mu << 6.25, 3.1, 1.0 / 3.0, 0.5, -1, -4, -9.75;
  m.mixture.components.push_back({0.4, mu, random_spd(7, 1.0, 51)});
  m.mixture.components.push_back({0.6, -mu, random_spd(7, 2.0, 52)});
  save_eq_model(m, dir.path("eq.model"));
  const EqModel r = load_eq_model(dir.path("eq.model"));
  EXPECT_EQ(r.sample_rate_hz, 16000);
  EXPECT_EQ(r.gain_method, GainMethod::kSmooth);
  EXPECT_EQ(r.fitted_rirs, 102);
  ASSERT_EQ(r.mixture.components.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(r.mixture.components[k].weight, m.mixture.components[k].weight);
    EXPECT_EQ(r.mixture.components[k].mean, m.mixture.components[k].mean);  // 17 digits: exact
    EXPECT_EQ(r.mixture.components[k].covariance, m.mixture.components[k].covariance);
  }
  const RelativeGainsDb mean = r.mean_db();
  EXPECT_NEAR(mean[0], 0.4 * 6.25 - 0.6 * 6.25, 1e-12);
}

TEST(EqModelFile, ParseErrorsNameFileAndLine) {
  const std::string good =
      "tsrir-eq-model 1\n"
      "sample_rate_hz 16000\n"
      "gain_method octave\n"
      "points_hz 62.5 125 250 500 2000 4000 8000\n"
      "reference_hz 1000\n"
      "fitted_rirs 30\n"
      "covariance diag\n"
      "components 1\n"
      "component 1\n"
      "weight 1\n"
      "mean 6 3 1 0 -1 -4 -9\n"
      "variance 4 2 1 1 1 2 6\n"
      "end\n";
  EXPECT_NO_THROW(parse_eq_model(good, "m.txt"));
  EXPECT_NO_THROW(parse_eq_model("# comment\n\n" + good, "m.txt"));
  struct Case {
    std::string from, to;
    std::string expect;  // prefix "m.txt:<line>:"
  };
  const std::vector<Case> cases = {
      {"tsrir-eq-model 1", "tsrir-eq-model 2", "m.txt:1:"},
      {"tsrir-eq-model 1", "hello", "m.txt:1:"},
      {"sample_rate_hz 16000", "sample_rate_hz 8000", "m.txt:2:"},
      {"sample_rate_hz 16000", "sample_rate_hz fast", "m.txt:2:"},
      {"gain_method octave", "gain_method third", "m.txt:3:"},
      {"points_hz 62.5 125 250 500 2000 4000 8000", "points_hz 63 125 250 500 2000 4000 8000", "m.txt:4:"},
      {"covariance diag", "covariance sparse", "m.txt:7:"},
      {"components 1", "components 2", "m.txt:13:"},  // component 2 expected where 'end' is
      {"mean 6 3 1 0 -1 -4 -9", "mean 6 3 1 0 -1 -4", "m.txt:11:"},
      {"mean 6 3 1 0 -1 -4 -9", "mean 6 3 1 0 -1 -4 nan", "m.txt:11:"},
      {"variance 4 2 1 1 1 2 6", "variance 4 2 1 1 1 2 -6", "m.txt:12:"},
      {"weight 1", "weight 0.5", "m.txt:"},  // weights must sum to 1
      {"end\n", "", "m.txt:13:"},            // truncated: reported one past the last line
      {"end\n", "end\nextra 1\n", "m.txt:14:"},
  };
  for (const Case& c : cases) {
    std::string text = good;
    const size_t at = text.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    text.replace(at, c.from.size(), c.to);
    try {
      parse_eq_model(text, "m.txt");
      ADD_FAILURE() << "no error for: " << c.to;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(c.expect, 0), 0u) << c.to << " -> " << e.what();
    }
  }
  // Full covariance that is not positive definite.
  std::string full = good;
  const std::string diag_line = "covariance diag", var_line = "variance 4 2 1 1 1 2 6\n";
  full.replace(full.find(diag_line), diag_line.size(), "covariance full");
  std::string rows;
  for (int i = 0; i < 7; ++i) rows += "covariance_row 1 1 1 1 1 1 1\n";
  full.replace(full.find(var_line), var_line.size(), rows);
  try {
    parse_eq_model(full, "m.txt");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("positive definite"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("m.txt:", 0), 0u) << e.what();
  }
  EXPECT_THROW(load_eq_model("/nonexistent/eq.model"), Error);
}

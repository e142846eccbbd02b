#include "eq/gaussian_mixture.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "util/error.h"

namespace tsrir {

const Choices<CovarianceType>& covariance_type_choices() {
  static const Choices<CovarianceType> choices = {{"diag", CovarianceType::kDiagonal}, {"full", CovarianceType::kFull}};
  return choices;
}

CovarianceType parse_covariance_type(const std::string& name) {
  return parse_choice(covariance_type_choices(), name, "covariance type");
}

std::string covariance_type_name(CovarianceType type) { return choice_name(covariance_type_choices(), type); }

long GaussianMixture::num_parameters(int k, int d, CovarianceType type) {
  const long cov = type == CovarianceType::kFull ? static_cast<long>(d) * (d + 1) / 2 : d;
  return (k - 1) + static_cast<long>(k) * d + static_cast<long>(k) * cov;
}

namespace {

constexpr double kLog2Pi = 1.8378770664093453;

// Cholesky factor and log-determinant of one component, reused for every vector.
struct ComponentDensity {
  Eigen::LLT<Eigen::MatrixXd> llt;
  double log_norm = 0.0;  // log(weight) - 0.5 log det - d/2 log 2 pi
  bool ok = false;
};

ComponentDensity prepare(const GaussianComponent& c) {
  ComponentDensity p;
  p.llt.compute(c.covariance);
  if (p.llt.info() != Eigen::Success || c.weight <= 0) return p;
  const Eigen::MatrixXd l = p.llt.matrixL();
  double log_det = 0.0;
  for (int i = 0; i < l.rows(); ++i) {
    if (!(l(i, i) > 0)) return p;
    log_det += 2.0 * std::log(l(i, i));
  }
  p.log_norm = std::log(c.weight) - 0.5 * log_det - 0.5 * l.rows() * kLog2Pi;
  p.ok = std::isfinite(p.log_norm);
  return p;
}

// log(weight_k * N(x_i; k)) for all i, k.
Eigen::MatrixXd log_joint(const GaussianMixture& gmm, const Eigen::MatrixXd& data, bool* ok) {
  const int k_count = static_cast<int>(gmm.components.size());
  Eigen::MatrixXd out(data.rows(), k_count);
  *ok = true;
  for (int k = 0; k < k_count; ++k) {
    const GaussianComponent& c = gmm.components[k];
    ComponentDensity p = prepare(c);
    if (!p.ok) {
      *ok = false;
      return out;
    }
    Eigen::MatrixXd centered = (data.rowwise() - c.mean.transpose()).transpose();  // d x n
    p.llt.matrixL().solveInPlace(centered);
    out.col(k) = (p.log_norm - 0.5 * centered.colwise().squaredNorm().array()).matrix().transpose();
  }
  return out;
}

Eigen::VectorXd log_sum_exp_rows(const Eigen::MatrixXd& m) {
  Eigen::VectorXd out(m.rows());
  for (int i = 0; i < m.rows(); ++i) {
    const double mx = m.row(i).maxCoeff();
    out(i) = mx + std::log((m.row(i).array() - mx).exp().sum());
  }
  return out;
}

Eigen::MatrixXd regularized(Eigen::MatrixXd cov, CovarianceType type, double floor) {
  if (type == CovarianceType::kDiagonal) {
    Eigen::VectorXd d = cov.diagonal();
    cov.setZero();
    cov.diagonal() = d;
  }
  cov = 0.5 * (cov + cov.transpose());
  cov.diagonal().array() += floor;
  return cov;
}

Eigen::MatrixXd sample_covariance(const Eigen::MatrixXd& data, const Eigen::VectorXd& mean, double denominator) {
  const Eigen::MatrixXd centered = data.rowwise() - mean.transpose();
  return centered.transpose() * centered / denominator;
}

// k-means++ seeding: spread initial means over the data.
std::vector<Eigen::VectorXd> kmeanspp_means(const Eigen::MatrixXd& data, int k, Rng& rng) {
  const long n = data.rows();
  std::vector<Eigen::VectorXd> means;
  means.push_back(data.row(static_cast<long>(rng.below(n))).transpose());
  Eigen::VectorXd dist2(n);
  for (long i = 0; i < n; ++i) dist2(i) = (data.row(i).transpose() - means[0]).squaredNorm();
  while (static_cast<int>(means.size()) < k) {
    const double total = dist2.sum();
    long pick = static_cast<long>(rng.below(n));
    if (total > 0) {
      double u = rng.uniform() * total;
      for (long i = 0; i < n; ++i) {
        u -= dist2(i);
        if (u <= 0) {
          pick = i;
          break;
        }
      }
    }
    means.push_back(data.row(pick).transpose());
    for (long i = 0; i < n; ++i) dist2(i) = std::min(dist2(i), (data.row(i).transpose() - means.back()).squaredNorm());
  }
  return means;
}

// One EM run; returns false if a component collapses or the likelihood breaks down.
bool run_em(const Eigen::MatrixXd& data, const GmmFitOptions& o, Rng& rng, GaussianMixture* out, double* mean_ll) {
  const long n = data.rows();
  const int k_count = o.num_components;
  const Eigen::VectorXd global_mean = data.colwise().mean().transpose();
  const Eigen::MatrixXd global_cov =
      regularized(sample_covariance(data, global_mean, static_cast<double>(n)), o.covariance_type, o.variance_floor);
  GaussianMixture gmm;
  gmm.covariance_type = o.covariance_type;
  for (const Eigen::VectorXd& m : kmeanspp_means(data, k_count, rng)) {
    gmm.components.push_back({1.0 / k_count, m, global_cov});
  }
  double previous = -std::numeric_limits<double>::infinity();
  for (int iter = 0; iter < o.max_iterations; ++iter) {
    bool ok = false;
    const Eigen::MatrixXd lj = log_joint(gmm, data, &ok);
    if (!ok) return false;
    const Eigen::VectorXd lse = log_sum_exp_rows(lj);
    const double ll = lse.mean();
    if (!std::isfinite(ll)) return false;
    const Eigen::MatrixXd resp = (lj.colwise() - lse).array().exp().matrix();  // n x K
    // M-step.
    for (int k = 0; k < k_count; ++k) {
      const double nk = resp.col(k).sum();
      if (nk < 1e-6 * n || nk < 1e-3) return false;  // collapsed: no vectors left to this component
      GaussianComponent& c = gmm.components[k];
      c.weight = nk / n;
      c.mean = (data.transpose() * resp.col(k)) / nk;
      const Eigen::MatrixXd centered = data.rowwise() - c.mean.transpose();
      const Eigen::MatrixXd cov = centered.transpose() * resp.col(k).asDiagonal() * centered / nk;
      c.covariance = regularized(cov, o.covariance_type, o.variance_floor);
    }
    *mean_ll = ll;
    if (ll - previous < o.tolerance && iter > 0) break;
    previous = ll;
  }
  bool ok = false;
  const Eigen::MatrixXd lj = log_joint(gmm, data, &ok);
  if (!ok) return false;
  *mean_ll = log_sum_exp_rows(lj).mean();
  *out = std::move(gmm);
  return std::isfinite(*mean_ll);
}

}  // namespace

double GaussianMixture::mean_log_likelihood(const Eigen::MatrixXd& data) const {
  bool ok = false;
  const Eigen::MatrixXd lj = log_joint(*this, data, &ok);
  if (!ok) throw Error("Gaussian mixture: a covariance is not positive definite");
  return log_sum_exp_rows(lj).mean();
}

Eigen::VectorXd GaussianMixture::sample(Rng& rng) const {
  if (components.empty()) throw Error("Gaussian mixture has no components");
  const double u = rng.uniform();
  double acc = 0.0;
  size_t pick = components.size() - 1;
  for (size_t k = 0; k < components.size(); ++k) {
    acc += components[k].weight;
    if (u < acc) {
      pick = k;
      break;
    }
  }
  const GaussianComponent& c = components[pick];
  Eigen::VectorXd z(c.mean.size());
  for (int i = 0; i < z.size(); ++i) z(i) = rng.normal();
  Eigen::LLT<Eigen::MatrixXd> llt(c.covariance);
  if (llt.info() != Eigen::Success) throw Error("Gaussian mixture: a covariance is not positive definite");
  return c.mean + llt.matrixL() * z;
}

void GaussianMixture::validate(const std::string& what) const {
  if (components.empty()) throw Error(what + ": no mixture components");
  const long d = components[0].mean.size();
  if (d == 0) throw Error(what + ": zero-dimensional mixture");
  double total = 0.0;
  for (size_t k = 0; k < components.size(); ++k) {
    const GaussianComponent& c = components[k];
    const std::string ck = what + ": component " + std::to_string(k + 1);
    if (!(c.weight > 0 && c.weight <= 1)) throw Error(ck + ": weight must be in (0, 1]");
    total += c.weight;
    if (c.mean.size() != d || c.covariance.rows() != d || c.covariance.cols() != d) {
      throw Error(ck + ": dimensions disagree");
    }
    if (!c.mean.allFinite() || !c.covariance.allFinite()) throw Error(ck + ": non-finite value");
    const double scale = std::max(1e-300, c.covariance.cwiseAbs().maxCoeff());
    if ((c.covariance - c.covariance.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) {
      throw Error(ck + ": covariance is not symmetric");
    }
    if (covariance_type == CovarianceType::kDiagonal) {
      Eigen::MatrixXd off = c.covariance;
      off.diagonal().setZero();
      if (off.cwiseAbs().maxCoeff() != 0.0) throw Error(ck + ": diagonal model with off-diagonal covariance");
    }
    Eigen::LLT<Eigen::MatrixXd> llt(c.covariance);
    if (llt.info() != Eigen::Success) throw Error(ck + ": covariance is not positive definite");
  }
  if (std::abs(total - 1.0) > 1e-6) throw Error(what + ": component weights sum to " + std::to_string(total) + ", not 1");
}

GaussianMixture fit_gaussian_mixture(const Eigen::MatrixXd& data, const GmmFitOptions& o) {
  const long n = data.rows();
  const int d = static_cast<int>(data.cols());
  if (o.num_components < 1) throw Error("Gaussian mixture: need at least one component");
  if (d < 1) throw Error("Gaussian mixture: zero-dimensional data");
  if (!data.allFinite()) throw Error("Gaussian mixture: non-finite data");
  const long params = GaussianMixture::num_parameters(o.num_components, d, o.covariance_type);
  if (n < params) {
    throw Error("too few vectors to fit the model: " + std::to_string(n) + " < " + std::to_string(params) +
                " free parameters (" + std::to_string(o.num_components) + " component(s), " +
                covariance_type_name(o.covariance_type) + " covariance); use more RIRs, fewer components or diag");
  }
  if (o.num_components == 1) {
    GaussianMixture gmm;
    gmm.covariance_type = o.covariance_type;
    const Eigen::VectorXd mean = data.colwise().mean().transpose();
    const double denom = n > 1 ? static_cast<double>(n - 1) : 1.0;  // unbiased
    gmm.components.push_back({1.0, mean, regularized(sample_covariance(data, mean, denom), o.covariance_type, o.variance_floor)});
    return gmm;
  }
  GaussianMixture best;
  double best_ll = -std::numeric_limits<double>::infinity();
  Rng rng(o.seed);
  for (int r = 0; r < std::max(1, o.restarts); ++r) {
    GaussianMixture g;
    double ll = 0.0;
    if (run_em(data, o, rng, &g, &ll) && ll > best_ll) {
      best_ll = ll;
      best = std::move(g);
    }
  }
  if (best.components.empty()) {
    throw Error("Gaussian mixture: every EM run collapsed a component; use fewer components or more RIRs");
  }
  return best;
}

}  // namespace tsrir

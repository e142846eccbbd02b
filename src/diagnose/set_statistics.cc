#include "diagnose/set_statistics.h"

#include <algorithm>
#include <cmath>

namespace tsrir::diagnose {
namespace {

// Continued fraction of the regularised incomplete beta function (Numerical Recipes' betacf
// formulation, written out here from the Lentz algorithm).
double beta_continued_fraction(double a, double b, double x) {
  const double tiny = 1e-300;
  double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
  if (std::abs(d) < tiny) d = tiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m <= 300; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((a - 1.0 + m2) * (a + m2));
    d = 1.0 + aa * d; if (std::abs(d) < tiny) d = tiny;
    c = 1.0 + aa / c; if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d; h *= d * c;
    aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + 1.0 + m2));
    d = 1.0 + aa * d; if (std::abs(d) < tiny) d = tiny;
    c = 1.0 + aa / c; if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-14) break;
  }
  return h;
}

double regularized_incomplete_beta(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double log_front = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  if (x < (a + 1.0) / (a + b + 2.0)) return std::exp(log_front) * beta_continued_fraction(a, b, x) / a;
  return 1.0 - std::exp(log_front) * beta_continued_fraction(b, a, 1.0 - x) / b;
}

// Regularised upper incomplete gamma Q(a, x) by series / continued fraction.
double gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double log_front = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {
    double sum = 1.0 / a, term = sum;
    for (int n = 1; n < 1000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * 1e-15) break;
    }
    return 1.0 - sum * std::exp(log_front);
  }
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b; if (std::abs(d) < tiny) d = tiny;
    c = b + an / c; if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-15) break;
  }
  return std::exp(log_front) * h;
}

}  // namespace

std::vector<double> finite_values(const std::vector<double>& x) {
  std::vector<double> out;
  for (double v : x) {
    if (std::isfinite(v)) out.push_back(v);
  }
  return out;
}

double mean_of(const std::vector<double>& x) {
  const std::vector<double> v = finite_values(x);
  if (v.empty()) return NAN;
  double s = 0.0;
  for (double a : v) s += a;
  return s / v.size();
}

double stddev_of(const std::vector<double>& x) {
  const std::vector<double> v = finite_values(x);
  if (v.size() < 2) return NAN;
  const double m = mean_of(v);
  double s = 0.0;
  for (double a : v) s += (a - m) * (a - m);
  return std::sqrt(s / (v.size() - 1));
}

double median_of(std::vector<double> x) {
  x = finite_values(x);
  if (x.empty()) return NAN;
  const size_t mid = x.size() / 2;
  std::nth_element(x.begin(), x.begin() + mid, x.end());
  if (x.size() % 2 == 1) return x[mid];
  const double upper = x[mid];
  return 0.5 * (upper + *std::max_element(x.begin(), x.begin() + mid));
}

double median_abs_deviation(const std::vector<double>& x) {
  const double m = median_of(x);
  std::vector<double> d;
  for (double v : finite_values(x)) d.push_back(std::abs(v - m));
  return median_of(d);
}

double student_t_two_sided_p(double t, double dof) {
  if (!std::isfinite(t)) return std::isnan(t) ? 1.0 : 0.0;
  return regularized_incomplete_beta(0.5 * dof, 0.5, dof / (dof + t * t));
}

double chi_square_upper_p(double x, double dof) { return gamma_q(0.5 * dof, 0.5 * x); }

double binomial_upper_p(size_t k, size_t n, double p) {
  if (k == 0) return 1.0;
  if (k > n) return 0.0;
  // P(K >= k) = I_p(k, n - k + 1).
  return regularized_incomplete_beta(static_cast<double>(k), static_cast<double>(n - k + 1), p);
}

OneSampleTest t_test(const std::vector<double>& x) {
  const std::vector<double> v = finite_values(x);
  OneSampleTest r;
  r.n = v.size();
  if (r.n == 0) return r;
  r.mean = mean_of(v);
  if (r.n < 3) return r;
  const double sd = stddev_of(v);
  r.standard_error = sd / std::sqrt(static_cast<double>(r.n));
  if (r.standard_error <= 0.0) {
    r.t = r.mean == 0.0 ? 0.0 : (r.mean > 0 ? INFINITY : -INFINITY);
    r.p_two_sided = r.mean == 0.0 ? 1.0 : 0.0;
    return r;
  }
  r.t = r.mean / r.standard_error;
  r.p_two_sided = student_t_two_sided_p(r.t, static_cast<double>(r.n - 1));
  return r;
}

double correlation(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> a, b;
  for (size_t i = 0; i < x.size() && i < y.size(); ++i) {
    if (std::isfinite(x[i]) && std::isfinite(y[i])) { a.push_back(x[i]); b.push_back(y[i]); }
  }
  if (a.size() < 2) return 0.0;
  const double ma = mean_of(a), mb = mean_of(b);
  double sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  if (saa <= 0 || sbb <= 0) return 0.0;
  return sab / std::sqrt(saa * sbb);
}

}  // namespace tsrir::diagnose

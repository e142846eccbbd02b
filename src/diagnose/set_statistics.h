// Statistics over a set of RIRs: the detections of rir-diagnose are decisions over the whole set
// (paired differences measured - simulated per RIR), never over one RIR.
#pragma once
#include <cstddef>
#include <vector>

namespace tsrir::diagnose {

// Finite values only (NaN/Inf are dropped by every function here).
std::vector<double> finite_values(const std::vector<double>& x);
double mean_of(const std::vector<double>& x);
double stddev_of(const std::vector<double>& x);     // sample standard deviation (n - 1)
double median_of(std::vector<double> x);
double median_abs_deviation(const std::vector<double>& x);

struct OneSampleTest {
  size_t n = 0;
  double mean = 0.0;
  double standard_error = 0.0;
  double t = 0.0;
  double p_two_sided = 1.0;
};
// Student's t test of mean = 0 on the finite values of x (n < 3 gives p = 1).
OneSampleTest t_test(const std::vector<double>& x);

// P(T > |t|) * 2 for Student's t with dof degrees of freedom.
double student_t_two_sided_p(double t, double dof);
// Upper tail of the chi-square distribution with dof degrees of freedom.
double chi_square_upper_p(double x, double dof);
// P(K >= k) for K ~ Binomial(n, p).
double binomial_upper_p(size_t k, size_t n, double p);

// Pearson correlation of paired finite values (0 if undefined).
double correlation(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace tsrir::diagnose

#include "fidelity_filters.h"

#include <algorithm>
#include <cmath>

namespace tsrir_test {
namespace {

struct Biquad {
  double b0, b1, b2, a1, a2;
};

// 4th-order Butterworth as two biquads (bilinear transform, Q = 0.5412 and 1.3066).
std::vector<Biquad> butterworth4(double cutoff_hz, double fs, bool high_pass) {
  std::vector<Biquad> sections;
  for (double q : {0.54119610, 1.30656296}) {
    const double w0 = 2 * M_PI * cutoff_hz / fs, c = std::cos(w0), alpha = std::sin(w0) / (2 * q);
    const double a0 = 1 + alpha;
    Biquad b;
    if (high_pass) {
      b.b0 = (1 + c) / 2 / a0, b.b1 = -(1 + c) / a0, b.b2 = (1 + c) / 2 / a0;
    } else {
      b.b0 = (1 - c) / 2 / a0, b.b1 = (1 - c) / a0, b.b2 = (1 - c) / 2 / a0;
    }
    b.a1 = -2 * c / a0, b.a2 = (1 - alpha) / a0;
    sections.push_back(b);
  }
  return sections;
}

void run_biquads(std::vector<double>& x, const std::vector<Biquad>& sections) {
  for (const Biquad& s : sections) {
    double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
    for (double& v : x) {
      const double y = s.b0 * v + s.b1 * x1 + s.b2 * x2 - s.a1 * y1 - s.a2 * y2;
      x2 = x1, x1 = v, y2 = y1, y1 = y, v = y;
    }
  }
}

}  // namespace

std::vector<double> zero_phase(const std::vector<double>& input, double cutoff_hz, double fs, bool high_pass) {
  std::vector<double> x = input;
  const auto sections = butterworth4(cutoff_hz, fs, high_pass);
  run_biquads(x, sections);
  std::reverse(x.begin(), x.end());
  run_biquads(x, sections);
  std::reverse(x.begin(), x.end());
  return x;
}

std::vector<double> above(const std::vector<double>& x, double cutoff_hz, double fs) {
  std::vector<double> high = x;
  run_biquads(high, butterworth4(cutoff_hz, fs, true));
  return high;
}

}  // namespace tsrir_test

#include "metrics/irstats.h"

#include <cmath>
#include <limits>

#include "metrics/decay_fit.h"
#include "util/strings.h"

namespace tsrir {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

size_t irstats_peak_index(const std::vector<float>& x, size_t* ties) {
  double best = -1;
  size_t index = 0, count = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    const double e = (double)x[i] * (double)x[i];
    if (e > best) {
      best = e;
      index = i;
      count = 1;
    } else if (e == best) {
      ++count;
    }
  }
  if (ties) *ties = count;
  return index;
}

double irstats_trapz_energy(const std::vector<float>& x, size_t begin, size_t end) {
  if (x.empty() || begin > end || end >= x.size()) return 0.0;
  double sum = 0;
  for (size_t i = begin; i <= end; ++i) sum += (double)x[i] * (double)x[i];
  const double first = (double)x[begin] * x[begin], last = (double)x[end] * x[end];
  return sum - 0.5 * (first + last);
}

std::vector<double> irstats_decay_curve(const std::vector<double>& y) {
  std::vector<double> z;
  irstats_decay_curve(y.data(), y.size(), &z);
  return z;
}

void irstats_decay_curve(const double* y, size_t n, std::vector<double>* out) {
  std::vector<double>& z = *out;
  z.assign(n, 0.0);
  if (n == 0) return;
  double acc = 0;
  double next = y[n - 1] * y[n - 1];
  for (size_t i = n - 1; i-- > 0;) {
    const double cur = y[i] * y[i];
    acc += 0.5 * (cur + next);
    z[i] = acc;
    next = cur;
  }
}

void IrstatsDecayFitter::reset(const double* z, size_t n) {
  // E = 10 log10(z) - max(E), keeping the samples before the first -inf.
  size_t len = 0;
  while (len < n && z[len] > 0) ++len;
  e_db_.resize(len);
  energy_to_db(z, len, e_db_.data());
  if (len == 0) return;
  double max_db = e_db_[0];
  for (size_t i = 1; i < len; ++i) max_db = std::max(max_db, e_db_[i]);
  for (double& v : e_db_) v -= max_db;
}

IrstatsDecay irstats_calc_decay(const double* z, size_t n, double fs, double fit_hi_db, double fit_lo_db,
                                double decay_db) {
  return IrstatsDecayFitter(z, n).fit(fs, fit_hi_db, fit_lo_db, decay_db);
}

IrstatsDecay IrstatsDecayFitter::fit(double fs, double fit_hi_db, double fit_lo_db, double decay_db) const {
  IrstatsDecay out{kNaN, true, ""};
  const std::vector<double>& e = e_db_;
  const size_t len = e.size();
  if (len < 2) {
    out.failure = "decay curve shorter than two samples";
    return out;
  }
  const double hi = std::max(fit_hi_db, fit_lo_db), lo = std::min(fit_hi_db, fit_lo_db);
  size_t ix1 = 0;
  while (ix1 < len && !(e[ix1] <= hi)) ++ix1;
  if (ix1 == len) ix1 = 0;  // findDB default 1
  size_t ix2 = ix1;
  while (ix2 < len && !(e[ix2] <= lo)) ++ix2;
  if (ix2 == len) {
    // irStats warns and evaluates at the last sample instead.
    out.range_reached = false;
    ix2 = len - 1;
  }
  if (ix2 <= ix1) {
    out.failure = "empty fit range";
    return out;
  }
  // polyfit(x, y, 1) over the 1-based indices ix1+1 .. ix2+1.
  const double m = (double)(ix2 - ix1 + 1);
  double sx = 0, sy = 0;
  for (size_t i = ix1; i <= ix2; ++i) {
    sx += (double)(i + 1);
    sy += e[i];
  }
  const double mx = sx / m, my = sy / m;
  double sxx = 0, sxy = 0;
  for (size_t i = ix1; i <= ix2; ++i) {
    const double dx = (double)(i + 1) - mx;
    sxx += dx * dx;
    sxy += dx * (e[i] - my);
  }
  const double p1 = sxy / sxx;
  const double p0 = my - p1 * mx;
  if (!(p1 < 0)) {
    out.failure = "decay curve does not fall";
    return out;
  }
  const double diff_y = hi - lo;
  // fit = polyval(p, 1:fitLength); fit0 = fit - max(fit) = fit - fit(1) for a falling line;
  // t = (y_dec / diff_y) * find(fit0 <= -diff_y, 1) / fs.
  const double fit_length = std::max((double)len, 1.1 * diff_y / std::abs((double)len * p1) * (double)len);
  const double fit1 = p1 * 1.0 + p0;
  double k = std::max(1.0, std::floor(diff_y / -p1));
  while (k > 1 && (p1 * (k - 1) + p0) - fit1 <= -diff_y) k -= 1;
  while ((p1 * k + p0) - fit1 > -diff_y) k += 1;
  if (k > std::floor(fit_length)) {
    out.failure = "fitted line does not reach -" + format_double(diff_y) + " dB";
    return out;
  }
  out.time_s = (decay_db / diff_y) * k / fs;
  return out;
}

IrstatsRatios irstats_drr_cte(const std::vector<float>& x, size_t t0, double fs, double correction_s, double te_s) {
  IrstatsRatios r{kNaN, kNaN, {}};
  const size_t n = x.size();
  const long c = std::lround(correction_s * fs);
  const long te = std::lround(te_s * fs);
  const size_t begin = t0 >= (size_t)c ? t0 - c : 0;
  if (t0 + c + 1 < n) {
    const double direct = irstats_trapz_energy(x, begin, t0 + c);
    const double reverb = irstats_trapz_energy(x, t0 + c + 1, n - 1);
    r.drr_db = 10.0 * std::log10(direct / reverb);
  } else {
    r.warnings.push_back("DRR: the direct window ends at or after the last sample");
  }
  if (t0 + te + 1 >= n) {
    r.warnings.push_back("CTE: early time limit (te) out of range");
  } else {
    const double early = irstats_trapz_energy(x, begin, t0 + te);
    const double late = irstats_trapz_energy(x, t0 + te + 1, n - 1);
    r.cte_db = 10.0 * std::log10(early / late);
  }
  return r;
}

std::vector<double> irstats_band_centers_hz(double fs) {
  std::vector<double> out;
  for (double fc = 31.25; fc <= 16000.0; fc *= 2) {
    if (fc > fs / 200.0 && fc < fs / 5.0) out.push_back(fc);
  }
  return out;
}

}  // namespace tsrir

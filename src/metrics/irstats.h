// The steps of IoSR irStats (IR-GAN copy of irStats.m; docs/reference/spec-digest.md §1.2), which produced the
// TS-RIR paper's Table 1, reproduced literally, with MATLAB's 1-based index conventions mapped to
// 0-based ones. Exposed one by one so each step is tested.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace tsrir {

// First index of the maximum of x^2; *ties (optional) receives how many samples share it.
size_t irstats_peak_index(const std::vector<float>& x, size_t* ties = nullptr);

// MATLAB trapz with unit spacing over x[begin..end] inclusive, of x^2: sum minus half the ends.
double irstats_trapz_energy(const std::vector<float>& x, size_t begin, size_t end);

// flipud(cumtrapz(flipud(y.^2))): z[n] = sum_{k=n}^{N-2} (y[k]^2 + y[k+1]^2) / 2, z[N-1] = 0.
std::vector<double> irstats_decay_curve(const std::vector<double>& y);
void irstats_decay_curve(const double* y, size_t n, std::vector<double>* z);

struct IrstatsDecay {
  double time_s;               // NaN when no fit exists
  bool range_reached = true;   // false: min(y_fit) never reached, fit ended at the last sample
  std::string failure;         // set when time_s is NaN
};

// calc_decay(z(t0:end), y_fit, y_dec, fs): dB re max, trailing -inf dropped, polyfit over the
// sample indices from the first <= max(y_fit) to the first <= min(y_fit), line anchored at 0 dB,
// time = (y_dec / |diff(y_fit)|) * (first index where the anchored line <= -|diff(y_fit)|) / fs.
IrstatsDecay irstats_calc_decay(const double* z, size_t n, double sample_rate_hz, double fit_hi_db,
                                double fit_lo_db, double decay_db = 60.0);

// The same for several fit ranges over one decay curve: the dB conversion is done once.
class IrstatsDecayFitter {
 public:
  IrstatsDecayFitter() = default;
  IrstatsDecayFitter(const double* z, size_t n) { reset(z, n); }
  void reset(const double* z, size_t n);  // reuses the buffer
  IrstatsDecay fit(double sample_rate_hz, double fit_hi_db, double fit_lo_db, double decay_db = 60.0) const;

 private:
  std::vector<double> e_db_;  // normalised to max 0 dB, trailing -inf removed
};

struct IrstatsRatios {
  double drr_db;
  double cte_db;
  std::vector<std::string> warnings;
};
// DRR = 10 log10(trapz(x(max(1,t0-C):t0+C).^2) / trapz(x(t0+C+1:end).^2)),
// CTE = 10 log10(trapz(x(max(1,t0-C):t0+te).^2) / trapz(x(t0+te+1:end).^2)), with
// C = round(correction_s fs), te = round(te_s fs); NaN plus a warning where irStats would warn or fail.
IrstatsRatios irstats_drr_cte(const std::vector<float>& x, size_t t0, double sample_rate_hz,
                              double correction_s = 0.0025, double te_s = 0.05);

// Centre frequencies irStats keeps: 31.25 .. 16000 Hz with fs/200 < fc < fs/5.
std::vector<double> irstats_band_centers_hz(double sample_rate_hz);

}  // namespace tsrir

#include "eq/eq_fir.h"

#include <cmath>
#include <complex>
#include <map>
#include <memory>
#include <mutex>

#include "dsp/fft.h"
#include "util/error.h"

namespace tsrir {

const Choices<FirWindow>& fir_window_choices() {
  static const Choices<FirWindow> choices = {
      {"hamming", FirWindow::kHamming}, {"hann", FirWindow::kHann}, {"blackman", FirWindow::kBlackman}};
  return choices;
}

FirWindow parse_fir_window(const std::string& name) { return parse_choice(fir_window_choices(), name, "FIR window"); }

std::string fir_window_name(FirWindow window) { return choice_name(fir_window_choices(), window); }

EqCurvePosition eq_curve_position(double freq_hz) {
  const double lo = kEqNodesHz.front(), hi = kEqNodesHz.back();
  if (freq_hz <= kEqFadeEndHz) return {0, 0.0, 0.0};
  if (freq_hz < kEqFadeStartHz) return {0, std::log2(freq_hz / kEqFadeEndHz) / std::log2(kEqFadeStartHz / kEqFadeEndHz), 0.0};
  if (freq_hz <= lo) return {0, 1.0, 0.0};
  if (freq_hz >= hi) return {kEqNumNodes - 1, 1.0, 0.0};
  // Nodes are octaves apart: log2(f / 62.5) is the fractional node index.
  const double x = std::log2(freq_hz / lo);
  const int node = static_cast<int>(std::floor(x));
  if (node >= kEqNumNodes - 1) return {kEqNumNodes - 1, 1.0, 0.0};
  return {node, 1.0 - (x - node), x - node};
}

double eq_curve_db(const EqNodeGainsDb& g, double freq_hz) {
  const EqCurvePosition p = eq_curve_position(freq_hz);
  double v = p.node_weight * g[p.node];
  if (p.next_weight != 0.0) v += p.next_weight * g[p.node + 1];
  return v;
}

size_t eq_fir_design_grid_size(int taps) {
  size_t n = 8192;
  while (n < 4 * static_cast<size_t>(taps)) n *= 2;
  return n;
}

namespace {

// Curve positions of every bin of a design grid; computing log2 per bin per design cost more
// than the FFTs.
std::shared_ptr<const std::vector<EqCurvePosition>> design_positions(size_t m, double fs) {
  static std::mutex mutex;
  static std::map<std::pair<size_t, double>, std::shared_ptr<const std::vector<EqCurvePosition>>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[{m, fs}];
  if (!slot) {
    auto positions = std::make_shared<std::vector<EqCurvePosition>>(m / 2 + 1);
    for (size_t b = 0; b <= m / 2; ++b) (*positions)[b] = eq_curve_position(b * fs / m);
    slot = positions;
  }
  return slot;
}

double window_value(FirWindow window, int i, int taps) {
  const double x = 2.0 * M_PI * i / (taps - 1);
  switch (window) {
    case FirWindow::kHamming: return 0.54 - 0.46 * std::cos(x);
    case FirWindow::kHann: return 0.5 - 0.5 * std::cos(x);
    case FirWindow::kBlackman: return 0.42 - 0.5 * std::cos(x) + 0.08 * std::cos(2 * x);
  }
  return 1.0;
}


// Window coefficients per (window, length), shared by all designs.
std::shared_ptr<const std::vector<double>> window_coefficients(FirWindow window, int taps) {
  static std::mutex mutex;
  static std::map<std::pair<int, int>, std::shared_ptr<const std::vector<double>>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[{static_cast<int>(window), taps}];
  if (!slot) {
    auto w = std::make_shared<std::vector<double>>(taps);
    for (int i = 0; i < taps; ++i) (*w)[i] = window_value(window, i, taps);
    slot = w;
  }
  return slot;
}

}  // namespace

int eq_fir_taps(const EqFirOptions& options, double sample_rate_hz) {
  if (options.taps == 0) return 2 * static_cast<int>(std::lround(1024.0 * sample_rate_hz / 16000.0)) + 1;
  if (options.taps < 3 || options.taps % 2 == 0) {
    throw Error("EQ FIR length must be odd and >= 3 (type I linear phase), got " + std::to_string(options.taps));
  }
  return options.taps;
}

std::vector<float> design_eq_fir(const EqNodeGainsDb& node_gains_db, double sample_rate_hz,
                                 const EqFirOptions& options) {
  check_eq_sample_rate(sample_rate_hz, "EQ FIR design");
  const int num_taps = eq_fir_taps(options, sample_rate_hz);
  for (double g : node_gains_db) {
    if (!std::isfinite(g)) throw Error("EQ FIR design: non-finite node gain");
  }
  const size_t m = eq_fir_design_grid_size(num_taps);
  RealFft fft(m);
  // Zero-phase desired response sampled on the grid; its inverse transform is real and even.
  const std::shared_ptr<const std::vector<EqCurvePosition>> positions = design_positions(m, sample_rate_hz);
  std::vector<std::complex<float>> spectrum(m / 2 + 1);
  constexpr double kNepersPerDb = 0.11512925464970229;  // ln(10) / 20
  for (size_t b = 0; b <= m / 2; ++b) {
    const EqCurvePosition& p = (*positions)[b];
    double db = p.node_weight * node_gains_db[p.node];
    if (p.next_weight != 0.0) db += p.next_weight * node_gains_db[p.node + 1];
    spectrum[b] = static_cast<float>(std::exp(kNepersPerDb * db));
  }
  std::vector<float> impulse(m);
  fft.inverse(spectrum.data(), impulse.data());
  const int half = (num_taps - 1) / 2;
  const std::shared_ptr<const std::vector<double>> window = window_coefficients(options.window, num_taps);
  std::vector<float> taps(num_taps);
  for (int i = 0; i < num_taps; ++i) {
    const int n = i - half;  // time relative to the centre
    const size_t idx = n >= 0 ? static_cast<size_t>(n) : m - static_cast<size_t>(-n);
    taps[i] = static_cast<float>(impulse[idx] / static_cast<double>(m) * (*window)[i]);
  }
  // Force exact symmetry (float FFT rounding differs between n and m-n).
  for (int i = 0; i < half; ++i) {
    const float avg = 0.5f * (taps[i] + taps[num_taps - 1 - i]);
    taps[i] = taps[num_taps - 1 - i] = avg;
  }
  return taps;
}

}  // namespace tsrir

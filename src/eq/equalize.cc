#include "eq/equalize.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>

#include "dsp/convolve.h"
#include "dsp/fft.h"
#include "util/error.h"

namespace tsrir {

EqLevel parse_eq_level(const std::string& name) {
  if (name == "peak") return EqLevel::kPeak;
  if (name == "energy") return EqLevel::kEnergy;
  if (name == "none") return EqLevel::kNone;
  throw Error("unknown level convention '" + name + "' (expected peak, energy or none)");
}

std::string eq_level_name(EqLevel level) {
  switch (level) {
    case EqLevel::kPeak: return "peak";
    case EqLevel::kEnergy: return "energy";
    case EqLevel::kNone: return "none";
  }
  return "peak";
}

std::vector<float> filter_zero_delay(const std::vector<float>& x, const std::vector<float>& taps) {
  if (taps.empty() || taps.size() % 2 == 0) throw Error("zero-delay filtering needs an odd-length filter");
  const std::vector<float> full = fft_convolve(x, taps);
  const size_t delay = (taps.size() - 1) / 2;
  return std::vector<float>(full.begin() + delay, full.begin() + delay + x.size());
}

namespace {

// Stage 2 corrects the written RIR's gains only when they miss the target by more than this.
constexpr double kEqOutputToleranceDb = 0.1;

// Band bins of one FFT grid with their position on the EQ curve, shared by all RIRs of a length.
struct MeasureGrid {
  EqBandGrid bands;
  // Per node band: (bin, curve position).
  std::array<std::vector<std::pair<size_t, EqCurvePosition>>, kEqNumNodes> bins;
  // Per node band: runs of bins no wider than 1/64 octave, with the curve position at their
  // centre. Stage 0 evaluates the curve once per run instead of once per bin; within 1/64 octave
  // the curve moves by < 0.5 dB even at a 30 dB/octave slope.
  struct Run {
    size_t first, last;
    EqCurvePosition position;
  };
  std::array<std::vector<Run>, kEqNumNodes> runs;

  MeasureGrid(size_t n, double fs, GainMethod method) : bands(n, fs, method) {
    for (int j = 0; j < kEqNumNodes; ++j) {
      for (size_t b = bands.first_bin(j); b <= bands.last_bin(j); ++b) {
        bins[j].emplace_back(b, eq_curve_position(bands.bin_hz(b)));
        if (runs[j].empty() || std::log2(std::max(bands.bin_hz(b), 1e-9) / std::max(bands.bin_hz(runs[j].back().first), 1e-9)) > 1.0 / 64) {
          runs[j].push_back({b, b, {}});
        }
        runs[j].back().last = b;
      }
      for (Run& r : runs[j]) r.position = eq_curve_position(std::sqrt(std::max(bands.bin_hz(r.first), 1e-9) * bands.bin_hz(r.last)));
    }
  }
};

using NodeMatrix = Eigen::Matrix<double, kEqNumNodes, kEqNumNodes>;
using PointMatrix = Eigen::Matrix<double, kEqNumPoints, kEqNumPoints>;

// Jacobian of the relative gains w.r.t. the point nodes, from mean_weight(band, node) = the
// power-weighted mean of node's interpolation weight over band: d gain_k / d node_j is band k's
// mean weight of node j minus the 1 kHz reference band's.
PointMatrix jacobian_from_mean_weights(const NodeMatrix& mean_weight) {
  PointMatrix jacobian;
  for (int k = 0; k < kEqNumPoints; ++k) {
    for (int j = 0; j < kEqNumPoints; ++j) {
      jacobian(k, j) = mean_weight(eq_node_of_point(k), eq_node_of_point(j)) -
                       mean_weight(kEqReferenceNode, eq_node_of_point(j));
    }
  }
  return jacobian;
}

std::shared_ptr<const MeasureGrid> measure_grid(size_t n, double fs, GainMethod method) {
  static std::mutex mutex;
  static std::map<std::tuple<size_t, double, int>, std::shared_ptr<const MeasureGrid>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto key = std::make_tuple(n, fs, static_cast<int>(method));
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  auto grid = std::make_shared<const MeasureGrid>(n, fs, method);
  if (cache.size() > 64) cache.clear();  // many distinct lengths: do not grow without bound
  cache[key] = grid;
  return grid;
}

}  // namespace

EqResult equalize_rir(const Signal& rir, const RelativeGainsDb& target_db, const EqApplyOptions& o) {
  const std::string what = "RIR '" + rir.id + "'";
  check_eq_sample_rate(rir.sample_rate_hz, what);
  if (rir.samples.empty()) throw Error(what + ": empty RIR");
  double peak_in = 0.0, energy_in = 0.0;
  for (float v : rir.samples) {
    if (!std::isfinite(v)) throw Error(what + ": non-finite sample");
    peak_in = std::max(peak_in, static_cast<double>(std::abs(v)));
    energy_in += static_cast<double>(v) * v;
  }
  if (peak_in == 0.0) throw Error(what + ": the RIR is silent (all samples are zero)");
  for (double t : target_db) {
    if (!std::isfinite(t)) throw Error(what + ": non-finite target gain");
  }

  const size_t n = eq_fft_size(rir.samples.size());
  const std::shared_ptr<const MeasureGrid> grid = measure_grid(n, rir.sample_rate_hz, o.gain_method);
  const std::vector<double> x_power = power_spectrum(rir.samples, n);

  EqResult result;
  result.target_db = target_db;
  result.before_db = EqBandGrid::relative_gains(grid->bands.band_powers(x_power), what);

  auto clamp_node = [&](double v) { return std::clamp(v, -o.max_cut_db, o.max_boost_db); };
  EqNodeGainsDb nodes{};  // the reference node stays at 0 dB
  for (int k = 0; k < kEqNumPoints; ++k) nodes[eq_node_of_point(k)] = clamp_node(target_db[k] - result.before_db[k]);

  // Jacobian of the gains of a filtered power spectrum w.r.t. the node gains.
  auto jacobian_of = [&](const std::vector<double>& filtered) {
    NodeMatrix mean_weight = NodeMatrix::Zero();
    for (int band = 0; band < kEqNumNodes; ++band) {
      double total = 0.0;
      for (const auto& [bin, pos] : grid->bins[band]) {
        const double p = filtered[bin];
        total += p;
        mean_weight(band, pos.node) += p * pos.node_weight;
        if (pos.next_weight > 0.0) mean_weight(band, pos.node + 1) += p * pos.next_weight;
      }
      if (total > 0.0) mean_weight.row(band) /= total;
    }
    return jacobian_from_mean_weights(mean_weight);
  };
  auto newton_step_with = [&](const PointMatrix& jacobian, const Eigen::VectorXd& residual) {
    const Eigen::VectorXd step = jacobian.fullPivLu().solve(residual);
    if (!step.allFinite()) return false;
    for (int j = 0; j < kEqNumPoints; ++j) nodes[eq_node_of_point(j)] = clamp_node(nodes[eq_node_of_point(j)] + step(j));
    return true;
  };
  auto newton_step = [&](const std::vector<double>& filtered, const Eigen::VectorXd& residual) {
    return newton_step_with(jacobian_of(filtered), residual);
  };
  auto residual_of = [&](const RelativeGainsDb& gains, double* max_error) {
    Eigen::VectorXd r(kEqNumPoints);
    *max_error = 0.0;
    for (int k = 0; k < kEqNumPoints; ++k) {
      r(k) = target_db[k] - gains[k];
      *max_error = std::max(*max_error, std::abs(r(k)));
    }
    return r;
  };

  // Stage 0 (cheap, no FFT): Newton steps on the ideal curve, |H|^2 = 10^(curve/10), evaluated
  // per 1/64-octave run of bins. It removes most of the neighbour spill before the first FIR is
  // designed, which saves one or two designs + transforms per RIR.
  if (o.refine_iterations > 0) {
    std::array<std::vector<double>, kEqNumNodes> run_power;
    for (int band = 0; band < kEqNumNodes; ++band) {
      for (const auto& r : grid->runs[band]) {
        double sum = 0.0;
        for (size_t b = r.first; b <= r.last; ++b) sum += x_power[b];
        run_power[band].push_back(sum);
      }
    }
    constexpr double kNepersPerDbPower = 0.23025850929940458;  // ln(10) / 10
    for (int iter = 0; iter < 3; ++iter) {
      std::array<double, kEqNumNodes> band_power{};
      NodeMatrix mean_weight = NodeMatrix::Zero();
      for (int band = 0; band < kEqNumNodes; ++band) {
        double total = 0.0;
        for (size_t i = 0; i < grid->runs[band].size(); ++i) {
          const EqCurvePosition& pos = grid->runs[band][i].position;
          double db = pos.node_weight * nodes[pos.node];
          if (pos.next_weight != 0.0) db += pos.next_weight * nodes[pos.node + 1];
          const double p = run_power[band][i] * std::exp(kNepersPerDbPower * db);
          total += p;
          mean_weight(band, pos.node) += p * pos.node_weight;
          if (pos.next_weight != 0.0) mean_weight(band, pos.node + 1) += p * pos.next_weight;
        }
        if (total > 0.0) mean_weight.row(band) /= total;
        band_power[band] = total / static_cast<double>(grid->bands.last_bin(band) - grid->bands.first_bin(band) + 1);
      }
      double max_error = 0.0;
      const Eigen::VectorXd residual = residual_of(EqBandGrid::relative_gains(band_power, what), &max_error);
      if (max_error < o.tolerance_db || !newton_step_with(jacobian_from_mean_weights(mean_weight), residual)) break;
    }
  }

  // Stage 1: refine on the predicted gains (input power spectrum times the FIR's), no filtering.
  std::vector<float> taps;
  std::vector<double> filtered(x_power.size());
  for (int iter = 0;; ++iter) {
    taps = design_eq_fir(nodes, rir.sample_rate_hz, o.fir);
    ++result.filters_designed;
    const std::vector<double> h_power = power_spectrum(taps, n);
    for (size_t b = 0; b < filtered.size(); ++b) filtered[b] = x_power[b] * h_power[b];
    result.predicted_db = EqBandGrid::relative_gains(grid->bands.band_powers(filtered), what);
    result.node_gains_db = nodes;
    double max_error = 0.0;
    const Eigen::VectorXd residual = residual_of(result.predicted_db, &max_error);
    if (max_error < o.tolerance_db || iter >= o.refine_iterations) break;
    if (!newton_step(filtered, residual)) break;
  }
  std::vector<float> output = filter_zero_delay(rir.samples, taps);

  // Stage 2: the written RIR differs from the prediction by what cropping to the original length
  // removes (the filter's ringing before sample 0, e.g. of a direct sound near the start, and
  // after the end). Correct on the measured output; at most two extra filters.
  RelativeGainsDb measured{};
  bool have_measured = false;
  if (o.refine_iterations > 0 || o.measure_output) {
    Signal probe;
    probe.id = rir.id;
    probe.sample_rate_hz = rir.sample_rate_hz;
    probe.samples = output;
    measured = relative_gains_db(probe, o.gain_method);
    have_measured = true;
  }
  for (int correction = 0; o.refine_iterations > 0 && correction < 2; ++correction) {
    double max_error = 0.0;
    const Eigen::VectorXd residual = residual_of(measured, &max_error);
    if (max_error < kEqOutputToleranceDb) break;
    const EqNodeGainsDb saved_nodes = nodes;
    if (!newton_step(filtered, residual)) break;
    const std::vector<float> new_taps = design_eq_fir(nodes, rir.sample_rate_hz, o.fir);
    ++result.filters_designed;
    Signal probe;
    probe.id = rir.id;
    probe.sample_rate_hz = rir.sample_rate_hz;
    probe.samples = filter_zero_delay(rir.samples, new_taps);
    const RelativeGainsDb new_measured = relative_gains_db(probe, o.gain_method);
    double new_error = 0.0;
    residual_of(new_measured, &new_error);
    if (new_error >= max_error) {
      nodes = saved_nodes;
      break;
    }
    taps = new_taps;
    output = std::move(probe.samples);
    measured = new_measured;
    result.node_gains_db = nodes;
  }

  for (double g : result.node_gains_db) {
    if (g >= o.max_boost_db || g <= -o.max_cut_db) result.clamped = true;
  }
  result.rir.id = rir.id;
  result.rir.sample_rate_hz = rir.sample_rate_hz;
  result.rir.samples = std::move(output);
  double peak_out = 0.0, energy_out = 0.0;
  for (float v : result.rir.samples) {
    peak_out = std::max(peak_out, static_cast<double>(std::abs(v)));
    energy_out += static_cast<double>(v) * v;
  }
  if (peak_out == 0.0) throw Error(what + ": the equalized RIR is silent");
  double scale = 1.0;
  if (o.level == EqLevel::kPeak) scale = peak_in / peak_out;
  if (o.level == EqLevel::kEnergy) scale = std::sqrt(energy_in / energy_out);
  if (scale != 1.0) {
    for (float& v : result.rir.samples) v = static_cast<float>(v * scale);
  }
  // Scaling does not change relative gains.
  if (o.measure_output) result.after_db = have_measured ? measured : relative_gains_db(result.rir, o.gain_method);
  return result;
}

}  // namespace tsrir

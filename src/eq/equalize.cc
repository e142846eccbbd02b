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

const Choices<EqLevel>& eq_level_choices() {
  static const Choices<EqLevel> choices = {{"peak", EqLevel::kPeak}, {"energy", EqLevel::kEnergy}, {"none", EqLevel::kNone}};
  return choices;
}

EqLevel parse_eq_level(const std::string& name) { return parse_choice(eq_level_choices(), name, "level convention"); }

std::string eq_level_name(EqLevel level) { return choice_name(eq_level_choices(), level); }

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

// The input's level, for the output to keep (EqLevel). Errors name `what`: a non-finite or silent
// RIR, a non-finite target.
struct InputLevel {
  double peak = 0.0, energy = 0.0;
};

InputLevel check_equalizable(const Signal& rir, const RelativeGainsDb& target_db, const std::string& what) {
  check_eq_sample_rate(rir.sample_rate_hz, what);
  if (rir.samples.empty()) throw Error(what + ": empty RIR");
  InputLevel level;
  for (float v : rir.samples) {
    if (!std::isfinite(v)) throw Error(what + ": non-finite sample");
    level.peak = std::max(level.peak, static_cast<double>(std::abs(v)));
    level.energy += static_cast<double>(v) * v;
  }
  if (level.peak == 0.0) throw Error(what + ": the RIR is silent (all samples are zero)");
  for (double t : target_db) {
    if (!std::isfinite(t)) throw Error(what + ": non-finite target gain");
  }
  return level;
}

// The node gains of one RIR's EQ curve, solved for by Newton steps on the relative gains in three
// stages of rising cost: on the ideal curve (no FIR), on the gains a designed FIR predicts, on the
// gains of the written (cropped) output.
class NodeSolver {
 public:
  NodeSolver(const Signal& rir, const RelativeGainsDb& target_db, const EqApplyOptions& o, std::string what)
      : rir_(rir), target_db_(target_db), o_(o), what_(std::move(what)),
        n_(eq_fft_size(rir.samples.size())),
        grid_(measure_grid(n_, rir.sample_rate_hz, o.gain_method)),
        x_power_(power_spectrum(rir.samples, n_)),
        before_db_(EqBandGrid::relative_gains(grid_->bands.band_powers(x_power_), what_)) {
    for (int k = 0; k < kEqNumPoints; ++k) nodes_[eq_node_of_point(k)] = clamp_node(target_db[k] - before_db_[k]);
  }

  const RelativeGainsDb& before_db() const { return before_db_; }

  // Stage 0 (cheap, no FFT): Newton steps on the ideal curve, |H|^2 = 10^(curve/10), evaluated
  // per 1/64-octave run of bins. It removes most of the neighbour spill before the first FIR is
  // designed, which saves one or two designs + transforms per RIR.
  void refine_on_ideal_curve() {
    std::array<std::vector<double>, kEqNumNodes> run_power;
    for (int band = 0; band < kEqNumNodes; ++band) {
      for (const auto& r : grid_->runs[band]) {
        double sum = 0.0;
        for (size_t b = r.first; b <= r.last; ++b) sum += x_power_[b];
        run_power[band].push_back(sum);
      }
    }
    for (int iter = 0; iter < 3; ++iter) {
      std::array<double, kEqNumNodes> band_power{};
      const NodeMatrix mean_weight = ideal_curve_weights(run_power, &band_power);
      double max_error = 0.0;
      const Eigen::VectorXd residual = residual_of(EqBandGrid::relative_gains(band_power, what_), &max_error);
      if (max_error < o_.tolerance_db || !newton_step_with(jacobian_from_mean_weights(mean_weight), residual)) break;
    }
  }

  // Stage 1: refine on the predicted gains (input power spectrum times the FIR's), no filtering.
  // Returns the final filter; sets result's predicted gains, node gains and design count.
  std::vector<float> refine_on_predicted_gains(EqResult* result) {
    std::vector<float> taps;
    filtered_.resize(x_power_.size());
    for (int iter = 0;; ++iter) {
      taps = design_eq_fir(nodes_, rir_.sample_rate_hz, o_.fir);
      ++result->filters_designed;
      const std::vector<double> h_power = power_spectrum(taps, n_);
      for (size_t b = 0; b < filtered_.size(); ++b) filtered_[b] = x_power_[b] * h_power[b];
      result->predicted_db = EqBandGrid::relative_gains(grid_->bands.band_powers(filtered_), what_);
      result->node_gains_db = nodes_;
      double max_error = 0.0;
      const Eigen::VectorXd residual = residual_of(result->predicted_db, &max_error);
      if (max_error < o_.tolerance_db || iter >= o_.refine_iterations) break;
      if (!newton_step(residual)) break;
    }
    return taps;
  }

  // Stage 2: the written RIR differs from the prediction by what cropping to the original length
  // removes (the filter's ringing before sample 0, e.g. of a direct sound near the start, and
  // after the end). Corrects on the measured output, at most two extra filters, each kept only if
  // it gets closer; *output and *measured are the kept ones.
  void correct_on_output(std::vector<float>* output, RelativeGainsDb* measured, EqResult* result) {
    for (int correction = 0; correction < 2; ++correction) {
      double max_error = 0.0;
      const Eigen::VectorXd residual = residual_of(*measured, &max_error);
      if (max_error < kEqOutputToleranceDb) break;
      const EqNodeGainsDb saved_nodes = nodes_;
      if (!newton_step(residual)) break;
      const std::vector<float> new_taps = design_eq_fir(nodes_, rir_.sample_rate_hz, o_.fir);
      ++result->filters_designed;
      Signal probe = with_samples(filter_zero_delay(rir_.samples, new_taps));
      const RelativeGainsDb new_measured = relative_gains_db(probe, o_.gain_method);
      double new_error = 0.0;
      residual_of(new_measured, &new_error);
      if (new_error >= max_error) {
        nodes_ = saved_nodes;
        break;
      }
      *output = std::move(probe.samples);
      *measured = new_measured;
      result->node_gains_db = nodes_;
    }
  }

  // A signal of the input's id and rate.
  Signal with_samples(std::vector<float> samples) const {
    Signal s;
    s.id = rir_.id;
    s.sample_rate_hz = rir_.sample_rate_hz;
    s.samples = std::move(samples);
    return s;
  }

 private:
  double clamp_node(double v) const { return std::clamp(v, -o_.max_cut_db, o_.max_boost_db); }

  // Per band: the power-weighted mean interpolation weight of each node over the curve's runs, and
  // (into *band_power) the band's mean power under the current nodes.
  NodeMatrix ideal_curve_weights(const std::array<std::vector<double>, kEqNumNodes>& run_power,
                                 std::array<double, kEqNumNodes>* band_power) const {
    constexpr double kNepersPerDbPower = 0.23025850929940458;  // ln(10) / 10
    NodeMatrix mean_weight = NodeMatrix::Zero();
    for (int band = 0; band < kEqNumNodes; ++band) {
      double total = 0.0;
      for (size_t i = 0; i < grid_->runs[band].size(); ++i) {
        const EqCurvePosition& pos = grid_->runs[band][i].position;
        double db = pos.node_weight * nodes_[pos.node];
        if (pos.next_weight != 0.0) db += pos.next_weight * nodes_[pos.node + 1];
        const double p = run_power[band][i] * std::exp(kNepersPerDbPower * db);
        total += p;
        mean_weight(band, pos.node) += p * pos.node_weight;
        if (pos.next_weight != 0.0) mean_weight(band, pos.node + 1) += p * pos.next_weight;
      }
      if (total > 0.0) mean_weight.row(band) /= total;
      (*band_power)[band] = total / static_cast<double>(grid_->bands.last_bin(band) - grid_->bands.first_bin(band) + 1);
    }
    return mean_weight;
  }

  // Jacobian of the gains of the filtered power spectrum (stage 1's) w.r.t. the node gains.
  PointMatrix jacobian_of_filtered() const {
    NodeMatrix mean_weight = NodeMatrix::Zero();
    for (int band = 0; band < kEqNumNodes; ++band) {
      double total = 0.0;
      for (const auto& [bin, pos] : grid_->bins[band]) {
        const double p = filtered_[bin];
        total += p;
        mean_weight(band, pos.node) += p * pos.node_weight;
        if (pos.next_weight > 0.0) mean_weight(band, pos.node + 1) += p * pos.next_weight;
      }
      if (total > 0.0) mean_weight.row(band) /= total;
    }
    return jacobian_from_mean_weights(mean_weight);
  }

  bool newton_step_with(const PointMatrix& jacobian, const Eigen::VectorXd& residual) {
    const Eigen::VectorXd step = jacobian.fullPivLu().solve(residual);
    if (!step.allFinite()) return false;
    for (int j = 0; j < kEqNumPoints; ++j) nodes_[eq_node_of_point(j)] = clamp_node(nodes_[eq_node_of_point(j)] + step(j));
    return true;
  }
  bool newton_step(const Eigen::VectorXd& residual) { return newton_step_with(jacobian_of_filtered(), residual); }

  Eigen::VectorXd residual_of(const RelativeGainsDb& gains, double* max_error) const {
    Eigen::VectorXd r(kEqNumPoints);
    *max_error = 0.0;
    for (int k = 0; k < kEqNumPoints; ++k) {
      r(k) = target_db_[k] - gains[k];
      *max_error = std::max(*max_error, std::abs(r(k)));
    }
    return r;
  }

  const Signal& rir_;
  const RelativeGainsDb& target_db_;
  const EqApplyOptions& o_;
  const std::string what_;
  const size_t n_;
  const std::shared_ptr<const MeasureGrid> grid_;
  const std::vector<double> x_power_;
  const RelativeGainsDb before_db_;
  EqNodeGainsDb nodes_{};      // the reference node stays at 0 dB
  std::vector<double> filtered_;  // stage 1's filtered power spectrum
};

// Scales the equalized RIR to the input's level convention; Error when it is silent.
void restore_level(const InputLevel& in, EqLevel level, const std::string& what, std::vector<float>* samples) {
  double peak_out = 0.0, energy_out = 0.0;
  for (float v : *samples) {
    peak_out = std::max(peak_out, static_cast<double>(std::abs(v)));
    energy_out += static_cast<double>(v) * v;
  }
  if (peak_out == 0.0) throw Error(what + ": the equalized RIR is silent");
  double scale = 1.0;
  if (level == EqLevel::kPeak) scale = in.peak / peak_out;
  if (level == EqLevel::kEnergy) scale = std::sqrt(in.energy / energy_out);
  if (scale != 1.0) {
    for (float& v : *samples) v = static_cast<float>(v * scale);
  }
}

}  // namespace

EqResult equalize_rir(const Signal& rir, const RelativeGainsDb& target_db, const EqApplyOptions& o) {
  const std::string what = "RIR '" + rir.id + "'";
  const InputLevel level_in = check_equalizable(rir, target_db, what);
  NodeSolver solver(rir, target_db, o, what);
  EqResult result;
  result.target_db = target_db;
  result.before_db = solver.before_db();
  if (o.refine_iterations > 0) solver.refine_on_ideal_curve();
  const std::vector<float> taps = solver.refine_on_predicted_gains(&result);
  std::vector<float> output = filter_zero_delay(rir.samples, taps);
  RelativeGainsDb measured{};
  const bool have_measured = o.refine_iterations > 0 || o.measure_output;
  if (have_measured) measured = relative_gains_db(solver.with_samples(output), o.gain_method);
  if (o.refine_iterations > 0) solver.correct_on_output(&output, &measured, &result);

  for (double g : result.node_gains_db) {
    if (g >= o.max_boost_db || g <= -o.max_cut_db) result.clamped = true;
  }
  result.rir = solver.with_samples(std::move(output));
  restore_level(level_in, o.level, what, &result.rir.samples);
  // Scaling does not change relative gains.
  if (o.measure_output) result.after_db = have_measured ? measured : relative_gains_db(result.rir, o.gain_method);
  return result;
}

EqResult equalize_rir_channels(const std::vector<Signal>& channels, const RelativeGainsDb& target_db,
                               const EqApplyOptions& options, std::vector<Signal>* others) {
  if (channels.empty()) throw Error("equalize_rir_channels: no channels");
  EqResult result = equalize_rir(channels.front(), target_db, options);
  others->clear();
  if (channels.size() == 1) return result;
  // The level factor channel 0 got: its output over its filtered input, compared at their peaks.
  const std::vector<float> taps = design_eq_fir(result.node_gains_db, channels.front().sample_rate_hz, options.fir);
  const std::vector<float> unscaled = filter_zero_delay(channels.front().samples, taps);
  double peak_unscaled = 0.0, peak_out = 0.0;
  for (float v : unscaled) peak_unscaled = std::max(peak_unscaled, static_cast<double>(std::abs(v)));
  for (float v : result.rir.samples) peak_out = std::max(peak_out, static_cast<double>(std::abs(v)));
  const double scale = peak_out / peak_unscaled;
  for (size_t c = 1; c < channels.size(); ++c) {
    Signal out = channels[c];
    out.samples = filter_zero_delay(channels[c].samples, taps);
    for (float& v : out.samples) v = static_cast<float>(v * scale);
    others->push_back(std::move(out));
  }
  return result;
}

}  // namespace tsrir

// diffuse_scattering: the surfaces scatter more (or less) than stated: the early reflections turn
// into a dense, noise-like field sooner (or later).
//   Statistic  early (2-20 ms) normalised echo density of the 1-7 kHz band, each RIR convolved
//              with the other's direct sound so that a chain's colouration or ringing cancels
//              (rir_features.h: cross_equalised_echo_density); paired mean, both directions.
//   Depends    source_directivity: a directional source weights the early reflections unequally
//              (those leaving near its axis strong, the others weak), which makes the early response
//              sparser, i.e. reads as less scattering. When it is detected, only a denser early
//              response than simulated (more scattering) is evidence: the decision is one-sided.
//   Extension  sim "scattering" (src/sim/room_refits.h): the scattering value whose simulated early
//              echo density matches the measured one, from a grid of trial renders (two seeds per
//              value) made monotone by pool-adjacent-violators.
#include <cmath>

#include "diagnose/decision_rules.h"
#include "diagnose/diagnose.h"
#include "diagnose/extension_fit.h"
#include "util/parallel.h"

namespace tsrir::diagnose {
namespace {

struct ScatteringThresholds {
  double min_echo_density = 0.05;
  std::vector<Threshold> list() const {
    return {{"min_echo_density", min_echo_density,
             "mean early echo density difference (normalised density: 1 = Gaussian noise; seed-vs-seed differences "
             "are about 0.02 per RIR)"}};
  }
};
constexpr ScatteringThresholds kThresholds{};

// Pool-adjacent-violators: the nondecreasing sequence nearest to `got` (least squares).
void make_nondecreasing(std::vector<double>& got) {
  std::vector<double> value(got), weight(got.size(), 1.0);
  std::vector<size_t> start(got.size());
  size_t blocks = 0;
  for (size_t g = 0; g < got.size(); ++g) {
    value[blocks] = got[g];
    weight[blocks] = 1.0;
    start[blocks] = g;
    ++blocks;
    while (blocks > 1 && value[blocks - 2] > value[blocks - 1]) {
      const double w = weight[blocks - 2] + weight[blocks - 1];
      value[blocks - 2] = (value[blocks - 2] * weight[blocks - 2] + value[blocks - 1] * weight[blocks - 1]) / w;
      weight[blocks - 2] = w;
      --blocks;
    }
  }
  for (size_t b = 0; b < blocks; ++b) {
    const size_t end = b + 1 < blocks ? start[b + 1] : got.size();
    for (size_t g = start[b]; g < end; ++g) got[g] = value[b];
  }
}

class DiffuseScatteringEffect : public Effect {
 public:
  std::string name() const override { return "diffuse_scattering"; }
  std::string description() const override {
    return "the surfaces scatter more or less than stated: early (2-20 ms) echo density of the 1-7 kHz band, "
           "cross-equalised; extension: scattering (value).";
  }
  std::vector<Threshold> thresholds() const override { return kThresholds.list(); }
  GainMetricId gain_metric() const override { return GainMetricId::own(OwnMetric::kEchoDensity); }
  std::vector<ResidualView> residual_views() const override { return {ResidualView::kEarlyPattern}; }
  std::vector<std::string> depends_on() const override { return {"source_directivity"}; }

  Finding detect(const DecisionContext& ctx) const override {
    const SetObservations& obs = ctx.obs();
    std::vector<double> ed_d, ed_e;
    for (const RirObservation& r : obs) {
      ed_d.push_back(r.echo_density_meas_a.first - r.echo_density_meas_a.second);
      ed_e.push_back(r.echo_density_b_a.first - r.echo_density_b_a.second);
    }
    const bool directional = ctx.detected("source_directivity");
    Finding f = decide_mean(name(), ed_d, ed_e, kThresholds.min_echo_density, directional ? +1 : 0,
                            "early (2-20 ms) normalised echo density, 1-7 kHz, cross-equalised", "");
    if (directional) {
      f.evidence += " Only a denser response counts: the detected source directivity makes the early response "
                    "sparser.";
    }
    return f;
  }

  Extension fit(const FitContext& ctx, Finding* finding) const override {
    const SetObservations& obs = ctx.obs();
    const DiagnoseOptions& options = ctx.options();
    std::vector<size_t> idx = ctx.fit_index();
    if (idx.size() > options.max_scattering_fit_rirs) idx.resize(options.max_scattering_fit_rirs);
    // For each grid value: mean over the fit RIRs of the cross-equalised density difference
    // (measured - simulated); the refit value is where it crosses zero.
    const double want = 0.0;
    const std::vector<double> grid = {0.0, 0.05, 0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0};
    std::vector<double> got(grid.size());
    // Two render seeds per grid value (the statistic's seed noise is ~0.02, the effect a few
    // hundredths), then an increasing fit (pool-adjacent-violators): a noisy grid point must not
    // move the crossing to the other end of the grid.
    for (size_t g = 0; g < grid.size(); ++g) {
      std::vector<double> ed(2 * idx.size());
      const std::string spec = options.baseline_model + "+scattering:value=" + spec_num(grid[g]);
      parallel_for(2 * idx.size(), options.num_threads, [&](size_t k) {
        const size_t i = idx[k % idx.size()];
        const Signal s =
            render_rir(spec, obs[i].room, options.sample_rate_hz, obs[i].measured.size(), options.seed + k / idx.size());
        const auto pair = cross_equalised_echo_density(obs[i].measured, obs[i].meas.onset_s, s, onset_time_s(s));
        ed[k] = pair.first - pair.second;
      });
      got[g] = -mean_of(ed);  // increases with scattering, like the simulated density
    }
    make_nondecreasing(got);
    double value = got.front() >= want ? grid.front() : grid.back();
    for (size_t g = 0; g + 1 < grid.size(); ++g) {
      if (got[g] <= want && got[g + 1] > want) {
        value = grid[g] + (grid[g + 1] - grid[g]) * (want - got[g]) / (got[g + 1] - got[g]);
        break;
      }
    }
    finding->parameters = {{"scattering", value}};
    return {"+scattering:value=" + spec_num(value), {}};
  }
};

}  // namespace

std::unique_ptr<Effect> make_diffuse_scattering_effect() { return std::make_unique<DiffuseScatteringEffect>(); }

}  // namespace tsrir::diagnose

// The TS-RIRGAN training loop (docs/reference/spec-digest.md §3.4-3.5): per iteration, disc_updates x [D_R step,
// D_S step], then a G_SR step and a G_RS step, each on a fresh pair of batches.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "gan/gan_band_gain.h"
#include "gan/gan_bfloat16.h"
#include "gan/gan_input.h"
#include "gan/gan_loss_plot.h"
#include "gan/gan_checkpoint.h"
#include "gan/gan_networks.h"
#include "gan/gan_runtime.h"
#include "gan/gan_tensor_allocator.h"
#include "gan/gan_weight_average.h"
#include "gan/gan_settings.h"
#include "gan/torch_compat.h"
#include "gan/ts_rirgan.h"
#include "io/rir_set.h"
#include "util/cli.h"
#include "util/error.h"
#include "util/parallel.h"
#include "util/rng.h"
#include "util/strings.h"

namespace fs = std::filesystem;

namespace tsrir {
namespace {

using gan::CycleGan;

// Loss weights of the original: LAMBDA = 10; D loss 0.5*LAMBDA*(...); G loss
// adv + 25*(10*L1_cycle_R + 10*L1_cycle_S) + 35*(5*L1_identity). The two generator L1 weights
// (250, 175) are settings (cycle_weight, identity_weight) with these defaults.
constexpr double kDiscriminatorWeight = 5.0;

const char* const kLogHeader =
    "step,d_real,d_synthetic,g_real,g_synthetic,adv_real,adv_synthetic,cycle_l1_real,"
    "cycle_l1_synthetic,identity_l1_real,identity_l1_synthetic,gain_rms_db,step_s";

// All RIRs of one domain as a [N, 1, 16384] CPU tensor.
torch::Tensor load_domain(const std::string& list, const std::string& name, int batch_size,
                          int num_threads) {
  const std::vector<RirRef> refs = read_rir_refs(list, run_inputs());
  if (refs.empty()) throw Error(list + ": the " + name + " set is empty");
  if (refs.size() < size_t(batch_size)) {
    throw Error(list + ": the " + name + " set has " + std::to_string(refs.size()) +
                " RIR(s); training needs at least --batch-size=" + std::to_string(batch_size));
  }
  std::vector<GanInput> inputs(refs.size());
  AudioReadOptions read_options;
  read_options.target_rate_hz = kGanSampleRateHz;
  read_options.channel = -1;  // the original averages multichannel files
  parallel_for(refs.size(), num_threads, [&](size_t i) {
    inputs[i] = prepare_gan_input(load_rir(refs[i], read_options));
  });
  torch::Tensor rirs = torch::empty({int64_t(refs.size()), 1, int64_t(kGanSliceLength)});
  size_t cropped = 0;
  for (size_t i = 0; i < refs.size(); ++i) {
    std::memcpy(rirs[i].data_ptr<float>(), inputs[i].samples.data(), kGanSliceLength * sizeof(float));
    cropped += inputs[i].cropped;
  }
  if (cropped > 0) {
    log_warning(list + ": " + std::to_string(cropped) + " of " + std::to_string(refs.size()) +
                " " + name + " RIRs are longer than 16384 samples at 16 kHz; only their first " +
                "16384 samples are used (as the original)");
  }
  log_info("loaded " + std::to_string(refs.size()) + " " + name + " RIRs from " + list);
  return rirs;
}

// Batches drawn from per-epoch permutations that depend only on (seed, domain, epoch): draw d of
// a run is the same whether the run was resumed or not.
class BatchSampler {
 public:
  BatchSampler(uint64_t seed, std::string domain, torch::Tensor rirs)
      : seed_(seed), domain_(std::move(domain)), rirs_(std::move(rirs)) {}

  torch::Tensor batch(long long draw, int batch_size) {
    const long long n = rirs_.size(0);
    std::vector<int64_t> index(batch_size);
    for (int b = 0; b < batch_size; ++b) {
      const long long c = draw * batch_size + b;
      index[b] = permutation(c / n)[c % n];
    }
    return rirs_.index_select(0, torch::tensor(index, torch::kInt64));
  }
  const torch::Tensor& rirs() const { return rirs_; }

 private:
  const std::vector<int64_t>& permutation(long long epoch) {
    auto it = cache_.find(epoch);
    if (it != cache_.end()) return it->second;
    if (cache_.size() > 4) cache_.erase(cache_.begin());
    std::vector<int64_t> p(rirs_.size(0));
    for (size_t i = 0; i < p.size(); ++i) p[i] = int64_t(i);
    Rng rng = Rng::for_item(seed_, domain_ + "/epoch/" + std::to_string(epoch));
    for (size_t i = p.size(); i > 1; --i) std::swap(p[i - 1], p[rng.below(i)]);
    return cache_.emplace(epoch, std::move(p)).first->second;
  }

  uint64_t seed_;
  std::string domain_;
  torch::Tensor rirs_;
  std::map<long long, std::vector<int64_t>> cache_;
};

struct StepLosses {
  double d_real = 0, d_synthetic = 0, g_real = 0, g_synthetic = 0, adv_real = 0, adv_synthetic = 0;
  double cycle_real = 0, cycle_synthetic = 0, identity_real = 0, identity_synthetic = 0;
  // RMS over batch, bands and knots of G_SR's log gains in its translation pass, dB (band-gain
  // generators; nan for the others).
  double gain_rms_db = std::numeric_limits<double>::quiet_NaN();
};

class NonFiniteLoss : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

double checked(const torch::Tensor& loss, const char* name) {
  const double v = loss.item<double>();
  if (!std::isfinite(v)) {
    throw NonFiniteLoss(std::string(name) + " loss is not finite (" + (std::isnan(v) ? "NaN" : "Inf") + ")");
  }
  return v;
}

void apply(gan::TfRmsProp& optimizer, const torch::Tensor& loss) {
  optimizer.step(torch::autograd::grad({loss}, optimizer.params()));
}

// --precision=bfloat16: the forward passes run under CPU autocast (convolutions and the dense
// layer in bfloat16 with float32 accumulation; weights, gradients, optimiser state and the losses
// stay float32). The scope ends before the gradients are taken.
class AutocastScope {
 public:
  explicit AutocastScope(bool enabled) : enabled_(enabled) {
    if (!enabled_) return;
    previous_ = torch_compat::cpu_autocast_enabled();
    torch_compat::set_cpu_autocast_dtype(at::kBFloat16);
    torch_compat::set_cpu_autocast_enabled(true);
  }
  ~AutocastScope() {
    if (!enabled_) return;
    torch_compat::set_cpu_autocast_enabled(previous_);
    at::autocast::clear_cache();
  }

 private:
  bool enabled_;
  bool previous_ = false;
};

// --disc-augment=shift-gain-polarity (gan_settings.h): per RIR a delay of 0-50 ms (zeros in front,
// the end dropped), a gain in [0.6, 1] and a random polarity; differentiable, so the generators'
// adversarial terms see their outputs through it too. Draws depend on (seed, tag, draw) only, so a
// resumed run augments exactly as an uninterrupted one.
torch::Tensor augment_for_discriminator(const torch::Tensor& x, uint64_t seed, const std::string& tag, long long draw) {
  constexpr int64_t kMaxDelaySamples = 800;  // 50 ms at 16 kHz
  const int64_t batch = x.size(0), length = x.size(2);
  Rng rng = Rng::for_item(seed, "disc-augment/" + tag + "/" + std::to_string(draw));
  std::vector<torch::Tensor> parts;
  for (int64_t b = 0; b < batch; ++b) {
    const int64_t delay = int64_t(rng.below(kMaxDelaySamples + 1));
    const double gain = (rng.uniform() < 0.5 ? -1.0 : 1.0) * rng.uniform(0.6, 1.0);
    torch::Tensor one = x.narrow(0, b, 1);
    if (delay > 0) one = torch::constant_pad_nd(one.narrow(2, 0, length - delay), {delay, 0}, 0.0);
    parts.push_back(one * gain);
  }
  return torch::cat(parts, 0);
}

class Trainer {
 public:
  // lanes: the joint step's two halves run at once, on two threads (joint_step says why that
  // changes no result).
  Trainer(CycleGan& model, BatchSampler& real, BatchSampler& synthetic, torch::Device device, bool lanes)
      : m_(model), real_(real), synthetic_(synthetic), device_(device),
        bfloat16_(model.settings.precision == GanPrecision::kBfloat16), lanes_(lanes) {}

  // What a discriminator sees of x (the identity unless --disc-augment).
  torch::Tensor seen(const torch::Tensor& x, const char* tag, long long draw) const {
    if (m_.settings.disc_augment == GanDiscAugment::kNone) return x;
    return augment_for_discriminator(x, m_.settings.seed, tag, draw);
  }

  StepLosses step(long long step_number) {
    // RMSProp normalises each update by its running gradient scale, so without history (ms0 = 0)
    // the first updates move every weight by ~lr whatever the gradient: the warm-up tames them.
    const long long warmup = m_.settings.warmup_steps;
    const double ramp = warmup > 0 ? std::min(1.0, double(step_number) / double(warmup)) : 1.0;
    const double g_rate = m_.settings.learning_rate;
    const double d_rate = m_.settings.disc_learning_rate > 0 ? m_.settings.disc_learning_rate : g_rate;
    for (size_t i = 0; i < m_.optimizers.size(); ++i) m_.optimizers[i].set_learning_rate(ramp * (i < 2 ? g_rate : d_rate));
    StepLosses L;
    if (m_.settings.generator_update == GanGeneratorUpdate::kJoint) {
      const int draws = 2 * m_.settings.disc_updates - 1;
      long long draw = (step_number - 1) * draws;
      joint_step(draw++, step_number, &L);
      for (int u = 1; u < m_.settings.disc_updates; ++u) {
        L.d_real = discriminator_step(m_.d_real, m_.g_real, m_.optimizers[2], draw++, true, "D_real");
        L.d_synthetic =
            discriminator_step(m_.d_synthetic, m_.g_synthetic, m_.optimizers[3], draw++, false, "D_synthetic");
      }
      return L;
    }
    const int draws = 2 * m_.settings.disc_updates + 2;
    long long draw = (step_number - 1) * draws;
    for (int u = 0; u < m_.settings.disc_updates; ++u) {
      L.d_real = discriminator_step(m_.d_real, m_.g_real, m_.optimizers[2], draw++, true, "D_real");
      L.d_synthetic =
          discriminator_step(m_.d_synthetic, m_.g_synthetic, m_.optimizers[3], draw++, false, "D_synthetic");
    }
    generator_step(draw++, true, &L);
    generator_step(draw++, false, &L);
    gan::update_generator_averages(m_, step_number);
    return L;
  }

 private:
  std::pair<torch::Tensor, torch::Tensor> batches(long long draw) {
    const int b = m_.settings.batch_size;
    return {real_.batch(draw, b).to(device_), synthetic_.batch(draw, b).to(device_)};
  }

  // A discriminator step on a fresh pair of batches and its own translation of the other domain.
  double discriminator_step(gan::Discriminator& d, gan::Generator& g, gan::TfRmsProp& optimizer,
                            long long draw, bool real_side, const char* name) {
    auto [x_real, x_synthetic] = batches(draw);
    const torch::Tensor& own = real_side ? x_real : x_synthetic;
    const torch::Tensor& other = real_side ? x_synthetic : x_real;
    torch::Tensor fake;
    {
      AutocastScope autocast(bfloat16_);
      torch::NoGradGuard no_grad;
      fake = g->forward(other);
    }
    return discriminator_update(d, optimizer, own, fake, draw, name);
  }

  // G_SR step (real_side) or G_RS step: adversarial + both cycle terms + own identity term.
  // Gradients reach only the stepped generator's weights; the other generator is differentiated
  // through (cycle) but not updated, as tf minimize(var_list=...) does.
  void generator_step(long long draw, bool real_side, StepLosses* L) {
    auto [x_real, x_synthetic] = batches(draw);
    gan::Generator& g = real_side ? m_.g_real : m_.g_synthetic;
    gan::Generator& f = real_side ? m_.g_synthetic : m_.g_real;
    gan::Discriminator& d = real_side ? m_.d_real : m_.d_synthetic;
    const torch::Tensor& source = real_side ? x_synthetic : x_real;   // translated by g
    const torch::Tensor& target = real_side ? x_real : x_synthetic;   // g's own domain
    torch::Tensor adv, cycle_source, cycle_target, identity, loss;
    {
      AutocastScope autocast(bfloat16_);
      torch::Tensor back;
      {
        torch::NoGradGuard no_grad;
        back = f->forward(target);  // for target -> f -> g, where only g is differentiated
      }
      const int64_t b = source.size(0);
      // One batched pass of g over [source; f(target); target].
      const gan::GeneratorPass pass = g->pass(torch::cat({source, back, target}, 0));
      const torch::Tensor& out = pass.output;
      // The translation pass's gains are the first b rows of the batched pass's.
      const torch::Tensor gains = generator_penalties(pass, b, 2 * b, real_side ? &L->gain_rms_db : nullptr);
      const torch::Tensor translated = out.narrow(0, 0, b);
      const torch::Tensor out_float = out.to(torch::kFloat);
      const torch::Tensor target_cycled = out_float.narrow(0, b, b);
      const torch::Tensor target_same = out_float.narrow(0, 2 * b, b);
      adv = (d->forward(seen(translated, real_side ? "g/fake_r" : "g/fake_s", draw)).to(torch::kFloat) - 1.0).pow(2).mean();
      cycle_source = (source - f->forward(translated).to(torch::kFloat)).abs().mean();
      cycle_target = (target - target_cycled).abs().mean();
      identity = (target - target_same).abs().mean();
      loss = adv + m_.settings.cycle_weight * (cycle_source + cycle_target) + m_.settings.identity_weight * identity +
             gains;
    }
    const double total = checked(loss, real_side ? "G_real" : "G_synthetic");
    apply(m_.optimizers[real_side ? 0 : 1], loss);
    if (real_side) {
      L->g_real = total;
      L->adv_real = adv.item<double>();
      L->cycle_real = cycle_target.item<double>();
      L->cycle_synthetic = cycle_source.item<double>();
      L->identity_real = identity.item<double>();
    } else {
      L->g_synthetic = total;
      L->adv_synthetic = adv.item<double>();
      L->identity_synthetic = identity.item<double>();
    }
  }

  // --generator-update=joint: both generators from one pair of batches (CycleGAN's reference
  // training): G_SR over [s; r] (translation, identity), G_RS over [r; s], then each over the
  // other's translation (cycles); one summed loss, whose gradient with respect to each
  // generator's weights is that generator's own loss gradient (the other terms do not depend on
  // it); both stepped. Then D_R and D_S train on this batch and its translations, detached.
  //
  // The loss splits into two halves that share no tensor but the weights (joint_half): the
  // translation into the real domain, its cycle back and D_R's verdict; and the mirror. Each
  // half's gradient is taken on its own and the two are added. That is the sum's gradient bit for
  // bit: every generator weight is used once in each half, so the one backward pass of the sum
  // also adds exactly two contributions per weight, and a + b = b + a in floating point
  // (GanCli.TwoThreadsTrainAsOne compares losses and translations). Each half then updates its own
  // discriminator, which reads no generator weight. So the halves can run at once on two threads
  // (--num-threads >= 2: lanes_), the generators stepped after both.
  void joint_step(long long draw, long long step_number, StepLosses* L) {
    auto [r, s] = batches(draw);
    // The identity halves also when only the gain identity asks for them (their L1 then has weight 0).
    const bool identity = m_.settings.identity_weight > 0 || m_.settings.identity_gain_weight > 0 ||
                          m_.settings.identity_direct_weight > 0;
    JointHalf to_real, to_synthetic;
    run_lanes([&] { to_real = joint_half(true, r, s, draw, identity); },
              [&] { to_synthetic = joint_half(false, s, r, draw, identity); });
    // The logged totals as the one summed loss has them: each generator's own terms, both cycles and
    // both generators' penalties.
    const double cw = m_.settings.cycle_weight, iw = m_.settings.identity_weight;
    const torch::Tensor cycles = cw * (to_real.cycle + to_synthetic.cycle) + to_real.penalties + to_synthetic.penalties;
    if (identity) {
      L->g_real = checked(to_real.adv + cycles + iw * to_real.identity, "G_real");
      L->g_synthetic = checked(to_synthetic.adv + cycles + iw * to_synthetic.identity, "G_synthetic");
      L->identity_real = to_real.identity.item<double>(), L->identity_synthetic = to_synthetic.identity.item<double>();
    } else {
      L->g_real = checked(to_real.adv + cycles, "G_real");
      L->g_synthetic = checked(to_synthetic.adv + cycles, "G_synthetic");
      L->identity_real = L->identity_synthetic = std::numeric_limits<double>::quiet_NaN();
    }
    L->adv_real = to_real.adv.item<double>(), L->adv_synthetic = to_synthetic.adv.item<double>();
    // cycle_l1_real is real RIRs' round trip (G_SR(G_RS(r))), which the other half computes.
    L->cycle_real = to_synthetic.cycle.item<double>(), L->cycle_synthetic = to_real.cycle.item<double>();
    L->gain_rms_db = to_real.gain_rms_db;
    L->d_real = to_real.d_loss, L->d_synthetic = to_synthetic.d_loss;
    // The generators step once both losses are known to be finite, each on a lane of its own (its
    // two gradient halves added, RMSProp, its weight average): elementwise work on separate
    // tensors, so the same arithmetic as one after the other.
    const size_t n_real = m_.optimizers[0].params().size();
    run_lanes([&] { step_generator(0, to_real.grads, to_synthetic.grads, 0, n_real, step_number); },
              [&] { step_generator(1, to_real.grads, to_synthetic.grads, n_real, to_real.grads.size(), step_number); });
  }

  // Generator `which` (0: G_SR, 1: G_RS) stepped on the sum of the halves' gradients [begin, end),
  // then its weight average (where the model keeps one) moved towards the new weights.
  void step_generator(int which, const std::vector<torch::Tensor>& a, const std::vector<torch::Tensor>& b,
                      size_t begin, size_t end, long long step_number) {
    std::vector<torch::Tensor> grads;
    for (size_t i = begin; i < end; ++i) grads.push_back(sum_defined(a[i], b[i]));
    m_.optimizers[size_t(which)].step(grads);
    gan::Generator& live = which == 0 ? m_.g_real : m_.g_synthetic;
    gan::Generator& average = which == 0 ? m_.g_real_average : m_.g_synthetic_average;
    if (average) gan::update_weight_average(*average, *live, m_.settings.generator_average_decay, step_number);
  }

  // One half of the joint step, into `own`'s domain: g (G_SR when real_side) translates `other`
  // (and `own`, for the identity terms), f translates that back (other's cycle), d judges it.
  struct JointHalf {
    torch::Tensor adv, cycle, identity, penalties;  // scalar terms, float32
    double gain_rms_db = std::numeric_limits<double>::quiet_NaN();
    std::vector<torch::Tensor> grads;  // the half's loss gradient: G_SR's weights, then G_RS's
    double d_loss = 0;                 // d's update on own and the (detached) translations
  };

  JointHalf joint_half(bool real_side, const torch::Tensor& own, const torch::Tensor& other, long long draw,
                       bool identity) {
    gan::Generator& g = real_side ? m_.g_real : m_.g_synthetic;
    gan::Generator& f = real_side ? m_.g_synthetic : m_.g_real;
    gan::Discriminator& d = real_side ? m_.d_real : m_.d_synthetic;
    const int64_t b = own.size(0);
    JointHalf h;
    torch::Tensor fake, loss;
    {
      AutocastScope autocast(bfloat16_);
      // With all identity weights 0 the identity half of each pass has no gradient (0 x its L1), so
      // it is not computed: 16 generator passes per step instead of 24. Each RIR's output and
      // gradient do not depend on the rest of its batch (no batch statistics;
      // GanNetworks.OutputAndGradientOfARirDoNotDependOnTheRestOfItsBatch). The identity columns of
      // the loss log then read "nan" (not measured).
      const gan::GeneratorPass pass = g->pass(identity ? torch::cat({other, own}, 0) : other);
      h.penalties = generator_penalties(pass, b, b, real_side ? &h.gain_rms_db : nullptr);
      fake = pass.output.narrow(0, 0, b);
      const torch::Tensor back = f->forward(fake).to(torch::kFloat);
      h.adv = (d->forward(seen(fake, real_side ? "g/fake_r" : "g/fake_s", draw)).to(torch::kFloat) - 1.0).pow(2).mean();
      h.cycle = (other - back).abs().mean();
      loss = h.adv + m_.settings.cycle_weight * h.cycle + h.penalties;
      if (identity) {
        h.identity = (own - pass.output.narrow(0, b, b).to(torch::kFloat)).abs().mean();
        loss = loss + m_.settings.identity_weight * h.identity;
      }
    }
    std::vector<torch::Tensor> params = m_.optimizers[0].params();
    const auto& more = m_.optimizers[1].params();
    params.insert(params.end(), more.begin(), more.end());
    h.grads = torch::autograd::grad({loss}, params, {}, false, false, /*allow_unused=*/true);
    h.d_loss = discriminator_update(d, m_.optimizers[real_side ? 2 : 3], own, fake.detach(), draw,
                                    real_side ? "D_real" : "D_synthetic");
    return h;
  }

  static torch::Tensor sum_defined(const torch::Tensor& a, const torch::Tensor& b) {
    if (!a.defined()) return b;
    return b.defined() ? a + b : a;
  }

  // Runs `first` and `second`, on two threads when lanes_ (the caller's and one more), else in
  // turn. An exception from either is rethrown after both have finished.
  template <typename F, typename G>
  void run_lanes(F&& first, G&& second) {
    if (!lanes_) {
      first();
      second();
      return;
    }
    std::future<void> other = std::async(std::launch::async, std::forward<F>(first));
    std::exception_ptr failure;
    try {
      second();
    } catch (...) {
      failure = std::current_exception();
    }
    other.get();  // rethrows first's exception (which wins: it is the real side's)
    if (failure) std::rethrow_exception(failure);
  }

  // The penalties on a generator's pass: on its first `rows` (its translations),
  // --correction-weight's on the waveform correction (residual and band-gain) and --gain-weight's
  // on the log gains (band-gain; their RMS in dB into *rms_db); on the `rows` from `identity_first`
  // (its identity rows: RIRs of its own domain, where the pass has them), --identity-gain-weight's
  // on the log gains gan::identity_held_gains() selects (the knots after the direct sound, and the
  // direct sound of --identity-direct-bands bands; why: its comment) and --identity-direct-weight's
  // on the other bands' direct sound. Zero where there is none.
  torch::Tensor generator_penalties(const gan::GeneratorPass& pass, int64_t rows, int64_t identity_first,
                                    double* rms_db) const {
    torch::Tensor penalty;  // undefined until a term exists, so that it lives on the terms' device
    const auto add = [&penalty](const torch::Tensor& term) { penalty = penalty.defined() ? penalty + term : term; };
    const torch::Tensor& c = pass.correction_ms;
    if (c.defined() && m_.settings.correction_weight > 0) {
      add(m_.settings.correction_weight * c.narrow(0, 0, rows).mean());
    }
    const torch::Tensor& v = pass.log_gains;
    if (v.defined()) {
      const torch::Tensor mean_square = v.narrow(0, 0, rows).to(torch::kFloat).pow(2).mean();
      if (rms_db) *rms_db = 20.0 / std::log(10.0) * std::sqrt(mean_square.item<double>());
      add(m_.settings.gain_weight * mean_square);
      if (v.size(0) >= identity_first + rows) {  // the pass has identity rows
        const torch::Tensor own = v.narrow(0, identity_first, rows);
        const int direct_bands = m_.settings.identity_direct_bands;
        if (m_.settings.identity_gain_weight > 0) {
          const torch::Tensor held = gan::identity_held_gains(own, direct_bands);
          add(m_.settings.identity_gain_weight * held.to(torch::kFloat).pow(2).mean());
        }
        if (m_.settings.identity_direct_weight > 0) {
          const torch::Tensor direct = gan::direct_gains_above(own, direct_bands);
          if (direct.defined()) add(m_.settings.identity_direct_weight * direct.to(torch::kFloat).pow(2).mean());
        }
      }
    }
    // None: a CPU zero, which adds to a loss on any device (a 0-dim tensor acts as a scalar).
    return penalty.defined() ? penalty : torch::zeros({}, torch::kFloat);
  }

  // LSGAN: 5 * [mean((D(own domain) - 1)^2) + mean(D(translated into it)^2)].
  double discriminator_update(gan::Discriminator& d, gan::TfRmsProp& optimizer, const torch::Tensor& own,
                              const torch::Tensor& fake, long long draw, const char* name) {
    torch::Tensor loss;
    {
      AutocastScope autocast(bfloat16_);
      const std::string tag = name;
      loss = kDiscriminatorWeight * ((d->forward(seen(own, (tag + "/own").c_str(), draw)).to(torch::kFloat) - 1.0).pow(2).mean() +
                                     d->forward(seen(fake, (tag + "/fake").c_str(), draw)).to(torch::kFloat).pow(2).mean());
    }
    const double value = checked(loss, name);
    apply(optimizer, loss);
    return value;
  }

  CycleGan& m_;
  BatchSampler& real_;
  BatchSampler& synthetic_;
  torch::Device device_;
  bool bfloat16_;
  bool lanes_;
};

// The collapse guard's probe: G_SR over a fixed batch of synthetic RIRs. A collapsed generator's
// outputs are silent or one template: their spread about their mean is a small fraction of the
// inputs' (distinct RIRs: ~1 of their norm). Returns why it collapsed, or "".
constexpr double kSilentFraction = 1e-3;   // output norm / input norm below this: silent
constexpr double kTemplateFraction = 0.1;  // relative spread of outputs / of inputs below this
std::string collapse_reason(gan::Generator& g, const torch::Tensor& probe) {
  torch::NoGradGuard no_grad;
  const torch::Tensor x = probe.to(torch::kFloat).flatten(1).cpu();
  const torch::Tensor y = g->forward(probe).to(torch::kFloat).flatten(1).cpu();
  auto spread = [](const torch::Tensor& v, double* norm) {
    *norm = v.norm(2, {1}).mean().item<double>();
    return (v - v.mean(0, true)).norm(2, {1}).mean().item<double>() / std::max(*norm, 1e-30);
  };
  double nx = 0, ny = 0;
  const double sx = spread(x, &nx), sy = spread(y, &ny);
  std::ostringstream os;
  os.precision(3);
  if (!(ny >= kSilentFraction * nx)) {
    os << "G_SR's outputs are silent (mean norm " << ny << " against " << nx << " for its inputs)";
  } else if (!(sy >= kTemplateFraction * sx)) {
    os << "G_SR's outputs are nearly equal across inputs (relative spread " << sy << " against " << sx
       << " for its inputs): it outputs one template, whatever the input";
  }
  return os.str();
}

bool parameters_finite(CycleGan& model) {
  torch::NoGradGuard no_grad;
  torch::nn::Module* modules[4] = {model.g_real.get(), model.g_synthetic.get(), model.d_real.get(),
                                   model.d_synthetic.get()};
  for (auto* m : modules) {
    for (const auto& p : m->parameters()) {
      if (!torch::isfinite(p).all().item<bool>()) return false;
    }
  }
  return true;
}

// Finite weights can still be too large to use (an exploding learning rate leaves ~1e30 weights
// that make Inf outputs): a checkpoint is good only if both generators translate the probe.
bool generators_finite_on(CycleGan& model, const torch::Tensor& probe) {
  torch::NoGradGuard no_grad;
  return torch::isfinite(model.g_real->forward(probe)).all().item<bool>() &&
         torch::isfinite(model.g_synthetic->forward(probe)).all().item<bool>();
}

// Keeps the header and the rows up to `last_step` (rows after the resumed checkpoint were lost
// with the interrupted run and are run again).
void truncate_loss_log(const std::string& path, long long last_step) {
  std::vector<std::string> kept;
  std::ifstream in(path);
  std::string line;
  bool first = true;
  while (std::getline(in, line)) {
    if (first) {
      first = false;
      continue;
    }
    const size_t comma = line.find(',');
    if (comma == std::string::npos) continue;
    const long long step = std::atoll(line.substr(0, comma).c_str());
    if (step >= 1 && step <= last_step) kept.push_back(line);
  }
  AtomicTextFile out(path);
  out.stream() << kLogHeader << "\n";
  for (const auto& row : kept) out.stream() << row << "\n";
  out.commit();
}

std::string format_row(long long step, const StepLosses& L, double seconds) {
  std::ostringstream os;
  os.precision(9);
  os << step << ',' << L.d_real << ',' << L.d_synthetic << ',' << L.g_real << ',' << L.g_synthetic << ','
     << L.adv_real << ',' << L.adv_synthetic << ',' << L.cycle_real << ',' << L.cycle_synthetic << ','
     << L.identity_real << ',' << L.identity_synthetic << ',' << L.gain_rms_db << ',';
  os.precision(4);
  os << seconds;
  return os.str();
}

void validate(const GanTrainOptions& o) {
  if (o.real_list.empty() || o.synthetic_list.empty()) throw Error("--real and --synthetic are required");
  if (o.steps < 1) throw Error("--steps must be >= 1");
  check_gan_settings(o.model, "");
  if (o.num_threads < 1) throw Error("--num-threads must be >= 1");
  if (o.checkpoint_every < 1) throw Error("--checkpoint-every must be >= 1");
  if (o.collapse_check_every < 0) throw Error("--collapse-check-every must be >= 0");
  if (o.model.precision == GanPrecision::kBfloat16 && o.device != ComputeDevice::kCpu) {
    throw Error("--precision=bfloat16 is for --device=cpu");
  }
  if (o.model.precision == GanPrecision::kBfloat16) require_float32_sums_for_bfloat16("ts-rirgan-train");
}

// Every stored setting must match, but the learning rates (a hand-made schedule), the lists (the
// same data may have moved) and the initialisers (they only matter when a model is created);
// compared on the settings text, so that a new setting is compared too.
void check_resume_settings(const GanSettings& saved, const GanSettings& asked, const std::string& where) {
  check_same_architecture(saved, asked, where + " (give the --width, --decoder, --generator and --disc-view options it was trained with)");
  const std::set<std::string> may_change = {"learning_rate", "disc_learning_rate", "real_list", "synthetic_list",
                                            "init", "rmsprop_initial_ms"};
  const SettingsValues was = gan_settings_values(saved), now = gan_settings_values(asked);
  std::string diff;
  for (const auto& [key, value] : was) {
    if (may_change.count(key) || (now.count(key) && now.at(key) == value)) continue;
    std::string option = key;
    std::replace(option.begin(), option.end(), '_', '-');
    diff += " --" + option + "=" + value;
  }
  if (!diff.empty()) {
    throw Error(where + ": the model was trained with" + diff + "; --resume continues exactly, so give the same settings (only the learning rates may change)");
  }
}

// Where a model dir keeps what training writes.
struct ModelDirPaths {
  explicit ModelDirPaths(const std::string& dir)
      : settings((fs::path(dir) / "settings.txt").string()),
        checkpoint((fs::path(dir) / "checkpoint.pt").string()),
        log((fs::path(dir) / "loss_log.csv").string()),
        curves((fs::path(dir) / "loss_curves.svg").string()) {}
  std::string settings, checkpoint, log, curves;
};

}  // namespace

GanSettings settings_to_store(const GanTrainOptions& o) {
  GanSettings settings = o.model;
  // The original generator has no correction to band-limit: the option is the residual's only.
  if (settings.generator == GanGenerator::kOriginal) settings.correction_max_hz = 0.0;
  // Only band-gain generators have gains to penalise; 0 otherwise, as in the settings of models
  // made before the option, so that those resume under today's defaults.
  if (settings.generator != GanGenerator::kBandGain) {
    settings.gain_weight = settings.identity_gain_weight = settings.identity_direct_weight = 0.0;
  }
  // The original generator has no correction to penalise.
  if (settings.generator == GanGenerator::kOriginal) settings.correction_weight = 0.0;
  settings.real_list = absolute_path(o.real_list);
  settings.synthetic_list = absolute_path(o.synthetic_list);
  return settings;
}

namespace {

// The settings this run trains with: settings_to_store's; on --resume checked against the saved
// ones, whose initialisers are kept (a new learning rate, the one setting a resumed run may
// change, is written back).
GanSettings plan_settings(const GanTrainOptions& o, const ModelDirPaths& paths) {
  GanSettings settings = settings_to_store(o);
  if (!o.resume) {
    if (fs::exists(paths.checkpoint)) {
      throw Error(o.model_dir + " already holds a checkpoint; use --resume to continue it, or another dir");
    }
    return settings;
  }
  if (!fs::exists(paths.checkpoint)) throw Error("--resume: no checkpoint " + paths.checkpoint);
  const GanSettings saved = read_gan_settings_file(paths.settings);
  check_resume_settings(saved, settings, paths.settings);
  // The initialisers only matter when a model is created.
  settings.init = saved.init;
  settings.rmsprop_initial_ms = saved.rmsprop_initial_ms;
  // A new learning rate is the one setting a resumed run may change (a hand-made schedule).
  if (saved.learning_rate != settings.learning_rate) {
    log_info("learning rate changed from " + format_double(saved.learning_rate, 10) + " to " +
             format_double(settings.learning_rate, 10));
    write_gan_settings_file(paths.settings, settings);
  }
  return settings;
}

// A fresh model dir (its settings and an empty loss log written), or the resumed checkpoint
// loaded into `model` (the log cut back to its step). Returns the step the model is at.
long long open_model(const GanTrainOptions& o, const ModelDirPaths& paths, CycleGan& model) {
  if (o.resume) {
    const long long step = gan::load_checkpoint(paths.checkpoint, model);
    log_info("resumed " + paths.checkpoint + " at step " + std::to_string(step));
    truncate_loss_log(paths.log, step);
    return step;
  }
  std::error_code ec;
  fs::create_directories(o.model_dir, ec);
  if (!fs::is_directory(o.model_dir)) throw Error("cannot create model dir " + o.model_dir);
  write_gan_settings_file(paths.settings, model.settings);
  truncate_loss_log(paths.log, 0);
  log_info("model width " + std::to_string(o.model.width) + ", decoder " + choice_name(kGanDecoderNames, o.model.decoder) +
           ", generator " + choice_name(kGanGeneratorNames, o.model.generator) + ": " +
           std::to_string(gan::count_parameters(*model.g_real)) + " parameters per generator, " +
           std::to_string(gan::count_parameters(*model.d_real)) + " per discriminator");
  return 0;
}

// Whether the joint step's two halves run at once on two threads: with --num-threads >= 2 on the
// CPU. Why: at width 16 one step's operators are too small to split among threads (2 threads gave
// no gain, bench/RESULTS.md), while the halves are independent and equal in size. On a GPU the
// halves would queue on one stream: in turn.
bool joint_lanes(const GanTrainOptions& o, const GanSettings& settings, torch::Device device) {
  return o.num_threads >= 2 && settings.generator_update == GanGeneratorUpdate::kJoint && device.is_cpu();
}

// The steps after the model's up to --steps: each logged, the collapse guard and the checkpoints
// on their schedules, progress on stderr; stops between steps on SIGINT/SIGTERM with a checkpoint.
class StepLoop {
 public:
  using Clock = std::chrono::steady_clock;
  StepLoop(const GanTrainOptions& o, const ModelDirPaths& paths, CycleGan& model, BatchSampler& real,
           BatchSampler& synthetic, torch::Device device, long long step)
      : o_(o), paths_(paths), model_(model), trainer_(model, real, synthetic, device, joint_lanes(o, model.settings, device)),
        probe_(synthetic.rirs().narrow(0, 0, std::min<int64_t>(8, synthetic.rirs().size(0))).to(device)),
        step_(step), checkpoint_step_(step) {
    result_.first_step = step + 1;
    result_.last_step = step;
  }

  GanTrainResult run() {
    std::ofstream log(paths_.log, std::ios::app);
    if (!log) throw Error("cannot append to " + paths_.log);
    // The curves are drawn however training ends (done, interrupted, collapse, non-finite loss).
    CurvesOnExit curves_on_exit{log, paths_.log, paths_.curves};
    try {
      train_steps(log);
      if (checkpoint_step_ != step_) save();
    } catch (const NonFiniteLoss& e) {
      log.flush();
      throw Error("step " + std::to_string(step_ + 1) + ": " + e.what() + "; training stopped. The last good checkpoint " +
                  kept_checkpoint(true) + " is kept; lower --learning-rate or check the input RIRs");
    }
    return finish();
  }

 private:
  struct CurvesOnExit {
    std::ofstream& log;
    std::string csv, svg;
    ~CurvesOnExit() {
      try {
        log.flush();
        write_loss_curves_svg(csv, svg);
      } catch (...) {
      }
    }
  };

  void train_steps(std::ofstream& log) {
    StopRequestGuard stop;
    while (step_ < o_.steps) {
      if (stop.stop_requested()) {
        result_.interrupted = true;
        return;
      }
      const auto t0 = Clock::now();
      // Trainer::step also moves the generators' weight averages.
      const StepLosses losses = trainer_.step(step_ + 1);
      ++step_;
      const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
      total_step_s_ += dt;
      log << format_row(step_, losses, dt) << '\n' << std::flush;
      result_.last_step = step_;
      if (o_.collapse_check_every > 0 && step_ % o_.collapse_check_every == 0) check_collapse();
      if (step_ % o_.checkpoint_every == 0) save();
      report_progress(losses);
    }
  }

  void check_collapse() const {
    const std::string why = collapse_reason(model_.g_real, probe_);
    if (why.empty()) return;
    throw Error("step " + std::to_string(step_) + ": generator collapse: " + why + ". Training stopped; the last checkpoint " +
                kept_checkpoint(false) +
                ". Try another --seed, a longer --warmup-steps, a lower --learning-rate or "
                "--generator=residual (--collapse-check-every=0 disables this check)");
  }

  // "(step N) is kept" material: which checkpoint survives a stop.
  std::string kept_checkpoint(bool with_path) const {
    if (checkpoint_step_ == 0) return "(none was written)";
    return "(step " + std::to_string(checkpoint_step_) + (with_path ? ", " + paths_.checkpoint : std::string()) + ")" +
           (with_path ? "" : " is kept");
  }

  void save() {
    if (!parameters_finite(model_)) {
      throw NonFiniteLoss("the parameters after step " + std::to_string(step_) + " are not finite");
    }
    if (!generators_finite_on(model_, probe_)) {
      throw NonFiniteLoss("the generators after step " + std::to_string(step_) + " give outputs that are not finite");
    }
    gan::save_checkpoint(paths_.checkpoint, model_, step_);
    gan::save_generator_files(paths_.checkpoint, model_, step_);
    checkpoint_step_ = step_;
  }

  void report_progress(const StepLosses& losses) {
    const auto now = Clock::now();
    if (step_ != result_.first_step && step_ != o_.steps &&
        std::chrono::duration<double>(now - last_progress_).count() < o_.progress_interval_s) {
      return;
    }
    last_progress_ = now;
    const double per_step = total_step_s_ / double(step_ - result_.first_step + 1);
    std::ostringstream os;
    os.precision(4);
    os << "step " << step_ << "/" << o_.steps << "  D_R " << losses.d_real << "  D_S " << losses.d_synthetic
       << "  G_SR " << losses.g_real << "  G_RS " << losses.g_synthetic << "  " << per_step << " s/step, "
       << "ETA " << int(per_step * double(o_.steps - step_)) << " s";
    log_info(os.str());
  }

  GanTrainResult finish() {
    if (result_.interrupted) {
      log_warning("interrupted after step " + std::to_string(step_) + "; checkpoint written to " + paths_.checkpoint +
                  " (continue with --resume)");
    }
    const long long steps_run = step_ - result_.first_step + 1;
    result_.mean_step_s = steps_run > 0 ? total_step_s_ / double(steps_run) : 0.0;
    result_.peak_rss_mb = peak_rss_mb();
    std::ostringstream os;
    os.precision(4);
    os << "done: steps " << result_.first_step << ".." << step_ << ", " << result_.mean_step_s << " s/step, peak RSS "
       << result_.peak_rss_mb << " MB";
    log_info(os.str());
    return result_;
  }

  const GanTrainOptions& o_;
  const ModelDirPaths& paths_;
  CycleGan& model_;
  Trainer trainer_;
  const torch::Tensor probe_;
  long long step_, checkpoint_step_;
  GanTrainResult result_;
  double total_step_s_ = 0.0;
  Clock::time_point last_progress_ = Clock::now();
};

}  // namespace

GanTrainResult train_ts_rirgan(const GanTrainOptions& o) {
  validate(o);
  tune_memory_for_torch();
  set_openblas_threads(1);
  const torch::Device device = gan::torch_device(o.device);
  const ModelDirPaths paths(o.model_dir);
  const GanSettings settings = plan_settings(o, paths);
  // Two lanes share the threads: each runs its half's operators on half of them.
  gan::set_torch_threads(joint_lanes(o, settings, device) ? o.num_threads / 2 : o.num_threads);
  BatchSampler real(o.model.seed, "real", load_domain(o.real_list, "real", o.model.batch_size, o.num_threads));
  BatchSampler synthetic(o.model.seed, "synthetic",
                         load_domain(o.synthetic_list, "synthetic", o.model.batch_size, o.num_threads));
  // The model dir is the toolkit's: never one holding a user's files, never an input (its lists were
  // noted as inputs while loading the domains).
  claim_output_dir(o.model_dir, {"settings.txt", "checkpoint.pt", "loss_log.csv", "generator-g_real.pt",
                                 "generator-g_synthetic.pt"});
  torch::manual_seed(o.model.seed);
  CycleGan model(settings, device);
  const long long step = open_model(o, paths, model);
  if (step >= o.steps) {
    log_info("the checkpoint is already at step " + std::to_string(step) + " >= --steps");
    GanTrainResult result;
    result.first_step = step + 1;
    result.last_step = step;
    result.peak_rss_mb = peak_rss_mb();
    return result;
  }
  return StepLoop(o, paths, model, real, synthetic, device, step).run();
}

}  // namespace tsrir

// The discriminators' band-level view (src/gan/gan_band_envelope.h), against signals whose band
// levels are known by construction in another formulation: two noises decaying at their own
// rates, one low-passed and one high-passed by time-domain recursions written here (not the
// view's FFT band split), must show each band's own decay rate in dB per second; the map is the
// same at any gain; a discriminator with the view keeps the waveform critic's weights and adds
// the envelope critic's logit; and the separable critic's logit has no term in which two bands meet.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "gan/gan_band_envelope.h"
#include "gan/gan_band_gain.h"
#include "gan/gan_networks.h"

using namespace tsrir;
using namespace tsrir::gan;

namespace {

constexpr double kFs = 16000.0;
constexpr int64_t kLength = 16384;

enum class Shape { kWhite, kLow, kHigh };

// Gaussian noise with amplitude exp(-3 ln10 t / T60) (60 dB of energy in t60_s): white, low-passed
// by four one-pole sections at 100 Hz (-24 dB per octave above) or high-passed by four first
// differences ((2 sin(pi f / fs))^4: -52 dB at 125 Hz relative to 1 at 4 kHz). Peak 1.
std::vector<double> decaying_noise(double t60_s, Shape shape, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<double> x(kLength);
  for (auto& v : x) v = gauss(rng);
  if (shape == Shape::kLow) {
    const double a = std::exp(-2.0 * M_PI * 100.0 / kFs);
    for (int section = 0; section < 4; ++section) {
      double y = 0;
      for (auto& v : x) v = y = a * y + (1 - a) * v;
    }
  } else if (shape == Shape::kHigh) {
    for (int section = 0; section < 4; ++section) {
      for (int64_t i = kLength - 1; i > 0; --i) x[i] -= x[i - 1];
    }
  }
  double peak = 0;
  for (int64_t i = 0; i < kLength; ++i) {
    x[i] *= std::exp(-3.0 * std::log(10.0) * (i / kFs) / t60_s);
    peak = std::max(peak, std::abs(x[i]));
  }
  for (auto& v : x) v /= peak;
  return x;
}

torch::Tensor levels_of(const torch::Tensor& x, const GanEnvelopeMap& map = {}) {
  return band_log_envelope(x, envelope_window(), envelope_band_responses(), map);
}

const GanEnvelopeMap kReDirectSound{GanEnvelopeReference::kDirectSound};

torch::Tensor as_batch(const std::vector<double>& x) {
  return torch::tensor(x, torch::kFloat).view({1, 1, -1});
}

// Least-squares slope of band b's level (dB) over frames whose centres lie in [from_s, to_s], dB/s.
double slope_db_per_s(const torch::Tensor& levels, int b, double from_s, double to_s) {
  double st = 0, sl = 0, stt = 0, stl = 0, n = 0;
  for (int64_t f = 0; f < levels.size(2); ++f) {
    const double t = (f * kEnvelopeHop + kEnvelopeFrameLength / 2.0) / kFs;
    if (t < from_s || t > to_s) continue;
    const double l = 20.0 * levels[0][b][f].item<double>();
    st += t, sl += l, stt += t * t, stl += t * l, n += 1;
  }
  return (n * stl - st * sl) / (n * stt - st * st);
}

}  // namespace

TEST(BandEnvelope, EachBandShowsItsOwnDecayRate) {
  // Low band T60 0.8 s (-75 dB/s), high band 0.2 s (-300 dB/s): the view must tell them apart
  // within 10 % (the fits' noise: ~3 % for the low band's few degrees of freedom per frame).
  for (uint32_t seed : {11u, 12u, 13u}) {
    const auto low = decaying_noise(0.8, Shape::kLow, seed), high = decaying_noise(0.2, Shape::kHigh, seed + 100);
    std::vector<double> sum(kLength);
    for (int64_t i = 0; i < kLength; ++i) sum[i] = low[i] + high[i];
    const torch::Tensor levels = levels_of(as_batch(sum));
    ASSERT_EQ(levels.size(1), kBandGainBands);
    ASSERT_EQ(levels.size(2), (kLength - kEnvelopeFrameLength) / kEnvelopeHop + 1);
    EXPECT_NEAR(slope_db_per_s(levels, 0, 0.05, 0.6), -75.0, 7.5) << "seed " << seed;
    EXPECT_NEAR(slope_db_per_s(levels, kBandGainBands - 1, 0.03, 0.18), -300.0, 30.0) << "seed " << seed;
    EXPECT_LE(levels.max().item<double>(), 1e-6);
    EXPECT_GE(levels.min().item<double>(), GanEnvelopeMap{}.floor_db / 20.0 - 1e-6);
  }
}

TEST(BandEnvelope, TheMapIsTheSameAtAnyGain) {
  const torch::Tensor x = as_batch(decaying_noise(0.5, Shape::kHigh, 7)) + as_batch(decaying_noise(0.3, Shape::kLow, 8));
  for (GanEnvelopeReference reference : {GanEnvelopeReference::kLoudestCell, GanEnvelopeReference::kDirectSound}) {
    const GanEnvelopeMap map{reference};
    const torch::Tensor a = levels_of(x, map), b = levels_of(x * 0.01, map);
    const torch::Tensor c = levels_of(-3.0 * x, map);
    EXPECT_LT((a - b).abs().max().item<double>(), 1e-4);
    EXPECT_LT((a - c).abs().max().item<double>(), 1e-4);
  }
}

TEST(BandEnvelope, DirectSoundReferenceIsThePeaksEnergy) {
  // Two impulses, amplitudes 1 and b, each at a frame's centre (frames 1 and 13: 96 ms apart): the
  // second's frame holds b^2 of the first's energy, so summed over the bands (which partition a
  // frame's energy) its level re the direct sound is 20 log10(b) dB; the first's is 0 dB.
  for (double b : {0.5, 0.1, 0.01}) {
    std::vector<double> x(kLength, 0.0);
    const int64_t first = kEnvelopeFrameLength / 2 + kEnvelopeHop, second = first + 12 * kEnvelopeHop;
    x[first] = 1.0, x[second] = b;
    const torch::Tensor levels = levels_of(as_batch(x), kReDirectSound);
    const auto frame_db = [&](int64_t f) {
      return 10.0 * std::log10(torch::pow(10.0, 2.0 * levels.select(2, f)).sum().item<double>());
    };
    EXPECT_NEAR(frame_db(1), 0.0, 0.01) << "b " << b;
    EXPECT_NEAR(frame_db(13), 20.0 * std::log10(b), 0.01) << "b " << b;
  }
}

TEST(BandEnvelope, DirectSoundReferenceIgnoresWhichCellIsLoudest) {
  // An impulse of 2 (the direct sound), a low-passed decaying noise from 5 ms (peak 0.03), and a
  // high-passed burst at 20-40 ms (an early reflection cluster) whose level varies 12 dB while its
  // peak stays below the impulse's: in the louder form the burst's frames hold the loudest cell.
  // Re the direct sound the low band's late frames (from 100 ms, after the burst's) do not move;
  // re the loudest cell they move by the burst's change (the control that the statistic sees a
  // shift of the reference). Over seeds.
  for (uint32_t seed : {21u, 22u, 23u}) {
    const auto low = decaying_noise(0.6, Shape::kLow, seed), high = decaying_noise(10.0, Shape::kHigh, seed + 50);
    const auto signal_with_burst = [&](double burst_gain) {
      std::vector<double> x(kLength, 0.0);
      x[160] = 2.0;
      for (int64_t i = 240; i < kLength; ++i) x[i] += 0.03 * low[i - 240];
      for (int64_t i = 480; i < 800; ++i) x[i] += burst_gain * high[i];
      return as_batch(x);
    };
    const torch::Tensor quiet = signal_with_burst(0.25), loud = signal_with_burst(1.0);
    ASSERT_EQ(quiet.abs().argmax().item<int64_t>(), 160);
    ASSERT_EQ(loud.abs().argmax().item<int64_t>(), 160);
    const auto late_low_shift_db = [&](GanEnvelopeReference reference) {
      const torch::Tensor a = levels_of(quiet, {reference}), b = levels_of(loud, {reference});
      return 20.0 * (b - a).select(1, 0).narrow(1, 13, 60).abs().max().item<double>();
    };
    EXPECT_LT(late_low_shift_db(GanEnvelopeReference::kDirectSound), 1e-3) << "seed " << seed;
    EXPECT_GT(late_low_shift_db(GanEnvelopeReference::kLoudestCell), 6.0) << "seed " << seed;
  }
}

TEST(BandEnvelope, NothingBelowTheFloorIsToldApart) {
  // White noise decaying 60 dB in 0.3 s falls ~200 dB over the slice. The map is 10 log10(E / ref +
  // 10^(floor / 10)): where the first form (80 dB) reads above -40 dB, a 60 dB floor adds at most
  // 10 log10(1 + 10^-2) = 0.04 dB; where it reads below -78 dB (the true level 2.3+ dB under its
  // floor), the 60 dB map reads its floor within 10 log10(1 + 10^-1.8) = 0.07 dB. Over seeds.
  for (uint32_t seed : {31u, 32u, 33u}) {
    const torch::Tensor x = as_batch(decaying_noise(0.3, Shape::kWhite, seed));
    const torch::Tensor first_form = 20.0 * levels_of(x), at_60 = 20.0 * levels_of(x, {GanEnvelopeReference::kLoudestCell, -60.0});
    const torch::Tensor loud = first_form > -40.0, quiet = first_form < -78.0;
    ASSERT_GT(loud.sum().item<int64_t>(), 100);
    ASSERT_GT(quiet.sum().item<int64_t>(), 100);
    EXPECT_LT((at_60 - first_form).masked_select(loud).abs().max().item<double>(), 0.045) << "seed " << seed;
    EXPECT_LT((at_60 + 60.0).masked_select(quiet).abs().max().item<double>(), 0.07) << "seed " << seed;
    EXPECT_GE(at_60.min().item<double>(), -60.0 - 1e-3) << "seed " << seed;
  }
}

namespace {
// How much a relative change of the late samples of white noise (250-350 ms, 50-70 dB down in a
// 0.3 s decay; every band well above the view's floor in both spans)
// moves a critic's logit against one of earlier ones (60-90 ms, 12-18 dB down; after the frames
// of the loudest cell, whose level every cell is measured against): the mean of
// |d logit / d x_i| * |x_i| over each span, late / early.
template <typename Critic>
double late_to_early_reach(Critic& critic, uint32_t seed) {
  torch::Tensor x = as_batch(decaying_noise(0.3, Shape::kWhite, seed)).requires_grad_(true);
  critic->forward(x).sum().backward();
  const torch::Tensor reach = x.grad().abs().squeeze() * x.detach().abs().squeeze();
  return reach.narrow(0, 4000, 1600).mean().item<double>() / reach.narrow(0, 960, 480).mean().item<double>();
}
}  // namespace

TEST(BandEnvelope, ALateLevelChangeReachesTheCriticsGradient) {
  // A waveform critic's gradient at a sample is about the same at any level, so a sample 50 dB
  // down moves its logit ~300x less than a loud one by the same relative change; the envelope's
  // is per dB, level-free. Both at their initial weights, over seeds.
  for (uint32_t seed : {1u, 2u, 3u}) {
    torch::manual_seed(seed);
    EnvelopeCritic envelope(8, kLength, GanInit::kHe);
    Discriminator waveform(8, 25, GanInit::kHe, GanDiscView::kWaveform);
    const double envelope_reach = late_to_early_reach(envelope, seed), waveform_reach = late_to_early_reach(waveform, seed);
    EXPECT_GT(envelope_reach, 0.1) << "seed " << seed;
    EXPECT_LT(waveform_reach, 0.02) << "seed " << seed;  // the control: the statistic can tell them apart
  }
}

namespace {
// The waveform layers of a discriminator with an envelope view draw the same initial weights as one
// without (the envelope critic is built after them).
void expect_waveform_weights_kept(Discriminator& plain, Discriminator& with_view) {
  const auto p = plain->named_parameters(), q = with_view->named_parameters();
  for (const auto& item : p) {
    ASSERT_TRUE(q.contains(item.key())) << item.key();
    EXPECT_TRUE(torch::equal(item.value(), q[item.key()])) << item.key();
  }
  EXPECT_GT(q.size(), p.size());
}

// A waveform-only discriminator and one with `view`, each built from `seed`; their shared waveform
// layers checked equal.
std::pair<Discriminator, Discriminator> plain_and_with_view(GanDiscView view, uint64_t seed,
                                                           const GanEnvelopeMap& map = {}) {
  torch::manual_seed(seed);
  Discriminator plain(4, 25, GanInit::kHe, GanDiscView::kWaveform);
  torch::manual_seed(seed);
  Discriminator with_view(4, 25, GanInit::kHe, view, map);
  expect_waveform_weights_kept(plain, with_view);
  return {plain, with_view};
}
}  // namespace

TEST(BandEnvelope, DiscriminatorWithTheViewAddsTheEnvelopeCritic) {
  auto [plain, both] = plain_and_with_view(GanDiscView::kWaveformEnvelope, 5);
  auto q = both->named_parameters();
  // And its logit is the waveform's plus the envelope critic's.
  torch::NoGradGuard no_grad;
  const torch::Tensor x = torch::randn({3, 1, kLength}) * 0.1;
  const torch::Tensor difference = both->forward(x) - plain->forward(x);
  EXPECT_GT(difference.abs().max().item<double>(), 0.0);
  // Shifting the envelope critic's output bias shifts exactly that part.
  const torch::Tensor before = both->forward(x);
  q["envelope.envelope_output.bias"].add_(0.25);
  EXPECT_LT((both->forward(x) - before - 0.25).abs().max().item<double>(), 1e-5);
}

namespace {
// The interaction of a change in band a with one in band b on a critic's logit of band levels:
// f(L + da + db) - f(L + da) - f(L + db) + f(L), as a fraction of |f(L + da) - f(L)| (the change's
// own effect), at levels L drawn in the map's range [-4, 0] (units of 20 dB) away from any shared
// reference: the critic is given the levels, not a waveform.
double band_interaction(EnvelopeCritic& critic, uint32_t seed) {
  torch::manual_seed(seed);
  const int64_t frames = (kLength - kEnvelopeFrameLength) / kEnvelopeHop + 1;
  const torch::Tensor levels = -4.0 * torch::rand({4, kBandGainBands, frames});
  torch::Tensor da = torch::zeros_like(levels), db = torch::zeros_like(levels);
  da.select(1, 2).narrow(1, 20, 60).fill_(0.5);   // band 2, 160-640 ms: 10 dB up
  db.select(1, 8).narrow(1, 30, 60).fill_(-0.5);  // band 8, 240-720 ms: 10 dB down
  torch::NoGradGuard no_grad;
  const torch::Tensor f0 = critic->logit_of_levels(levels), fa = critic->logit_of_levels(levels + da);
  const torch::Tensor fb = critic->logit_of_levels(levels + db), fab = critic->logit_of_levels(levels + da + db);
  return ((fab - fa - fb + f0).abs().max() / (fa - f0).abs().max()).item<double>();
}
}  // namespace

TEST(BandEnvelope, SeparableCriticJudgesEachBandAlone) {
  // Its logit is a sum of per-band terms, so a change in one band cannot alter how a change in
  // another counts: the interaction is rounding. The joint critic is the control that the
  // statistic can see an interaction (its first layer mixes the bands).
  for (uint32_t seed : {11u, 12u, 13u}) {
    torch::manual_seed(seed);
    EnvelopeCritic separable(8, kLength, GanInit::kHe, EnvelopeCriticKind::kSeparable);
    torch::manual_seed(seed);
    EnvelopeCritic joint(8, kLength, GanInit::kHe, EnvelopeCriticKind::kJoint);
    EXPECT_LT(band_interaction(separable, seed), 1e-4) << "seed " << seed;
    EXPECT_GT(band_interaction(joint, seed), 1e-2) << "seed " << seed;
  }
}

TEST(BandEnvelope, SeparableViewKeepsTheWaveformCriticAndIsSelectable) {
  auto [plain, separable] = plain_and_with_view(GanDiscView::kWaveformSeparableEnvelope, 6);
  auto q = separable->named_parameters();
  EXPECT_TRUE(q.contains("envelope.envelope_band_output.weight"));
  EXPECT_FALSE(q.contains("envelope.envelope_output.weight"));
  // Each envelope layer is grouped by band: 11 groups of width << i channels.
  EXPECT_EQ(q["envelope.envelope_conv_0.weight"].sizes(), torch::IntArrayRef({kBandGainBands * 4, 1, 5}));
  EXPECT_EQ(q["envelope.envelope_conv_2.weight"].sizes(), torch::IntArrayRef({kBandGainBands * 16, 8, 5}));
  torch::NoGradGuard no_grad;
  const torch::Tensor x = torch::randn({3, 1, kLength}) * 0.1;
  EXPECT_EQ(separable->forward(x).sizes(), torch::IntArrayRef({3}));
  EXPECT_GT((separable->forward(x) - plain->forward(x)).abs().max().item<double>(), 0.0);
  // The name parses to the view.
  EXPECT_EQ(parse_choice(kGanDiscViewNames, "waveform+separable-envelope", "--disc-view"),
            GanDiscView::kWaveformSeparableEnvelope);
}

TEST(BandEnvelope, TheViewReadsLevelsThroughItsMap) {
  // A discriminator's envelope logit is its waveform logit's difference from a plain one's; a
  // joint critic given the view's weights reproduces it from the levels of the view's own map (its
  // reference and floor), not from the first form's (the control that the two maps differ here).
  torch::Tensor x = torch::randn({3, 1, kLength}) * 0.01;
  x.select(2, 200).fill_(1.0);  // a direct sound
  x.narrow(2, 8000, kLength - 8000).mul_(1e-3);  // a late part 60 dB down, where the floors differ
  for (const GanEnvelopeMap& map : {kReDirectSound, GanEnvelopeMap{GanEnvelopeReference::kLoudestCell, -60.0}}) {
    auto [plain, with_map] = plain_and_with_view(GanDiscView::kWaveformEnvelope, 7, map);
    auto q = with_map->named_parameters();
    EXPECT_TRUE(q.contains("envelope.envelope_output.weight"));  // the joint critic
    torch::NoGradGuard no_grad;
    EnvelopeCritic joint(4, kLength, GanInit::kHe);
    for (auto& item : joint->named_parameters()) item.value().copy_(q["envelope." + item.key()]);
    const torch::Tensor envelope_part = with_map->forward(x) - plain->forward(x);
    const torch::Tensor by_its_map = joint->logit_of_levels(levels_of(x, map));
    const torch::Tensor by_first_form = joint->logit_of_levels(levels_of(x));
    EXPECT_LT((envelope_part - by_its_map).abs().max().item<double>(), 1e-4);
    EXPECT_GT((envelope_part - by_first_form).abs().max().item<double>(), 1e-3);
  }
  EXPECT_EQ(parse_choice(kGanEnvelopeReferenceNames, "direct-sound", "--envelope-reference"),
            GanEnvelopeReference::kDirectSound);
}

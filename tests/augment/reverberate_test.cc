// reverberate_channel() against the independent float64 model of the documented semantics.
#include <gtest/gtest.h>

#include <cmath>

#include "augment/reverberate.h"
#include "reference_model.h"
#include "util/error.h"

namespace {

using reftest::Vec;

std::vector<float> to_float(const Vec& v) { return std::vector<float>(v.begin(), v.end()); }
std::shared_ptr<const std::vector<float>> shared(const Vec& v) {
  return std::make_shared<const std::vector<float>>(to_float(v));
}

double max_abs(const Vec& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// Float32 FFT convolution and float accumulation: errors of a few 1e-7 of the output's peak
// per operation; 1e-5 of the peak leaves a 10x margin and is still 3x below one int16 step of
// a full-scale signal.
void expect_close(const std::vector<float>& got, const Vec& want, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  const double tol = 1e-5 * std::max(max_abs(want), 1e-3);
  double worst = 0;
  for (size_t i = 0; i < got.size(); ++i) worst = std::max(worst, std::abs(got[i] - want[i]));
  EXPECT_LE(worst, tol) << what;
}

struct Case {
  const char* name;
  bool use_rir;
  tsrir::ReverbOptions options;
  std::vector<reftest::Additive> additive;
};

class ReverberateFixture : public ::testing::Test {
 protected:
  const double fs = 16000;
  Vec x = reftest::quantise16(reftest::speech_like(12000, fs, 1));
  Vec h = reftest::synthetic_rir(3000, fs, 120, 0.4, 2);
  Vec n1 = reftest::noise_signal(5000, 3);   // shorter than the speech: looping matters
  Vec n2 = reftest::noise_signal(20000, 4);

  void check(const Case& c) {
    tsrir::PreparedRir rir(to_float(h), fs);
    std::vector<tsrir::AdditiveSignal> additive;
    for (const auto& a : c.additive) {
      tsrir::AdditiveSignal s;
      s.samples = shared(a.samples);
      s.snr_db = a.snr_db;
      s.start_time_s = a.start_s;
      s.offset_s = a.offset_s;
      additive.push_back(s);
    }
    tsrir::ReverbParts parts;
    std::vector<float> got =
        tsrir::reverberate_channel(to_float(x), fs, c.use_rir ? &rir : nullptr, additive, c.options, &parts);
    reftest::Options o;
    o.shift_output = c.options.shift_output;
    o.normalize_output = c.options.normalize_output;
    o.volume = c.options.volume;
    o.duration_s = c.options.duration_s;
    o.full_reference = c.options.snr_reference == tsrir::SnrReference::kFullReverb;
    o.loop = c.options.loop_additive_signals;
    reftest::Result want = reftest::wav_reverberate(x, fs, c.use_rir ? h : Vec{}, c.additive, o);
    expect_close(got, want.output, c.name);
    EXPECT_NEAR(parts.reference_energy, want.reference_energy, 1e-5 * want.reference_energy) << c.name;
  }
};

TEST_F(ReverberateFixture, MatchesFloat64ModelAcrossOptions) {
  tsrir::ReverbOptions base;
  std::vector<Case> cases;
  cases.push_back({"rir, defaults", true, base, {}});
  tsrir::ReverbOptions no_shift = base;
  no_shift.shift_output = false;
  cases.push_back({"rir, no shift (full tail)", true, no_shift, {}});
  tsrir::ReverbOptions no_norm = base;
  no_norm.normalize_output = false;
  cases.push_back({"no normalisation", true, no_norm, {{n2, 5.0, 0.1, 0.0}}});
  tsrir::ReverbOptions volume = base;
  volume.volume = 0.5;
  cases.push_back({"volume overrides normalisation", true, volume, {{n1, 10.0, 0.0, 0.0}}});
  tsrir::ReverbOptions shorter = base;
  shorter.duration_s = 0.4;
  cases.push_back({"duration shorter: trimmed", true, shorter, {}});
  tsrir::ReverbOptions longer = base;
  longer.duration_s = 2.0;
  cases.push_back({"duration longer: tiled", true, longer, {}});
  cases.push_back({"two additive signals with start times", true, base,
                   {{n1, 3.0, 0.0, 0.0}, {n2, 12.0, 0.52, 0.0}}});
  cases.push_back({"start time beyond the end adds nothing", true, base, {{n1, 0.0, 5.0, 0.0}}});
  cases.push_back({"no rir, noise only", false, base, {{n2, 2.0, 0.25, 0.0}}});
  tsrir::ReverbOptions no_rir_duration = base;
  no_rir_duration.duration_s = 1.9;
  cases.push_back({"no rir, tiled to a duration (Kaldi's noise extension)", false, no_rir_duration, {}});
  tsrir::ReverbOptions looped = base;
  looped.loop_additive_signals = true;
  cases.push_back({"looped noise with offset", true, looped, {{n1, 1.5, 0.0, 0.1234}}});
  tsrir::ReverbOptions full = looped;
  full.snr_reference = tsrir::SnrReference::kFullReverb;
  cases.push_back({"full-reverb SNR reference", true, full, {{n2, 1.0, 0.0, 0.9}}});
  cases.push_back({"offset into a non-looped signal", true, base, {{n2, 4.0, 0.0, 0.5}}});
  for (const Case& c : cases) check(c);
}

TEST(Reverberate, UtteranceShorterThanRir) {
  const double fs = 16000;
  Vec x = reftest::quantise16(reftest::speech_like(400, fs, 5));
  Vec h = reftest::synthetic_rir(4000, fs, 300, 0.5, 6);
  tsrir::PreparedRir rir(to_float(h), fs);
  for (bool shift : {true, false}) {
    tsrir::ReverbOptions o;
    o.shift_output = shift;
    std::vector<float> got = tsrir::reverberate_channel(to_float(x), fs, &rir, {}, o);
    reftest::Options ro;
    ro.shift_output = shift;
    expect_close(got, reftest::wav_reverberate(x, fs, h, {}, ro).output, shift ? "shift" : "no shift");
    EXPECT_EQ(got.size(), shift ? x.size() : x.size() + h.size() - 1);
  }
}

// Kaldi's --shift-output=false output is y[0:N] followed by y[0:M-1]; ours keeps the real tail.
TEST(Reverberate, NoShiftKeepsTheReverberantTail) {
  const double fs = 16000;
  Vec x = reftest::quantise16(reftest::speech_like(8000, fs, 7));
  Vec h = reftest::synthetic_rir(2000, fs, 50, 0.3, 8);
  tsrir::PreparedRir rir(to_float(h), fs);
  tsrir::ReverbOptions o;
  o.shift_output = false;
  o.normalize_output = false;
  std::vector<float> got = tsrir::reverberate_channel(to_float(x), fs, &rir, {}, o);
  Vec y = reftest::convolve(x, h);
  ASSERT_EQ(got.size(), y.size());
  double tail_err = 0, wrapped_diff = 0;
  for (size_t i = x.size(); i < y.size(); ++i) {
    tail_err = std::max(tail_err, std::abs(got[i] - y[i]));
    wrapped_diff = std::max(wrapped_diff, static_cast<double>(std::abs(got[i] - got[i - x.size()])));
  }
  EXPECT_LT(tail_err, 1e-5 * max_abs(y));
  EXPECT_GT(wrapped_diff, 1e-2 * max_abs(y));  // would be 0 with Kaldi's wrap-around
}

TEST(Reverberate, EarlyWindowIsKaldis) {
  size_t b, e;
  tsrir::early_reverb_window(1000, 16000, 16000, &b, &e);
  EXPECT_EQ(b, 984u);
  EXPECT_EQ(e, 1800u);
  tsrir::early_reverb_window(1000, 16000, 8000, &b, &e);
  EXPECT_EQ(b, 992u);
  EXPECT_EQ(e, 1400u);
  // 44.1 kHz: Kaldi computes 1000 - 44.1 in float and truncates: 955, i.e. 45 samples before.
  tsrir::early_reverb_window(1000, 100000, 44100, &b, &e);
  EXPECT_EQ(b, 955u);
  EXPECT_EQ(e, 3205u);
  tsrir::early_reverb_window(5, 300, 16000, &b, &e);  // clipped to the RIR
  EXPECT_EQ(b, 0u);
  EXPECT_EQ(e, 300u);
}

TEST(Reverberate, PeakIsSignedMaximum) {
  std::vector<float> h(100, 0.0f);
  h[10] = -0.9f;  // largest |h|, but Kaldi takes the signed maximum
  h[30] = 0.5f;
  tsrir::PreparedRir rir(h, 16000);
  EXPECT_EQ(rir.peak_index(), 30u);
}

// The realised SNR, from the separately kept speech and noise parts, is the requested one.
TEST(Reverberate, RealisedSnrUnderBothDefinitions) {
  const double fs = 16000;
  Vec x = reftest::quantise16(reftest::speech_like(16000, fs, 11));
  Vec h = reftest::synthetic_rir(8000, fs, 200, 0.6, 12);
  Vec n = reftest::noise_signal(7001, 13);  // shorter than the speech, nonstationary
  tsrir::PreparedRir rir(to_float(h), fs);
  // Independent speech references: early window [pk - 16, pk + 800) at 16 kHz.
  Vec early(h.begin() + 184, h.begin() + 1000);
  const double e_early = reftest::mean_power(reftest::convolve(x, early));
  const double e_full = reftest::mean_power(reftest::convolve(x, h));
  for (auto reference : {tsrir::SnrReference::kEarlyReverb, tsrir::SnrReference::kFullReverb}) {
    for (double snr : {1.0, 1.7, 2.0, 15.0}) {
      tsrir::ReverbOptions o;
      o.loop_additive_signals = true;
      o.snr_reference = reference;
      tsrir::AdditiveSignal a;
      a.samples = shared(n);
      a.snr_db = snr;
      a.offset_s = 0.3;
      tsrir::ReverbParts parts;
      tsrir::reverberate_channel(to_float(x), fs, &rir, {a}, o, &parts);
      // The noise covers the whole reverberant signal; its power over that span:
      const double p_noise = reftest::mean_power(parts.noise);
      const double speech = reference == tsrir::SnrReference::kEarlyReverb ? e_early : e_full;
      const double realised = 10 * std::log10(speech / p_noise);
      EXPECT_NEAR(realised, snr, 0.1) << tsrir::snr_reference_name(reference);
      EXPECT_NEAR(realised, snr, 1e-3) << "float rounding only";
      // Offset and looping: noise part = scale * n[(offset + j) mod K] everywhere.
      const size_t offset = static_cast<size_t>(std::llround(0.3 * fs));
      const double scale = parts.noise[0] / static_cast<float>(n[offset]);
      double worst = 0;
      for (size_t j = 0; j < parts.noise.size(); ++j)
        worst = std::max(worst, std::abs(parts.noise[j] - scale * static_cast<float>(n[(offset + j) % n.size()])));
      EXPECT_LT(worst, 1e-6 * std::abs(scale));
      EXPECT_EQ(parts.noise.size(), x.size() + h.size() - 1);
    }
  }
}

TEST(Reverberate, BadInputs) {
  tsrir::ReverbOptions o;
  EXPECT_THROW(tsrir::reverberate_channel({}, 16000, nullptr, {}, o), tsrir::Error);
  tsrir::AdditiveSignal a;
  a.samples = std::make_shared<const std::vector<float>>(std::vector<float>(100, 0.1f));
  a.offset_s = 1.0;  // beyond 100 samples, not looped
  EXPECT_THROW(tsrir::reverberate_channel(std::vector<float>(1000, 0.1f), 16000, nullptr, {a}, o), tsrir::Error);
  o.loop_additive_signals = true;  // looped: the offset wraps
  EXPECT_NO_THROW(tsrir::reverberate_channel(std::vector<float>(1000, 0.1f), 16000, nullptr, {a}, o));
  EXPECT_THROW(tsrir::parse_snr_reference("late"), tsrir::Error);
}

}  // namespace

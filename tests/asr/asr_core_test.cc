// The recogniser's torch-free parts against independent references: log-mel features against a
// float64 direct-DFT implementation written here from the definition in asr_features.h, CTC
// greedy collapsing and Levenshtein counting against hand-worked cases, and compute-wer's format.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "asr/asr_features.h"
#include "asr/asr_text.h"
#include "util/error.h"
#include "util/rng.h"

namespace tsrir {
namespace {

// Float64 reference: O(N^2) DFT, filter weights from the triangle definition in mel.
std::vector<std::vector<double>> reference_log_mel(const std::vector<float>& x, double fs, int bins,
                                                   double low_hz, double high_hz) {
  const int L = int(std::lround(0.025 * fs)), S = int(std::lround(0.010 * fs));
  int N = 1;
  while (N < L) N *= 2;
  auto mel = [](double f) { return 1127.0 * std::log(1.0 + f / 700.0); };
  const double ml = mel(low_hz), mh = mel(high_hz);
  std::vector<std::vector<double>> out;
  for (int start = 0; start + L <= int(x.size()); start += S) {
    std::vector<double> frame(L);
    double mean = 0;
    for (int n = 0; n < L; ++n) mean += x[start + n];
    mean /= L;
    for (int n = 0; n < L; ++n) frame[n] = x[start + n] - mean;
    std::vector<double> emph(L);
    for (int n = 0; n < L; ++n) {
      emph[n] = frame[n] - 0.97 * frame[n > 0 ? n - 1 : 0];
      emph[n] *= 0.54 - 0.46 * std::cos(2 * M_PI * n / (L - 1));
    }
    std::vector<double> power(N / 2 + 1);
    for (int k = 0; k <= N / 2; ++k) {
      std::complex<double> acc = 0;
      for (int n = 0; n < L; ++n) acc += emph[n] * std::polar(1.0, -2 * M_PI * double(k) * n / N);
      power[k] = std::norm(acc);
    }
    std::vector<double> row(bins);
    for (int m = 0; m < bins; ++m) {
      const double left = ml + (mh - ml) * m / (bins + 1);
      const double centre = ml + (mh - ml) * (m + 1) / (bins + 1);
      const double right = ml + (mh - ml) * (m + 2) / (bins + 1);
      double e = 0;
      for (int k = 0; k <= N / 2; ++k) {
        const double mk = mel(k * fs / N);
        const double w = std::max(0.0, std::min((mk - left) / (centre - left), (right - mk) / (right - centre)));
        e += w * power[k];
      }
      row[m] = std::log(std::max(e, 1e-10));
    }
    out.push_back(row);
  }
  return out;
}

TEST(LogMel, MatchesFloat64Reference) {
  for (double fs : {16000.0, 8000.0}) {
    Rng rng(7);
    std::vector<float> x(size_t(0.3 * fs));
    for (size_t n = 0; n < x.size(); ++n) {
      x[n] = float(0.3 * std::sin(2 * M_PI * 440.0 * n / fs) + 0.1 * std::sin(2 * M_PI * 2950.0 * n / fs) +
                   0.05 * rng.normal());
    }
    LogMelOptions o;
    o.sample_rate_hz = fs;
    o.high_hz = fs / 2 - 400;
    const FeatureMatrix f = compute_log_mel(x, o);
    const auto ref = reference_log_mel(x, fs, o.num_mel_bins, o.low_hz, o.high_hz);
    ASSERT_EQ(f.num_frames, ref.size());
    ASSERT_EQ(f.num_frames, 1 + (x.size() - size_t(0.025 * fs)) / size_t(0.010 * fs));
    ASSERT_EQ(f.num_bins, 40u);
    double worst = 0;
    for (size_t t = 0; t < f.num_frames; ++t) {
      for (size_t m = 0; m < f.num_bins; ++m) worst = std::max(worst, std::abs(f.row(t)[m] - ref[t][m]));
    }
    // float32 FFT against float64: log energies agree to ~1e-5; 1e-3 leaves margin, far below
    // any real difference in the definition (a window or mel-scale change moves them by > 0.05).
    EXPECT_LT(worst, 1e-3) << "fs " << fs;
  }
}

TEST(LogMel, ToneLandsInItsMelFilter) {
  const double fs = 16000;
  std::vector<float> x(8000);
  for (size_t n = 0; n < x.size(); ++n) x[n] = float(0.5 * std::sin(2 * M_PI * 1000.0 * n / fs));
  LogMelOptions o;
  const FeatureMatrix f = compute_log_mel(x, o);
  // Filter m is centred at mel_low + (m + 1) * delta.
  auto mel = [](double hz) { return 1127.0 * std::log(1.0 + hz / 700.0); };
  const double delta = (mel(o.high_hz) - mel(o.low_hz)) / (o.num_mel_bins + 1);
  const int expected = int(std::lround((mel(1000.0) - mel(o.low_hz)) / delta)) - 1;
  size_t best = 0;
  for (size_t m = 1; m < f.num_bins; ++m) if (f.row(5)[m] > f.row(5)[best]) best = m;
  EXPECT_NEAR(double(best), double(expected), 1.0);
}

TEST(LogMel, ShortSignalAndBadOptionsAreErrors) {
  LogMelOptions o;
  EXPECT_THROW(compute_log_mel(std::vector<float>(399, 0.f), o), Error);
  EXPECT_EQ(compute_log_mel(std::vector<float>(400, 0.f), o).num_frames, 1u);  // silence: floor, no NaN
  EXPECT_FLOAT_EQ(compute_log_mel(std::vector<float>(400, 0.f), o).values[0], float(std::log(1e-10)));
  o.high_hz = 9000;
  EXPECT_THROW(compute_log_mel(std::vector<float>(1000, 0.f), o), Error);
}

TEST(LogMel, NormalisationGivesZeroMeanUnitVariance) {
  FeatureMatrix f;
  f.num_frames = 4;
  f.num_bins = 2;
  f.values = {1, 10, 2, 10, 3, 10, 6, 10};
  normalise_mean_variance(&f);
  // Column 0: mean 3, variance (4 + 1 + 0 + 9) / 4 = 3.5.
  EXPECT_NEAR(f.values[0], -2 / std::sqrt(3.5), 1e-6);
  EXPECT_NEAR(f.values[6], 3 / std::sqrt(3.5), 1e-6);
  EXPECT_NEAR(f.values[1], 0.0, 1e-6);  // constant column: 0, not NaN
}

TEST(Text, NormaliseAndEncode) {
  EXPECT_EQ(normalise_transcript("  Hello,  World! It's 3 o'clock. "), "hello world it's o'clock");
  EXPECT_EQ(normalise_transcript("WELL-KNOWN"), "well known");
  EXPECT_EQ(encode_characters("ab z'"), (std::vector<int>{2, 3, 1, 27, 28}));
  EXPECT_EQ(decode_characters({2, 0, 3, 1, 27, 28}), "ab z'");
  EXPECT_THROW(encode_characters("A"), Error);
}

TEST(Ctc, GreedyCollapseHandWorked) {
  // blank a a blank a space space blank b  ->  a a space b
  EXPECT_EQ(ctc_collapse({0, 2, 2, 0, 2, 1, 1, 0, 3}), (std::vector<int>{2, 2, 1, 3}));
  EXPECT_EQ(ctc_collapse({0, 0, 0}), std::vector<int>{});
  EXPECT_EQ(ctc_collapse({4, 4, 4, 5, 5, 4}), (std::vector<int>{4, 5, 4}));
  EXPECT_EQ(decode_characters(ctc_collapse({0, 9, 9, 6, 0, 13, 13, 0, 13, 16, 1, 0})), "hello ");
}

std::vector<std::string> w(const std::string& s) { return word_tokens(s); }

TEST(EditCounts, HandWorked) {
  EditCounts c = count_edits(w("a b c d"), w("a x c d e"));
  EXPECT_EQ(c.ref_length, 4u);
  EXPECT_EQ(c.substitutions, 1u);
  EXPECT_EQ(c.insertions, 1u);
  EXPECT_EQ(c.deletions, 0u);
  c = count_edits(w("the cat sat"), w("cat sat on"));
  EXPECT_EQ(c.errors(), 2u);
  EXPECT_EQ(c.deletions, 1u);
  EXPECT_EQ(c.insertions, 1u);
  c = count_edits(w("a b c"), {});
  EXPECT_EQ(c.deletions, 3u);
  EXPECT_EQ(c.errors(), 3u);
  c = count_edits({}, w("x y"));
  EXPECT_EQ(c.insertions, 2u);
  EXPECT_EQ(c.ref_length, 0u);
  c = count_edits(w("one two three"), w("one two three"));
  EXPECT_EQ(c.errors(), 0u);
  // Characters: "kitten" -> "sitting" = 2 substitutions + 1 insertion (the classic 3).
  c = count_edits(character_tokens("kitten"), character_tokens("sitting"));
  EXPECT_EQ(c.substitutions, 2u);
  EXPECT_EQ(c.insertions, 1u);
  EXPECT_EQ(c.deletions, 0u);
  EXPECT_EQ(character_tokens("ab c").size(), 4u);
}

TEST(EditCounts, ComputeWerFormat) {
  EditCounts t;
  t.ref_length = 454;
  t.insertions = 3;
  t.deletions = 20;
  t.substitutions = 33;
  EXPECT_EQ(format_compute_wer(t, 5, 10, 0),
            "%WER 12.33 [ 56 / 454, 3 ins, 20 del, 33 sub ]\n%SER 50.00 [ 5 / 10 ]\n"
            "Scored 10 sentences, 0 not present in hyp.\n");
}

}  // namespace
}  // namespace tsrir

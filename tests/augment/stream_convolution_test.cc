// The streaming building blocks: chunked convolution and the piecewise power sum must give the
// very numbers of their whole-signal counterparts, however the signal is cut into pieces.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "augment/reverb_steps.h"
#include "augment/stream_convolution.h"
#include "dsp/convolve.h"

namespace {

std::vector<float> random_signal(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g(0.0f, 0.3f);
  std::vector<float> v(n);
  for (float& s : v) s = g(rng);
  return v;
}

// Feeds x in random piece sizes (1 to max_piece) and collects the emitted runs, checking that
// they are contiguous and in order.
std::vector<float> stream(const tsrir::Convolver& engine, const std::vector<float>& x, size_t chunk_samples,
                          size_t max_piece, uint32_t seed) {
  std::vector<float> y;
  tsrir::StreamingConvolution conv(
      engine,
      [&](size_t first, float* run, size_t count) {
        EXPECT_EQ(first, y.size());
        y.insert(y.end(), run, run + count);
      },
      chunk_samples);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<size_t> piece(1, max_piece);
  for (size_t i = 0; i < x.size();) {
    const size_t n = std::min(piece(rng), x.size() - i);
    conv.push(x.data() + i, n);
    i += n;
  }
  conv.finish();
  return y;
}

// Exact equality with the engine on the whole signal: the chunks sit on the engine's block grid
// (see stream_convolution.h), so every output comes from the same FFT segment. Lengths around
// one, two and three blocks reach the first-chunk, single-transform and last-chunk edge cases.
TEST(StreamingConvolution, EqualsWholeSignalConvolutionBitForBit) {
  for (size_t m : {1u, 40u, 64u, 65u, 1024u, 3000u}) {
    const std::vector<float> h = random_signal(m, 100 + static_cast<uint32_t>(m));
    const tsrir::Convolver engine(h);
    const size_t b = tsrir::engine_block_length(engine);
    for (size_t n : {size_t{1}, size_t{5}, b - 1, b, b + 1, 2 * b - 1, 2 * b, 2 * b + 1, 3 * b, 3 * b + 7, 7 * b + 123}) {
      const std::vector<float> x = random_signal(n, static_cast<uint32_t>(n * 7 + m));
      const std::vector<float> want = engine.convolve(x);
      for (size_t chunk : {size_t{1}, 3 * b}) {
        const std::vector<float> got = stream(engine, x, chunk, 5000, static_cast<uint32_t>(n + chunk));
        ASSERT_EQ(got.size(), want.size()) << "m=" << m << " n=" << n << " chunk=" << chunk;
        size_t mismatches = 0;
        for (size_t i = 0; i < got.size(); ++i) mismatches += got[i] != want[i];
        EXPECT_EQ(mismatches, 0u) << "m=" << m << " n=" << n << " chunk=" << chunk;
      }
    }
  }
}

// And it is the convolution, not merely the engine's output: against the float64 direct sum.
// Float32 FFT blocks of 16k points are accurate to a few 1e-7 of the output's peak; 1e-5 leaves
// margin while any lost or repeated history sample would cost ~1e-1.
TEST(StreamingConvolution, IsTheLinearConvolution) {
  const std::vector<float> h = random_signal(3000, 7), x = random_signal(60000, 8);
  const std::vector<float> got = stream(tsrir::Convolver(h), x, 1, 3000, 9);
  const std::vector<double> want =
      tsrir::direct_convolve(std::vector<double>(x.begin(), x.end()), std::vector<double>(h.begin(), h.end()));
  ASSERT_EQ(got.size(), want.size());
  double peak = 0, worst = 0;
  for (size_t i = 0; i < want.size(); ++i) {
    peak = std::max(peak, std::abs(want[i]));
    worst = std::max(worst, std::abs(got[i] - want[i]));
  }
  EXPECT_LE(worst, 1e-5 * peak);
}

// PowerSum against an independent statement of the in-memory sum (lanes i % 4, the last
// incomplete group into lane 0), for the whole vector and for random pieces: equal exactly.
TEST(PowerSum, SameSumHoweverThePiecesAreCut) {
  for (size_t n : {0u, 1u, 3u, 4u, 5u, 1001u, 65539u}) {
    const std::vector<float> v = random_signal(n, static_cast<uint32_t>(n + 1));
    double lane[4] = {0, 0, 0, 0};
    const size_t n4 = n - n % 4;
    for (size_t i = 0; i < n4; ++i) lane[i % 4] += static_cast<double>(v[i]) * v[i];
    for (size_t i = n4; i < n; ++i) lane[0] += static_cast<double>(v[i]) * v[i];
    const double want = n ? (lane[0] + lane[1] + lane[2] + lane[3]) / static_cast<double>(n) : 0.0;
    EXPECT_EQ(tsrir::mean_power(v), want) << n;
    std::mt19937 rng(static_cast<uint32_t>(n));
    std::uniform_int_distribution<size_t> piece(0, 9);
    tsrir::PowerSum sum;
    for (size_t i = 0; i < n;) {
      const size_t k = std::min(piece(rng), n - i);
      sum.add(v.data() + i, k);
      i += k;
    }
    EXPECT_EQ(sum.count(), n);
    EXPECT_EQ(sum.mean(), want) << n;
  }
}

}  // namespace

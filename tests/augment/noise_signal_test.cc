// nested_noise_signal() reads a noise it is lent (const&) and reuses one it is given (&&): both
// give the same samples for every branch (with and without an RIR; kept, cut and tiled; 16-bit
// and float noises; Kaldi's truncation or the pipe's rounding), the lent noise is left as it was,
// and the unreverberated 16-bit noise is the noise repeated (sample n = noise[n mod size]).
#include "augment/noise_signal.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

namespace tsrir {
namespace {

TEST(NestedNoiseSignal, ALentAndAGivenNoiseGiveTheSameSamples) {
  const double fs = 16000;
  std::vector<float> float_noise(1000), int16_noise(1000);
  for (size_t n = 0; n < float_noise.size(); ++n) {
    float_noise[n] = static_cast<float>(0.3 * std::sin(0.05 * static_cast<double>(n)) + 0.01 * std::cos(1.7 * n));
    int16_noise[n] = std::round(float_noise[n] * 32768.0f) / 32768.0f;
  }
  std::vector<float> rir_samples(40, 0.0f);
  rir_samples[2] = 1.0f;
  rir_samples[9] = -0.4f;
  rir_samples[30] = 0.1f;
  const PreparedRir rir(rir_samples, fs);
  for (const bool is_int16 : {false, true}) {
    const std::vector<float>& noise = is_int16 ? int16_noise : float_noise;
    for (const PreparedRir* r : {static_cast<const PreparedRir*>(nullptr), &rir}) {
      // As is, cut, tiled: the duration and the length of the nested program's output.
      for (const auto& [duration_s, length] : {std::pair<double, size_t>{0.0, 1000}, {0.03, 480}, {0.2, 3200}}) {
        for (const bool kaldi_compat : {false, true}) {
          SCOPED_TRACE(::testing::Message() << "int16 " << is_int16 << ", RIR " << (r != nullptr) << ", duration "
                                            << duration_s << ", kaldi_compat " << kaldi_compat);
          const std::vector<float> lent = nested_noise_signal(noise, fs, r, duration_s, is_int16, kaldi_compat);
          EXPECT_EQ(noise, is_int16 ? int16_noise : float_noise);
          std::vector<float> given_noise = noise;
          const std::vector<float> given =
              nested_noise_signal(std::move(given_noise), fs, r, duration_s, is_int16, kaldi_compat);
          EXPECT_EQ(lent, given);
          if (!r && is_int16) {
            ASSERT_EQ(lent.size(), length);
            for (size_t n = 0; n < lent.size(); ++n) ASSERT_EQ(lent[n], noise[n % noise.size()]) << n;
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace tsrir

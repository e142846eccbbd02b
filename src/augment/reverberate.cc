#include "augment/reverberate.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "util/error.h"
#include "util/strings.h"

namespace tsrir {
namespace {

// Kaldi adds FLT_EPSILON to the noise power with samples in int16 units; our samples are in
// full-scale units (int16 / 32768), so the same guard is FLT_EPSILON / 32768^2.
constexpr double kNoisePowerGuard = FLT_EPSILON / (32768.0 * 32768.0);

// Four independent accumulators: the same double-precision sum, ~4x faster than one chain.
double mean_power(const std::vector<float>& v) {
  if (v.empty()) return 0.0;
  double acc[4] = {0, 0, 0, 0};
  const size_t n = v.size(), n4 = n - n % 4;
  for (size_t i = 0; i < n4; i += 4)
    for (int j = 0; j < 4; ++j) acc[j] += static_cast<double>(v[i + j]) * v[i + j];
  for (size_t i = n4; i < n; ++i) acc[0] += static_cast<double>(v[i]) * v[i];
  return (acc[0] + acc[1] + acc[2] + acc[3]) / static_cast<double>(n);
}

// Visits `count` samples of `noise` starting at `offset`, wrapping at its end, as contiguous
// runs: body(noise_pointer, output_index, run_length).
template <typename Body>
void for_each_run(const std::vector<float>& noise, size_t offset, size_t count, Body body) {
  size_t done = 0, k = offset;
  while (done < count) {
    const size_t run = std::min(count - done, noise.size() - k);
    body(noise.data() + k, done, run);
    done += run;
    k = 0;
  }
}

std::vector<float> padded_early_part(const std::vector<float>& rir, size_t begin, size_t end) {
  size_t padded = 1;
  while (padded < end - begin) padded *= 2;
  std::vector<float> out(padded, 0.0f);
  std::copy(rir.begin() + static_cast<long>(begin), rir.begin() + static_cast<long>(end), out.begin());
  return out;
}

size_t signed_peak(const std::vector<float>& rir) {
  if (rir.empty()) throw Error("empty impulse response");
  return static_cast<size_t>(std::max_element(rir.begin(), rir.end()) - rir.begin());
}

}  // namespace

SnrReference parse_snr_reference(const std::string& name) {
  if (name == "early") return SnrReference::kEarlyReverb;
  if (name == "full") return SnrReference::kFullReverb;
  throw Error("unknown SNR reference '" + name + "' (expected early or full)");
}

std::string snr_reference_name(SnrReference reference) {
  return reference == SnrReference::kEarlyReverb ? "early" : "full";
}

void early_reverb_window(size_t peak, size_t length, double sample_rate_hz, size_t* begin, size_t* end) {
  // Kaldi evaluates these in float and truncates toward zero; at 16 kHz that is exactly
  // 16 samples before and 800 after the peak, at 44.1 kHz 45 before.
  const float fs = static_cast<float>(sample_rate_hz);
  const float peak_f = static_cast<float>(peak);
  long b = static_cast<long>(peak_f - 0.001f * fs);
  long e = static_cast<long>(peak_f + 0.05f * fs);
  if (b < 0) b = 0;
  if (e > static_cast<long>(length)) e = static_cast<long>(length);
  *begin = static_cast<size_t>(b);
  *end = static_cast<size_t>(std::max(e, b));
}

PreparedRir::PreparedRir(std::vector<float> rir, double sample_rate_hz)
    : rir_(std::move(rir)),
      peak_(signed_peak(rir_)),
      full_(rir_),
      early_((early_reverb_window(peak_, rir_.size(), sample_rate_hz, &early_begin_, &early_end_),
              padded_early_part(rir_, early_begin_, early_end_))) {}

double PreparedRir::early_reverb_energy(const std::vector<float>& x) const {
  const std::vector<float> early = early_.convolve(x);
  const size_t true_length = x.size() + (early_end_ - early_begin_) - 1;
  return mean_power(early) * static_cast<double>(early.size()) / static_cast<double>(true_length);
}

std::vector<float> reverberate_channel(const std::vector<float>& input, double sample_rate_hz,
                                       const PreparedRir* rir,
                                       const std::vector<AdditiveSignal>& additive,
                                       const ReverbOptions& options, ReverbParts* parts) {
  if (input.empty()) throw Error("empty input signal");
  if (!(sample_rate_hz > 0)) throw Error("invalid sample rate");
  const size_t n = input.size();
  const double power_before = mean_power(input);

  std::vector<float> y;
  double reference_energy = power_before;
  if (rir) {
    y = rir->convolve_full(input);
    // Only the additive signals' scales use it (the early convolution is a third of the work).
    if (!additive.empty() || parts)
      reference_energy = options.snr_reference == SnrReference::kEarlyReverb ? rir->early_reverb_energy(input)
                                                                             : mean_power(y);
  } else {
    y = input;
  }
  if (parts) {
    parts->reverberant_speech.assign(y.begin(), y.end());
    parts->noise.assign(y.size(), 0.0);
    parts->noise_power.clear();
    parts->reference_energy = reference_energy;
  }

  const float fs_f = static_cast<float>(sample_rate_hz);
  for (size_t i = 0; i < additive.size(); ++i) {
    const AdditiveSignal& a = additive[i];
    if (!a.samples || a.samples->empty()) throw Error("additive signal " + std::to_string(i + 1) + " is empty");
    const std::vector<float>& noise = *a.samples;
    if (a.start_time_s < 0 || a.offset_s < 0)
      throw Error("additive signal " + std::to_string(i + 1) + ": negative start time or offset");
    // Kaldi: int32 offset = BaseFloat time * BaseFloat samp_freq (float product, truncated).
    const size_t start = static_cast<size_t>(static_cast<float>(a.start_time_s) * fs_f);
    size_t offset = static_cast<size_t>(std::llround(a.offset_s * sample_rate_hz));
    size_t count = 0;
    if (options.loop_additive_signals) {
      offset %= noise.size();
      count = start < y.size() ? y.size() - start : 0;
    } else {
      if (offset >= noise.size())
        throw Error("additive signal " + std::to_string(i + 1) + ": offset " + format_double(a.offset_s) +
                    " s is beyond its length " + format_double(noise.size() / sample_rate_hz) + " s");
      count = start < y.size() ? std::min(y.size() - start, noise.size() - offset) : 0;
    }
    // Power over the samples added when looping; over the signal's own length otherwise (Kaldi).
    const size_t power_count = options.loop_additive_signals ? count : noise.size() - offset;
    double sum[4] = {0, 0, 0, 0};
    for_each_run(noise, offset, power_count, [&](const float* p, size_t, size_t run) {
      size_t r = 0;
      for (; r + 4 <= run; r += 4)
        for (int j = 0; j < 4; ++j) sum[j] += static_cast<double>(p[r + j]) * p[r + j];
      for (; r < run; ++r) sum[0] += static_cast<double>(p[r]) * p[r];
    });
    const double sum_all = sum[0] + sum[1] + sum[2] + sum[3];
    const double noise_power = (power_count ? sum_all / static_cast<double>(power_count) : 0.0) + kNoisePowerGuard;
    const double scale = std::sqrt(std::pow(10.0, -a.snr_db / 10.0) * reference_energy / noise_power);
    const float scale_f = static_cast<float>(scale);
    for_each_run(noise, offset, count, [&](const float* p, size_t at, size_t run) {
      float* target = y.data() + start + at;
      for (size_t r = 0; r < run; ++r) target[r] += scale_f * p[r];
      if (parts)
        for (size_t r = 0; r < run; ++r) parts->noise[start + at + r] += scale_f * p[r];
    });
    if (parts) parts->noise_power.push_back(noise_power);
  }

  double gain = 1.0;
  if (options.volume > 0) {
    gain = options.volume;
  } else if (options.normalize_output) {
    const double power_after = mean_power(y);
    if (power_after > 0) gain = std::sqrt(power_before / power_after);
  }
  if (parts) parts->output_gain = gain;

  const size_t shift = (rir && options.shift_output) ? rir->peak_index() : 0;
  const size_t available = (rir && options.shift_output) ? n : y.size();
  const size_t out_len = options.duration_s > 0
                             ? static_cast<size_t>(fs_f * static_cast<float>(options.duration_s))
                             : available;
  std::vector<float> out(out_len);
  const float gain_f = static_cast<float>(gain);
  const float* src = y.data() + shift;
  for (size_t done = 0; done < out_len;) {
    const size_t run = std::min(available, out_len - done);
    for (size_t j = 0; j < run; ++j) out[done + j] = gain_f * src[j];
    done += run;
  }
  return out;
}

}  // namespace tsrir

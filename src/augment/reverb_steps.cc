#include "augment/reverb_steps.h"

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

inline double square(float v) { return static_cast<double>(v) * v; }

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

}  // namespace

void PowerSum::add(const float* x, size_t count) {
  count_ += count;
  size_t i = 0;
  // First complete a group of four begun by an earlier piece.
  while (pending_count_ > 0 && i < count) {
    if (pending_count_ < 3) {
      pending_[pending_count_++] = x[i++];
      continue;
    }
    for (int j = 0; j < 3; ++j) lane_[j] += square(pending_[j]);
    lane_[3] += square(x[i++]);
    pending_count_ = 0;
  }
  if (pending_count_ > 0) return;
  double acc[4] = {lane_[0], lane_[1], lane_[2], lane_[3]};
  for (; i + 4 <= count; i += 4)
    for (int j = 0; j < 4; ++j) acc[j] += square(x[i + j]);
  for (int j = 0; j < 4; ++j) lane_[j] = acc[j];
  while (i < count) pending_[pending_count_++] = x[i++];
}

double PowerSum::mean() const {
  if (count_ == 0) return 0.0;
  double lane0 = lane_[0];
  for (size_t j = 0; j < pending_count_; ++j) lane0 += square(pending_[j]);
  return (lane0 + lane_[1] + lane_[2] + lane_[3]) / static_cast<double>(count_);
}

double mean_power(const std::vector<float>& v) {
  PowerSum sum;
  sum.add(v.data(), v.size());
  return sum.mean();
}

double early_energy_from_padded_power(double padded_mean_power, size_t input_length, const PreparedRir& rir) {
  const size_t padded_length = input_length + rir.early_filter_length() - 1;
  const size_t true_length = input_length + (rir.early_end() - rir.early_begin()) - 1;
  return padded_mean_power * static_cast<double>(padded_length) / static_cast<double>(true_length);
}

AdditivePlacement place_additive(const AdditiveSignal& a, size_t index, size_t y_length, double sample_rate_hz,
                                 double reference_energy, bool loop) {
  const std::string which = "additive signal " + std::to_string(index + 1);
  if (!a.samples || a.samples->empty()) throw Error(which + " is empty");
  const std::vector<float>& noise = *a.samples;
  if (a.start_time_s < 0 || a.offset_s < 0) throw Error(which + ": negative start time or offset");
  AdditivePlacement p;
  p.samples = &noise;
  // Kaldi: int32 offset = BaseFloat time * BaseFloat samp_freq (float product, truncated).
  p.start = static_cast<size_t>(static_cast<float>(a.start_time_s) * static_cast<float>(sample_rate_hz));
  p.offset = static_cast<size_t>(std::llround(a.offset_s * sample_rate_hz));
  if (loop) {
    p.offset %= noise.size();
    p.count = p.start < y_length ? y_length - p.start : 0;
  } else {
    if (p.offset >= noise.size())
      throw Error(which + ": offset " + format_double(a.offset_s) + " s is beyond its length " +
                  format_double(noise.size() / sample_rate_hz) + " s");
    p.count = p.start < y_length ? std::min(y_length - p.start, noise.size() - p.offset) : 0;
  }
  // Power over the samples added when looping; over the signal's own length otherwise (Kaldi).
  const size_t power_count = loop ? p.count : noise.size() - p.offset;
  double sum[4] = {0, 0, 0, 0};
  for_each_run(noise, p.offset, power_count, [&](const float* q, size_t, size_t run) {
    size_t r = 0;
    for (; r + 4 <= run; r += 4)
      for (int j = 0; j < 4; ++j) sum[j] += square(q[r + j]);
    for (; r < run; ++r) sum[0] += square(q[r]);
  });
  const double sum_all = sum[0] + sum[1] + sum[2] + sum[3];
  p.noise_power = (power_count ? sum_all / static_cast<double>(power_count) : 0.0) + kNoisePowerGuard;
  const double scale = std::sqrt(std::pow(10.0, -a.snr_db / 10.0) * reference_energy / p.noise_power);
  p.scale = static_cast<float>(scale);
  return p;
}

void add_placed(const AdditivePlacement& p, size_t first, float* y_part, size_t length) {
  const size_t lo = std::max(first, p.start);
  const size_t hi = std::min(first + length, p.start + p.count);
  if (lo >= hi) return;
  const std::vector<float>& noise = *p.samples;
  // Sample d of the added stretch is noise[(offset + d) mod size] (d < size - offset unless looped).
  size_t k = (p.offset + (lo - p.start)) % noise.size();
  float* target = y_part + (lo - first);
  for (size_t done = 0, total = hi - lo; done < total;) {
    const size_t run = std::min(total - done, noise.size() - k);
    const float* q = noise.data() + k;
    for (size_t r = 0; r < run; ++r) target[done + r] += p.scale * q[r];
    done += run;
    k = 0;
  }
}

size_t kaldi_duration_samples(double sample_rate_hz, float duration_s) {
  return static_cast<size_t>(static_cast<float>(sample_rate_hz) * duration_s);
}

OutputGeometry output_geometry(size_t input_length, const PreparedRir* rir, const ReverbOptions& options,
                               double sample_rate_hz) {
  OutputGeometry g;
  const size_t y_length = rir ? input_length + rir->size() - 1 : input_length;
  g.shift = (rir && options.shift_output) ? rir->peak_index() : 0;
  g.available = (rir && options.shift_output) ? input_length : y_length;
  g.length = options.duration_s > 0 ? kaldi_duration_samples(sample_rate_hz, options.duration_s) : g.available;
  // Kaldi tiles the input-length head of y whenever the output is longer than the input: with
  // --shift-output=false its N + M - 1 samples end with the first M - 1 again (kaldi_compat).
  if (options.kaldi_compat) g.available = input_length;
  return g;
}

double output_gain(const ReverbOptions& options, double power_before, double power_after) {
  if (options.volume > 0) return options.volume;
  if (options.normalize_output && power_after > 0) return std::sqrt(power_before / power_after);
  return 1.0;
}

}  // namespace tsrir

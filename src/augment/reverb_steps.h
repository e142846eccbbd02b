// The steps of one utterance's reverberation (reverberate.h) that both the in-memory path
// (reverberate_channel) and the streaming one (reverberate_stream.h) take. They are shared so that
// the two compute every number with the same operations in the same order: their outputs are
// equal bit for bit, not merely to rounding.
#pragma once
#include <cstddef>
#include <vector>

#include "augment/reverberate.h"

namespace tsrir {

// Mean square of a sequence given in pieces. Summed in double over four interleaved lanes
// (sample i into lane i % 4, a last incomplete group into lane 0: ~4x faster than one chain);
// the result is the same, operation for operation, however the sequence is cut into pieces.
class PowerSum {
 public:
  void add(const float* x, size_t count);
  size_t count() const { return count_; }
  double mean() const;  // 0 for no samples

 private:
  double lane_[4] = {0, 0, 0, 0};
  float pending_[3] = {0, 0, 0};  // an incomplete group of four, not yet in its lanes
  size_t pending_count_ = 0;
  size_t count_ = 0;
};

double mean_power(const std::vector<float>& v);

// Kaldi's early-reverberation energy from the mean square of x ⊛ h_early as computed with the
// zero-padded early filter over its N + padded - 1 outputs: rescaled to the true N + L_early - 1.
double early_energy_from_padded_power(double padded_mean_power, size_t input_length, const PreparedRir& rir);

// How an additive signal enters the unshifted reverberant signal y.
struct AdditivePlacement {
  const std::vector<float>* samples = nullptr;
  size_t start = 0;          // first index of y it is added to
  size_t offset = 0;         // its first sample added
  size_t count = 0;          // samples added (wrapping around its end when looped)
  double noise_power = 0.0;  // as used for its scale
  float scale = 0.0f;
};

// Validates additive signal number `index` (0-based) and computes its placement in a y of
// `y_length` samples at the SNR relative to `reference_energy`. Throws Error as reverberate_channel.
AdditivePlacement place_additive(const AdditiveSignal& a, size_t index, size_t y_length, double sample_rate_hz,
                                 double reference_energy, bool loop);

// y_part holds y[first, first + length): adds the placed signal's samples that fall there.
void add_placed(const AdditivePlacement& p, size_t first, float* y_part, size_t length);

// Kaldi's length of a --duration output: int32(BaseFloat fs * BaseFloat duration).
size_t kaldi_duration_samples(double sample_rate_hz, float duration_s);

// The output is out[t] = gain * y[shift + t % available] for t < length.
struct OutputGeometry {
  size_t shift = 0;
  size_t available = 0;
  size_t length = 0;
};
OutputGeometry output_geometry(size_t input_length, const PreparedRir* rir, const ReverbOptions& options,
                               double sample_rate_hz);

double output_gain(const ReverbOptions& options, double power_before, double power_after);

}  // namespace tsrir

// One far-field utterance: x_f = (x ⊛ h) + sum_i λ_i n_i[t + l_i], with the exact semantics of
// Kaldi's wav-reverberate (docs/reference/kaldi-conventions.md) plus three documented extensions:
// the SNR reference can be the full reverberant speech instead of the early part, an additive
// signal can start at an offset into itself, and it can be looped to cover the rest of the output.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "dsp/convolve.h"
#include "util/options.h"

namespace tsrir {

// What the SNR of an additive signal is relative to.
enum class SnrReference {
  // Kaldi (and the REVERB challenge): the energy of x ⊛ h_early, h_early = h[peak - 1 ms,
  // peak + 50 ms) around the signed maximum of h, averaged over its full convolution length.
  kEarlyReverb,
  // The whole reverberant speech x ⊛ h, averaged over its full length N + M - 1.
  kFullReverb,
};
const Choices<SnrReference>& snr_reference_choices();       // "early" | "full"
SnrReference parse_snr_reference(const std::string& name);
std::string snr_reference_name(SnrReference reference);

// An RIR ready to be applied many times (filter spectra computed once; thread-safe to share).
class PreparedRir {
 public:
  PreparedRir(std::vector<float> rir, double sample_rate_hz);
  size_t size() const { return rir_.size(); }
  // Index of the largest value (signed maximum, not |h|, as Kaldi): the direct path.
  size_t peak_index() const { return peak_; }
  size_t early_begin() const { return early_begin_; }
  size_t early_end() const { return early_end_; }
  const std::vector<float>& samples() const { return rir_; }
  std::vector<float> convolve_full(const std::vector<float>& x) const { return full_.convolve(x); }
  // Kaldi's early-reverberation energy: mean((x ⊛ h_early)^2) over N + L_early - 1 samples.
  double early_reverb_energy(const std::vector<float>& x) const;
  // The same as Kaldi's binary computes it, with the error of its block convolution.
  double kaldi_early_reverb_energy(const std::vector<float>& x) const;
  // The engines themselves, for the streaming path (reverberate_stream.h): h and the zero-padded
  // h_early, whose length early_filter_length() is >= early_end() - early_begin().
  const Convolver& full_convolver() const { return full_; }
  const Convolver& early_convolver() const { return early_; }
  size_t early_filter_length() const { return early_.filter_length(); }

 private:
  std::vector<float> rir_;
  size_t peak_ = 0, early_begin_ = 0, early_end_ = 0;
  Convolver full_;
  // h_early zero-padded to a power of two, which makes the engine's FFT a power of two that fits
  // the cache (4096 points at 16 kHz instead of 3375: ~3x faster here); padding only adds zeros
  // after the true output, so the energy is unchanged.
  Convolver early_;
};

// Kaldi's early window [begin, end) for a peak at `peak` in an RIR of `length` samples at `fs`,
// computed in single precision and truncated as Kaldi's int32 conversion does.
void early_reverb_window(size_t peak, size_t length, double sample_rate_hz, size_t* begin, size_t* end);

struct AdditiveSignal {
  // At the speech's sample rate; shared so that many utterances can use one loaded noise.
  std::shared_ptr<const std::vector<float>> samples;
  double snr_db = 0.0;
  double start_time_s = 0.0;    // where it enters the unshifted reverberant signal: int(t * fs)
  double offset_s = 0.0;        // extension: first sample read from it, round(offset * fs)
  bool loop = false;            // extension: looped as with ReverbOptions::loop_additive_signals
};

struct ReverbOptions {
  bool shift_output = true;      // drop the direct-path delay (shift by the RIR's peak index)
  bool normalize_output = true;  // rescale to the input's power
  float volume = 0.0f;           // > 0: fixed gain instead of normalisation (Kaldi's BaseFloat)
  float duration_s = 0.0f;       // > 0: output length int(fs * duration), tiled if longer (BaseFloat)
  SnrReference snr_reference = SnrReference::kEarlyReverb;
  // Extension: each additive signal is tiled from its offset to the end of the reverberant
  // signal (paper §4.1: noise started at a random position and repeated in a loop), and its
  // power is measured over exactly the samples that are added. Without it (Kaldi), a signal is
  // added once and its power is measured over its own length.
  bool loop_additive_signals = false;
  // Extension: reproduce Kaldi's wav-reverberate numerics, defects included (kaldi_block_error.h):
  // the error of its FFT block convolution in the reverberant speech and in the early energy, and
  // with shift_output false its output of N + M - 1 samples made of the first N repeated (the
  // reverberant tail dropped). The caller also truncates 16-bit output toward zero, as Kaldi does
  // (kaldi_truncate_to_int16).
  bool kaldi_compat = false;

  // The options wav-reverberate and reverberate-data share, under Kaldi's names: --shift-output,
  // --normalize-output, and tsrir's --snr-reference. wav-reverberate registers the others itself.
  void Register(OptionsItf* opts);
};

// Kaldi's 16-bit output: samples (full scale 1) truncated toward zero to s / 32768 and clipped to
// [-32768, 32767] / 32768, in place; returns how many were clipped.
long long kaldi_truncate_to_int16(std::vector<float>* samples);

// Parts kept separately for verification: both are in the unshifted, full-length domain
// (length N + M - 1, or N without an RIR) and before normalisation/volume.
struct ReverbParts {
  std::vector<double> reverberant_speech;   // x ⊛ h
  std::vector<double> noise;                // sum of the scaled additive signals
  double reference_energy = 0.0;            // the SNR reference's mean power
  std::vector<double> noise_power;          // per additive signal, as used for its scale
  double output_gain = 1.0;                 // normalisation or volume factor applied
};

// Applies the RIR (may be null: no reverberation), the additive signals and the output rules of
// wav-reverberate to one channel. Kaldi's --shift-output=false tail bug is not reproduced: the
// output is then the whole reverberant signal (N + M - 1 samples), tail included.
// Throws Error for an additive offset beyond a non-looped signal or empty inputs.
std::vector<float> reverberate_channel(const std::vector<float>& input, double sample_rate_hz,
                                       const PreparedRir* rir,
                                       const std::vector<AdditiveSignal>& additive,
                                       const ReverbOptions& options, ReverbParts* parts = nullptr);

}  // namespace tsrir

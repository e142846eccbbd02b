// The band-gain generator's full-band stage (LibTorch; private to src/gan and its unit tests).
//
// What separates simulated from measured RIRs above a few hundred Hz is mostly a matter of LEVELS
// in time and frequency: how strong the direct sound is per band (a directional source, a
// transducer's response), how much energy arrives early, how fast each band decays and whether
// that rate changes over time. Each input already has the fine structure a translation must keep
// (its own reflections and noise). So this stage does not synthesise waveform: it predicts, per
// RIR, a smooth gain per frequency band and per time knot after the input's direct sound, and
// applies it to the input's own band signals:
//
//   change(t) = mask(t) * sum_b (g_b(t) - 1) * x_b(t),    g_b(t) = exp(interp_k(v_bk; t - onset))
//
// - x_b: the input split into kBands zero-phase bands whose responses sum to one at every
//   frequency (raised-cosine crossfades half an octave wide on a log-frequency axis, centred at
//   kBandEdgesHz, half an octave apart), so equal gains give the input back exactly and the
//   overall spectral gain is a smooth interpolation of the band gains (a short filter: the fine
//   structure survives). Half-octave bands: with octave bands and octave-wide crossfades, a change
//   above 2-3 kHz (a loudspeaker's or an absorber's) also moved 700-1400 Hz, which the band above
//   1 kHz reaches (the fidelity suite's decay kind, bench/RESULTS.md).
// - v_bk: log gains (nepers, bounded to +-kMaxGainDb by a tanh) at kKnotMs after the input's onset
//   (its first sample within 20 dB of its peak), linear in time between knots and held beyond
//   the last. The first two knots share one value, the direct-sound gain (a flat window from
//   1 ms before to 1 ms after the onset), so the direct-to-reverberant ratio per band is one
//   parameter; the others (3 ms ... 768 ms, doubling) carry early energy and per-band decay
//   changes that may vary over time.
// - mask: zero before the onset (an RIR is silent before its direct sound). The band signals
//   of the direct sound ring on both sides of it (zero-phase bands); the mask keeps the part after
//   the onset, so what a direct-sound gain does to the direct sound is a causal filter, weaker
//   than the gain itself near the band centres (about half of g - 1), as a transducer's response
//   is causal; from a few ms after the onset on, the gains act as stated.
// - v is predicted by a linear head from the mean and maximum over positions of the generator's
//   bottleneck features (its input at unit RMS), zero-initialised: a new stage changes nothing,
//   and since d change / d v = x_b * g_b is not zero there, it is not a saddle (unlike a
//   zero-initialised waveform correction, gan_networks.cc).
#pragma once
#include <torch/torch.h>

#include <cstdint>
#include <vector>

namespace tsrir {
namespace gan {

constexpr int kBandGainBands = 11;
constexpr double kBandEdgesHz[kBandGainBands - 1] = {250.0,  353.553, 500.0,  707.107,  1000.0,
                                                     1414.21, 2000.0,  2828.43, 4000.0, 5656.85};
constexpr double kCrossfadeOctaves = 0.5;
constexpr int kBandGainKnots = 11;
constexpr double kKnotMs[kBandGainKnots] = {-1.0, 1.0, 3.0, 6.0, 12.0, 24.0, 48.0, 96.0, 192.0, 384.0, 768.0};
// The direct-sound window's knots (the first two, one shared value); the rest follow it.
constexpr int kDirectSoundKnots = 2;
constexpr double kMaxGainDb = 24.0;

// The band responses on the bins of a real FFT of `fft_length` at 16 kHz: [bands][bins], each >= 0,
// summing to 1 at every bin.
std::vector<std::vector<float>> band_gain_responses(int64_t fft_length);
// The same as a float32 tensor [bands, bins].
torch::Tensor band_gain_response_tensor(int64_t fft_length);

// Where each sample lies among the knots, for onsets [batch, 1, 1] (sample index): the segment
// [knot k, knot k+1] holding it and how far along it (0..1), both [batch, 1, length]; samples
// before the first knot or after the last are held at it.
struct KnotPosition {
  torch::Tensor segment, fraction;
};
KnotPosition knot_positions(const torch::Tensor& onset, int64_t length, double sample_rate_hz);
// Values [batch, rows, knots] interpolated linearly in time at `at`: [batch, rows, length].
torch::Tensor interpolate_knots(const torch::Tensor& values, const KnotPosition& at);

// The log gains [rows, bands, knots] that the gain identity (--identity-gain-weight) holds, [rows, held]:
// every band's knots after the direct sound, and the direct-sound knots of the lowest
// `direct_bands` bands (--identity-direct-bands). The other bands' direct sound is left to
// --gain-weight: held too, the direct kind's translators moved the direct sound 0.25-0.50 of the
// gap on five seeds; not held below 250 Hz, the decay kind's translators added a low-band part
// shared across RIRs (lf_db 1.1-2.0 dB on two seeds; 0.14 and 0.33 with it held; bench/RESULTS.md).
torch::Tensor identity_held_gains(const torch::Tensor& log_gains, int direct_bands);
// The direct-sound log gains [rows, held] of the bands from `first_band` up: the ones
// identity_held_gains(log_gains, first_band) leaves out (--identity-direct-weight's). Undefined if none.
torch::Tensor direct_gains_above(const torch::Tensor& log_gains, int first_band);

class BandGainImpl : public torch::nn::Module {
 public:
  explicit BandGainImpl(int feature_channels);
  // input [batch, 1, n] at its own scale, features [batch, channels, positions], onset [batch, 1, 1]
  // (sample index). Returns change(t) above without its mask (the generator applies its causal
  // mask to everything it adds), [batch, 1, n], float32.
  // *log_gains (if given) receives knot_log_gains(features).
  torch::Tensor forward(const torch::Tensor& input, const torch::Tensor& features, const torch::Tensor& onset,
                        torch::Tensor* log_gains = nullptr);
  // The log gains v [batch, bands, knots] (nepers) the head predicts for `features`.
  torch::Tensor knot_log_gains(const torch::Tensor& features);
  // The input's band signals x_b, [batch, bands, n], float32.
  torch::Tensor band_signals(const torch::Tensor& input);
  torch::nn::Linear head{nullptr};

 private:
  torch::Tensor responses_;  // [bands, bins] of the FFT length below, a buffer
  int64_t fft_length_ = 0;
};
TORCH_MODULE(BandGain);

}  // namespace gan
}  // namespace tsrir

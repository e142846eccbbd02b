// The error of Kaldi's FFT block convolution, for wav-reverberate --kaldi-compat (reverberate.h).
//
// Kaldi's FFTbasedBlockConvolveSignals (feat/signal.cc, used by wav-reverberate for the RIR and for
// the early-reverberation energy) convolves in blocks: FFT length L = the power of two >= 4 M for a
// filter of M taps, B = L - M + 1 input samples per block, overlap-add. Its split-radix real FFT
// packs the spectrum as [X_0, X_{L/2}, re X_1, im X_1, ...], and ElementwiseProductOfFft multiplies
// every pair as a complex number, the first pair too: DC and Nyquist come out as
//   X_0' = H_0 X_0 - H_{L/2} X_{L/2},   X_{L/2}' = H_0 X_{L/2} + H_{L/2} X_0
// instead of H_0 X_0 and H_{L/2} X_{L/2}. With X_0 = sum of the block's samples, X_{L/2} = their
// alternating sum (likewise H_0, H_{L/2} of the filter), each block's L outputs therefore carry
//   e[i] = (d + n (-1)^i) / L,   d = -H_{L/2} X_{L/2},   n = H_0 X_{L/2} + H_{L/2} X_0 - H_{L/2} X_{L/2},
// added at the block's start like its true outputs. A one-tap RIR 0.5 turns a 10 s utterance into
// half of it plus this error: ~2,500 LSB with a 4-sample RIR file (L = 16), tens of LSB with 1,000
// samples (docs/reference/kaldi-conventions.md has the derivation and measurements).
#pragma once
#include <cstddef>
#include <vector>

namespace tsrir {

// Adds Kaldi's block error for x (N samples) convolved with h (M taps) to y, the exact full
// convolution (y[0, y_length), y_length <= N + M - 1; errors past y_length are dropped as Kaldi drops
// outputs past N + M - 1).
void add_kaldi_block_error(const std::vector<float>& x, const std::vector<float>& h, float* y, size_t y_length);

// Kaldi's FFT length for a filter of `filter_length` taps: the power of two >= 4 * filter_length.
size_t kaldi_block_fft_length(size_t filter_length);

}  // namespace tsrir

// Test-only, independent float64 model of the documented wav-reverberate semantics
// (docs/reference/kaldi-conventions.md, docs/reference/spec-digest.md §4.5) plus tsrir's documented extensions,
// and generators of test signals. Shares no code with src/augment.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace reftest {

using Vec = std::vector<double>;

// Deterministic signals: a speech-like signal (noise shaped by a 4 Hz syllable envelope plus a
// gliding harmonic), an RIR (direct path of height 1 at `peak`, exponentially decaying noise
// tail with negative and positive values), a noise.
Vec speech_like(size_t n, double fs, uint64_t seed);
Vec synthetic_rir(size_t m, double fs, size_t peak, double rt60_s, uint64_t seed);
Vec noise_signal(size_t n, uint64_t seed, double amplitude = 0.3);
// Quantises to int16 steps (value * 32768 rounded, / 32768): what a 16-bit file stores.
Vec quantise16(const Vec& x);

Vec convolve(const Vec& x, const Vec& h);  // full, O(N*M)
double mean_power(const Vec& x);

struct Additive {
  Vec samples;
  double snr_db = 0;
  double start_s = 0;
  double offset_s = 0;
};

struct Options {
  bool shift_output = true;
  bool normalize_output = true;
  double volume = 0;
  double duration_s = 0;
  bool full_reference = false;   // extension: SNR relative to the whole reverberant speech
  bool loop = false;             // extension: tile additive signals from their offset
};

struct Result {
  Vec output;
  Vec reverberant;     // x * h, full length
  Vec noise;           // scaled additive signals, full length
  double reference_energy = 0;
};

// rir empty = no reverberation.
Result wav_reverberate(const Vec& x, double fs, const Vec& rir, const std::vector<Additive>& additive,
                       const Options& options);

// Minimal RIFF/WAVE writer (PCM 16/24-bit or IEEE float 32-bit), independent of libsndfile.
void write_wav(const std::string& path, const std::vector<Vec>& channels, double fs, int bits, bool is_float = false);

}  // namespace reftest

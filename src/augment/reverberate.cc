#include "augment/reverberate.h"

#include <algorithm>
#include <cmath>

#include "augment/kaldi_block_error.h"
#include "augment/reverb_steps.h"
#include "util/error.h"

namespace tsrir {
namespace {

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

const Choices<SnrReference>& snr_reference_choices() {
  static const Choices<SnrReference> choices = {{"early", SnrReference::kEarlyReverb},
                                                {"full", SnrReference::kFullReverb}};
  return choices;
}

SnrReference parse_snr_reference(const std::string& name) {
  return parse_choice(snr_reference_choices(), name, "SNR reference");
}

std::string snr_reference_name(SnrReference reference) { return choice_name(snr_reference_choices(), reference); }

void ReverbOptions::Register(OptionsItf* opts) {
  opts->Register("shift-output", &shift_output,
                 "Advance the output by the RIR's peak index (direct-path delay) and keep the input's length; "
                 "false: the whole reverberant signal (input length + RIR length - 1)");
  opts->Register("normalize-output", &normalize_output,
                 "Scale the output to the power of the input after reverberation and noise");
  opts->RegisterEnum("snr-reference", &snr_reference, snr_reference_choices(),
                     "tsrir extension: what the SNRs are relative to: early = Kaldi's early-reverberation "
                     "energy (speech convolved with the RIR from 1 ms before to 50 ms after its peak), full = "
                     "the whole reverberant speech");
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

double PreparedRir::kaldi_early_reverb_energy(const std::vector<float>& x) const {
  // Kaldi convolves the unpadded early part, over N + E - 1 outputs, with its block error.
  const std::vector<float> early(rir_.begin() + static_cast<long>(early_begin_),
                                 rir_.begin() + static_cast<long>(early_end_));
  const size_t length = x.size() + early.size() - 1;
  std::vector<float> y(length);
  early_.convolve_blocks(x, [&y, length](size_t first, const float* values, size_t count) {
    if (first < length) std::copy(values, values + std::min(count, length - first), y.begin() + static_cast<long>(first));
  });
  add_kaldi_block_error(x, early, y.data(), y.size());
  return mean_power(y);
}

long long kaldi_truncate_to_int16(std::vector<float>* samples) {
  long long clipped = 0;
  for (float& v : *samples) {
    float s = std::trunc(v * 32768.0f);
    if (s > 32767.0f || s < -32768.0f) {
      ++clipped;
      s = std::clamp(s, -32768.0f, 32767.0f);
    }
    v = s / 32768.0f;
  }
  return clipped;
}

double PreparedRir::early_reverb_energy(const std::vector<float>& x) const {
  // Summed block by block as it is produced (PowerSum gives the same sum however it is cut).
  PowerSum sum;
  early_.convolve_blocks(x, [&sum](size_t, const float* values, size_t count) { sum.add(values, count); });
  return early_energy_from_padded_power(sum.mean(), x.size(), *this);
}

std::vector<float> reverberate_channel(const std::vector<float>& input, double sample_rate_hz,
                                       const PreparedRir* rir,
                                       const std::vector<AdditiveSignal>& additive,
                                       const ReverbOptions& options, ReverbParts* parts) {
  if (input.empty()) throw Error("empty input signal");
  if (!(sample_rate_hz > 0)) throw Error("invalid sample rate");
  const double power_before = mean_power(input);

  std::vector<float> y;
  double reference_energy = power_before;
  if (rir) {
    y = rir->convolve_full(input);
    if (options.kaldi_compat) add_kaldi_block_error(input, rir->samples(), y.data(), y.size());
    // Only the additive signals' scales use it (the early convolution is a third of the work).
    if (!additive.empty() || parts) {
      if (options.snr_reference == SnrReference::kFullReverb) {
        reference_energy = mean_power(y);
      } else {
        reference_energy =
            options.kaldi_compat ? rir->kaldi_early_reverb_energy(input) : rir->early_reverb_energy(input);
      }
    }
  } else {
    y = input;
  }
  if (parts) {
    parts->reverberant_speech.assign(y.begin(), y.end());
    parts->noise.assign(y.size(), 0.0);
    parts->noise_power.clear();
    parts->reference_energy = reference_energy;
  }

  for (size_t i = 0; i < additive.size(); ++i) {
    const AdditivePlacement p = place_additive(additive[i], i, y.size(), sample_rate_hz, reference_energy,
                                               options.loop_additive_signals || additive[i].loop);
    add_placed(p, 0, y.data(), y.size());
    if (parts) {
      std::vector<float> alone(y.size(), 0.0f);
      add_placed(p, 0, alone.data(), alone.size());
      for (size_t t = 0; t < y.size(); ++t) parts->noise[t] += alone[t];
      parts->noise_power.push_back(p.noise_power);
    }
  }

  const double gain = output_gain(options, power_before, mean_power(y));
  if (parts) parts->output_gain = gain;

  const OutputGeometry g = output_geometry(input.size(), rir, options, sample_rate_hz);
  std::vector<float> out(g.length);
  const float gain_f = static_cast<float>(gain);
  const float* src = y.data() + g.shift;
  for (size_t done = 0; done < g.length;) {
    const size_t run = std::min(g.available, g.length - done);
    for (size_t j = 0; j < run; ++j) out[done + j] = gain_f * src[j];
    done += run;
  }
  return out;
}

}  // namespace tsrir

#include "eq/relative_gain.h"

#include <algorithm>
#include <cmath>

#include "dsp/fft.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {

const Choices<GainMethod>& gain_method_choices() {
  static const Choices<GainMethod> choices = {
      {"octave", GainMethod::kOctave}, {"smooth", GainMethod::kSmooth}, {"bin", GainMethod::kBin}};
  return choices;
}

GainMethod parse_gain_method(const std::string& name) {
  return parse_choice(gain_method_choices(), name, "gain method");
}

std::string gain_method_name(GainMethod method) { return choice_name(gain_method_choices(), method); }

size_t eq_fft_size(size_t num_samples) {
  size_t n = 16384;
  while (n < num_samples) n *= 2;
  return n;
}

void check_eq_sample_rate(double sample_rate_hz, const std::string& what) {
  if (!(sample_rate_hz >= kEqMinSampleRateHz)) {
    throw Error(what + ": sample rate " + format_double(sample_rate_hz) +
                " Hz is too low for the EQ: the 8000 Hz sample point lies above Nyquist; resample to at least " +
                format_double(kEqMinSampleRateHz) + " Hz");
  }
}

EqBandGrid::EqBandGrid(size_t fft_size, double sample_rate_hz, GainMethod method)
    : fft_size_(fft_size), sample_rate_hz_(sample_rate_hz), method_(method) {
  check_eq_sample_rate(sample_rate_hz, "EQ band grid");
  const size_t nyquist_bin = fft_size / 2;
  const double bin_width_hz = sample_rate_hz / fft_size;
  for (int j = 0; j < kEqNumNodes; ++j) {
    const double fc = kEqNodesHz[j];
    if (method == GainMethod::kBin) {
      size_t b = static_cast<size_t>(std::lround(fc / bin_width_hz));
      first_[j] = last_[j] = std::min(b, nyquist_bin);
      continue;
    }
    const double half_width = method == GainMethod::kOctave ? std::sqrt(2.0) : std::pow(2.0, 1.0 / 6.0);
    const double lo_hz = fc / half_width;
    const double hi_hz = std::min(fc * half_width, sample_rate_hz / 2);  // clipped at Nyquist
    size_t first = static_cast<size_t>(std::ceil(lo_hz / bin_width_hz - 1e-9));
    size_t last = static_cast<size_t>(std::floor(hi_hz / bin_width_hz + 1e-9));
    last = std::min(last, nyquist_bin);
    if (first > last) {  // only possible for absurdly small FFTs; keep the nearest bin
      first = last = std::min(static_cast<size_t>(std::lround(fc / bin_width_hz)), nyquist_bin);
    }
    first_[j] = first;
    last_[j] = last;
  }
}

std::array<double, kEqNumNodes> EqBandGrid::band_powers(const std::vector<double>& power) const {
  if (power.size() != fft_size_ / 2 + 1) throw Error("EQ band grid: power spectrum has the wrong size");
  std::array<double, kEqNumNodes> out{};
  for (int j = 0; j < kEqNumNodes; ++j) {
    double sum = 0.0;
    for (size_t b = first_[j]; b <= last_[j]; ++b) sum += power[b];
    out[j] = sum / static_cast<double>(last_[j] - first_[j] + 1);
  }
  return out;
}

RelativeGainsDb EqBandGrid::relative_gains(const std::array<double, kEqNumNodes>& band_power, const std::string& what) {
  double max_power = 0.0;
  for (double p : band_power) {
    if (!std::isfinite(p)) throw Error(what + ": non-finite spectrum");
    max_power = std::max(max_power, p);
  }
  if (max_power <= 0.0) throw Error(what + ": the RIR is silent (no energy in any EQ band)");
  // 120 dB below the strongest band is near the rounding noise of float samples (~-140 dB):
  // treat it as no energy rather than as a gain the EQ would try to correct with absurd boosts.
  const double floor = max_power * 1e-12;
  for (int j = 0; j < kEqNumNodes; ++j) {
    if (band_power[j] <= floor) {
      throw Error(what + ": no energy in the " + format_double(kEqNodesHz[j]) +
                  " Hz band (more than 120 dB below the strongest band); relative gains are undefined");
    }
  }
  RelativeGainsDb g{};
  for (int k = 0; k < kEqNumPoints; ++k) {
    g[k] = 10.0 * std::log10(band_power[eq_node_of_point(k)] / band_power[kEqReferenceNode]);
  }
  return g;
}

RelativeGainsDb relative_gains_db(const Signal& rir, GainMethod method) {
  const std::string what = "RIR '" + rir.id + "'";
  check_eq_sample_rate(rir.sample_rate_hz, what);
  if (rir.samples.empty()) throw Error(what + ": empty RIR");
  bool any = false;
  for (float v : rir.samples) {
    if (!std::isfinite(v)) throw Error(what + ": non-finite sample");
    if (v != 0.0f) any = true;
  }
  if (!any) throw Error(what + ": the RIR is silent (all samples are zero)");
  const size_t n = eq_fft_size(rir.samples.size());
  EqBandGrid grid(n, rir.sample_rate_hz, method);
  return EqBandGrid::relative_gains(grid.band_powers(power_spectrum(rir.samples, n)), what);
}

}  // namespace tsrir

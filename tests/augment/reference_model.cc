#include "reference_model.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <stdexcept>

namespace reftest {

Vec speech_like(size_t n, double fs, uint64_t seed) {
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  Vec x(n);
  double lp = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double t = i / fs;
    const double envelope = 0.5 * (1.0 - std::cos(2 * M_PI * 4.0 * t)) * (0.6 + 0.4 * std::sin(2 * M_PI * 0.7 * t));
    lp = 0.7 * lp + 0.3 * g(gen);
    const double f0 = 120.0 + 30.0 * std::sin(2 * M_PI * 0.5 * t);
    x[i] = envelope * (0.25 * lp + 0.15 * std::sin(2 * M_PI * f0 * t) + 0.05 * std::sin(2 * M_PI * 3 * f0 * t));
  }
  return x;
}

Vec synthetic_rir(size_t m, double fs, size_t peak, double rt60_s, uint64_t seed) {
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  Vec h(m, 0.0);
  const double decay = 6.9077552789821 / rt60_s;  // ln(1000): 60 dB amplitude^2 over rt60
  for (size_t i = peak + 1; i < m; ++i) h[i] = 0.3 * g(gen) * std::exp(-decay * (i - peak) / fs);
  for (size_t i = peak + 1; i < m; ++i) h[i] = std::clamp(h[i], -0.9, 0.9);
  h[peak] = 0.95;
  return h;
}

Vec noise_signal(size_t n, uint64_t seed, double amplitude) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  Vec x(n);
  double slow = 0.0;
  for (size_t i = 0; i < n; ++i) {
    slow = 0.999 * slow + 0.001 * u(gen) * 30.0;  // nonstationary level: makes offsets matter
    x[i] = std::clamp(u(gen) * (0.5 + std::abs(slow)), -0.99, 0.99);
  }
  return x;
}

Vec quantise16(const Vec& x) {
  Vec q(x.size());
  for (size_t i = 0; i < x.size(); ++i) q[i] = std::clamp(std::round(x[i] * 32768.0), -32768.0, 32767.0) / 32768.0;
  return q;
}

Vec convolve(const Vec& x, const Vec& h) {
  Vec y(x.size() + h.size() - 1, 0.0);
  for (size_t k = 0; k < h.size(); ++k) {
    if (h[k] == 0.0) continue;
    for (size_t n = 0; n < x.size(); ++n) y[n + k] += h[k] * x[n];
  }
  return y;
}

double mean_power(const Vec& x) {
  double s = 0;
  for (double v : x) s += v * v;
  return x.empty() ? 0.0 : s / x.size();
}

Result wav_reverberate(const Vec& x, double fs, const Vec& rir, const std::vector<Additive>& additive,
                       const Options& o) {
  Result r;
  const size_t n = x.size();
  const double p_in = mean_power(x);
  size_t shift = 0;
  Vec y;
  double e = p_in;
  if (!rir.empty()) {
    size_t pk = std::max_element(rir.begin(), rir.end()) - rir.begin();
    long b = static_cast<long>(pk) - static_cast<long>(0.001 * fs);
    long end = static_cast<long>(pk) + static_cast<long>(0.05 * fs);
    b = std::max(0L, b);
    end = std::min(static_cast<long>(rir.size()), end);
    Vec early(rir.begin() + b, rir.begin() + end);
    y = convolve(x, rir);
    e = o.full_reference ? mean_power(y) : mean_power(convolve(x, early));
    if (o.shift_output) shift = pk;
  } else {
    y = x;
  }
  r.reverberant = y;
  r.noise.assign(y.size(), 0.0);
  r.reference_energy = e;
  for (const Additive& a : additive) {
    const size_t start = static_cast<size_t>(a.start_s * fs);
    const size_t k = a.samples.size();
    size_t off = static_cast<size_t>(std::llround(a.offset_s * fs));
    Vec seg;
    if (o.loop) {
      off %= k;
      for (size_t j = 0; start + j < y.size(); ++j) seg.push_back(a.samples[(off + j) % k]);
    } else {
      seg.assign(a.samples.begin() + off, a.samples.end());
    }
    const double p_noise = mean_power(seg) + FLT_EPSILON / (32768.0 * 32768.0);
    const double scale = std::sqrt(std::pow(10.0, -a.snr_db / 10.0) * e / p_noise);
    for (size_t j = 0; j < seg.size() && start + j < y.size(); ++j) {
      y[start + j] += scale * seg[j];
      r.noise[start + j] += scale * seg[j];
    }
  }
  double gain = 1.0;
  if (o.volume > 0) gain = o.volume;
  else if (o.normalize_output) gain = std::sqrt(p_in / mean_power(y));
  const size_t avail = (!rir.empty() && o.shift_output) ? n : y.size();
  // Kaldi: int32 num_samp_output = samp_freq * duration, a product of two BaseFloats.
  const size_t out_len =
      o.duration_s > 0 ? static_cast<size_t>(static_cast<float>(fs) * static_cast<float>(o.duration_s)) : avail;
  r.output.resize(out_len);
  for (size_t j = 0; j < out_len; ++j) r.output[j] = gain * y[shift + j % avail];
  return r;
}

namespace {
void put16(std::ofstream& f, uint32_t v) { f.put(char(v & 0xff)); f.put(char((v >> 8) & 0xff)); }
void put32(std::ofstream& f, uint32_t v) { put16(f, v & 0xffff); put16(f, v >> 16); }
}  // namespace

void write_wav(const std::string& path, const std::vector<Vec>& channels, double fs, int bits, bool is_float) {
  std::ofstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("cannot write " + path);
  const uint32_t nch = channels.size(), frames = channels[0].size(), bytes = bits / 8;
  const uint32_t data = frames * nch * bytes;
  f.write("RIFF", 4);
  put32(f, 36 + data);
  f.write("WAVEfmt ", 8);
  put32(f, 16);
  put16(f, is_float ? 3 : 1);
  put16(f, nch);
  put32(f, static_cast<uint32_t>(fs));
  put32(f, static_cast<uint32_t>(fs) * nch * bytes);
  put16(f, nch * bytes);
  put16(f, bits);
  f.write("data", 4);
  put32(f, data);
  for (uint32_t i = 0; i < frames; ++i) {
    for (uint32_t c = 0; c < nch; ++c) {
      const double v = channels[c][i];
      if (is_float) {
        float fv = static_cast<float>(v);
        uint32_t u;
        std::memcpy(&u, &fv, 4);
        put32(f, u);
      } else {
        const double full = std::pow(2.0, bits - 1);
        long q = std::lround(std::clamp(v * full, -full, full - 1));
        uint32_t u = static_cast<uint32_t>(q);
        for (uint32_t b = 0; b < bytes; ++b) f.put(char((u >> (8 * b)) & 0xff));
      }
    }
  }
}

}  // namespace reftest

#include "metrics/lundeby.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace tsrir {

namespace {

struct Envelope {
  std::vector<double> time_s;  // block centres
  std::vector<double> level_db;
};

// Non-overlapping block means of the energy; a final partial block is kept if at least half full.
// `tail` holds the backward sums tail[i] = sum_{k>=i} e[k] (tail[n] = 0), so a block costs O(1)
// however often Lundeby's iterations re-smooth; differences of backward sums stay accurate in the
// quiet end where the noise is measured.
Envelope smooth_blocks(const double* tail, size_t n, size_t block, double fs) {
  Envelope env;
  block = std::max<size_t>(block, 1);
  env.time_s.reserve(n / block + 1);
  env.level_db.reserve(n / block + 1);
  for (size_t start = 0; start < n; start += block) {
    const size_t stop = std::min(n, start + block);
    if (stop - start < (block + 1) / 2 && start > 0) break;
    const double mean = std::max(0.0, tail[start] - tail[stop]) / (double)(stop - start);
    env.time_s.push_back(0.5 * (double)(start + stop) / fs);
    env.level_db.push_back(mean > 0 ? 10.0 * std::log10(mean) : -400.0);
  }
  return env;
}

double mean_energy(const double* tail, size_t begin, size_t n) {
  if (begin >= n) begin = n - 1;
  return std::max(0.0, tail[begin] - tail[n]) / (double)(n - begin);
}

struct Line {
  bool ok = false;
  double slope = 0, intercept = 0;  // dB = intercept + slope * t
};

Line regress(const Envelope& env, size_t first, size_t last) {
  Line line;
  if (last <= first || last >= env.time_s.size()) return line;
  const double m = (double)(last - first + 1);
  double sx = 0, sy = 0;
  for (size_t i = first; i <= last; ++i) {
    sx += env.time_s[i];
    sy += env.level_db[i];
  }
  const double mx = sx / m, my = sy / m;
  double sxx = 0, sxy = 0;
  for (size_t i = first; i <= last; ++i) {
    sxx += (env.time_s[i] - mx) * (env.time_s[i] - mx);
    sxy += (env.time_s[i] - mx) * (env.level_db[i] - my);
  }
  if (!(sxx > 0)) return line;
  line.slope = sxy / sxx;
  line.intercept = my - line.slope * mx;
  line.ok = line.slope < 0;
  return line;
}

}  // namespace

LundebyResult lundeby_intersection(const double* energy, size_t n, double fs, double center_hz) {
  std::vector<double> tail(n + 1, 0.0);
  for (size_t i = n; i-- > 0;) tail[i] = tail[i + 1] + energy[i];
  return lundeby_intersection_from_tail(tail.data(), n, fs, center_hz);
}

LundebyResult lundeby_intersection_from_tail(const double* tail, size_t n, double fs, double center_hz) {
  LundebyResult r;
  if (n < 16 || !(fs > 0)) {
    r.failure = "too few samples for a noise estimate";
    return r;
  }
  const double duration_s = (double)n / fs;
  // Step 1: initial smoothing, 30 ms broadband or (800/fc + 10) ms in a band.
  const double block_s = center_hz > 0 ? (800.0 / center_hz + 10.0) * 1e-3 : 30e-3;
  Envelope env = smooth_blocks(tail, n, (size_t)std::lround(block_s * fs), fs);
  if (env.level_db.size() < 3) {
    r.failure = "RIR too short for the noise-floor analysis";
    return r;
  }
  // Step 2: noise from the last 10 %.
  double noise = mean_energy(tail, (size_t)(0.9 * (double)n), n);
  const size_t peak_block = (size_t)(std::max_element(env.level_db.begin(), env.level_db.end()) - env.level_db.begin());
  const double peak_db = env.level_db[peak_block];
  if (noise <= 0) {
    // An exactly silent tail (zero-padded or synthetic): nothing to truncate.
    r.ok = true;
    r.intersection = n;
    r.noise_power = 0;
    r.late_decay_time_s = 0;
    r.peak_to_noise_db = std::numeric_limits<double>::infinity();
    return r;
  }
  double noise_db = 10.0 * std::log10(noise);
  r.peak_to_noise_db = peak_db - noise_db;
  if (r.peak_to_noise_db < 10.0) {
    r.failure = "decay only " + std::to_string((int)std::lround(r.peak_to_noise_db)) + " dB above the noise";
    return r;
  }
  // Step 3: regression from the peak to 10 dB above the noise.
  size_t stop = peak_block;
  while (stop + 1 < env.level_db.size() && env.level_db[stop + 1] > noise_db + 10.0) ++stop;
  Line line = regress(env, peak_block, stop);
  if (!line.ok) {
    r.failure = "no decay found above the noise";
    return r;
  }
  // Step 4: preliminary crossing point.
  double cross_s = std::clamp((noise_db - line.intercept) / line.slope, 0.0, duration_s);
  // Steps 5-6: re-smooth at 5 blocks per 10 dB of decay and iterate.
  const double onset_db = peak_db;
  int it = 0;
  for (; it < 30; ++it) {
    const double decay10_s = -10.0 / line.slope;
    const size_t block = std::max<size_t>(1, (size_t)std::lround(decay10_s / 5.0 * fs));
    env = smooth_blocks(tail, n, block, fs);
    const size_t noise_start = std::min((size_t)std::lround((cross_s + decay10_s) * fs), (size_t)(0.9 * (double)n));
    noise = mean_energy(tail, noise_start, n);
    if (!(noise > 0)) break;
    noise_db = 10.0 * std::log10(noise);
    // Late decay: 20 dB of range ending 10 dB above the noise (from the peak if it is lower).
    const double top_db = std::min(noise_db + 30.0, onset_db);
    size_t first = 0;
    const size_t peak = (size_t)(std::max_element(env.level_db.begin(), env.level_db.end()) - env.level_db.begin());
    first = peak;
    while (first < env.level_db.size() && env.level_db[first] > top_db) ++first;
    size_t last = first;
    while (last + 1 < env.level_db.size() && env.level_db[last + 1] > noise_db + 10.0) ++last;
    const Line next = regress(env, first, last);
    if (!next.ok || last < first + 1) break;
    line = next;
    const double new_cross = std::clamp((noise_db - line.intercept) / line.slope, 0.0, duration_s);
    const bool converged = std::abs(new_cross - cross_s) < 0.01;
    cross_s = new_cross;
    if (converged) break;
  }
  r.ok = true;
  r.iterations = it + 1;
  r.intersection = std::clamp<size_t>((size_t)std::lround(cross_s * fs), 1, n);
  r.noise_power = noise;
  r.late_decay_time_s = -60.0 / line.slope;
  return r;
}

double lundeby_tail_energy(const LundebyResult& result, double fs) {
  if (!result.ok || !(result.noise_power > 0) || !(result.late_decay_time_s > 0)) return 0.0;
  return result.noise_power * result.late_decay_time_s / (6.0 * std::log(10.0)) * fs;
}

}  // namespace tsrir

// Deterministic random numbers that do not depend on the standard library's distribution code
// (so results are the same with any libstdc++), with per-item streams derived from (seed, key):
// an item's draws never depend on thread count or processing order.
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace tsrir {

// 64-bit FNV-1a of a string; stable across platforms.
uint64_t stable_hash(std::string_view text);

class Rng {
 public:
  explicit Rng(uint64_t seed = 0);
  // A stream for one item: independent of every other key for the same seed.
  static Rng for_item(uint64_t seed, std::string_view key);

  uint64_t next_u64();
  double uniform();                         // [0, 1)
  double uniform(double lo, double hi);     // [lo, hi)
  // out[i] = float(uniform(lo, hi)) for i = 0..n-1: the same draws and values as that loop, without
  // a call per draw (a diffuse tail draws one per sample).
  void fill_uniform(double lo, double hi, float* out, size_t n);
  uint64_t below(uint64_t n);               // uniform integer in [0, n), unbiased
  double normal();                          // standard normal (Box-Muller, cached pair)
  double normal(double mean, double stddev);

 private:
  uint64_t s_[4];
  bool have_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace tsrir

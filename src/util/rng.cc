#include "util/rng.h"

namespace tsrir {
namespace {
uint64_t splitmix64(uint64_t& x) {
  uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
inline uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
}  // namespace

uint64_t stable_hash(std::string_view text) {
  uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

Rng::Rng(uint64_t seed) {
  uint64_t x = seed;
  for (auto& s : s_) s = splitmix64(x);
}

Rng Rng::for_item(uint64_t seed, std::string_view key) {
  uint64_t x = seed ^ 0x5851f42d4c957f2dULL;
  uint64_t mixed = splitmix64(x) ^ stable_hash(key);
  return Rng(mixed);
}

namespace {
// xoshiro256**: fast, 256-bit state, passes BigCrush. A local function, which the compiler inlines
// (a member of this position-independent library could be interposed, so it would not).
inline uint64_t xoshiro_next(uint64_t* s) {
  const uint64_t result = rotl(s[1] * 5, 7) * 9;
  const uint64_t t = s[1] << 17;
  s[2] ^= s[0];
  s[3] ^= s[1];
  s[1] ^= s[2];
  s[0] ^= s[3];
  s[2] ^= t;
  s[3] = rotl(s[3], 45);
  return result;
}
inline double unit_interval(uint64_t bits) { return (bits >> 11) * 0x1.0p-53; }
}  // namespace

uint64_t Rng::next_u64() { return xoshiro_next(s_); }

double Rng::uniform() { return unit_interval(next_u64()); }
double Rng::uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

void Rng::fill_uniform(double lo, double hi, float* out, size_t n) {
  uint64_t s[4] = {s_[0], s_[1], s_[2], s_[3]};  // in registers, not reloaded after every store
  for (size_t i = 0; i < n; ++i) out[i] = static_cast<float>(lo + (hi - lo) * unit_interval(xoshiro_next(s)));
  for (int k = 0; k < 4; ++k) s_[k] = s[k];
}

uint64_t Rng::below(uint64_t n) {
  if (n <= 1) return 0;
  const uint64_t limit = UINT64_MAX - UINT64_MAX % n;
  uint64_t r;
  do r = next_u64();
  while (r >= limit);
  return r % n;
}

double Rng::normal() {
  if (have_spare_) {
    have_spare_ = false;
    return spare_;
  }
  double u1;
  do u1 = uniform();
  while (u1 <= 0.0);
  const double u2 = uniform();
  const double r = std::sqrt(-2.0 * std::log(u1));
  const double a = 2.0 * M_PI * u2;
  spare_ = r * std::sin(a);
  have_spare_ = true;
  return r * std::cos(a);
}

double Rng::normal(double mean, double stddev) { return mean + stddev * normal(); }

}  // namespace tsrir

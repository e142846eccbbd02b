#include "dsp/octave_filter.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "util/cpu_clones.h"
#include "util/error.h"

namespace tsrir {

namespace {

using cd = std::complex<double>;

Biquad section_from_poles(cd p1, cd p2) {
  // Every bandpass section carries one zero at z = 1 and one at z = -1: numerator 1 - z^-2.
  Biquad q;
  q.b0 = 1.0;
  q.b1 = 0.0;
  q.b2 = -1.0;
  q.a1 = -(p1 + p2).real();
  q.a2 = (p1 * p2).real();
  return q;
}

}  // namespace

SosFilter butterworth_bandpass(int order, double low_hz, double high_hz, double sample_rate_hz) {
  if (order < 1 || !(sample_rate_hz > 0) || !(low_hz > 0) || !(high_hz > low_hz) ||
      !(high_hz < sample_rate_hz / 2)) {
    throw Error("butterworth_bandpass: need order >= 1 and 0 < low < high < fs/2 (order " +
                std::to_string(order) + ", " + std::to_string(low_hz) + ".." + std::to_string(high_hz) +
                " Hz at " + std::to_string(sample_rate_hz) + " Hz)");
  }
  const double two_fs = 2.0 * sample_rate_hz;
  // Pre-warp so the digital -3 dB points land exactly on the requested edges.
  const double w1 = two_fs * std::tan(M_PI * low_hz / sample_rate_hz);
  const double w2 = two_fs * std::tan(M_PI * high_hz / sample_rate_hz);
  const double bw = w2 - w1;
  const double w0_sq = w1 * w2;

  std::vector<cd> complex_poles, real_poles;
  for (int k = 0; k < order; ++k) {
    const cd p = std::polar(1.0, M_PI * (2.0 * k + order + 1) / (2.0 * order));
    if (p.imag() < -1e-12) continue;  // its conjugate's sections cover it
    const cd half = p * bw / 2.0;
    const cd root = std::sqrt(half * half - w0_sq);
    for (cd s : {half + root, half - root}) {
      const cd z = (1.0 + s / two_fs) / (1.0 - s / two_fs);
      if (std::abs(p.imag()) <= 1e-12) {
        // A real prototype pole maps to a conjugate pair (or two real poles for wide bands).
        if (std::abs(z.imag()) > 1e-12) {
          if (z.imag() > 0) complex_poles.push_back(z);
        } else {
          real_poles.push_back(cd(z.real(), 0.0));
        }
      } else {
        complex_poles.push_back(z);
      }
    }
  }
  SosFilter f;
  for (const cd& z : complex_poles) f.sections.push_back(section_from_poles(z, std::conj(z)));
  for (size_t i = 0; i + 1 < real_poles.size(); i += 2) f.sections.push_back(section_from_poles(real_poles[i], real_poles[i + 1]));

  // Unit gain at the centre: the analog bandpass has |H(j w0)| = 1, and the bilinear map sends
  // w0 to 2 atan(w0 / 2fs).
  const double centre_hz = sample_rate_hz / M_PI * std::atan(std::sqrt(w0_sq) / two_fs);
  const double g = 1.0 / std::abs(sos_response(f, centre_hz, sample_rate_hz));
  const double per_section = std::pow(g, 1.0 / f.sections.size());
  for (Biquad& q : f.sections) {
    q.b0 *= per_section;
    q.b1 *= per_section;
    q.b2 *= per_section;
  }
  return f;
}

BandEdgesHz ansi_octave_edges_hz(double center_hz, int order) {
  const double beta = (M_PI / 2.0 / order) / std::sin(M_PI / 2.0 / order);
  const double alpha = (1.0 + std::sqrt(1.0 + 8.0 * beta * beta)) / (4.0 * beta);
  return {center_hz / std::sqrt(2.0) / alpha, center_hz * std::sqrt(2.0) * alpha};
}

SosFilter ansi_octave_filter(double center_hz, double sample_rate_hz, int order) {
  const BandEdgesHz e = ansi_octave_edges_hz(center_hz, order);
  return butterworth_bandpass(order, e.low_hz, e.high_hz, sample_rate_hz);
}

std::complex<double> sos_response(const SosFilter& filter, double freq_hz, double sample_rate_hz) {
  const cd zi = std::polar(1.0, -2.0 * M_PI * freq_hz / sample_rate_hz);  // z^-1
  cd h = 1.0;
  for (const Biquad& q : filter.sections) {
    h *= (q.b0 + q.b1 * zi + q.b2 * zi * zi) / (1.0 + q.a1 * zi + q.a2 * zi * zi);
  }
  return h;
}

void sos_filter(const SosFilter& filter, const float* x, size_t n, double* y) {
  for (size_t i = 0; i < n; ++i) y[i] = x[i];
  for (const Biquad& q : filter.sections) {
    double z1 = 0, z2 = 0;  // transposed direct form II
    for (size_t i = 0; i < n; ++i) {
      const double v = y[i];
      const double out = q.b0 * v + z1;
      z1 = q.b1 * v - q.a1 * out + z2;
      z2 = q.b2 * v - q.a2 * out;
      y[i] = out;
    }
  }
}

std::vector<double> sos_filter(const SosFilter& filter, const std::vector<float>& x) {
  std::vector<double> y(x.size());
  sos_filter(filter, x.data(), x.size(), y.data());
  return y;
}

std::vector<double> sos_filter_reversed(const SosFilter& filter, const std::vector<float>& x) {
  std::vector<float> r(x.rbegin(), x.rend());
  std::vector<double> y = sos_filter(filter, r);
  std::reverse(y.begin(), y.end());
  return y;
}

namespace {

// Bandpass sections all have numerator g (1 - z^-2). With the gains pulled out, a section is
//   o = v + z1;  z1 = z2 - a1 o;  z2 = -v - a2 o
// and four bands run as the four lanes of one vector (AVX2 where the CPU has it).
typedef double Lanes __attribute__((vector_size(32)));

// One sample through a cascade of bandpass sections (numerator 1 - z^-2, transposed direct form II),
// lane by lane, in place in *x; V is a vector of lanes. Inlined into each caller, so it takes the
// caller's target (vectors pass by pointer: by value they would tie the ABI to the target).
template <typename V>
__attribute__((always_inline)) inline void bandpass_cascade(V* x, V* z1, V* z2, const V* a1, const V* a2, size_t ns) {
  V v = *x;
  for (size_t s = 0; s < ns; ++s) {
    const V o = v + z1[s];
    z1[s] = z2[s] - a1[s] * o;
    z2[s] = -v - a2[s] * o;
    v = o;
  }
  *x = v;
}

bool is_bandpass_form(const SosFilter& f) {
  for (const Biquad& q : f.sections)
    if (q.b1 != 0.0 || q.b2 != -q.b0) return false;
  return true;
}

// Filters b0 .. b0 + lanes - 1 (bandpass form, same section count) as per-lane coefficients
// ([section][lane]) and gains: lanes past the last filter run a harmless stable section with gain 0.
void pack_bandpass_lanes(const std::vector<SosFilter>& filters, size_t b0, size_t lanes, double* a1, double* a2,
                         double* gain) {
  const size_t nb = filters.size(), ns = filters[0].sections.size();
  for (size_t l = 0; l < lanes; ++l) {
    const size_t b = b0 + l;
    double g = 1.0;
    for (size_t s = 0; s < ns; ++s) {
      a1[lanes * s + l] = b < nb ? filters[b].sections[s].a1 : 0.0;
      a2[lanes * s + l] = b < nb ? filters[b].sections[s].a2 : 0.0;
      if (b < nb) g *= filters[b].sections[s].b0;
    }
    gain[l] = b < nb ? g : 0.0;
  }
}

TSRIR_AVX2_CLONES
void bandpass_lanes(const float* x, size_t n, bool time_reversed, size_t ns, const double* a1_coef,
                    const double* a2_coef, const double* gain_coef, double* const* dst) {
  // Coefficients arrive as plain doubles ([section][lane]): vector-typed parameters would tie
  // the ABI to the instruction set of each clone.
  Lanes z1[16], z2[16], a1[16], a2[16];
  for (size_t s = 0; s < ns; ++s) {
    z1[s] = Lanes{0, 0, 0, 0};
    z2[s] = Lanes{0, 0, 0, 0};
    a1[s] = Lanes{a1_coef[4 * s], a1_coef[4 * s + 1], a1_coef[4 * s + 2], a1_coef[4 * s + 3]};
    a2[s] = Lanes{a2_coef[4 * s], a2_coef[4 * s + 1], a2_coef[4 * s + 2], a2_coef[4 * s + 3]};
  }
  const Lanes gain = {gain_coef[0], gain_coef[1], gain_coef[2], gain_coef[3]};
  for (size_t k = 0; k < n; ++k) {
    const size_t i = time_reversed ? n - 1 - k : k;
    const double in = x[i];
    Lanes v = {in, in, in, in};
    bandpass_cascade(&v, z1, z2, a1, a2, ns);
    v *= gain;
    dst[0][i] = v[0];
    dst[1][i] = v[1];
    dst[2][i] = v[2];
    dst[3][i] = v[3];
  }
}

// Eight lanes time-reversed, each output squared and summed from the end as it is made, as G = 8 / L
// vectors V of L lanes (two of four, or one of eight). Per lane the arithmetic is bandpass_lanes'
// and then a square and an add, in the order a band-by-band loop does them, so the values are the
// same to the bit whatever the vector width; two groups of four overlap their recursions' latency.
// The squares go out as whole vectors, sample-major (energy[8 i + lane]); the sums band by band, as
// the decay analysis reads them. NS > 0 fixes the section count at compile time (the state then
// stays in registers); NS = 0 takes `ns`.
template <typename V, size_t NS>
__attribute__((always_inline)) inline void energy_lanes_body(const float* x, size_t n, size_t ns,
                                                             const double* a1_coef, const double* a2_coef,
                                                             const double* gain_coef, double* energy,
                                                             double* const* tail_rows, double* peak) {
  constexpr int L = sizeof(V) / sizeof(double), G = 8 / L;
  if (NS > 0) ns = NS;
  V z1[G][16], z2[G][16], a1[G][16], a2[G][16], gain[G], sum[G], top[G];
  double* tail[8];
  for (int l = 0; l < 8; ++l) tail[l] = tail_rows[l];
  for (int g = 0; g < G; ++g) {
    for (size_t s = 0; s < ns; ++s) {
      z1[g][s] = V{};
      z2[g][s] = V{};
      std::memcpy(&a1[g][s], a1_coef + 8 * s + L * g, sizeof(V));
      std::memcpy(&a2[g][s], a2_coef + 8 * s + L * g, sizeof(V));
    }
    std::memcpy(&gain[g], gain_coef + L * g, sizeof(V));
    sum[g] = V{};
    top[g] = V{};
  }
  for (size_t i = n; i-- > 0;) {
    const double in = x[i];
    for (int g = 0; g < G; ++g) {
      V v;
      for (int l = 0; l < L; ++l) v[l] = in;
      bandpass_cascade(&v, z1[g], z2[g], a1[g], a2[g], ns);
      v *= gain[g];
      const V e = v * v;
      sum[g] += e;
      top[g] = top[g] < e ? e : top[g];
      std::memcpy(energy + 8 * i + L * g, &e, sizeof e);
      for (int l = 0; l < L; ++l) tail[L * g + l][i] = sum[g][l];
    }
  }
  for (int g = 0; g < G; ++g) std::memcpy(peak + L * g, &top[g], sizeof(V));
}

#if TSRIR_HAVE_AVX512_TARGET
// The eight lanes as one 512-bit vector, for CPUs with AVX-512F: half the vector instructions of two
// groups of four, the same values (the target keeps AVX-512F's fused multiply-adds out: cpu_clones.h).
// The octave bands' order only (3 sections); other orders take bandpass_energy_lanes.
typedef double Lanes8 __attribute__((vector_size(64)));

TSRIR_AVX512_TARGET void bandpass_energy_lanes8(const float* x, size_t n, const double* a1_coef,
                                                const double* a2_coef, const double* gain_coef, double* energy,
                                                double* const* tail, double* peak) {
  energy_lanes_body<Lanes8, 3>(x, n, 3, a1_coef, a2_coef, gain_coef, energy, tail, peak);
}
#endif

// Coefficients arrive as plain doubles, as in bandpass_lanes.
TSRIR_AVX2_CLONES
void bandpass_energy_lanes(const float* x, size_t n, size_t ns, const double* a1_coef, const double* a2_coef,
                           const double* gain_coef, double* energy, double* const* tail, double* peak) {
  if (ns == 3) {  // ANSI order 3, the octave bands' order
    energy_lanes_body<Lanes, 3>(x, n, ns, a1_coef, a2_coef, gain_coef, energy, tail, peak);
  } else {
    energy_lanes_body<Lanes, 0>(x, n, ns, a1_coef, a2_coef, gain_coef, energy, tail, peak);
  }
}

}  // namespace

void sos_filter_bank_energies(const std::vector<SosFilter>& filters, const float* x, size_t n, BankEnergies* out) {
  const size_t nb = filters.size();
  out->stride = 8 * ((nb + 7) / 8);
  out->energy.resize(n * out->stride);  // every value is written below (no fill: a reused buffer)
  out->tail.resize(nb);
  out->peak.assign(nb, 0.0);
  for (size_t b = 0; b < nb; ++b) {
    out->tail[b].resize(n + 1);
    out->tail[b][n] = 0.0;
  }
  if (nb == 0) return;
  const size_t ns = filters[0].sections.size();
  bool bandpass = ns >= 1 && ns <= 16;
  for (const SosFilter& f : filters) bandpass = bandpass && f.sections.size() == ns && is_bandpass_form(f);
  if (!bandpass) {
    // Other filters: the general bank, then the squares and sums in the same order.
    std::vector<std::vector<double>> y;
    sos_filter_bank(filters, x, n, /*time_reversed=*/true, &y);
    std::fill(out->energy.begin(), out->energy.end(), 0.0);
    for (size_t b = 0; b < nb; ++b) {
      double* t = out->tail[b].data();
      for (size_t i = n; i-- > 0;) {
        const double e = y[b][i] * y[b][i];
        out->energy[i * out->stride + b] = e;
        t[i] = t[i + 1] + e;
        out->peak[b] = std::max(out->peak[b], e);
      }
    }
    return;
  }
  std::vector<double> group_energy(nb > 8 ? 8 * n : 0), spare_tail(n + 1);
  for (size_t b0 = 0; b0 < nb; b0 += 8) {
    double a1[16 * 8], a2[16 * 8], gain[8], peak[8];
    double* tail[8];
    pack_bandpass_lanes(filters, b0, 8, a1, a2, gain);
    for (size_t l = 0; l < 8; ++l) tail[l] = b0 + l < nb ? out->tail[b0 + l].data() : spare_tail.data();
    // One group of eight writes the bank's rows directly; more are gathered into them.
    double* energy = nb > 8 ? group_energy.data() : out->energy.data();
#if TSRIR_HAVE_AVX512_TARGET
    if (ns == 3 && __builtin_cpu_supports("avx512f")) {
      bandpass_energy_lanes8(x, n, a1, a2, gain, energy, tail, peak);
    } else {
      bandpass_energy_lanes(x, n, ns, a1, a2, gain, energy, tail, peak);
    }
#else
    bandpass_energy_lanes(x, n, ns, a1, a2, gain, energy, tail, peak);
#endif
    for (size_t l = 0; l < 8 && b0 + l < nb; ++l) out->peak[b0 + l] = peak[l];
    if (nb > 8) {
      for (size_t i = 0; i < n; ++i) std::copy_n(&group_energy[8 * i], 8, &out->energy[i * out->stride + b0]);
    }
  }
}

void sos_filter_bank(const std::vector<SosFilter>& filters, const float* x, size_t n, bool time_reversed,
                     std::vector<std::vector<double>>* out) {
  const size_t nb = filters.size();
  out->resize(nb);
  if (nb == 0) return;
  const size_t ns = filters[0].sections.size();
  bool bandpass = ns <= 16;
  for (const SosFilter& f : filters) {
    if (f.sections.size() != ns) throw Error("sos_filter_bank: filters differ in their number of sections");
    bandpass = bandpass && is_bandpass_form(f);
  }
  for (auto& o : *out) o.resize(n);
  if (ns == 0) {
    for (size_t b = 0; b < nb; ++b) (*out)[b].assign(x, x + n);
    return;
  }
  if (bandpass) {
    std::vector<double> spare(n);
    for (size_t b0 = 0; b0 < nb; b0 += 4) {
      double a1[16 * 4], a2[16 * 4], gain[4];
      double* dst[4];
      pack_bandpass_lanes(filters, b0, 4, a1, a2, gain);
      for (size_t l = 0; l < 4; ++l) dst[l] = b0 + l < nb ? (*out)[b0 + l].data() : spare.data();
      bandpass_lanes(x, n, time_reversed, ns, a1, a2, gain, dst);
    }
    return;
  }
  // General sections: structure of arrays [section][band] so the inner band loop is a straight
  // vector operation; the recursion runs along samples, the bands are independent lanes.
  std::vector<double> b0(ns * nb), b1(ns * nb), b2(ns * nb), a1(ns * nb), a2(ns * nb);
  for (size_t s = 0; s < ns; ++s) {
    for (size_t b = 0; b < nb; ++b) {
      const Biquad& q = filters[b].sections[s];
      b0[s * nb + b] = q.b0;
      b1[s * nb + b] = q.b1;
      b2[s * nb + b] = q.b2;
      a1[s * nb + b] = q.a1;
      a2[s * nb + b] = q.a2;
    }
  }
  std::vector<double> z1(ns * nb, 0.0), z2(ns * nb, 0.0), v(nb);
  std::vector<double*> dst(nb);
  for (size_t b = 0; b < nb; ++b) dst[b] = (*out)[b].data();
  for (size_t k = 0; k < n; ++k) {
    const size_t i = time_reversed ? n - 1 - k : k;
    const double in = x[i];
    for (size_t b = 0; b < nb; ++b) v[b] = in;
    for (size_t s = 0; s < ns; ++s) {
      double* __restrict z1s = &z1[s * nb];
      double* __restrict z2s = &z2[s * nb];
      const double* c0 = &b0[s * nb];
      const double* c1 = &b1[s * nb];
      const double* c2 = &b2[s * nb];
      const double* d1 = &a1[s * nb];
      const double* d2 = &a2[s * nb];
      for (size_t b = 0; b < nb; ++b) {
        const double vin = v[b];
        const double o = c0[b] * vin + z1s[b];
        z1s[b] = c1[b] * vin - d1[b] * o + z2s[b];
        z2s[b] = c2[b] * vin - d2[b] * o;
        v[b] = o;
      }
    }
    for (size_t b = 0; b < nb; ++b) dst[b][i] = v[b];
  }
}

}  // namespace tsrir

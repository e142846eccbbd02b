#include "measured_rir_generator.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "dsp/fft.h"

namespace tsrir::testdata {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMixingTimeS = 0.070;    // centre of the image -> statistical crossfade
constexpr double kCrossfadeS = 0.020;     // its full width

// Weight of the statistical field at time t (0 before the crossfade, 1 after).
double late_weight(double t) {
  const double a = (t - (kMixingTimeS - kCrossfadeS / 2)) / kCrossfadeS;
  if (a <= 0.0) return 0.0;
  if (a >= 1.0) return 1.0;
  return 0.5 - 0.5 * std::cos(kPi * a);
}

// Linear interpolation weights of frequency f between octave centres in log frequency (flat
// outside the first and last centre).
void octave_interp(double f, int* lo, double* w) {
  const double x = std::log2(std::max(f, 1e-3) / kOctaveCentersHz[0]);
  if (x <= 0.0) { *lo = 0; *w = 0.0; return; }
  if (x >= kNumOctaveBands - 1) { *lo = kNumOctaveBands - 2; *w = 1.0; return; }
  *lo = static_cast<int>(std::floor(x));
  *w = x - *lo;
}

double polygon_area(const std::vector<std::array<double, 2>>& p) {
  double a = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    const auto& u = p[i];
    const auto& v = p[(i + 1) % p.size()];
    a += u[0] * v[1] - v[0] * u[1];
  }
  return 0.5 * a;
}

// The absorption (surface index) of the side wall from floor vertex u to v: the shoebox wall its
// outward normal is nearest to (x0, x1, y0, y1).
int side_wall_surface(const std::array<double, 2>& u, const std::array<double, 2>& v) {
  const double nx = v[1] - u[1], ny = -(v[0] - u[0]);  // outward for a counter-clockwise polygon
  if (std::abs(nx) >= std::abs(ny)) return nx < 0 ? sim::kWallX0 : sim::kWallX1;
  return ny < 0 ? sim::kWallY0 : sim::kWallY1;
}

double volume(const TrueRoom& r) {
  return r.floor_polygon.empty() ? r.size_m[0] * r.size_m[1] * r.size_m[2] : polygon_area(r.floor_polygon) * r.size_m[2];
}
// The area of the surfaces with absorption index s.
double area(const TrueRoom& r, int s) {
  if (!r.floor_polygon.empty()) {
    if (s == sim::kFloor || s == sim::kCeiling) return polygon_area(r.floor_polygon);
    double a = 0.0;
    for (size_t i = 0; i < r.floor_polygon.size(); ++i) {
      const auto& u = r.floor_polygon[i];
      const auto& v = r.floor_polygon[(i + 1) % r.floor_polygon.size()];
      if (side_wall_surface(u, v) == s) a += std::hypot(v[0] - u[0], v[1] - u[1]) * r.size_m[2];
    }
    return a;
  }
  const int axis = s / 2;  // x walls, y walls, floor/ceiling
  const double a = r.size_m[(axis + 1) % 3], b = r.size_m[(axis + 2) % 3];
  return a * b;
}

// ---- Image sources of a convex prism room (TrueRoom::floor_polygon), by mirroring across its
// planes (Allen & Berkley generalised by Borish 1984): an image is mirrored across a wall only
// when it lies on the wall's room side (so every child is farther from the microphone than its
// parent, and the distance bound prunes exactly), and kept when its path, traced back from the
// microphone, meets every wall it was mirrored across inside that wall's face.
struct Wall {
  sim::Vec3 point{}, normal{};  // a point on the plane, the unit normal into the room
  int surface = 0;              // absorption index
  std::array<double, 2> u{}, v{};  // side walls: floor edge; floor and ceiling: unused
};

double dot(const sim::Vec3& a, const sim::Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
sim::Vec3 minus(const sim::Vec3& a, const sim::Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

std::vector<Wall> room_walls(const TrueRoom& r) {
  const double h = r.size_m[2];
  std::vector<Wall> walls;
  walls.push_back({{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, sim::kFloor, {}, {}});
  walls.push_back({{0.0, 0.0, h}, {0.0, 0.0, -1.0}, sim::kCeiling, {}, {}});
  for (size_t i = 0; i < r.floor_polygon.size(); ++i) {
    const auto& u = r.floor_polygon[i];
    const auto& v = r.floor_polygon[(i + 1) % r.floor_polygon.size()];
    const double len = std::hypot(v[0] - u[0], v[1] - u[1]);
    walls.push_back({{u[0], u[1], 0.0}, {-(v[1] - u[1]) / len, (v[0] - u[0]) / len, 0.0}, side_wall_surface(u, v), u, v});
  }
  return walls;
}

// Whether point p (on wall w's plane) lies on the wall's face.
bool on_face(const TrueRoom& r, const Wall& w, const sim::Vec3& p) {
  constexpr double kEps = 1e-9;
  if (w.surface == sim::kFloor || w.surface == sim::kCeiling) {
    for (size_t i = 0; i < r.floor_polygon.size(); ++i) {
      const auto& u = r.floor_polygon[i];
      const auto& v = r.floor_polygon[(i + 1) % r.floor_polygon.size()];
      if ((v[0] - u[0]) * (p[1] - u[1]) - (v[1] - u[1]) * (p[0] - u[0]) < -kEps) return false;
    }
    return true;
  }
  const double ex = w.v[0] - w.u[0], ey = w.v[1] - w.u[1];
  const double t = ((p[0] - w.u[0]) * ex + (p[1] - w.u[1]) * ey) / (ex * ex + ey * ey);
  return t >= -kEps && t <= 1.0 + kEps && p[2] >= -kEps && p[2] <= r.size_m[2] + kEps;
}

}  // namespace

std::vector<ConvexImage> convex_room_images(const TrueRoom& r, double max_distance_m) {
  const std::vector<Wall> walls = room_walls(r);
  struct Node { sim::Vec3 pos; int wall; int parent; };
  std::vector<Node> nodes = {{r.source_m, -1, -1}};
  std::vector<ConvexImage> out;
  for (size_t i = 0; i < nodes.size() && nodes.size() < 2000000; ++i) {
    // Trace the path of node i back from the microphone: every wall it was mirrored across must be
    // met inside its face.
    sim::Vec3 q = r.mic_m;
    bool valid = true;
    ConvexImage im;
    for (int j = static_cast<int>(i); j > 0 && valid; j = nodes[j].parent) {
      const Wall& w = walls[nodes[j].wall];
      const sim::Vec3 dir = minus(nodes[j].pos, q);
      const double denom = dot(dir, w.normal);
      const double s = denom != 0.0 ? dot(minus(w.point, q), w.normal) / denom : -1.0;
      const sim::Vec3 hit = {q[0] + s * dir[0], q[1] + s * dir[1], q[2] + s * dir[2]};
      valid = s > 0.0 && s < 1.0 && on_face(r, w, hit);
      im.surfaces.push_back(w.surface);
      q = hit;
    }
    if (valid) {
      im.distance_m = std::sqrt(dot(minus(nodes[i].pos, r.mic_m), minus(nodes[i].pos, r.mic_m)));
      out.push_back(im);
    }
    for (size_t k = 0; k < walls.size(); ++k) {
      if (static_cast<int>(k) == nodes[i].wall) continue;
      const double side = dot(minus(nodes[i].pos, walls[k].point), walls[k].normal);
      if (side <= 0.0) continue;  // behind the wall: its mirror image has no path
      const sim::Vec3 child = {nodes[i].pos[0] - 2.0 * side * walls[k].normal[0],
                               nodes[i].pos[1] - 2.0 * side * walls[k].normal[1],
                               nodes[i].pos[2] - 2.0 * side * walls[k].normal[2]};
      if (dot(minus(child, r.mic_m), minus(child, r.mic_m)) > max_distance_m * max_distance_m) continue;
      nodes.push_back({child, static_cast<int>(k), static_cast<int>(i)});
    }
  }
  return out;
}

namespace {

// Image coordinate and wall hits of image k on one axis (length L, source coordinate s).
struct AxisImage { double coord; int near_hits, far_hits; };
AxisImage axis_image(int k, double L, double s) {
  AxisImage im;
  im.coord = k * L + ((k % 2 == 0) ? s : L - s);
  const int m = std::abs(k);
  if (k >= 0) { im.far_hits = (m + 1) / 2; im.near_hits = m / 2; }
  else { im.near_hits = (m + 1) / 2; im.far_hits = m / 2; }
  return im;
}

}  // namespace

double test_air_attenuation_db_per_m(double f, double temperature_c, double humidity) {
  // ISO 9613-1:1993, equations (3)-(5) and (B.1)-(B.3), at the reference pressure.
  const double T = temperature_c + 273.15, Tr = 293.15, T01 = 273.16;
  const double csat = -6.8346 * std::pow(T01 / T, 1.261) + 4.6151;
  const double h = humidity * std::pow(10.0, csat);
  const double frO = 24.0 + 4.04e4 * h * (0.02 + h) / (0.391 + h);
  const double frN = std::pow(T / Tr, -0.5) * (9.0 + 280.0 * h * std::exp(-4.170 * (std::pow(T / Tr, -1.0 / 3.0) - 1.0)));
  const double oxygen = 0.01275 * std::exp(-2239.1 / T) / (frO + f * f / frO);
  const double nitrogen = 0.1068 * std::exp(-3352.0 / T) / (frN + f * f / frN);
  return 8.686 * f * f * (1.84e-11 * std::pow(T / Tr, 0.5) + std::pow(T / Tr, -2.5) * (oxygen + nitrogen));
}

sim::BandValues test_eyring_rate_per_s(const TrueRoom& r) {
  double s_total = 0.0;
  for (int s = 0; s < sim::kNumSurfaces; ++s) s_total += area(r, s);
  sim::BandValues rate{};
  for (int b = 0; b < kNumOctaveBands; ++b) {
    double a = 0.0;
    for (int s = 0; s < sim::kNumSurfaces; ++s) a += area(r, s) * r.absorption[s][b];
    a /= s_total;
    // Energy falls by (1 - a) at each reflection, c S / 4V reflections per second.
    rate[b] = -std::log(1.0 - std::min(a, 0.999)) * r.speed_of_sound_m_s * s_total / (4.0 * volume(r));
  }
  return rate;
}

double test_schroeder_hz(const TrueRoom& r) {
  return 2000.0 * std::sqrt(13.815510557964274 / test_eyring_rate_per_s(r)[1] / volume(r));
}

std::vector<double> test_modal_field(const TrueRoom& room, double fs, size_t n, Rng& rng) {
  const double c = room.speed_of_sound_m_s, V = volume(room);
  const double f_max = room.modal_max_factor * test_schroeder_hz(room);
  // Long enough that the slowest mode has died away before the inverse FFT wraps it onto the
  // start (4 s: a mode with a 2 s T60 is 120 dB down).
  const size_t nfft = next_fast_fft_size(std::max(n, static_cast<size_t>(4.0 * fs)));
  const double df = fs / nfft;
  // Transfer functions are summed up to twice the top mode (their tails reach above it), then
  // faded out over the octave above the top mode: no sharp edge in the spectrum, no ringing.
  const size_t bins = std::min(nfft / 2 + 1, static_cast<size_t>(std::ceil(2.0 * f_max / df)) + 1);
  std::vector<std::complex<double>> spec(bins, 0.0);
  const double gain = std::pow(10.0, room.modal_gain_db / 20.0);
  const double lx = room.size_m[0], ly = room.size_m[1], lz = room.size_m[2];
  const int px = static_cast<int>(2.0 * f_max * lx / c) + 1, py = static_cast<int>(2.0 * f_max * ly / c) + 1,
            pz = static_cast<int>(2.0 * f_max * lz / c) + 1;
  for (int p = 0; p <= px; ++p) {
    for (int q = 0; q <= py; ++q) {
      for (int r = 0; r <= pz; ++r) {
        const double f = 0.5 * c * std::sqrt(std::pow(p / lx, 2) + std::pow(q / ly, 2) + std::pow(r / lz, 2));
        if (f < 20.0 || f > f_max) continue;
        // Morse & Bolt's damping of a rectangular room's mode: each wall pair adds
        // (c / 16) eps (-ln(1 - a0) - ln(1 - a1)) / L of its axis, eps = 2 where the mode has a
        // node count along that axis (it meets the walls head-on), 1 where it grazes them. An
        // oblique mode (every eps 2) decays at Eyring's rate c S (-ln(1 - a)) / 8V in amplitude.
        int lo;
        double w;
        octave_interp(f, &lo, &w);
        const int index[3] = {p, q, r};
        double delta = 0.0;
        for (int a = 0; a < 3; ++a) {
          double exponent = 0.0;
          for (int side = 0; side < 2; ++side) {
            const sim::BandValues& ab = room.absorption[2 * a + side];
            const double alpha = (1.0 - w) * ab[lo] + w * ab[lo + 1];
            exponent += -std::log(1.0 - std::min(alpha, 0.999));
          }
          delta += c / 16.0 * (index[a] ? 2.0 : 1.0) * exponent / room.size_m[a];
        }
        delta *= std::exp(rng.normal(0.0, room.modal_damping_spread)) / room.modal_decay_factor;
        auto shape = [&](const sim::Vec3& v) {
          return std::cos(p * kPi * v[0] / lx) * std::cos(q * kPi * v[1] / ly) * std::cos(r * kPi * v[2] / lz);
        };
        const double norm = (p ? 2.0 : 1.0) * (q ? 2.0 : 1.0) * (r ? 2.0 : 1.0);  // 1 / Lambda
        // Amplitudes fade over the top half octave of the modes (a smooth upper edge).
        const double x = std::clamp(std::log2(f_max / f) / 0.5, 0.0, 1.0);
        const double taper = 0.5 - 0.5 * std::cos(kPi * x);
        const double amp = gain * c * c / V * norm * shape(room.source_m) * shape(room.mic_m) * taper;
        if (amp == 0.0) continue;
        const double wn2 = std::pow(2.0 * kPi * f, 2);
        // The mode's transfer function amp / (w_n^2 - w^2 + 2 j delta w): impulse response
        // amp exp(-delta t) sin(w_d t) / w_d.
        for (size_t k = 0; k < bins; ++k) {
          const double wk = 2.0 * kPi * k * df;
          spec[k] += amp / std::complex<double>(wn2 - wk * wk, 2.0 * delta * wk);
        }
      }
    }
  }
  std::vector<std::complex<float>> specf(nfft / 2 + 1, 0.0f);
  for (size_t k = 0; k < bins; ++k) {
    const double x = std::clamp(std::log2(k * df / f_max), 0.0, 1.0);
    specf[k] = std::complex<float>(spec[k] * (0.5 + 0.5 * std::cos(kPi * x)));
  }
  specf[0] = 0.0f;
  std::vector<float> h(nfft);
  RealFft(nfft).inverse(specf.data(), h.data());
  // Unnormalised inverse / nfft = h(t) / fs, the same discrete scale as the image sources'
  // 1 / (4 pi d) per sample.
  std::vector<double> out(n, 0.0);
  for (size_t i = 0; i < n && i < nfft; ++i) out[i] = h[i] / static_cast<double>(nfft);
  return out;
}

TrueRoom true_room_from(const sim::RoomSpec& stated) {
  TrueRoom t;
  t.size_m = stated.size_m;
  t.source_m = stated.source_m;
  t.mic_m = stated.mic_m;
  t.absorption = stated.absorption;
  t.scattering = stated.scattering;
  t.speed_of_sound_m_s = stated.speed_of_sound_m_s;
  return t;
}

Signal generate_measured_rir(const TrueRoom& room, double fs, size_t n, Rng& rng) {
  const double c = room.speed_of_sound_m_s, V = volume(room);
  double S = 0.0;
  for (int s = 0; s < sim::kNumSurfaces; ++s) S += area(room, s);
  const double mean_free_time_s = 4.0 * V / (c * S);
  const double image_end_s = kMixingTimeS + kCrossfadeS / 2;

  // ---- Early part: exact frequency-domain sum of the image sources.
  const size_t ne = 8192 * static_cast<size_t>(std::max(1.0, std::ceil(fs / 16000.0)));
  const size_t bins = ne / 2 + 1;
  std::vector<int> lo_of(bins);
  std::vector<double> w_of(bins), air_np_per_m(bins, 0.0);
  for (size_t k = 0; k < bins; ++k) {
    octave_interp(k * fs / ne, &lo_of[k], &w_of[k]);
    if (room.air) {
      air_np_per_m[k] = room.air_scale * test_air_attenuation_db_per_m(k * fs / ne, room.air_temperature_c, room.air_humidity_percent) *
                        std::log(10.0) / 20.0;
    }
  }
  sim::BandValues band_air_np{};
  for (int b = 0; b < kNumOctaveBands; ++b) {
    band_air_np[b] = room.air ? room.air_scale * test_air_attenuation_db_per_m(kOctaveCentersHz[b], room.air_temperature_c,
                                                              room.air_humidity_percent) * std::log(10.0) / 20.0
                              : 0.0;
  }
  // Source directivity: per bin and per band, m = Q - 1 of the pattern (m + 1) u^m.
  bool directional = false;
  for (double di : room.directivity_db) directional = directional || di != 0.0;
  std::vector<double> half_m(bins, 0.0), half_log_q(bins, 0.0);
  sim::BandValues band_m{};
  sim::Vec3 aim{};
  if (directional) {
    for (size_t k = 0; k < bins; ++k) {
      const double di = (1.0 - w_of[k]) * room.directivity_db[lo_of[k]] + w_of[k] * room.directivity_db[lo_of[k] + 1];
      const double q = std::pow(10.0, di / 10.0);
      half_m[k] = 0.5 * (q - 1.0);
      half_log_q[k] = 0.5 * std::log(q);
    }
    for (int b = 0; b < kNumOctaveBands; ++b) band_m[b] = std::pow(10.0, room.directivity_db[b] / 10.0) - 1.0;
    double norm = 0.0;
    for (int a = 0; a < 3; ++a) { aim[a] = room.mic_m[a] - room.source_m[a]; norm += aim[a] * aim[a]; }
    for (double& v : aim) v /= std::sqrt(norm);
  }
  std::vector<std::complex<double>> spec(bins, 0.0);
  // Scattered energy rain per band on a 1 ms grid.
  const double grid_s = 1e-3;
  const size_t grid_n = static_cast<size_t>(std::ceil(n / fs / grid_s)) + 2;
  std::vector<std::array<double, kNumOctaveBands>> rain(grid_n);
  for (auto& r : rain) r.fill(0.0);

  sim::BandValues log_r[sim::kNumSurfaces], log_spec{};
  for (int s = 0; s < sim::kNumSurfaces; ++s) {
    for (int b = 0; b < kNumOctaveBands; ++b) log_r[s][b] = 0.5 * std::log(std::max(1e-6, 1.0 - room.absorption[s][b]));
  }
  for (int b = 0; b < kNumOctaveBands; ++b) log_spec[b] = 0.5 * std::log(std::max(1e-9, 1.0 - room.scattering[b]));
  std::vector<double> lg(kNumOctaveBands);
  // One image: at distance d from the microphone, with per-band log amplitude `unscattered` after
  // its wall reflections (absorption only), `hits` reflections, leaving the real source in the
  // direction whose log pattern argument is log_u (0: omni).
  auto add_image = [&](double d, const sim::BandValues& unscattered, int hits, double log_u) {
    const double tau = d / c + room.latency_s;
    if (tau >= image_end_s + room.latency_s) return;
    const double specular_weight = 1.0 - late_weight(tau - room.latency_s);
    for (int b = 0; b < kNumOctaveBands; ++b) {
      lg[b] = unscattered[b] + hits * log_spec[b];
      // The scattered share of this image's energy, air included at the band centre.
      const double pattern = directional ? (band_m[b] + 1.0) * std::exp(band_m[b] * log_u) : 1.0;
      const double e_unscattered =
          pattern * std::exp(2.0 * unscattered[b] - 2.0 * band_air_np[b] * d) / std::pow(4.0 * kPi * d, 2);
      const double e_scattered = e_unscattered * (1.0 - std::exp(2.0 * hits * log_spec[b]));
      if (e_scattered <= 0.0) continue;
      // Spread over the following mean free time: density (E / T) exp(-(t - tau) / T).
      for (size_t g = static_cast<size_t>(tau / grid_s); g < grid_n; ++g) {
        const double t0 = std::max(tau, g * grid_s), t1 = (g + 1) * grid_s;
        if (t1 <= t0) continue;
        const double share = std::exp(-(t0 - tau) / mean_free_time_s) - std::exp(-(t1 - tau) / mean_free_time_s);
        rain[g][b] += e_scattered * share;
        if ((t1 - tau) > 8.0 * mean_free_time_s) break;
      }
    }
    if (specular_weight <= 0.0) return;
    const double amp0 = specular_weight / (4.0 * kPi * d);
    const std::complex<double> step = std::polar(1.0, -2.0 * kPi * tau * fs / ne);
    std::complex<double> phasor = 1.0;
    for (size_t k = 0; k < bins; ++k) {
      const int lo = lo_of[k];
      double log_gain = (1.0 - w_of[k]) * lg[lo] + w_of[k] * lg[lo + 1] - air_np_per_m[k] * d;
      if (directional) log_gain += half_log_q[k] + half_m[k] * log_u;
      spec[k] += amp0 * std::exp(log_gain) * phasor;
      phasor *= step;
    }
  };
  if (!room.floor_polygon.empty()) {
    for (const ConvexImage& im : convex_room_images(room, c * image_end_s)) {
      sim::BandValues unscattered{};
      for (int surface : im.surfaces) {
        for (int b = 0; b < kNumOctaveBands; ++b) unscattered[b] += log_r[surface][b];
      }
      add_image(im.distance_m, unscattered, static_cast<int>(im.surfaces.size()), 0.0);
    }
  }
  int K[3];
  for (int a = 0; a < 3; ++a) K[a] = static_cast<int>(std::ceil(c * image_end_s / room.size_m[a])) + 1;
  for (int kx = -K[0]; kx <= K[0] && room.floor_polygon.empty(); ++kx) {
    const AxisImage ix = axis_image(kx, room.size_m[0], room.source_m[0]);
    for (int ky = -K[1]; ky <= K[1]; ++ky) {
      const AxisImage iy = axis_image(ky, room.size_m[1], room.source_m[1]);
      for (int kz = -K[2]; kz <= K[2]; ++kz) {
        const AxisImage iz = axis_image(kz, room.size_m[2], room.source_m[2]);
        const double dx = ix.coord - room.mic_m[0], dy = iy.coord - room.mic_m[1], dz = iz.coord - room.mic_m[2];
        const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
        // The direction this image's sound left the real source in: towards the microphone from
        // the image, mirrored back on every axis with an odd image index.
        double log_u = 0.0;
        if (directional) {
          const double ex = (kx % 2 == 0 ? -dx : dx), ey = (ky % 2 == 0 ? -dy : dy), ez = (kz % 2 == 0 ? -dz : dz);
          const double cos_theta = (ex * aim[0] + ey * aim[1] + ez * aim[2]) / d;
          log_u = std::log(std::max(0.5 * (1.0 + cos_theta), 1e-12));
        }
        sim::BandValues unscattered{};
        for (int b = 0; b < kNumOctaveBands; ++b) {
          unscattered[b] = ix.near_hits * log_r[0][b] + ix.far_hits * log_r[1][b] + iy.near_hits * log_r[2][b] +
                           iy.far_hits * log_r[3][b] + iz.near_hits * log_r[4][b] + iz.far_hits * log_r[5][b];
        }
        add_image(d, unscattered, std::abs(kx) + std::abs(ky) + std::abs(kz), log_u);
      }
    }
  }
  std::vector<std::complex<float>> specf(bins);
  for (size_t k = 0; k < bins; ++k) specf[k] = std::complex<float>(spec[k]);
  // The Nyquist bin of a real signal is real.
  specf[bins - 1] = std::complex<float>(specf[bins - 1].real(), 0.0f);
  std::vector<float> early(ne);
  RealFft(ne).inverse(specf.data(), early.data());
  Signal out;
  out.sample_rate_hz = fs;
  out.samples.assign(n, 0.0f);
  // Keep the causal part (the sinc tails of early arrivals wrap to the buffer's end).
  const size_t keep = std::min(n, ne * 3 / 4);
  for (size_t i = 0; i < keep; ++i) out.samples[i] = early[i] / static_cast<float>(ne);  // unnormalised inverse

  // ---- Diffuse part: noise shaped by the time-frequency energy envelope.
  const sim::BandValues rate = test_eyring_rate_per_s(room);
  const size_t frame = 512 * static_cast<size_t>(std::max(1.0, std::round(fs / 16000.0))), hop = frame / 4;
  const size_t fb = frame / 2 + 1;
  std::vector<double> f_rate(fb), f_w(fb);
  std::vector<int> f_lo(fb);
  for (size_t k = 0; k < fb; ++k) {
    const double f = k * fs / frame;
    octave_interp(f, &f_lo[k], &f_w[k]);
    const double lr = (1.0 - f_w[k]) * std::log(rate[f_lo[k]]) + f_w[k] * std::log(rate[f_lo[k] + 1]);
    const double air = room.air ? room.air_scale * test_air_attenuation_db_per_m(f, room.air_temperature_c, room.air_humidity_percent) *
                                      std::log(10.0) / 10.0 * c
                                : 0.0;
    f_rate[k] = std::exp(lr) + air;
  }
  std::vector<double> win(frame);
  for (size_t i = 0; i < frame; ++i) win[i] = std::sqrt(0.5 - 0.5 * std::cos(2.0 * kPi * i / frame));
  std::vector<float> padded(n + 2 * frame);
  for (float& v : padded) v = static_cast<float>(rng.normal());
  std::vector<double> diffuse(padded.size(), 0.0);
  RealFft fft(frame);
  std::vector<float> x(frame), y(frame);
  std::vector<std::complex<float>> fx(fb);
  const double direct_s = std::sqrt(std::pow(room.source_m[0] - room.mic_m[0], 2) + std::pow(room.source_m[1] - room.mic_m[1], 2) +
                                    std::pow(room.source_m[2] - room.mic_m[2], 2)) / c;
  for (size_t start = 0; start + frame <= padded.size(); start += hop) {
    const double t_abs = (static_cast<double>(start) + frame / 2.0 - frame) / fs;  // time in the RIR
    const double t = t_abs - room.latency_s;                                       // time since emission
    if (t < direct_s - frame / fs) continue;
    for (size_t i = 0; i < frame; ++i) x[i] = static_cast<float>(padded[start + i] * win[i]);
    fft.forward(x.data(), fx.data());
    const size_t g = static_cast<size_t>(std::clamp(t_abs / grid_s, 0.0, static_cast<double>(grid_n - 1)));
    const double wl = late_weight(t);
    for (size_t k = 0; k < fb; ++k) {
      const int lo = f_lo[k];
      const double rain_density = ((1.0 - f_w[k]) * rain[g][lo] + f_w[k] * rain[g][lo + 1]) / grid_s;
      double late_density = t > 0.0 ? c / (4.0 * kPi * V) * std::exp(-f_rate[k] * t) : 0.0;
      if (room.coupled_level_db > -90.0 && t > 0.0) {
        // The coupled volume's field: coupled_level_db below the room's at the mixing time, then
        // decaying coupled_decay_factor times more slowly.
        const double t_mix = kMixingTimeS;
        late_density += std::pow(10.0, room.coupled_level_db / 10.0) * c / (4.0 * kPi * V) *
                        std::exp(-f_rate[k] * (t_mix + (t - t_mix) / room.coupled_decay_factor));
      }
      const double density = (1.0 - wl) * rain_density + wl * late_density;   // squared samples per second
      fx[k] *= static_cast<float>(std::sqrt(density / fs));
    }
    fft.inverse(fx.data(), y.data());
    for (size_t i = 0; i < frame; ++i) diffuse[start + i] += y[i] * win[i] / (2.0 * frame);
  }
  // Nothing arrives before the direct sound (a 1 ms raised-cosine fade-in at its arrival).
  const double t_direct_abs = direct_s + room.latency_s;
  for (size_t i = 0; i < n; ++i) {
    const double t = i / fs - t_direct_abs;
    const double fade = t <= 0.0 ? 0.0 : (t >= 1e-3 ? 1.0 : 0.5 - 0.5 * std::cos(kPi * t / 1e-3));
    out.samples[i] += static_cast<float>(diffuse[frame + i] * fade);
  }

  // ---- Flutter echo between the x walls: one reflection every 2 Lx / c after the direct sound.
  if (room.flutter_level_db > -90.0) {
    const double period_s = 2.0 * room.size_m[0] / c;
    std::vector<float> train(n, 0.0f);
    for (int k = 1;; ++k) {
      const size_t i = static_cast<size_t>(std::lround((t_direct_abs + k * period_s) * fs));
      if (i >= n) break;
      // The first reflection flutter_level_db re the direct sound, then the trip loss and the
      // spreading of the longer path.
      const double d0 = direct_s * c, d_k = d0 + k * 2.0 * room.size_m[0], d_1 = d0 + 2.0 * room.size_m[0];
      train[i] = static_cast<float>(std::pow(10.0, (room.flutter_level_db - (k - 1) * room.flutter_trip_loss_db) / 20.0) /
                                    (4.0 * kPi * d0) * d_1 / d_k);
    }
    for (int section = 0; section < 2; ++section) apply_test_biquad(test_high_pass(1000.0, std::sqrt(0.5), fs), train);
    for (size_t i = 0; i < n; ++i) out.samples[i] += train[i];
  }

  // ---- Modal part: the true room's modes below mode_max_hz, random phases.
  if (room.mode_gain_db > -90.0) {
    const double lx = room.size_m[0], ly = room.size_m[1], lz = room.size_m[2];
    const double t60_low = 13.8155 / rate[1] * room.mode_decay_factor;
    const double scale = std::pow(10.0, room.mode_gain_db / 20.0) * c * c / (V * fs);
    for (int p = 0; p < 16; ++p) {
      for (int q = 0; q < 16; ++q) {
        for (int r = 0; r < 10; ++r) {
          const double f = 0.5 * c * std::sqrt(std::pow(p / lx, 2) + std::pow(q / ly, 2) + std::pow(r / lz, 2));
          if (f < 20.0 || f > room.mode_max_hz) continue;
          auto shape = [&](const sim::Vec3& v) {
            return std::cos(p * kPi * v[0] / lx) * std::cos(q * kPi * v[1] / ly) * std::cos(r * kPi * v[2] / lz);
          };
          const double norm = (p ? 2.0 : 1.0) * (q ? 2.0 : 1.0) * (r ? 2.0 : 1.0);
          const double jitter = std::pow(10.0, rng.normal(0.0, 3.0) / 20.0);
          const double amp = scale * norm * shape(room.source_m) * shape(room.mic_m) * jitter / (2.0 * kPi * f);
          const double delta = 6.907755 / (t60_low * rng.uniform(0.85, 1.15));
          const double phase = rng.uniform(0.0, 2.0 * kPi);
          const size_t i0 = static_cast<size_t>(std::ceil(t_direct_abs * fs));
          for (size_t i = i0; i < n; ++i) {
            const double t = i / fs - t_direct_abs;
            // A 2 ms rise (the mode builds up as energy arrives).
            const double rise = t < 2e-3 ? 0.5 - 0.5 * std::cos(kPi * t / 2e-3) : 1.0;
            out.samples[i] += static_cast<float>(rise * amp * std::sin(2.0 * kPi * f * t + phase) * std::exp(-delta * t));
          }
        }
      }
    }
  }
  // ---- Modal field: every mode of the true room, added from the direct sound on.
  if (room.modal_gain_db > -90.0) {
    const std::vector<double> modal = test_modal_field(room, fs, n, rng);
    const long shift = std::lround(room.latency_s * fs);
    for (size_t i = 0; i < n; ++i) {
      const double t = i / fs - t_direct_abs;
      if (t <= 0.0) continue;
      const long j = static_cast<long>(i) - shift;
      if (j < 0 || j >= static_cast<long>(n)) continue;
      // The same 2 ms rise as the modal part above (no modal sound before the direct sound).
      const double rise = t < 2e-3 ? 0.5 - 0.5 * std::cos(kPi * t / 2e-3) : 1.0;
      out.samples[i] += static_cast<float>(rise * modal[j]);
    }
  }
  return out;
}

TestBiquad test_peaking(double f0, double gain_db, double q, double fs) {
  const double a = std::pow(10.0, gain_db / 40.0), w = 2.0 * kPi * f0 / fs, alpha = std::sin(w) / (2.0 * q);
  const double a0 = 1.0 + alpha / a;
  return {(1.0 + alpha * a) / a0, -2.0 * std::cos(w) / a0, (1.0 - alpha * a) / a0, -2.0 * std::cos(w) / a0,
          (1.0 - alpha / a) / a0};
}

TestBiquad test_high_shelf(double f0, double gain_db, double fs) {
  const double a = std::pow(10.0, gain_db / 40.0), w = 2.0 * kPi * f0 / fs;
  const double alpha = std::sin(w) / 2.0 * std::sqrt(2.0), cw = std::cos(w), sa = 2.0 * std::sqrt(a) * alpha;
  const double a0 = (a + 1) - (a - 1) * cw + sa;
  return {a * ((a + 1) + (a - 1) * cw + sa) / a0, -2 * a * ((a - 1) + (a + 1) * cw) / a0,
          a * ((a + 1) + (a - 1) * cw - sa) / a0, 2 * ((a - 1) - (a + 1) * cw) / a0, ((a + 1) - (a - 1) * cw - sa) / a0};
}

TestBiquad test_high_pass(double f0, double q, double fs) {
  const double w = 2.0 * kPi * f0 / fs, alpha = std::sin(w) / (2.0 * q), cw = std::cos(w);
  const double a0 = 1.0 + alpha;
  return {(1.0 + cw) / 2.0 / a0, -(1.0 + cw) / a0, (1.0 + cw) / 2.0 / a0, -2.0 * cw / a0, (1.0 - alpha) / a0};
}

void apply_test_biquad(const TestBiquad& f, std::vector<float>& x) {
  double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
  for (float& v : x) {
    const double y = f.b0 * v + f.b1 * x1 + f.b2 * x2 - f.a1 * y1 - f.a2 * y2;
    x2 = x1; x1 = v; y2 = y1; y1 = y;
    v = static_cast<float>(y);
  }
}

double test_cascade_octave_gain_db(const std::vector<TestBiquad>& chain, double fc, double fs) {
  double e = 0.0;
  for (int j = 0; j < 32; ++j) {
    const double f = fc * std::pow(2.0, (j + 0.5) / 32.0 - 0.5);
    const std::complex<double> z = std::exp(std::complex<double>(0.0, -2.0 * kPi * f / fs));
    std::complex<double> h = 1.0;
    for (const TestBiquad& q : chain) h *= (q.b0 + q.b1 * z + q.b2 * z * z) / (1.0 + q.a1 * z + q.a2 * z * z);
    e += std::norm(h) / 32.0;
  }
  return 10.0 * std::log10(e);
}

}  // namespace tsrir::testdata

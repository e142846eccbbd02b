// The tests' independent generator checked against itself where two of its formulations must agree,
// and its out-of-catalog and modal parts against what they are meant to show.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "dsp/fft.h"
#include "hidden_effects.h"
#include "measured_rir_generator.h"
#include "util/rng.h"

namespace tsrir {
namespace {

double energy(const std::vector<float>& x, size_t a, size_t b) {
  double e = 0.0;
  for (size_t i = a; i < b && i < x.size(); ++i) e += double(x[i]) * x[i];
  return e;
}

// The convex-room image method (mirroring across planes with Borish's path check) on a rectangular
// floor is the shoebox's own image lattice: the two responses agree to float precision.
TEST(MeasuredRirGenerator, ConvexImagesOfARectangleAreTheShoeboxImages) {
  const std::vector<sim::RoomSpec> rooms = testing::make_test_rooms(3, 5);
  for (const sim::RoomSpec& stated : rooms) {
    testing::TrueRoom box = testing::true_room_from(stated);
    testing::TrueRoom prism = box;
    prism.floor_polygon = {{0.0, 0.0}, {box.size_m[0], 0.0}, {box.size_m[0], box.size_m[1]}, {0.0, box.size_m[1]}};
    Rng r1(9), r2(9);
    const Signal a = testing::generate_measured_rir(box, 16000.0, 16000, r1);
    const Signal b = testing::generate_measured_rir(prism, 16000.0, 16000, r2);
    double diff = 0.0;
    for (size_t i = 0; i < a.size(); ++i) diff += std::pow(double(a.samples[i]) - b.samples[i], 2);
    EXPECT_LT(diff, 1e-8 * energy(a.samples, 0, a.size())) << stated.rir_id;
  }
}

// A splayed room has images the shoebox does not: its first side-wall reflections arrive elsewhere.
TEST(MeasuredRirGenerator, SplayedWallsMoveTheFirstReflections) {
  testing::TrueRoom box = testing::true_room_from(testing::make_test_rooms(1, 5).front());
  testing::TrueRoom splayed = box;
  splayed.floor_polygon = {{0.0, 0.0}, {box.size_m[0], 0.0}, {box.size_m[0] + 1.0, box.size_m[1]}, {-1.0, box.size_m[1]}};
  const auto images_box = testing::convex_room_images(
      [&] {
        testing::TrueRoom r = box;
        r.floor_polygon = {{0.0, 0.0}, {box.size_m[0], 0.0}, {box.size_m[0], box.size_m[1]}, {0.0, box.size_m[1]}};
        return r;
      }(),
      15.0);
  const auto images_splayed = testing::convex_room_images(splayed, 15.0);
  ASSERT_FALSE(images_box.empty());
  EXPECT_EQ(images_box.front().surfaces.size(), 0u);  // the direct sound first
  // First-order images: six in the box, six in the splayed prism, at other distances for the side
  // walls (and the same for floor and ceiling).
  auto first_order = [](const std::vector<testing::ConvexImage>& im) {
    std::vector<double> d;
    for (const auto& i : im) {
      if (i.surfaces.size() == 1) d.push_back(i.distance_m);
    }
    std::sort(d.begin(), d.end());
    return d;
  };
  const std::vector<double> a = first_order(images_box), b = first_order(images_splayed);
  ASSERT_EQ(a.size(), 6u);
  ASSERT_EQ(b.size(), 6u);
  int moved = 0;
  for (size_t k = 0; k < a.size(); ++k) moved += std::abs(a[k] - b[k]) > 0.05;
  EXPECT_GE(moved, 2);
}

// Flutter: the late 1 kHz-and-up envelope repeats every 2 Lx / c.
TEST(MeasuredRirGenerator, FlutterRepeatsAtTheWallPairsRoundTrip) {
  testing::TrueRoom room = testing::true_room_from(testing::make_test_rooms(1, 5).front());
  room.flutter_level_db = -6.0;
  room.flutter_trip_loss_db = 0.5;
  Rng rng(3);
  const Signal s = testing::generate_measured_rir(room, 16000.0, 16000, rng);
  const std::vector<float> hp = [&] {
    std::vector<float> x = s.samples;
    for (int k = 0; k < 2; ++k) testing::apply_test_biquad(testing::test_high_pass(1000.0, std::sqrt(0.5), 16000.0), x);
    return x;
  }();
  // Energy envelope of 0.2-0.7 s in 1 ms bins; its autocorrelation peaks at the round trip.
  std::vector<double> e;
  for (size_t i = 3200; i + 16 <= 11200; i += 16) e.push_back(energy(hp, i, i + 16));
  double mean = 0.0;
  for (double v : e) mean += v / e.size();
  auto ac = [&](size_t lag) {
    double r = 0.0, n = 0.0;
    for (size_t i = 0; i + lag < e.size(); ++i) r += (e[i] - mean) * (e[i + lag] - mean);
    for (double v : e) n += (v - mean) * (v - mean);
    return r / n;
  };
  const size_t trip = static_cast<size_t>(std::lround(2.0 * room.size_m[0] / room.speed_of_sound_m_s * 1000.0));
  EXPECT_GT(std::max({ac(trip - 1), ac(trip), ac(trip + 1)}), 0.3);
  EXPECT_LT(ac(trip / 2), 0.2);
}

// A coupled volume: a double slope. Against the same room without it, the early decay (100-200 ms)
// is nearly unchanged and the late one (600-700 ms) much slower (broadband drops, whose own bands
// mix into a curve of their own).
TEST(MeasuredRirGenerator, CoupledVolumeMakesADoubleSlope) {
  testing::TrueRoom room = testing::true_room_from(testing::make_test_rooms(1, 5).front());
  Rng r1(4), r2(4);
  const Signal single = testing::generate_measured_rir(room, 16000.0, 16000, r1);
  room.coupled_level_db = -10.0;
  room.coupled_decay_factor = 3.0;
  const Signal coupled = testing::generate_measured_rir(room, 16000.0, 16000, r2);
  // Level drop per 100 ms early (100-200 ms) and late (600-700 ms).
  auto drop = [&](const Signal& s, size_t a) { return 10.0 * std::log10(energy(s.samples, a, a + 1600) / energy(s.samples, a + 1600, a + 3200)); };
  EXPECT_GT(drop(coupled, 1600), 0.7 * drop(single, 1600));
  EXPECT_LT(drop(coupled, 9600), 0.6 * drop(single, 9600));
}

// The dense modal field: every mode up to past the Schroeder frequency, so it raises the energy up
// to there, not beyond; and the modes persist where the diffuse field does not.
TEST(MeasuredRirGenerator, DenseModalFieldCoversTheModalRange) {
  testing::TrueRoom room = testing::true_room_from(testing::make_test_rooms(1, 5).front());
  Rng r1(6), r2(6);
  const Signal plain = testing::generate_measured_rir(room, 16000.0, 16000, r1);
  room.modal_gain_db = 0.0;
  const Signal modal = testing::generate_measured_rir(room, 16000.0, 16000, r2);
  const double schroeder = testing::test_schroeder_hz(room);
  auto band = [](const Signal& s, double lo, double hi) {
    const std::vector<double> p = power_spectrum(s.samples, 32768);
    double e = 0.0;
    for (size_t k = 0; k < p.size(); ++k) {
      const double f = k * s.sample_rate_hz / 32768;
      if (f >= lo && f < hi) e += p[k];
    }
    return 10.0 * std::log10(e);
  };
  EXPECT_GT(band(modal, 30.0, schroeder) - band(plain, 30.0, schroeder), 2.0);
  EXPECT_LT(std::abs(band(modal, 4.0 * schroeder, 8.0 * schroeder) - band(plain, 4.0 * schroeder, 8.0 * schroeder)), 0.3);
}

}  // namespace
}  // namespace tsrir

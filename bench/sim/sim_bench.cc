// Speed of the simulator (issue 4): the reference room, scaling with threads, and how time grows
// with T60 and room volume. Prints a table; times are medians of repeated renders.
//   sim_bench [--quick]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <ctime>
#include <vector>

#include "metrics/rir_metrics.h"
#include "sim/model.h"
#include "sim/room_list.h"
#include "util/parallel.h"

using namespace tsrir;
using namespace tsrir::sim;
using Clock = std::chrono::steady_clock;

namespace {

constexpr double kFs = 16000.0;
// Comparisons with other simulators run the peers in the same run: bench/peers/sim_speed.sh.

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// CPU time of the calling thread: single-core figures stay meaningful on a shared, loaded machine
// (wall time there measures the other users).
double thread_cpu_s() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Median single-thread CPU time per RIR over `reps` renders (seeds differ).
double time_per_rir(const Model& model, const RoomSpec& room, size_t n, int reps) {
  std::vector<double> t;
  model.render(room, kFs, n, 999);  // warm-up: FFT plans, kernel table
  for (int r = 0; r < reps; ++r) {
    const double t0 = thread_cpu_s();
    model.render(room, kFs, n, r);
    t.push_back(thread_cpu_s() - t0);
  }
  return median(t);
}

// Worst relative departure of the measured T30 from the Eyring T60 the diffuse tail is shaped with,
// 125..4000 Hz, mean T30 over `seeds` renders: a consistency check of render + measurement (the
// tail is built from that decay rate), not accuracy; accuracy against independent references is
// bench/peers/band_accuracy.sh and bench/peers/ism_accuracy.py.
double worst_t30_error(const Model& model, const RoomSpec& room, size_t n, int seeds) {
  const BandValues eyring = eyring_t60_s(room);
  std::vector<double> sum(kNumOctaveBands, 0.0);
  for (int s = 0; s < seeds; ++s) {
    const RirMetrics m = measure_rir(model.render(room, kFs, n, 50 + s));
    for (const BandMetrics& b : m.bands) sum[octave_band_index(b.center_hz)] += b.t30_s / seeds;
  }
  double worst = 0.0;
  for (int b = 1; b <= 6; ++b) worst = std::max(worst, std::abs(sum[b] / eyring[b] - 1.0));
  return worst;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const int reps = quick ? 20 : 200;
  const Model gas = Model::parse("gas");
  const RoomSpec ref = parse_room_list_line("ref room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.6", "bench:1");
  const size_t n1s = static_cast<size_t>(kFs);

  std::printf("rir-simulate benchmark (model gas, fs 16 kHz, %u hardware threads)\n\n",
              std::thread::hardware_concurrency());
  std::printf("## Reference room 6 x 4.5 x 3 m, T60 0.6 s, 1.0 s RIR, one core (median thread CPU time)\n");
  const double t_ref = time_per_rir(gas, ref, n1s, reps);
  const double t_ism = time_per_rir(Model::parse("ism"), ref, n1s, reps);
  const double t_diffuse = time_per_rir(Model::parse("diffuse"), ref, n1s, reps);
  const double err = worst_t30_error(gas, ref, n1s, quick ? 4 : 10);
  std::printf("| what | ms per RIR |\n|---|---|\n");
  std::printf("| gas (ism+diffuse) | %.2f |\n", 1e3 * t_ref);
  std::printf("| ism alone (2000 images) + band sum | %.2f |\n", 1e3 * t_ism);
  std::printf("| diffuse alone + band sum | %.2f |\n", 1e3 * t_diffuse);
  std::printf("consistency (not accuracy): worst band T30 departure from the Eyring decay the tail is built with "
              "(125-4000 Hz, mean of %d seeds): %.1f%%\n\n", quick ? 4 : 10, 100.0 * err);

  std::printf("## Threads: %d reference RIRs rendered with parallel_for (as rir-simulate does), wall time\n",
              quick ? 32 : 256);
  std::printf("| threads | RIRs/s | speed-up | efficiency |\n|---|---|---|---|\n");
  const int count = quick ? 32 : 256;
  double base = 0.0;
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  for (unsigned threads = 1; threads <= std::min(hw, 16u); threads *= 2) {
    std::vector<Signal> out(count);
    const auto t0 = Clock::now();
    parallel_for(count, static_cast<int>(threads), [&](size_t i) { out[i] = gas.render(ref, kFs, n1s, i); });
    const double rate = count / seconds_since(t0);
    if (threads == 1) base = rate;
    std::printf("| %u | %.0f | %.2fx | %.0f%% |\n", threads, rate, rate / base, 100.0 * rate / base / threads);
  }

  std::printf("\n## Time vs T60 (reference room, --length=auto = direct delay + T60)\n");
  std::printf("| T60 s | length s | ms per RIR | ms per RIR at 1.0 s length |\n|---|---|---|---|\n");
  for (double t60 : {0.2, 0.4, 0.6, 1.0, 1.5}) {
    const RoomSpec room = parse_room_list_line(
        "t room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=" + std::to_string(t60), "bench:1");
    const double len = gas.auto_length_s(room);
    std::printf("| %.1f | %.2f | %.2f | %.2f |\n", t60, len,
                1e3 * time_per_rir(gas, room, static_cast<size_t>(len * kFs), reps / 2),
                1e3 * time_per_rir(gas, room, n1s, reps / 2));
  }

  std::printf("\n## Time vs room volume (reference room scaled, T60 0.6 s, 1.0 s RIR)\n");
  std::printf("| scale | volume m^3 | transition ms | ms per RIR |\n|---|---|---|---|\n");
  for (double scale : {0.5, 1.0, 2.0, 4.0}) {
    char line[256];
    std::snprintf(line, sizeof line, "v room=%g,%g,%g src=%g,%g,%g mic=%g,%g,%g t60=0.6", 6 * scale, 4.5 * scale,
                  3 * scale, 2 * scale, 1.5 * scale, 1.6 * scale, 4 * scale, 3 * scale, 1.2 * scale);
    const RoomSpec room = parse_room_list_line(line, "bench:1");
    RenderFacts facts;
    gas.render_band_signals(room, kFs, n1s, 0, &facts);
    std::printf("| %.1f | %.0f | %.0f | %.2f |\n", scale, room.volume_m3(), 1e3 * facts.transition_time_s,
                1e3 * time_per_rir(gas, room, n1s, reps / 2));
  }
  return 0;
}

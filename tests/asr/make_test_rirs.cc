// Reverberant RIRs for the recogniser's sensitivity test (asr_sensitivity_test.sh) where the
// measured R3VIVAL RIRs of ../shared/data are absent: rendered by the independent "measured RIR"
// generator of tests/diagnose (measured_rir_generator.h: its own image sum and diffuse field, no
// code of src/sim), so the test never trains on the simulator it exists to judge.
// Rooms: random shoeboxes (5-10 x 4-8 x 2.5-3.5 m), flat absorption 0.1-0.25 per surface (Eyring
// T60 ~0.45-1.2 s), scattering 0.3, source 1.5-3.5 m from the microphone.
// Usage: make_test_rirs <out-dir> <count> <seed>
// Writes <out-dir>/<id>.wav (16 kHz float, 1 s) and <out-dir>/rir_list (Kaldi's format).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "io/wav_writer.h"
#include "measured_rir_generator.h"
#include "util/options.h"
#include "util/rng.h"

int main(int argc, char** argv) {
  using namespace tsrir;
  if (argc != 4) {
    std::cerr << "Usage: make_test_rirs <out-dir> <count> <seed>\n";
    return 1;
  }
  const std::string out = argv[1];
  const int count = std::stoi(argv[2]);
  const Seed seed = std::stoull(argv[3]);
  constexpr double kFs = 16000.0;
  std::filesystem::create_directories(out);
  std::ofstream list(out + "/rir_list");
  for (int i = 0; i < count; ++i) {
    const std::string id = "gen" + std::to_string(seed) + "-" + std::to_string(i);
    Rng rng = Rng::for_item(seed, id);
    testdata::TrueRoom room;
    room.size_m = {rng.uniform(5.0, 10.0), rng.uniform(4.0, 8.0), rng.uniform(2.5, 3.5)};
    const double a = rng.uniform(0.1, 0.25);
    for (auto& surface : room.absorption) surface.fill(a);
    room.scattering.fill(0.3);
    room.mic_m = {rng.uniform(1.0, room.size_m[0] - 1.0), rng.uniform(1.0, room.size_m[1] - 1.0), 1.3};
    // A source 1.5-3.5 m away in a random horizontal direction, kept 0.5 m inside the walls.
    for (int tries = 0;; ++tries) {
      const double r = rng.uniform(1.5, 3.5), phi = rng.uniform(0.0, 2.0 * M_PI);
      const double x = room.mic_m[0] + r * std::cos(phi), y = room.mic_m[1] + r * std::sin(phi);
      if ((x > 0.5 && x < room.size_m[0] - 0.5 && y > 0.5 && y < room.size_m[1] - 0.5) || tries > 1000) {
        room.source_m = {std::clamp(x, 0.5, room.size_m[0] - 0.5), std::clamp(y, 0.5, room.size_m[1] - 0.5), 1.6};
        break;
      }
    }
    const Signal h = testdata::generate_measured_rir(room, kFs, size_t(kFs), rng);
    AudioWriteOptions write;
    write.format = SampleFormat::kFloat32;
    const std::string path = std::filesystem::absolute(out + "/" + id + ".wav").string();
    write_wav(path, h, write);
    list << "--rir-id " << id << " --room-id " << id << " " << path << "\n";
  }
  if (!list.flush()) {
    std::cerr << "make_test_rirs: cannot write " << out << "/rir_list\n";
    return 1;
  }
  return 0;
}

// rir-simulate's room lists (src/sim/room_list.h). Invariants: every parsed room passes
// validate_room (the simulator's preconditions), and format_room_list_line writes a line that
// parses back to the same room (9 significant digits: relative error <= 5e-9, allowed 1e-8).
#include <cmath>

#include "fuzz_common.h"
#include "sim/room_list.h"

using namespace tsrir;
using namespace tsrir::sim;

namespace {

bool close(double a, double b) { return std::fabs(a - b) <= 1e-8 * std::max(std::fabs(a), std::fabs(b)) + 1e-300; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = fuzz::as_text(data, size);
  fuzz::expect_only_errors([&] {
    for (const RoomSpec& room : parse_room_list(text, "fuzz.rooms")) {
      validate_room(room);
      const std::string line = format_room_list_line(room);
      RoomSpec back;
      try {
        back = parse_room_list_line(line, "formatted");
      } catch (const Error& e) {
        fuzz::fail("a formatted room must parse back", line + " -> " + e.what());
      }
      FUZZ_CHECK(back.rir_id == room.rir_id && back.effective_room_id() == room.effective_room_id(), line);
      for (int i = 0; i < 3; ++i) {
        FUZZ_CHECK(close(back.size_m[i], room.size_m[i]), line);
        FUZZ_CHECK(close(back.source_m[i], room.source_m[i]), line);
        FUZZ_CHECK(close(back.mic_m[i], room.mic_m[i]), line);
      }
      for (int s = 0; s < kNumSurfaces; ++s)
        for (int b = 0; b < kNumOctaveBands; ++b) FUZZ_CHECK(close(back.absorption[s][b], room.absorption[s][b]), line);
      for (int b = 0; b < kNumOctaveBands; ++b) FUZZ_CHECK(close(back.scattering[b], room.scattering[b]), line);
      FUZZ_CHECK(close(back.speed_of_sound_m_s, room.speed_of_sound_m_s), line);
    }
  });
  return 0;
}

// Room-list parsing: keys, precedence, t60 inversion and the errors users see (file:line).
#include <gtest/gtest.h>

#include <cmath>

#include "sim/room_list.h"
#include "util/error.h"

namespace tsrir::sim {
namespace {

// Expects parse_room_list(text) to fail with a message containing every fragment.
void expect_error(const std::string& text, const std::vector<std::string>& fragments) {
  try {
    parse_room_list(text, "rooms.txt");
    FAIL() << "no error for: " << text;
  } catch (const Error& e) {
    for (const std::string& f : fragments) {
      EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << "'" << f << "' not in: " << e.what();
    }
  }
}

TEST(RoomList, ParsesRequiredKeysAndDefaults) {
  const auto rooms = parse_room_list("# header\n\nr1 room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2  # trailing\n", "x");
  ASSERT_EQ(rooms.size(), 1u);
  const RoomSpec& r = rooms[0];
  EXPECT_EQ(r.rir_id, "r1");
  EXPECT_EQ(r.effective_room_id(), "r1");
  EXPECT_EQ(r.where, "x:3");
  EXPECT_DOUBLE_EQ(r.size_m[1], 4.5);
  EXPECT_DOUBLE_EQ(r.mic_m[2], 1.2);
  EXPECT_DOUBLE_EQ(r.speed_of_sound_m_s, 343.0);
  for (int s = 0; s < kNumSurfaces; ++s) EXPECT_DOUBLE_EQ(r.absorption[s][3], kDefaultAbsorption);
  EXPECT_DOUBLE_EQ(r.scattering[0], kDefaultScattering);
  EXPECT_DOUBLE_EQ(r.volume_m3(), 81.0);
  EXPECT_DOUBLE_EQ(r.surface_area_m2(), 2.0 * (27.0 + 13.5 + 18.0));
}

TEST(RoomList, SurfaceAbsorptionPrecedence) {
  const RoomSpec r = parse_room_list_line(
      "r room=5,4,3 src=1,1,1 mic=2,2,2 absorption=0.1 absorption.walls=0.2 absorption.y1=0.3 "
      "absorption.ceiling=0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8 scattering=0,0,0,0.1,0.2,0.3,0.4,0.5 room-id=lab",
      "x:1");
  EXPECT_DOUBLE_EQ(r.absorption[kWallX0][0], 0.2);
  EXPECT_DOUBLE_EQ(r.absorption[kWallX1][7], 0.2);
  EXPECT_DOUBLE_EQ(r.absorption[kWallY0][4], 0.2);
  EXPECT_DOUBLE_EQ(r.absorption[kWallY1][4], 0.3);
  EXPECT_DOUBLE_EQ(r.absorption[kFloor][2], 0.1);
  EXPECT_DOUBLE_EQ(r.absorption[kCeiling][5], 0.6);
  EXPECT_DOUBLE_EQ(r.scattering[7], 0.5);
  EXPECT_EQ(r.effective_room_id(), "lab");
}

TEST(RoomList, T60IsInvertedWithEyringPerBand) {
  const RoomSpec r = parse_room_list_line("r room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.3,0.4,0.5,0.6,0.6,0.5,0.4,0.3", "x:1");
  const BandValues t60 = eyring_t60_s(r);
  const double want[8] = {0.3, 0.4, 0.5, 0.6, 0.6, 0.5, 0.4, 0.3};
  for (int b = 0; b < kNumOctaveBands; ++b) EXPECT_NEAR(t60[b], want[b], 1e-9);
  // Independent check of one value: Sabine-style constant 0.161 = 24 ln10 / 343 within 0.1%.
  const double a = r.absorption[0][3];
  EXPECT_NEAR(0.161 * 81.0 / (-117.0 * std::log(1.0 - a)), 0.6, 0.6e-3 * 1.5);
}

TEST(RoomList, TemperatureSetsSpeedOfSound) {
  const RoomSpec r = parse_room_list_line("r room=5,4,3 src=1,1,1 mic=2,2,2 temperature=0 humidity=30", "x:1");
  EXPECT_NEAR(r.speed_of_sound_m_s, 331.3, 1e-9);
  EXPECT_DOUBLE_EQ(r.relative_humidity_percent, 30.0);
}

TEST(RoomList, FormatRoundTrips) {
  const RoomSpec a = parse_room_list_line(
      "r room=5.5,4,3.1 src=1,1.25,1 mic=2,2,2 absorption.walls=0.2 absorption.floor=0.05,0.06,0.07,0.08,0.09,0.1,0.11,0.12 "
      "scattering=0.3 room-id=q temperature=25",
      "x:1");
  const RoomSpec b = parse_room_list_line(format_room_list_line(a), "x:2");
  EXPECT_EQ(a.rir_id, b.rir_id);
  EXPECT_EQ(a.room_id, b.room_id);
  EXPECT_EQ(a.size_m, b.size_m);
  EXPECT_EQ(a.source_m, b.source_m);
  EXPECT_EQ(a.absorption, b.absorption);
  EXPECT_EQ(a.scattering, b.scattering);
  EXPECT_DOUBLE_EQ(a.speed_of_sound_m_s, b.speed_of_sound_m_s);
}

TEST(RoomList, BadInputNamesFileAndLine) {
  const std::string ok = "ok room=5,4,3 src=1,1,1 mic=2,2,2\n";
  expect_error(ok + "b room=5,4,3 src=6,1,1 mic=2,2,2\n", {"rooms.txt:2", "source", "inside"});
  expect_error(ok + "b room=5,4,3 src=1,1,1 mic=2,2,3\n", {"rooms.txt:2", "microphone"});
  expect_error(ok + "b room=5,0,3 src=1,1,1 mic=2,2,2\n", {"rooms.txt:2", "positive"});
  expect_error(ok + "b room=5,-4,3 src=1,1,1 mic=2,2,2\n", {"rooms.txt:2", "positive"});
  expect_error(ok + "b room=5,4,3 src=1,1,1 mic=2,2,2 absorption=0\n", {"rooms.txt:2", "(0,1]"});
  expect_error(ok + "b room=5,4,3 src=1,1,1 mic=2,2,2 absorption=1.2\n", {"rooms.txt:2", "(0,1]"});
  expect_error(ok + "b room=5,4,3 src=1,1,1 mic=2,2,2 absorption.x1=0.1,0.2\n", {"rooms.txt:2", "1 or 8"});
  expect_error(ok + "b room=5,4,3 src=1,1,1 mic=2,2,2 absorption.door=0.3\n", {"rooms.txt:2", "surface"});
  expect_error(ok + "b room=5,4,3 src=1,1,1 mic=2,2,2 t60=30\n", {"rooms.txt:2", "cannot be reached"});
  expect_error(ok + "b room=5,4,3 src=1,1,1 mic=2,2,2 t60=-1\n", {"rooms.txt:2", "positive"});
  expect_error(ok + "b room=5,4,3 src=1,1,1 mic=2,2,2 t60=0.5 absorption=0.2\n", {"rooms.txt:2", "not both"});
  expect_error(ok + "b room=5,4,3 src=1,1,1 mic=2,2,2 colour=red\n", {"rooms.txt:2", "unknown key 'colour'"});
  expect_error(ok + "b room=5,4,3 src=1,1,1\n", {"rooms.txt:2", "mic"});
  expect_error(ok + "b room=5,4,3 src=1,1 mic=2,2,2\n", {"rooms.txt:2", "3 comma-separated"});
  expect_error(ok + "b room=5,4,3 src=1,1,x mic=2,2,2\n", {"rooms.txt:2"});
  expect_error(ok + "b room=5,4,3 src=1,1,1 mic=2,2,2 room=5,4,3\n", {"rooms.txt:2", "twice"});
  expect_error(ok + "ok room=5,4,3 src=1,1,1 mic=2,2,2\n", {"rooms.txt:2", "duplicate"});
  expect_error(ok + "b room=5,4,3 src=1,1,1 mic=2,2,2 scattering=1.5\n", {"rooms.txt:2", "[0,1]"});
  expect_error(ok + "a/b room=5,4,3 src=1,1,1 mic=2,2,2\n", {"rooms.txt:2", "file name"});
  expect_error(ok + "b room=5,4,3 src=1,1,1 mic=1,1,1\n", {"rooms.txt:2", "same point"});
  expect_error("# nothing\n", {"no entries"});
}

}  // namespace
}  // namespace tsrir::sim

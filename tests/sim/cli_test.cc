// rir-simulate and rir-room-list as users run them: outputs, Kaldi lists, determinism across
// threads, and bad input (clear error with file:line, non-zero exit, nothing written).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/audio_io.h"
#include "io/kaldi_lists.h"
#include "sim/room_list.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;

class SimCli : public tsrir_test::TempDirTest {
 protected:
  static std::string read_file(const std::string& p) { return tsrir_test::slurp(p); }
  // Runs a program from the build's bin dir; returns its exit status, stderr in *err.
  int run(const std::string& program, const std::string& args, std::string* err = nullptr) const {
    const tsrir_test::CommandResult r = tsrir_test::run_command(tsrir_test::program_path(program) + " " + args);
    if (err) *err = r.err;
    last_out_ = r.out;
    return r.status;
  }
  mutable std::string last_out_;  // stdout of the last run()
};

const char* kRooms =
    "# two rooms\n"
    "small room=4,3,2.5 src=1,1,1.5 mic=3,2,1.2 t60=0.3 room-id=office\n"
    "\n"
    "ref room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 absorption=0.1,0.1,0.15,0.2,0.25,0.3,0.35,0.4\n"
    "walls room=5,4,3 src=1,2,1.5 mic=4,2,1.5 absorption.walls=0.3 absorption.floor=0.05 absorption.ceiling=0.6\n";

TEST_F(SimCli, HelpExitsZeroWithExample) {
  std::string err;
  ASSERT_EQ(run("rir-simulate", "--help", &err), 0);
  const std::string out = last_out_ + err;
  EXPECT_NE(out.find("Example"), std::string::npos);
  EXPECT_NE(out.find("absorption.walls"), std::string::npos);
  EXPECT_NE(out.find("gas = ism+diffuse"), std::string::npos);
  ASSERT_EQ(run("rir-room-list", "--help", &err), 0);
  EXPECT_NE((last_out_ + err).find("r3vival"), std::string::npos);
}

TEST_F(SimCli, WritesWavsAndKaldiLists) {
  write_text("rooms.txt", kRooms);
  std::string err;
  ASSERT_EQ(run("rir-simulate", "--fs=8000 --length=auto " + path("rooms.txt") + " " + path("out"), &err), 0) << err;
  const auto entries = tsrir::read_rir_list(path("out/rir_list"));
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[0].rir_id, "ref");
  EXPECT_EQ(entries[1].rir_id, "small");
  EXPECT_EQ(entries[1].room_id, "office");
  EXPECT_EQ(entries[0].room_id, "ref");
  for (const auto& e : entries) {
    const tsrir::Signal s = tsrir::read_audio(e.rxfilename);
    EXPECT_EQ(s.sample_rate_hz, 8000.0);
    EXPECT_GT(s.samples.size(), 800u);
  }
  // auto length: 0.3 s T60 room -> well under 1 s; the 0.4 s-ish room longer.
  EXPECT_LT(tsrir::read_audio(path("out/small.wav")).samples.size(), 8000u * 0.4);
  EXPECT_NE(read_file(path("out/rir.scp")).find("walls "), std::string::npos);
}

TEST_F(SimCli, ThreadCountDoesNotChangeOutput) {
  write_text("rooms.txt", kRooms);
  ASSERT_EQ(run("rir-simulate", "--seed=5 --num-threads=1 " + path("rooms.txt") + " " + path("a")), 0);
  ASSERT_EQ(run("rir-simulate", "--seed=5 --num-threads=3 " + path("rooms.txt") + " " + path("b")), 0);
  ASSERT_EQ(run("rir-simulate", "--seed=6 --num-threads=3 " + path("rooms.txt") + " " + path("c")), 0);
  for (const char* id : {"small", "ref", "walls"}) {
    const std::string a = read_file(path("a/") + id + ".wav");
    EXPECT_FALSE(a.empty());
    EXPECT_EQ(a, read_file(path("b/") + id + ".wav")) << id;
    EXPECT_NE(a, read_file(path("c/") + id + ".wav")) << id;
  }
}

TEST_F(SimCli, FloatFormat) {
  // 3 samples (3 * 343 / 16000 m) from the source: the arrival falls on a sample.
  write_text("rooms.txt", "near room=4,3,2.5 src=1,1,1.5 mic=1.0643125,1,1.5\n");
  ASSERT_EQ(run("rir-simulate", "--format=float --length=0.2 " + path("rooms.txt") + " " + path("out")), 0);
  const tsrir::Signal s = tsrir::read_audio(path("out/near.wav"));
  // 1/(4 pi 0.0643) = 1.24 > full scale, kept by float output.
  float peak = 0.0f;
  for (float x : s.samples) peak = std::max(peak, std::abs(x));
  EXPECT_NEAR(peak, 1.0 / (4.0 * 3.14159265 * 0.0643125), 0.02);
  std::string err;
  // int16 cannot hold it: an error, not silent clipping.
  EXPECT_NE(run("rir-simulate", "--length=0.2 " + path("rooms.txt") + " " + path("out16"), &err), 0);
  EXPECT_NE(err.find("full scale"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(path("out16")));
}

TEST_F(SimCli, ArraysWriteOneChannelPerMicrophoneAndPatternDefaultsComeFromTheOptions) {
  // A line without mic_pattern= takes --mic-pattern / --src-pattern; a line's own key wins.
  write_text("rooms.txt", "arr room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2;4.05,3,1.2;4.1,3,1.2 t60=0.4\n");
  write_text("keyed.txt", "arr room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2;4.05,3,1.2;4.1,3,1.2 t60=0.4 "
                          "mic_pattern=cardioid src_pattern=hypercardioid\n");
  const std::string common = "--format=float --length=0.3 ";
  ASSERT_EQ(run("rir-simulate", common + path("rooms.txt") + " " + path("omni")), 0);
  ASSERT_EQ(run("rir-simulate", common + "--mic-pattern=cardioid --src-pattern=hypercardioid " + path("rooms.txt") +
                                    " " + path("by_option")),
            0);
  ASSERT_EQ(run("rir-simulate", common + "--mic-pattern=figure8 " + path("keyed.txt") + " " + path("by_key")), 0);
  tsrir::AudioInfo info;
  EXPECT_EQ(tsrir::read_audio_channels(path("omni/arr.wav"), &info).size(), 3u);
  EXPECT_EQ(read_file(path("by_option/arr.wav")), read_file(path("by_key/arr.wav")));
  EXPECT_NE(read_file(path("by_option/arr.wav")), read_file(path("omni/arr.wav")));
  std::string err;
  EXPECT_NE(run("rir-simulate", "--mic-pattern=shotgun " + path("rooms.txt") + " " + path("bad"), &err), 0);
  EXPECT_NE(err.find("cardioid"), std::string::npos) << err;  // the choices are listed
}

TEST_F(SimCli, BadInputFailsWithLocationAndWritesNothing) {
  struct Case { std::string line, fragment; };
  const Case cases[] = {
      {"bad room=4,3,2.5 src=5,1,1 mic=3,2,1.2", "source"},
      {"bad room=4,-3,2.5 src=1,1,1 mic=3,2,1.2", "positive"},
      {"bad room=4,3,2.5 src=1,1,1 mic=3,2,1.2 absorption=1.5", "(0,1]"},
      {"bad room=40,30,25 src=1,1,1 mic=3,2,1.2 t60=90", "cannot be reached"},
      {"bad room=4,3,2.5 src=1,1,1 mic=3,2,1.2 wall=3", "unknown key"},
  };
  for (const Case& c : cases) {
    write_text("rooms.txt", std::string(kRooms) + c.line + "\n");
    std::string err;
    EXPECT_NE(run("rir-simulate", path("rooms.txt") + " " + path("out"), &err), 0) << c.line;
    EXPECT_NE(err.find("rooms.txt:6"), std::string::npos) << err;
    EXPECT_NE(err.find(c.fragment), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(path("out"))) << "nothing may be written for a failed run";
  }
  // A previous good output survives a failed run.
  write_text("good.txt", kRooms);
  ASSERT_EQ(run("rir-simulate", path("good.txt") + " " + path("out")), 0);
  const std::string before = read_file(path("out/rir_list"));
  EXPECT_NE(run("rir-simulate", path("rooms.txt") + " " + path("out")), 0);
  EXPECT_EQ(read_file(path("out/rir_list")), before);
  // Bad options.
  EXPECT_NE(run("rir-simulate", "--no-such-option " + path("good.txt") + " " + path("o2")), 0);
  EXPECT_NE(run("rir-simulate", "--model=gas+nosuch " + path("good.txt") + " " + path("o2")), 0);
  EXPECT_NE(run("rir-simulate", "--length=-1 " + path("good.txt") + " " + path("o2")), 0);
  EXPECT_NE(run("rir-simulate", "--format=int8 " + path("good.txt") + " " + path("o2")), 0);
  EXPECT_FALSE(fs::exists(path("o2")));
}

TEST_F(SimCli, RoomListFromTableIsSeededPerRir) {
  write_text("setups.txt",
             "# measured set-ups\n"
             "rir-id room-id Lx Ly Lz sx sy sz mx my mz\n"
             "a lab 6 4 3 1 1 1.5 4 3 1.2\n"
             "b lab 6 4 3 2 1 1.5 4 3 1.2\n");
  write_text("setups_rev.txt",
             "rir-id Lx Ly Lz sx sy sz mx my mz room-id\n"
             "b 6 4 3 2 1 1.5 4 3 1.2 lab\n");
  std::string err;
  ASSERT_EQ(run("rir-room-list", "--seed=3 --absorption-range=0.2,0.4 " + path("setups.txt") + " " + path("rooms.txt"), &err), 0) << err;
  ASSERT_EQ(run("rir-room-list", "--seed=3 --absorption-range=0.2,0.4 " + path("setups_rev.txt") + " " + path("rooms_rev.txt")), 0);
  const auto rooms = tsrir::sim::read_room_list(path("rooms.txt"));
  const auto rev = tsrir::sim::read_room_list(path("rooms_rev.txt"));
  ASSERT_EQ(rooms.size(), 2u);
  EXPECT_EQ(rooms[1].absorption, rev[0].absorption) << "a RIR's draw does not depend on the rest of the list";
  EXPECT_NE(rooms[0].absorption, rooms[1].absorption);
  for (const auto& r : rooms) {
    EXPECT_EQ(r.effective_room_id(), "lab");
    for (const auto& s : r.absorption)
      for (double a : s) {
        EXPECT_GE(a, 0.2);
        EXPECT_LE(a, 0.4);
      }
  }
  // The list feeds rir-simulate directly.
  ASSERT_EQ(run("rir-simulate", "--length=0.3 " + path("rooms.txt") + " " + path("out"), &err), 0) << err;
  EXPECT_TRUE(fs::exists(path("out/b.wav")));
  // Errors name the line.
  write_text("bad.txt", "rir-id Lx Ly Lz sx sy sz mx my mz\nx 6 4 3 7 1 1.5 4 3 1.2\n");
  EXPECT_NE(run("rir-room-list", path("bad.txt") + " " + path("r.txt"), &err), 0);
  EXPECT_NE(err.find("bad.txt:2"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(path("r.txt")));
  EXPECT_NE(run("rir-room-list", "--absorption-range=0,0.5 " + path("setups.txt") + " " + path("r.txt"), &err), 0);
}

TEST_F(SimCli, RoomListFromButReverbDbLayout) {
  // A miniature tree in the BUT ReverbDB layout; one microphone outside the room is skipped.
  const fs::path room = dir_ / "db" / "VUT_FIT_X1";
  fs::create_directories(room / "MicID01" / "SpkID01_20170901_S" / "01");
  fs::create_directories(room / "MicID01" / "SpkID01_20170901_S" / "02");
  std::ofstream(room / "env_meta.txt") << "$EnvName\tX1\n$EnvDepth\t7.0\n$EnvWidth\t5.0\n$EnvHeight\t3.0\n";
  std::ofstream(room / "MicID01" / "SpkID01_20170901_S" / "spk_meta.txt")
      << "$EnvSpk1Depth\t1.5\n$EnvSpk1Width\t2.0\n$EnvSpk1Height\t1.4\n";
  std::ofstream(room / "MicID01" / "SpkID01_20170901_S" / "01" / "mic_meta.txt")
      << "$EnvMicID\t1\n$EnvMic1Depth\t4.0\n$EnvMic1Width\t3.0\n$EnvMic1Height\t1.2\n";
  std::ofstream(room / "MicID01" / "SpkID01_20170901_S" / "02" / "mic_meta.txt")
      << "$EnvMicID\t2\n$EnvMic2Depth\t7.5\n$EnvMic2Width\t3.0\n$EnvMic2Height\t1.2\n";
  std::string err;
  ASSERT_EQ(run("rir-room-list", "--format=but " + (dir_ / "db").string() + " " + path("rooms.txt"), &err), 0) << err;
  EXPECT_NE(err.find("skipped"), std::string::npos);
  const auto rooms = tsrir::sim::read_room_list(path("rooms.txt"));
  ASSERT_EQ(rooms.size(), 1u);
  EXPECT_EQ(rooms[0].rir_id, "VUT_FIT_X1_MicID01_SpkID01_20170901_S_01");
  EXPECT_EQ(rooms[0].effective_room_id(), "VUT_FIT_X1");
  EXPECT_DOUBLE_EQ(rooms[0].size_m[0], 7.0);
  EXPECT_DOUBLE_EQ(rooms[0].source_m[1], 2.0);
  EXPECT_DOUBLE_EQ(rooms[0].mic_m[0], 4.0);
}

TEST_F(SimCli, RoomListFromR3vivalPositions) {
  const std::string csv = std::string(TSRIR_SOURCE_DIR) + "/../shared/data/rirs/r3vival/positions_approx_from_Plan_png.csv";
  if (!fs::exists(csv)) GTEST_SKIP() << "shared data absent: " << csv;
  std::string err;
  ASSERT_EQ(run("rir-room-list",
                "--format=r3vival --conditions=000,100 "
                "--id-format=RLRVarAcLab_Absorptive_{condition}_{s_source}_R1_FRL10cm_ch7 " + csv + " " + path("rooms.txt"),
                &err),
            0) << err;
  const auto rooms = tsrir::sim::read_room_list(path("rooms.txt"));
  ASSERT_EQ(rooms.size(), 68u);  // 34 sources x 2 conditions
  // Every id names a real R3VIVAL file.
  const fs::path data = fs::path(csv).parent_path();
  for (const auto& r : rooms) EXPECT_TRUE(fs::exists(data / (r.rir_id + ".wav"))) << r.rir_id;
  // Distances agree with the CSV's distance column for the directional sources (+-0.1 m plan reading).
  for (const auto& r : rooms) {
    if (r.rir_id.find("_S000-200_") != std::string::npos) {
      EXPECT_NEAR(r.source_mic_distance_m(), 2.0, 0.1);
    }
    if (r.rir_id.find("_S090-150_") != std::string::npos) {
      EXPECT_NEAR(r.source_mic_distance_m(), 1.5, 0.1);
    }
  }
  EXPECT_EQ(rooms[0].effective_room_id(), "r3vival_000");
}

}  // namespace

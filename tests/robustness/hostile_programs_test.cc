// Hostile names and content through the programs themselves (each test skips when its program is
// not built): ids and paths with quotes, ';', '$()' and backticks in the pipes reverberate-data
// writes, in rir-simulate's outputs and in wav-reverberate's inputs; lying headers; 10^5-line
// lists whose one bad line is the last (the error must name it, quickly and in bounded memory).
// A canary file appears if any command hidden in a name is ever run.
// rir-diagnose, rir-room-list and validate-data-dir get the same treatment: hostile ids and paths,
// broken measured WAVs, metadata that is missing, duplicated, non-numeric, non-finite or
// physically impossible, empty inputs, and Kaldi data dirs broken in each way Kaldi's
// validate_data_dir.sh catches. Every failure must name the file (and line where there is one),
// exit 1 and leave no output under its final name.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "io/audio_io.h"
#include "io/kaldi_table.h"
#include "io/rir_set.h"
#include "robust_test_util.h"
#include "util/error.h"

namespace fs = std::filesystem;
using robust::make_wav;

namespace {

class HostilePrograms : public robust::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    // The canary lands in the working directory of whatever shell would run a hidden command;
    // the hostile names below create it by relative name, so run everything from dir_.
    old_cwd_ = fs::current_path();
    fs::current_path(dir_);
    // A directory whose name alone would run commands if it were ever pasted unquoted into bash.
    hostile_dir_ = (dir_ / "d ir;$(touch CANARY)'q'").string();
    fs::create_directories(hostile_dir_);
  }
  void TearDown() override {
    fs::current_path(old_cwd_);
    ScratchDirTest::TearDown();
  }
  void expect_no_canary() const {
    EXPECT_FALSE(fs::exists(dir_ / "CANARY")) << "a command hidden in a name was run";
    EXPECT_FALSE(fs::exists(dir_ / "PWNED")) << "a command hidden in a name was run";
  }
  // A failure as the guide defines it: exit status 1, stderr naming `where` (file, or file:line).
  void expect_error(const robust::RunResult& r, const std::string& where, const std::string& what = "") const {
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find(where), std::string::npos) << "the error does not name " << where << ":\n" << r.output;
    if (!what.empty()) {
      EXPECT_NE(r.output.find(what), std::string::npos) << r.output;
    }
    EXPECT_NE(r.output.find("ERROR"), std::string::npos) << r.output;
  }
  std::string need(const std::string& program) const { return robust::program_path(program); }
  std::string rir_path() const { return hostile_dir_ + "/r 1;$(touch CANARY).wav"; }
  void write_inputs() const {
    std::vector<int16_t> rir(4000, 0);
    rir[40] = 20000;
    for (size_t i = 41; i < rir.size(); ++i) rir[i] = static_cast<int16_t>(((i * 7919) % 2001) - 1000) / static_cast<int16_t>(1 + i / 400);
    write_bytes(rir_path(), make_wav({}, rir));
    write_bytes(hostile_dir_ + "/s`touch CANARY`.wav", make_wav({}, robust::test_tone(16000)));
    write_bytes(hostile_dir_ + "/n\"oise.wav", make_wav({}, robust::test_tone(8000, 1000)));
    write_bytes(path("rir.scp"), "r1 " + rir_path() + "\n");
    write_bytes(path("noise.scp"), "n1 " + hostile_dir_ + "/n\"oise.wav\n");
  }
  fs::path old_cwd_;
  std::string hostile_dir_;
};

// A Kaldi id may hold any non-whitespace byte: this one is a command in every shell syntax.
const std::string kHostileId = "spk1-u;$(touch${IFS}CANARY)`touch${IFS}CANARY`'\"1";

TEST_F(HostilePrograms, ReverberateDataPipesRunOnlyWhatTheUserWrote) {
  const std::string prog = need("reverberate-data");
  if (prog.empty()) GTEST_SKIP() << "reverberate-data not built";
  write_inputs();
  fs::create_directories(path("data"));
  write_bytes(path("data/wav.scp"), kHostileId + " " + hostile_dir_ + "/s`touch CANARY`.wav\n");
  write_bytes(path("data/utt2spk"), kHostileId + " spk1\n");
  write_bytes(path("data/spk2utt"), "spk1 " + kHostileId + "\n");
  auto r = robust::run_argv({prog, "--rir-set-parameters", path("rir.scp"), "--noise-set-parameters", path("noise.scp"),
                             "--random-seed=3", path("data"), path("out")});
  ASSERT_EQ(r.status, 0) << r.output;
  tsrir::Table wav = tsrir::read_table(path("out/wav.scp"));
  ASSERT_EQ(wav.entries.size(), 1u);
  EXPECT_EQ(wav.entries[0].key, kHostileId);
  // Running the generated pipe through bash, as Kaldi will: audio out, nothing else run.
  tsrir::Signal s = tsrir::read_audio(wav.entries[0].value);
  EXPECT_EQ(s.size(), 16000u);
  expect_no_canary();
  // --write-wavs names files after the ids: the hostile id must stay one inert file name.
  r = robust::run_argv({prog, "--rir-set-parameters", path("rir.scp"), "--random-seed=3", "--write-wavs=" + path("wavs"),
                        path("data"), path("out2")});
  ASSERT_EQ(r.status, 0) << r.output;
  wav = tsrir::read_table(path("out2/wav.scp"));
  ASSERT_EQ(wav.entries.size(), 1u);
  EXPECT_EQ(tsrir::read_audio(wav.entries[0].value).size(), 16000u);
  expect_no_canary();
}

TEST_F(HostilePrograms, IdsThatClimbOutOfTheOutputDirectoryAreRefused) {
  const std::string prog = need("reverberate-data");
  if (prog.empty()) GTEST_SKIP() << "reverberate-data not built";
  write_inputs();
  fs::create_directories(path("data"));
  const std::string id = "spk1-../../escaped";
  write_bytes(path("data/wav.scp"), id + " " + hostile_dir_ + "/s`touch CANARY`.wav\n");
  write_bytes(path("data/utt2spk"), id + " spk1\n");
  write_bytes(path("data/spk2utt"), "spk1 " + id + "\n");
  fs::create_directories(path("deep/er"));
  auto r = robust::run_argv({prog, "--rir-set-parameters", path("rir.scp"), "--random-seed=3",
                             "--write-wavs=" + path("deep/er/wavs"), path("data"), path("out")});
  // Either refused with the id named, or written inside the wav directory: never outside it.
  if (r.status != 0) {
    EXPECT_NE(r.output.find("escaped"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(path("escaped.wav")) || fs::exists(path("deep/escaped.wav")))
      << "an utterance id wrote a file outside --write-wavs";
}

TEST_F(HostilePrograms, RirSimulateWithHostileIdsWritesReadableLists) {
  const std::string prog = need("rir-simulate");
  if (prog.empty()) GTEST_SKIP() << "rir-simulate not built";
  write_bytes(path("rooms.txt"), "r;$(touch${IFS}CANARY)'1 room=5,4,3 src=1,1,1.5 mic=3,2.5,1.2 t60=0.3\n");
  auto r = robust::run_argv({prog, path("rooms.txt"), hostile_dir_ + "/sim"});
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* list : {"rir.scp", "rir_list"}) {
    auto refs = tsrir::read_rir_refs(hostile_dir_ + "/sim/" + list, nullptr);
    ASSERT_EQ(refs.size(), 1u) << list;
    EXPECT_EQ(refs[0].id, "r;$(touch${IFS}CANARY)'1");
    EXPECT_GT(tsrir::load_rir(refs[0]).size(), 1000u) << list;
  }
  expect_no_canary();
}

TEST_F(HostilePrograms, WavReverberateRejectsLyingHeadersWithoutOutput) {
  const std::string prog = need("wav-reverberate");
  if (prog.empty()) GTEST_SKIP() << "wav-reverberate not built";
  write_inputs();
  robust::WavSpec lie;
  lie.data_size = 64000;  // claims 2 s, holds 0.1 s
  write_bytes(path("short.wav"), make_wav(lie, robust::test_tone(1600)));
  auto r = robust::run_argv({prog, "--impulse-response=" + rir_path(), path("short.wav"), path("out.wav")});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("short.wav"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("out.wav")));
  // An RIR file that is text, through the Kaldi-style option.
  write_bytes(path("text.wav"), "not audio\n");
  r = robust::run_argv({prog, "--impulse-response=" + path("text.wav"), hostile_dir_ + "/s`touch CANARY`.wav", path("out.wav")});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("text.wav"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("out.wav")));
  expect_no_canary();
}

// 10^5-line lists whose only bad line is the last: every program reads the whole list before
// working, so the error names line 100001 at once (no RIR simulated or measured first).
TEST_F(HostilePrograms, HundredThousandLineListsFailAtTheirLastLine) {
  const int n = 100000;
  std::ostringstream rooms, scp;
  for (int i = 0; i < n; ++i) {
    rooms << "r" << i << " room=5,4,3 src=1,1,1 mic=3,2,1.5 t60=0.4\n";
    scp << "r" << i << " /nonexistent/r.wav\n";
  }
  rooms << "r5 room=5,4,3 src=1,1,1 mic=3,2,1.5 t60=0.4\n";
  scp << "r5 /nonexistent/r.wav\n";
  write_bytes(path("rooms.txt"), rooms.str());
  write_bytes(path("rir.scp"), scp.str());
  struct Case {
    std::string program;
    std::vector<std::string> args;
    std::string where;
  };
  const std::vector<Case> cases = {
      {"rir-simulate", {path("rooms.txt"), path("sim")}, "rooms.txt:100001"},
      {"rir-metrics", {path("rir.scp")}, "rir.scp:100001"},
      {"rir-eq", {"gains", path("rir.scp"), "-"}, "rir.scp:100001"},
  };
  for (const auto& c : cases) {
    const std::string prog = need(c.program);
    if (prog.empty()) continue;
    std::vector<std::string> argv = {prog};
    argv.insert(argv.end(), c.args.begin(), c.args.end());
    auto r = robust::run_argv(argv);
    EXPECT_EQ(r.status, 1) << c.program;
    EXPECT_NE(r.output.find(c.where), std::string::npos) << c.program << ": " << r.output.substr(0, 2000);
  }
  EXPECT_FALSE(fs::exists(path("sim")));
  // Peak memory of those children: a 10^5-line list is a few MB of text.
  EXPECT_LT(robust::children_peak_rss_mb(), 1024.0);
}

// ---- rir-diagnose ----------------------------------------------------------------------------

// Ids m0..m{n-1}, WAVs in `dir`, room list and scp under the given names.
void write_plain_diagnose_set(size_t n, const std::string& dir, const std::string& rooms, const std::string& scp) {
  std::vector<std::string> ids, wavs;
  for (size_t i = 0; i < n; ++i) {
    ids.push_back("m" + std::to_string(i));
    wavs.push_back(dir + "/m" + std::to_string(i) + ".wav");
  }
  robust::write_diagnose_inputs(ids, wavs, rooms, scp);
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

TEST_F(HostilePrograms, RirDiagnoseTakesHostileIdsAndPathsAsData) {
  const std::string prog = need("rir-diagnose");
  if (prog.empty()) GTEST_SKIP() << "rir-diagnose not built";
  std::vector<std::string> ids, wavs;
  for (int i = 0; i < 8; ++i) {
    ids.push_back("m" + std::to_string(i) + ";$(touch${IFS}PWNED)`touch${IFS}CANARY`'\"<b>&amp;");
    wavs.push_back(hostile_dir_ + "/rir " + std::to_string(i) + ";$(touch PWNED)'\".wav");
  }
  const std::string rooms = hostile_dir_ + "/rooms $(touch PWNED).txt", scp = hostile_dir_ + "/m;e`touch CANARY`.scp";
  robust::write_diagnose_inputs(ids, wavs, rooms, scp);
  // One room, with a hostile room id: extended_models is keyed by it.
  const std::string room_id = "hall;$(touch${IFS}PWNED)'\"<i>";
  std::string list;
  for (const auto& line : lines_of(read_bytes(rooms))) list += line + " room-id=" + room_id + "\n";
  write_bytes(rooms, list);
  const std::string out = hostile_dir_ + "/out $(touch PWNED)";
  auto r = robust::run_argv({prog, "--num-threads=1", rooms, scp, out});
  ASSERT_EQ(r.status, 0) << r.output;
  // The report shows ids as text: '<b>' escaped, never markup.
  const std::string html = read_bytes(out + "/report.html");
  EXPECT_EQ(html.find("<b>"), std::string::npos);
  EXPECT_NE(html.find("&lt;b&gt;&amp;amp;"), std::string::npos);
  // findings.json holds the ids as JSON strings (the quote escaped).
  EXPECT_NE(read_bytes(out + "/findings.json").find("m0;$(touch${IFS}PWNED)`touch${IFS}CANARY`'\\\"<b>&amp;"),
            std::string::npos);
  // The command line it shows holds the hostile paths, quotes escaped.
  EXPECT_NE(html.find("d ir;$(touch CANARY)&#39;q&#39;/rooms $(touch PWNED).txt"), std::string::npos);
  // extended_models: "<room id> <model>" per room.
  const auto models = lines_of(read_bytes(out + "/extended_models"));
  ASSERT_EQ(models.size(), 1u);
  EXPECT_EQ(models[0].rfind(room_id + " gas", 0), 0u) << models[0];
  expect_no_canary();
}

// Each broken WAV replaces the 4th of 8 measured RIRs: the error names scp line 4 and the file.
TEST_F(HostilePrograms, RirDiagnoseNamesTheListLineAndFileOfABrokenMeasuredWav) {
  const std::string prog = need("rir-diagnose");
  if (prog.empty()) GTEST_SKIP() << "rir-diagnose not built";
  write_plain_diagnose_set(8, dir_.string(), path("rooms.txt"), path("measured.scp"));
  const std::string good = read_bytes(path("m3.wav"));
  robust::WavSpec lying;
  lying.data_size = 320000;  // claims 10 s, holds 0.5 s
  robust::WavSpec one_hz;
  one_hz.sample_rate = 1;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"truncated.wav", good.substr(0, 2000)},
      {"lying header.wav", make_wav(lying, robust::test_tone(8000))},
      {"text.wav", "not a wav\n"},
      {"empty.wav", ""},
      {"silent.wav", make_wav({}, std::vector<int16_t>(8000, 0))},
      {"three samples.wav", make_wav({}, {20000, 100, 50})},
      {"one hertz.wav", make_wav(one_hz, robust::test_tone(8000))},
      {"missing.wav", ""},  // not written
  };
  for (const auto& [name, bytes] : cases) {
    SCOPED_TRACE(name);
    if (name != "missing.wav") write_bytes(path(name), bytes);
    auto lines = lines_of(read_bytes(path("measured.scp")));
    lines[3] = "m3 " + path(name);
    write_bytes(path("bad.scp"), joined(lines));
    auto r = robust::run_argv({prog, "--num-threads=1", path("rooms.txt"), path("bad.scp"), path("out")});
    expect_error(r, "bad.scp:4");
    EXPECT_NE(r.output.find(name), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(path("out")));
  }
}

TEST_F(HostilePrograms, RirDiagnoseRejectsBadRoomListsAndScpsByLine) {
  const std::string prog = need("rir-diagnose");
  if (prog.empty()) GTEST_SKIP() << "rir-diagnose not built";
  write_plain_diagnose_set(8, dir_.string(), path("rooms.txt"), path("measured.scp"));
  const auto rooms = lines_of(read_bytes(path("rooms.txt")));
  const auto scp = lines_of(read_bytes(path("measured.scp")));
  auto with_room_line = [&](const std::string& line) {
    auto l = rooms;
    l[4] = line;
    return joined(l);
  };
  struct Case {
    std::string what, rooms, scp, where, message;
  };
  const std::string tail = " src=1,1,1.5 mic=2.3,2.5,1.2 t60=0.5";
  auto without_m4 = rooms;
  without_m4.erase(without_m4.begin() + 4);
  const std::vector<Case> cases = {
      {"measured id without a room", joined(without_m4), joined(scp), "measured.scp:5", "has no line in the room list"},
      {"duplicate room line", joined(rooms) + rooms[4] + "\n", joined(scp), "rooms.txt:9", "duplicate"},
      {"non-numeric size", with_room_line("m4 room=6,four,3" + tail), joined(scp), "rooms.txt:5", "four"},
      {"NaN size", with_room_line("m4 room=6,nan,3" + tail), joined(scp), "rooms.txt:5", "nan"},
      {"infinite T60", with_room_line("m4 room=6,4,3 src=1,1,1.5 mic=2.3,2.5,1.2 t60=inf"), joined(scp), "rooms.txt:5", "inf"},
      {"negative room size", with_room_line("m4 room=-6,4,3" + tail), joined(scp), "rooms.txt:5", "positive"},
      {"source outside the room", with_room_line("m4 room=6,4,3 src=7,1,1.5 mic=2.3,2.5,1.2 t60=0.5"), joined(scp),
       "rooms.txt:5", "not strictly inside"},
      {"source on the microphone", with_room_line("m4 room=6,4,3 src=2,2,1 mic=2,2,1 t60=0.5"), joined(scp), "rooms.txt:5",
       "same point"},
      {"negative T60", with_room_line("m4 room=6,4,3 src=1,1,1.5 mic=2.3,2.5,1.2 t60=-0.5"), joined(scp), "rooms.txt:5", ""},
      {"T60 needing absorption below 0.01", with_room_line("m4 room=6,4,3 src=1,1,1.5 mic=2.3,2.5,1.2 t60=100"), joined(scp),
       "rooms.txt:5", ""},
      {"absorption above 1", with_room_line("m4 room=6,4,3 src=1,1,1.5 mic=2.3,2.5,1.2 absorption=1.5"), joined(scp),
       "rooms.txt:5", "absorption"},
      {"missing room key", with_room_line("m4 src=1,1,1.5 mic=2.3,2.5,1.2"), joined(scp), "rooms.txt:5", "room="},
      {"empty room list", "", joined(scp), "rooms.txt", "no entries"},
      {"empty scp", joined(rooms), "", "measured.scp", "empty"},
      {"duplicate measured id", joined(rooms), joined(scp) + scp[2] + "\n", "measured.scp:9", "duplicate"},
      {"scp line without a file", joined(rooms), joined(scp) + "m9\n", "measured.scp:9", ""},
      {"five RIRs", joined(rooms), joined(std::vector<std::string>(scp.begin(), scp.begin() + 5)), "measured.scp",
       "at least 6"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    write_bytes(path("rooms.txt"), c.rooms);
    write_bytes(path("measured.scp"), c.scp);
    fs::remove_all(path("out"));
    auto r = robust::run_argv({prog, "--num-threads=1", path("rooms.txt"), path("measured.scp"), path("out")});
    expect_error(r, c.where, c.message);
    EXPECT_FALSE(fs::exists(path("out")));
  }
}

// ---- rir-room-list ---------------------------------------------------------------------------

const char* kTableHeader = "rir-id Lx Ly Lz sx sy sz mx my mz room-id\n";

TEST_F(HostilePrograms, RirRoomListTakesHostileIdsAndPathsAsData) {
  const std::string prog = need("rir-room-list");
  if (prog.empty()) GTEST_SKIP() << "rir-room-list not built";
  const std::string id = "r;$(touch${IFS}PWNED)'\"1", room = "room`touch${IFS}CANARY`'\"";
  const std::string table = hostile_dir_ + "/set ups;$(touch PWNED).txt";
  write_bytes(table, std::string(kTableHeader) + id + " 6 4 3 1 1 1.5 3 2.5 1.2 " + room + "\n");
  const std::string out = hostile_dir_ + "/rooms $(touch PWNED).txt";
  auto r = robust::run_argv({prog, table, out});
  ASSERT_EQ(r.status, 0) << r.output;
  const auto lines = lines_of(read_bytes(out));
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].rfind("# made by rir-room-list", 0), 0u) << lines[0];
  EXPECT_EQ(lines[1].rfind(id + " room=6,4,3 src=1,1,1.5 mic=3,2.5,1.2 ", 0), 0u) << lines[1];
  EXPECT_NE(lines[1].find(" room-id=" + room), std::string::npos) << lines[1];
  // The list reads back in rir-simulate with the same ids.
  if (!need("rir-simulate").empty()) {
    r = robust::run_argv({need("rir-simulate"), out, hostile_dir_ + "/sim"});
    ASSERT_EQ(r.status, 0) << r.output;
    auto refs = tsrir::read_rir_refs(hostile_dir_ + "/sim/rir_list", nullptr);
    ASSERT_EQ(refs.size(), 1u);
    EXPECT_EQ(refs[0].id, id);
    EXPECT_EQ(refs[0].room_id, room);
  }
  expect_no_canary();
}

// Ids a room list cannot hold (whitespace, newline, '#', control bytes, '/', '='): refused up
// front, naming where the id came from; was: written, giving a list rir-simulate misreads or refuses.
TEST_F(HostilePrograms, RirRoomListRefusesIdsARoomListCannotHold) {
  const std::string prog = need("rir-room-list");
  if (prog.empty()) GTEST_SKIP() << "rir-room-list not built";
  const std::string csv_head = "source_id,azimuth_deg,distance_m,x_m_approx,y_m_approx,source_type\n";
  const std::string receiver = "R,0,0,6.2,2.75,receiver\n";
  write_bytes(path("spaced.csv"), csv_head + "S 1,0,1.5,4.7,2.75,g\n" + receiver);
  write_bytes(path("plain.csv"), csv_head + "S1,0,1.5,4.7,2.75,g\n" + receiver);
  struct Case {
    std::string what;
    std::vector<std::string> args;
    std::string where;
  };
  auto table = [&](const std::string& name, const std::string& row) {
    write_bytes(path(name), std::string(kTableHeader) + "ok 6 4 3 1 1 1.5 3 2.5 1.2 a\n" + row + "\n");
    return path(name);
  };
  const std::vector<Case> cases = {
      {"space in a CSV source id", {"--format=r3vival", path("spaced.csv")}, "spaced.csv:2"},
      {"newline in --id-format", {"--format=r3vival", "--id-format=a\nb{s_source}", path("plain.csv")}, "plain.csv:2"},
      {"'#' in --id-format", {"--format=r3vival", "--id-format=x#{s_source}", path("plain.csv")}, "plain.csv:2"},
      {"space in --conditions", {"--format=r3vival", "--conditions=a b", path("plain.csv")}, "plain.csv:2"},
      {"'/' in a rir id", {table("slash.txt", "r/1 6 4 3 1 1 1.5 3 2.5 1.2 a")}, "slash.txt:3"},
      {"'=' in a rir id", {table("equals.txt", "r=1 6 4 3 1 1 1.5 3 2.5 1.2 a")}, "equals.txt:3"},
      {"control byte in a rir id", {table("ctl.txt", "r\x01x 6 4 3 1 1 1.5 3 2.5 1.2 a")}, "ctl.txt:3"},
      {"control byte in a room id", {table("ctlroom.txt", "r2 6 4 3 1 1 1.5 3 2.5 1.2 a\x7f")}, "ctlroom.txt:3"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    std::vector<std::string> argv = {prog};
    argv.insert(argv.end(), c.args.begin(), c.args.end());
    argv.push_back(path("rooms.txt"));
    auto r = robust::run_argv(argv);
    expect_error(r, c.where);
    EXPECT_FALSE(fs::exists(path("rooms.txt")));
  }
  // A BUT ReverbDB room directory with a space in its name gives a room id with a space.
  const fs::path room = dir_ / "but" / "Hotel Room";
  fs::create_directories(room / "cfg" / "spk" / "mic1");
  write_bytes((room / "env_meta.txt").string(), "$EnvDepth\t6\n$EnvWidth\t4\n$EnvHeight\t3\n");
  write_bytes((room / "cfg/spk/spk_meta.txt").string(), "$EnvSpk1Depth\t1\n$EnvSpk1Width\t1\n$EnvSpk1Height\t1.5\n");
  write_bytes((room / "cfg/spk/mic1/mic_meta.txt").string(),
              "$EnvMicID\t1\n$EnvMic1Depth\t3\n$EnvMic1Width\t2\n$EnvMic1Height\t1.2\n");
  auto r = robust::run_argv({prog, "--format=but", path("but"), path("rooms.txt")});
  expect_error(r, "mic1/mic_meta.txt", "Hotel Room");
  EXPECT_FALSE(fs::exists(path("rooms.txt")));
}

TEST_F(HostilePrograms, RirRoomListRejectsBadMetadataByFileAndLine) {
  const std::string prog = need("rir-room-list");
  if (prog.empty()) GTEST_SKIP() << "rir-room-list not built";
  struct Case {
    std::string what, format, text, where, message;
  };
  const std::string h = kTableHeader, ok = "ok 6 4 3 1 1 1.5 3 2.5 1.2 a\n";
  const std::string csv = "source_id,azimuth_deg,distance_m,x_m_approx,y_m_approx,source_type\n";
  const std::vector<Case> cases = {
      {"header without mz", "table", "rir-id Lx Ly Lz sx sy sz mx my\n", "in.txt:1", "mz"},
      {"non-numeric", "table", h + ok + "r 6 4 3 1 1 x1.5 3 2.5 1.2 a\n", "in.txt:3", "sz"},
      {"NaN", "table", h + ok + "r 6 4 3 1 1 nan 3 2.5 1.2 a\n", "in.txt:3", "nan"},
      {"infinity", "table", h + ok + "r inf 4 3 1 1 1 3 2.5 1.2 a\n", "in.txt:3", "inf"},
      {"overflow", "table", h + ok + "r 1e999 4 3 1 1 1 3 2.5 1.2 a\n", "in.txt:3", "1e999"},
      {"negative room size", "table", h + ok + "r 6 -4 3 1 1 1 3 2.5 1.2 a\n", "in.txt:3", "positive"},
      {"zero room size", "table", h + ok + "r 6 4 0 1 1 1 3 2.5 1.2 a\n", "in.txt:3", "positive"},
      {"source outside", "table", h + ok + "r 6 4 3 7 1 1 3 2.5 1.2 a\n", "in.txt:3", "source"},
      {"microphone outside", "table", h + ok + "r 6 4 3 1 1 1 3 2.5 -1.2 a\n", "in.txt:3", "microphone"},
      {"source on the microphone", "table", h + ok + "r 6 4 3 1 1 1 1 1 1 a\n", "in.txt:3", "same point"},
      // Strictly inside as given, on the wall as a room list writes it (9 significant digits).
      {"source a hair inside a wall", "table", h + ok + "r 6 4 3 5.9999999999 1 1 3 2.5 1.2 a\n", "in.txt:3", "inside"},
      {"missing field", "table", h + ok + "r 6 4 3 1 1 1 3 2.5 a\n", "in.txt:3", "fields"},
      {"duplicate id", "table", h + ok + ok, "in.txt:3", "duplicate"},
      {"empty table", "table", "", "in.txt", "no setups"},
      {"header only", "table", h, "in.txt", "no setups"},
      {"CSV without receiver", "r3vival", csv + "S1,0,1.5,4.7,2.75,g\n", "in.txt", "receiver"},
      {"CSV with two receivers", "r3vival", csv + "S1,0,1.5,4.7,2.75,g\nR,0,0,6,2,receiver\nR2,0,0,6,2,receiver\n",
       "in.txt:4", "second receiver"},
      {"CSV non-numeric x", "r3vival", csv + "S1,0,1.5,four,2.75,g\nR,0,0,6,2,receiver\n", "in.txt:2", "x_m_approx"},
      {"CSV short row", "r3vival", csv + "S1,0,1.5\nR,0,0,6,2,receiver\n", "in.txt:2", "fields"},
      {"CSV source outside the room", "r3vival", csv + "S1,0,1.5,40,2.75,g\nR,0,0,6,2,receiver\n", "in.txt:2", "source"},
      {"empty CSV", "r3vival", "", "in.txt", "receiver"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    write_bytes(path("in.txt"), c.text);
    auto r = robust::run_argv({prog, "--format=" + c.format, path("in.txt"), path("rooms.txt")});
    expect_error(r, c.where, c.message);
    EXPECT_FALSE(fs::exists(path("rooms.txt")));
  }
  // The input is a directory (a BUT root given with --format=table): named as such.
  auto r = robust::run_argv({prog, dir_.string(), path("rooms.txt")});
  expect_error(r, dir_.string(), "is a directory");
  // BUT ReverbDB metadata: missing and non-numeric keys name the file; set-ups outside their room
  // are skipped with a warning naming the file; none left is an error.
  const fs::path room = dir_ / "but" / "Room1";
  fs::create_directories(room / "cfg" / "spk" / "mic1");
  const std::string env = (room / "env_meta.txt").string(), spk = (room / "cfg/spk/spk_meta.txt").string(),
                    mic = (room / "cfg/spk/mic1/mic_meta.txt").string();
  const std::string good_env = "$EnvDepth\t6\n$EnvWidth\t4\n$EnvHeight\t3\n";
  const std::string good_spk = "$EnvSpk1Depth\t1\n$EnvSpk1Width\t1\n$EnvSpk1Height\t1.5\n";
  const std::string good_mic = "$EnvMicID\t1\n$EnvMic1Depth\t3\n$EnvMic1Width\t2\n$EnvMic1Height\t1.2\n";
  struct ButCase {
    std::string what, env, spk, mic, where, message;
  };
  const std::vector<ButCase> but_cases = {
      {"missing room height", "$EnvDepth\t6\n$EnvWidth\t4\n", good_spk, good_mic, "env_meta.txt", "EnvHeight"},
      {"non-numeric speaker depth", good_env, "$EnvSpk1Depth\tone\n$EnvSpk1Width\t1\n$EnvSpk1Height\t1.5\n", good_mic,
       "spk_meta.txt", "EnvSpk1Depth"},
      {"missing mic id", good_env, good_spk, "$EnvMic1Depth\t3\n", "mic_meta.txt", "EnvMicID"},
      {"only set-up outside its room", good_env, good_spk,
       "$EnvMicID\t1\n$EnvMic1Depth\t30\n$EnvMic1Width\t2\n$EnvMic1Height\t1.2\n", "mic_meta.txt", "outside"},
  };
  for (const ButCase& c : but_cases) {
    SCOPED_TRACE(c.what);
    write_bytes(env, c.env);
    write_bytes(spk, c.spk);
    write_bytes(mic, c.mic);
    r = robust::run_argv({prog, "--format=but", path("but"), path("rooms.txt")});
    expect_error(r, c.where, c.message);
    EXPECT_FALSE(fs::exists(path("rooms.txt")));
  }
}

// A newline in the input's file name or in an option would end the list's header comment early,
// leaving a line no reader accepts; it is written as '?'.
TEST_F(HostilePrograms, RirRoomListKeepsItsHeaderCommentOnOneLine) {
  const std::string prog = need("rir-room-list");
  if (prog.empty()) GTEST_SKIP() << "rir-room-list not built";
  const std::string in = path("set\nups.txt");
  write_bytes(in, std::string(kTableHeader) + "r1 6 4 3 1 1 1.5 3 2.5 1.2 a\n");
  auto r = robust::run_argv({prog, "--absorption-range=0.1,0.6\n", in, path("rooms.txt")});
  ASSERT_EQ(r.status, 0) << r.output;
  const auto lines = lines_of(read_bytes(path("rooms.txt")));
  ASSERT_EQ(lines.size(), 2u) << read_bytes(path("rooms.txt"));
  EXPECT_EQ(lines[0].rfind("# made by", 0), 0u);
  EXPECT_EQ(lines[1].rfind("r1 room=", 0), 0u);
}

// ---- validate-data-dir -----------------------------------------------------------------------

class ValidateDataDir : public HostilePrograms {
 protected:
  // A valid directory: 3 utterances of 2 speakers, text, utt2uniq; with segments, 2 recordings.
  void write_valid(const std::string& d, bool segments = false) const {
    fs::create_directories(d);
    if (segments) {
      write_bytes(d + "/wav.scp", "rec1 /a/rec1.wav\nrec2 cat /a/rec2.wav |\n");
      write_bytes(d + "/segments", "s1-u1 rec1 0 1.5\ns1-u2 rec1 1.5 3.25\ns2-u1 rec2 0 -1\n");
      write_bytes(d + "/reco2dur", "rec1 3.5\nrec2 10\n");
    } else {
      write_bytes(d + "/wav.scp", "s1-u1 /a/u1.wav\ns1-u2 /a/u2.wav\ns2-u1 /a/u3.wav\n");
    }
    write_bytes(d + "/utt2spk", "s1-u1 s1\ns1-u2 s1\ns2-u1 s2\n");
    write_bytes(d + "/spk2utt", "s1 s1-u1 s1-u2\ns2 s2-u1\n");
    write_bytes(d + "/text", "s1-u1 HELLO\ns1-u2 \xc3\xa9t\xc3\xa9 \xe4\xbd\xa0\xe5\xa5\xbd\ns2-u1 AGAIN\n");
    write_bytes(d + "/utt2uniq", "s1-u1 u1\ns1-u2 u2\ns2-u1 u3\n");
  }
};

TEST_F(ValidateDataDir, AcceptsValidDirsWhateverTheirNames) {
  const std::string prog = need("validate-data-dir");
  if (prog.empty()) GTEST_SKIP() << "validate-data-dir not built";
  write_valid(path("plain"));
  write_valid(path("segmented"), true);
  const std::string hostile = hostile_dir_ + "/data $(touch PWNED)";
  write_valid(hostile);
  // Paths with spaces, quotes and '$()' in wav.scp, and a pipe: values, never run.
  write_bytes(hostile + "/wav.scp", "s1-u1 " + hostile_dir_ + "/a b;$(touch PWNED).wav\ns1-u2 cat '" + hostile_dir_ +
                                        "/x`touch CANARY`.wav' |\ns2-u1 /a/\"q\".wav\n");
  for (const std::string& d : {path("plain"), path("segmented"), hostile}) {
    SCOPED_TRACE(d);
    auto r = robust::run_argv({prog, d});
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("valid"), std::string::npos) << r.output;
  }
  expect_no_canary();
}

// Each case breaks one thing in a valid directory: exit 1 and a message naming the file and,
// where the problem is on one line, the line.
TEST_F(ValidateDataDir, RejectsEachBrokenDirNamingFileAndLine) {
  const std::string prog = need("validate-data-dir");
  if (prog.empty()) GTEST_SKIP() << "validate-data-dir not built";
  struct Case {
    std::string what;
    bool segments;
    std::string file, content;  // content "" with remove: the file is deleted
    bool remove;
    std::string where, message;
    std::string file2 = "", content2 = "";  // a second edit, when one file alone cannot show it
  };
  const std::vector<Case> cases = {
      {"unsorted wav.scp", false, "wav.scp", "s1-u2 /a/u2.wav\ns1-u1 /a/u1.wav\ns2-u1 /a/u3.wav\n", false, "wav.scp:2",
       "not sorted"},
      {"duplicate key", false, "utt2spk", "s1-u1 s1\ns1-u1 s1\ns1-u2 s1\ns2-u1 s2\n", false, "utt2spk:2", "duplicate key"},
      {"missing wav.scp", false, "wav.scp", "", true, "wav.scp: missing", ""},
      {"missing utt2spk", false, "utt2spk", "", true, "utt2spk: missing", ""},
      {"missing spk2utt", false, "spk2utt", "", true, "spk2utt: missing", ""},
      {"missing text", false, "text", "", true, "text: missing", ""},
      {"empty utt2spk", false, "utt2spk", "", false, "utt2spk: empty", ""},
      {"utterance in no recording", false, "wav.scp", "s1-u1 /a/u1.wav\ns2-u1 /a/u3.wav\n", false, "utt2spk:2",
       "not in wav.scp"},
      {"recording without utt2spk", false, "wav.scp", "s1-u1 /a/u1.wav\ns1-u2 /a/u2.wav\ns1-u3 /a/x.wav\ns2-u1 /a/u3.wav\n",
       false, "wav.scp:3", "no utt2spk"},
      {"spk2utt disagreeing", false, "spk2utt", "s1 s1-u1\ns2 s2-u1\n", false, "spk2utt:1", "disagrees"},
      {"speaker missing from spk2utt", false, "spk2utt", "s1 s1-u1 s1-u2\n", false, "utt2spk:3", "s2"},
      {"utt2spk with three fields", false, "utt2spk", "s1-u1 s1\ns1-u2 s1 x\ns2-u1 s2\n", false, "utt2spk:2", ""},
      {"segment of an unknown recording", true, "segments", "s1-u1 rec1 0 1.5\ns1-u2 rec9 1.5 3\ns2-u1 rec2 0 -1\n",
       false, "segments:2", "rec9"},
      {"segment end before start", true, "segments", "s1-u1 rec1 0 1.5\ns1-u2 rec1 3 1.5\ns2-u1 rec2 0 -1\n", false,
       "segments:2", "after its start"},
      {"negative segment start", true, "segments", "s1-u1 rec1 0 1.5\ns1-u2 rec1 -1 3\ns2-u1 rec2 0 -1\n", false,
       "segments:2", "negative"},
      {"segment past the recording's end", true, "segments", "s1-u1 rec1 0 1.5\ns1-u2 rec1 1.5 30\ns2-u1 rec2 0 -1\n",
       false, "segments:2", "after the end of recording"},
      {"NaN segment time", true, "segments", "s1-u1 rec1 0 1.5\ns1-u2 rec1 nan 3\ns2-u1 rec2 0 -1\n", false,
       "segments:2", "nan"},
      {"segment with 3 fields", true, "segments", "s1-u1 rec1 0 1.5\ns1-u2 rec1 1.5\ns2-u1 rec2 0 -1\n", false,
       "segments:2", ""},
      {"CRLF line endings", false, "utt2spk", "s1-u1 s1\r\ns1-u2 s1\r\ns2-u1 s2\r\n", false, "utt2spk:1",
       "carriage return"},
      {"non-UTF-8 transcript", false, "text", "s1-u1 HELLO\ns1-u2 caf\xe9\ns2-u1 AGAIN\n", false, "text:2", "UTF-8"},
      {"truncated UTF-8 sequence", false, "text", "s1-u1 HELLO\ns1-u2 AGAIN\ns2-u1 \xe4\xbd\n", false, "text:3", "UTF-8"},
      {"control character in text", false, "text", "s1-u1 HELLO\ns1-u2 A\x01GAIN\ns2-u1 AGAIN\n", false, "text:2",
       "control character"},
      {"control character in wav.scp", false, "wav.scp", "s1-u1 /a/u1.wav\ns1-u2 /a/u\x1b[2.wav\ns2-u1 /a/u3.wav\n",
       false, "wav.scp:2", "control character"},
      {"'~' in wav.scp", false, "wav.scp", "s1-u1 /a/u1.wav~\ns1-u2 /a/u2.wav\ns2-u1 /a/u3.wav\n", false, "wav.scp:1",
       "'~'"},
      {"blank line", false, "utt2spk", "s1-u1 s1\n\ns1-u2 s1\ns2-u1 s2\n", false, "utt2spk:2", "empty key"},
      {"text missing an utterance", false, "text", "s1-u1 HELLO\ns2-u1 AGAIN\n", false, "text", "s1-u2"},
      {"utt2uniq missing an utterance", false, "utt2uniq", "s1-u1 u1\n", false, "utt2uniq", "s1-u2"},
      {"utt2spk not sorted by speaker", false, "utt2spk", "s1-u1 s2\ns1-u2 s1\ns2-u1 s1\n", false, "utt2spk",
       "sorted on speaker", "spk2utt", "s1 s1-u2 s2-u1\ns2 s1-u1\n"},
  };
  int n = 0;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const std::string d = path("case" + std::to_string(n++));
    write_valid(d, c.segments);
    if (c.remove) {
      fs::remove(d + "/" + c.file);
    } else {
      write_bytes(d + "/" + c.file, c.content);
    }
    if (!c.file2.empty()) write_bytes(d + "/" + c.file2, c.content2);
    auto r = robust::run_argv({prog, d});
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find(d + "/" + c.where), std::string::npos) << "expected " << c.where << " in:\n" << r.output;
    if (!c.message.empty()) {
      EXPECT_NE(r.output.find(c.message), std::string::npos) << r.output;
    }
  }
  auto r = robust::run_argv({prog, path("no such dir")});
  expect_error(r, path("no such dir"));
}

// ---- 10^5-line inputs whose one bad line is the last -------------------------------------------

TEST_F(HostilePrograms, HundredThousandLineMetadataFailsAtItsLastLine) {
  const int n = 100000;
  // rir-room-list: a table whose last row has a non-numeric field (line n + 2: header first).
  if (const std::string prog = need("rir-room-list"); !prog.empty()) {
    std::string table = kTableHeader;
    for (int i = 0; i < n; ++i) table += "r" + std::to_string(i) + " 6 4 3 1 1 1.5 3 2.5 1.2 a\n";
    write_bytes(path("setups.txt"), table + "bad 6 4 3 1 1 1.5 3 2.5 x1.2 a\n");
    auto r = robust::run_argv({prog, path("setups.txt"), path("rooms.txt")});
    expect_error(r, "setups.txt:100002", "x1.2");
    EXPECT_FALSE(fs::exists(path("rooms.txt")));
  }
  // rir-diagnose: 10^5 measured ids, all present in the room list except the last; every line
  // names one real 0.5 s WAV. The ids are checked before any RIR is read (was: every RIR loaded
  // first, 10^5 x 0.5 s of samples, ~3.2 GB, before the error).
  if (const std::string prog = need("rir-diagnose"); !prog.empty()) {
    write_plain_diagnose_set(1, dir_.string(), path("one_room.txt"), path("one.scp"));
    std::string rooms, scp;
    for (int i = 0; i < n; ++i) {
      rooms += robust::diagnose_room_line("m" + std::to_string(i), static_cast<size_t>(i)) + "\n";
      scp += "m" + std::to_string(i) + " " + path("m0.wav") + "\n";
    }
    write_bytes(path("big_rooms.txt"), rooms);
    write_bytes(path("big.scp"), scp + "ghost " + path("m0.wav") + "\n");
    auto r = robust::run_argv({prog, path("big_rooms.txt"), path("big.scp"), path("out")});
    expect_error(r, "big.scp:100001", "ghost");
    // The room list's own last line broken: named before anything is simulated.
    write_bytes(path("big_rooms.txt"), rooms + "bad room=6,4,3 src=1,1,1.5 mic=2,2.5,1.2 t60=nan\n");
    r = robust::run_argv({prog, path("big_rooms.txt"), path("big.scp"), path("out")});
    expect_error(r, "big_rooms.txt:100001", "nan");
    EXPECT_FALSE(fs::exists(path("out")));
  }
  // validate-data-dir: 10^5 utterances, the last line of utt2spk a duplicate; the last transcript
  // not UTF-8.
  if (const std::string prog = need("validate-data-dir"); !prog.empty()) {
    fs::create_directories(path("big"));
    std::string wav, u2s, s2u = "spk", text;
    for (int i = 0; i < n; ++i) {
      char id[32];
      std::snprintf(id, sizeof id, "spk-u%06d", i);
      wav += std::string(id) + " /a/" + id + ".wav\n";
      u2s += std::string(id) + " spk\n";
      s2u += std::string(" ") + id;
      text += std::string(id) + (i + 1 < n ? " WORDS\n" : " caf\xe9\n");
    }
    write_bytes(path("big/wav.scp"), wav);
    write_bytes(path("big/spk2utt"), s2u + "\n");
    write_bytes(path("big/text"), text);
    write_bytes(path("big/utt2spk"), u2s + "spk-u099999 spk\n");
    auto r = robust::run_argv({need("validate-data-dir"), path("big")});
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("big/utt2spk:100001: duplicate key"), std::string::npos) << r.output.substr(0, 2000);
    write_bytes(path("big/utt2spk"), u2s);
    r = robust::run_argv({need("validate-data-dir"), path("big")});
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("big/text:100000"), std::string::npos) << r.output.substr(0, 2000);
    EXPECT_NE(r.output.find("UTF-8"), std::string::npos) << r.output.substr(0, 2000);
  }
  EXPECT_LT(robust::children_peak_rss_mb(), 1024.0);
}

}  // namespace

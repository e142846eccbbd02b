// Hostile names and content at the foundation level (every program reads and writes through it):
// file names with spaces, quotes, ';', '$()' and newlines; WAV headers that lie; absurd sample
// rates and channel counts. Each gets a correct result or a clear Error naming the file, and no
// command the user did not write is ever run (a canary file would appear).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>

#include "io/atomic_output.h"
#include "io/audio_io.h"
#include "io/kaldi_lists.h"
#include "io/kaldi_table.h"
#include "io/owned_output.h"
#include "io/rir_set.h"
#include "io/rxfile.h"
#include "io/shell.h"
#include "robust_test_util.h"
#include "util/error.h"

using namespace tsrir;
namespace fs = std::filesystem;

namespace {

class HostileInput : public robust::ScratchDirTest {
 protected:
  std::string canary() const { return path("CANARY"); }
  // Names that break naive shell use. Each embeds a command that would create the canary.
  std::vector<std::string> hostile_names() const {
    const std::string c = canary();
    return {"with space.wav", "semi;touch " + c + ";.wav", "dollar$(touch " + c + ").wav",
            "back`touch " + c + "`tick.wav", "single'quote.wav", "double\"quote.wav",
            "amp&&touch " + c + ".wav", "pipe|touch " + c + ".wav", "-leading-dash.wav", "ünïcødé.wav"};
  }
  void expect_no_canary() const { EXPECT_FALSE(fs::exists(canary())) << "a command hidden in a name was run"; }
  std::string error_of(const std::function<void()>& fn) const {
    try {
      fn();
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(HostileInput, HostileFileNamesReadThroughEveryListForm) {
  const auto tone = robust::test_tone(800);
  for (const auto& name : hostile_names()) {
    // '/' cannot be in a file name: those names go into a sub-directory path instead.
    std::string leaf = name;
    std::replace(leaf.begin(), leaf.end(), '/', '_');
    const std::string p = path(leaf);
    write_bytes(p, robust::make_wav({}, tone));
    // scp form: the value is the rest of the line, spaces included.
    write_bytes(path("list.scp"), "r1 " + p + "\n");
    auto refs = read_rir_refs(path("list.scp"), nullptr);
    ASSERT_EQ(refs.size(), 1u) << name;
    EXPECT_EQ(refs[0].rxfilename, p);
    EXPECT_EQ(load_rir(refs[0]).size(), tone.size()) << name;
    // rir_list form as our writer formats it (shell-quoted), read back by the shlex reader.
    RirListEntry e;
    e.rir_id = "r1";
    e.room_id = "room one";
    e.rxfilename = p;
    write_bytes(path("rir_list"), format_rir_list_line(e) + "\n");
    refs = read_rir_refs(path("rir_list"), nullptr);
    ASSERT_EQ(refs.size(), 1u) << name;
    EXPECT_EQ(refs[0].rxfilename, p) << format_rir_list_line(e);
    EXPECT_EQ(refs[0].room_id, "room one");
    EXPECT_EQ(load_rir(refs[0]).size(), tone.size()) << name;
    // A pipe the user wrote, with the name quoted as Kaldi scripts do: runs cat only.
    Signal s = read_audio("cat " + shell_quote(p) + " |");
    EXPECT_EQ(s.size(), tone.size()) << name;
    expect_no_canary();
  }
}

TEST_F(HostileInput, CommandsHiddenInNonPipeNamesAreNeverRun) {
  const std::string c = canary();
  for (const std::string& rx : {"x.wav; touch " + c, "$(touch " + c + ")", "`touch " + c + "`", "x.wav && touch " + c,
                                "touch " + c + " #|x"}) {
    // Not ending in '|': a file name, so opening fails with the name in the message.
    std::string msg = error_of([&] { read_audio(rx, AudioReadOptions{0, 0.0, "wav.scp:3"}); });
    EXPECT_NE(msg.find("wav.scp:3"), std::string::npos) << rx << " -> " << msg;
    expect_no_canary();
  }
  // In a rir_list line, an unquoted $(...) is two words: an error, never a command.
  write_bytes(path("rir_list"), "--rir-id a --room-id b $(touch " + c + ") x.wav\n");
  std::string msg = error_of([&] { read_rir_list(path("rir_list")); });
  EXPECT_NE(msg.find("rir_list:1"), std::string::npos) << msg;
  expect_no_canary();
}

TEST_F(HostileInput, NewlinesInIdsAreRejectedBeforeAnythingIsWritten) {
  EXPECT_THROW(write_table(path("t.scp"), {{"a\nb", "x"}}), Error);
  EXPECT_THROW(write_table(path("t.scp"), {{"a", "x\ny"}}), Error);
  EXPECT_FALSE(fs::exists(path("t.scp")));
  RirSetWriter w(path("set"), SampleFormat::kFloat32);
  EXPECT_THROW(w.add(Signal{"a\nb", 16000, {1.0f}}), Error);
  EXPECT_THROW(w.add(Signal{"a b", 16000, {1.0f}}), Error);
  EXPECT_THROW(w.add(Signal{"..", 16000, {1.0f}}), Error);
  // A room id with a newline would split its rir_list line in two: the writer must refuse it
  // rather than commit a rir_list that no reader can parse.
  EXPECT_THROW(w.add(Signal{"ok", 16000, {1.0f}}, "room\none"), Error);
}

TEST_F(HostileInput, OutputSetInHostileDirectoryIsReadableAndQuoted) {
  const std::string out = path("out dir;$(touch " + canary() + ")'q'");
  {
    RirSetWriter w(out, SampleFormat::kInt16);
    w.add(Signal{"r1", 16000, {0.5f, 0.25f}}, "room 'A'");
    w.commit();
  }
  for (const char* table : {"rir.scp", "rir_list"}) {
    auto refs = read_rir_refs(out + "/" + table, nullptr);
    ASSERT_EQ(refs.size(), 1u) << table;
    EXPECT_EQ(load_rir(refs[0]).size(), 2u) << table;
  }
  // The rir_list line run through bash as Kaldi's scripts would (echo of the file name word):
  // prints the path, runs nothing.
  auto list = read_bytes(out + "/rir_list");
  auto words = shlex_split(list, "rir_list");
  std::string echoed;
  auto bytes = run_command_capture("printf '%s' " + shell_quote(words.back()));
  echoed.assign(bytes.begin(), bytes.end());
  EXPECT_EQ(echoed, words.back());
  expect_no_canary();
}

TEST_F(HostileInput, WavHeadersThatLie) {
  const auto tone = robust::test_tone(1600);
  struct Case {
    std::string name;
    robust::WavSpec spec;
    bool readable;            // else: an Error naming the file
    size_t frames;            // when readable
  };
  std::vector<Case> cases;
  robust::WavSpec s;
  s.data_size = 10 * 3200;  // claims ten times the data present
  cases.push_back({"data_too_long.wav", s, false, 0});
  s = {};
  s.data_size = 1600;       // claims half: the rest is trailing junk, read as the header says
  cases.push_back({"data_too_short.wav", s, true, 800});
  s = {};
  s.riff_size = 0xFFFFFFFF;  // streaming writers' placeholder RIFF size
  cases.push_back({"riff_ffff.wav", s, true, 1600});
  s = {};
  s.channels = 0;
  cases.push_back({"zero_channels.wav", s, false, 0});
  s = {};
  s.sample_rate = 0;
  cases.push_back({"zero_rate.wav", s, false, 0});
  s = {};
  s.data_size = 0xFFFFFFFF;  // the other placeholder of writers that cannot seek: read to the end
  cases.push_back({"data_ffff.wav", s, true, 1600});
  s = {};
  s.data_size = 0;  // Kaldi reads such a stream to its end; libsndfile sees no data: a clear error
  cases.push_back({"data_zero.wav", s, false, 0});
  s = {};
  s.format_tag = 0x55;  // MP3-in-WAV: unsupported
  cases.push_back({"mp3_tag.wav", s, false, 0});
  for (const auto& c : cases) {
    write_bytes(path(c.name), robust::make_wav(c.spec, tone));
    if (c.readable) {
      Signal sig = read_audio(path(c.name));
      EXPECT_EQ(sig.size(), c.frames) << c.name;
      EXPECT_NEAR(sig.samples[100], tone[100] / 32768.0, 1e-6) << c.name;
    } else {
      std::string msg = error_of([&] { read_audio(path(c.name)); });
      EXPECT_NE(msg.find(c.name), std::string::npos) << c.name << ": " << msg;
    }
  }
}

TEST_F(HostileInput, SoxPipeWavWithPlaceholderLengthIsRead) {
  // `sox ... -t wav - |` cannot seek back to fix its header, so it writes placeholder sizes
  // (0x7ffff024 / 0x7ffff000): every Kaldi wav.scp pipe looks like this. It must read in full.
  if (std::system("command -v sox >/dev/null 2>&1") != 0) GTEST_SKIP() << "sox not installed";
  Signal s = read_audio("sox -n -r 16000 -b 16 -t wav - synth 0.5 sine 440 2>/dev/null |");
  EXPECT_EQ(s.size(), 8000u);
  EXPECT_EQ(s.sample_rate_hz, 16000.0);
}

TEST_F(HostileInput, AbsurdSampleRateIsAnErrorNotAHugeAllocation) {
  // A header claiming 1 Hz, read at 16 kHz, would be resampled 16000-fold (a 1 s file -> 1 GB).
  robust::WavSpec s;
  s.sample_rate = 1;
  write_bytes(path("rate1.wav"), robust::make_wav(s, robust::test_tone(16000)));
  AudioReadOptions o;
  o.target_rate_hz = 16000;
  std::string msg = error_of([&] { read_audio(path("rate1.wav"), o); });
  EXPECT_NE(msg.find("rate1.wav"), std::string::npos) << msg;
  EXPECT_NE(msg.find("sample rate"), std::string::npos) << msg;
}

TEST_F(HostileInput, ResamplingFailureIsNeverSilentZeros) {
  // Whatever ratio libsox accepts must produce the signal, not a zero-padded placeholder.
  std::vector<float> x(16000);
  for (size_t i = 0; i < x.size(); ++i) x[i] = static_cast<float>(0.5 * std::sin(2 * M_PI * 100 * i / 16000.0));
  for (double to : {8000.0, 44100.0, 96000.0, 1000.0}) {
    std::vector<float> y;
    try {
      y = resample(x, 16000.0, to);
    } catch (const Error&) {
      continue;  // a refused ratio is fine: it is an error, not a wrong result
    }
    double energy = 0;
    for (size_t i = y.size() / 4; i < 3 * y.size() / 4; ++i) energy += y[i] * y[i];
    // A 100 Hz sine at amplitude 0.5 has mean power 0.125 at any rate above 200 Hz.
    EXPECT_NEAR(energy / (y.size() / 2), 0.125, 0.01) << "to " << to;
  }
}

TEST_F(HostileInput, FailedDirectoryReplacementKeepsThePreviousOutput) {
  const std::string out = path("set");
  {
    OwnedOutputDir first(out);
    write_bytes(first.path() + "/old.txt", "previous complete output");
    first.commit();
  }
  {
    OwnedOutputDir dir(out);
    write_bytes(dir.path() + "/new.txt", "new");
    fs::remove_all(dir.path());  // the new output vanishes (disk cleaner, full disk...): commit fails
    EXPECT_THROW(dir.commit(), Error);
  }
  EXPECT_EQ(read_bytes(out + "/old.txt"), "previous complete output");
  for (const auto& e : fs::recursive_directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
}

TEST_F(HostileInput, PipesKeepTheirQuotingThroughRirLists) {
  // A pipe whose command quotes a file name with a space, as Kaldi writes it in a rir_list.
  const std::string p = path("my rir.wav");
  write_bytes(p, robust::make_wav({}, robust::test_tone(500)));
  const std::string pipe = "cat " + shell_quote(p) + " |";
  write_bytes(path("in_list"), "--rir-id r1 --room-id a " + shell_quote(pipe) + "\n");
  RirListEntry e = read_rir_list(path("in_list")).at(0);
  ASSERT_EQ(e.rxfilename, pipe);
  // Written back by our formatter and read again: the same command, which still runs.
  write_bytes(path("out_list"), format_rir_list_line(e) + "\n");
  auto refs = read_rir_refs(path("out_list"), nullptr);
  ASSERT_EQ(refs.size(), 1u);
  EXPECT_EQ(refs[0].rxfilename, pipe) << format_rir_list_line(e);
  EXPECT_EQ(load_rir(refs[0]).size(), 500u);
}

}  // namespace

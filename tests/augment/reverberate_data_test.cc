// reverberate-data end to end: Kaldi data dirs in, validated data dirs out, pipes that
// regenerate exactly what --write-wavs materialises, and failures that leave nothing behind.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "io/audio_io.h"
#include "io/data_dir.h"
#include "io/kaldi_lists.h"
#include "io/rxfile.h"
#include "io/shell.h"
#include "reference_model.h"
#include "test_support.h"
#include "util/strings.h"

namespace fs = std::filesystem;

namespace {

const std::string kBin = std::string(TSRIR_BIN_DIR) + "/reverberate-data";

struct CliRun {
  int status;
  std::string log;
};

CliRun run_in(const std::string& dir, const std::string& args) {
  const std::string log = dir + "/last.log";
  const std::string cmd = "cd " + dir + " && " + kBin + " " + args + " > " + log + " 2>&1";
  int status = std::system(cmd.c_str());
  std::ifstream f(log);
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text};
}

void write_text(const std::string& path, const std::string& text) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path) << text;
}

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

// A small corpus: 2 speakers x 3 recordings (0.6-1.4 s), one under a hostile file name; RIRs in
// two rooms (16-bit, float, 48 kHz); an isotropic noise linked to room A, a point-source noise
// at 8 kHz, a short one (0.3 s, looped).
class ReverberateData : public ::testing::Test {
 protected:
  std::string dir;
  void SetUp() override {
    dir = tsrir_test::make_scratch_dir("rvbdata").string();
    for (const char* sub : {"/audio", "/rirs", "/noise", "/lists"}) fs::create_directories(dir + sub);
    std::string wav_scp, utt2spk, text;
    int k = 0;
    for (const std::string spk : {"spkA", "spkB"}) {
      for (int i = 0; i < 3; ++i, ++k) {
        const std::string utt = spk + "-u" + std::to_string(i);
        const std::string file = (k == 4) ? "audio/it's a;b $(touch PWNED).wav" : "audio/" + utt + ".wav";
        reftest::write_wav(dir + "/" + file, {reftest::quantise16(reftest::speech_like(9600 + 3200 * i, 16000, 100 + k))},
                           16000, 16);
        wav_scp += utt + " " + dir + "/" + file + "\n";
        utt2spk += utt + " " + spk + "\n";
        text += utt + " HELLO WORLD " + std::to_string(k) + "\n";
      }
    }
    write_text(dir + "/in/wav.scp", wav_scp);
    write_text(dir + "/in/utt2spk", utt2spk);
    write_text(dir + "/in/text", text);
    reftest::write_wav(dir + "/rirs/a1.wav", {reftest::quantise16(reftest::synthetic_rir(4000, 16000, 40, 0.3, 1))}, 16000, 16);
    reftest::write_wav(dir + "/rirs/a2 f;loat'.wav", {reftest::synthetic_rir(6000, 16000, 70, 0.5, 2)}, 16000, 32, true);
    reftest::write_wav(dir + "/rirs/b1_48k.wav", {reftest::synthetic_rir(12000, 48000, 100, 0.2, 3)}, 48000, 16);
    tsrir::RirListEntry a1, a2, b1;
    a1.rir_id = "a1"; a1.room_id = "roomA"; a1.rxfilename = "rirs/a1.wav";
    a2.rir_id = "a2"; a2.room_id = "roomA"; a2.rxfilename = "rirs/a2 f;loat'.wav";
    b1.rir_id = "b1"; b1.room_id = "roomB"; b1.rxfilename = "rirs/b1_48k.wav";
    write_text(dir + "/lists/rir_list_a", tsrir::format_rir_list_line(a1) + "\n" + tsrir::format_rir_list_line(a2) + "\n");
    write_text(dir + "/lists/rir_list_b", tsrir::format_rir_list_line(b1) + "\n");
    reftest::write_wav(dir + "/noise/iso_a.wav", {reftest::quantise16(reftest::noise_signal(48000, 4))}, 16000, 16);
    reftest::write_wav(dir + "/noise/ps_8k.wav", {reftest::quantise16(reftest::noise_signal(16000, 5))}, 8000, 16);
    reftest::write_wav(dir + "/noise/short.wav", {reftest::quantise16(reftest::noise_signal(4800, 6))}, 16000, 16);
    write_text(dir + "/lists/noise_list",
               "--noise-id iso_a --noise-type isotropic --room-linkage roomA noise/iso_a.wav\n"
               "--noise-id ps_8k --noise-type point-source --bg-fg-type background noise/ps_8k.wav\n"
               "--noise-id short --noise-type point-source noise/short.wav\n");
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir);
  }
  std::string lists() const {
    return "--rir-set-parameters '0.6, lists/rir_list_a' --rir-set-parameters 'lists/rir_list_b' "
           "--noise-set-parameters lists/noise_list ";
  }
};

// Kaldi's noise rules (isotropic noise of the room, point sources through an RIR of the same room,
// foreground ones at random times), then tsrir's looped noise from random offsets with an 8 kHz
// noise: each pipe must give the materialised wav exactly. (Nested point-source pipes resample
// after convolving, the materialised path before, so the Kaldi-mode run uses 16 kHz noises.)
TEST_F(ReverberateData, PipesRegenerateTheMaterialisedAudio) {
  write_text(dir + "/lists/noise_list_16k",
             "--noise-id iso_a --noise-type isotropic --room-linkage roomA noise/iso_a.wav\n"
             "--noise-id short --noise-type point-source --bg-fg-type foreground noise/short.wav\n"
             "--noise-id iso_a_ps --noise-type point-source noise/iso_a.wav\n");
  const std::string kaldi_mode = "--rir-set-parameters '0.6, lists/rir_list_a' --rir-set-parameters lists/rir_list_b "
                                 "--noise-set-parameters lists/noise_list_16k --max-noises-per-recording 3 "
                                 "--foreground-snrs 5:0 --background-snrs 20:10 --random-seed 5 ";
  const std::string looped = lists() + "--random-seed 5 --background-snrs 1..2 --noise-start random "
                                       "--max-noises-per-recording 2 --point-source-noise-rir none ";
  for (const std::string& mode : {kaldi_mode, looped}) {
  SCOPED_TRACE(mode);
  fs::remove_all(dir + "/out_pipe");
  fs::remove_all(dir + "/out_wav");
  CliRun piped = run_in(dir, mode + "in out_pipe");
  ASSERT_EQ(piped.status, 0) << piped.log;
  CliRun written = run_in(dir, mode + "--write-wavs out_wav/wavs --num-threads 2 in out_wav");
  ASSERT_EQ(written.status, 0) << written.log;
  for (const std::string out : {"out_pipe", "out_wav"}) {
    EXPECT_TRUE(tsrir::validate_data_dir(dir + "/" + out, true).empty()) << out;
    EXPECT_TRUE(fs::exists(dir + "/" + out + "/utt2uniq"));
  }
  tsrir::DataDir p = tsrir::read_data_dir(dir + "/out_pipe"), w = tsrir::read_data_dir(dir + "/out_wav");
  ASSERT_EQ(p.wav_scp.size(), 6u);
  EXPECT_EQ(p.utt2spk, w.utt2spk);
  EXPECT_EQ(p.text.at("spkA-u1"), "HELLO WORLD 1");
  int with_noise = 0;
  for (const auto& [id, pipe] : p.wav_scp) {
    ASSERT_TRUE(tsrir::ends_with(pipe, " - |")) << pipe;
    EXPECT_NE(pipe.find(std::string(TSRIR_BIN_DIR) + "/wav-reverberate"), std::string::npos);
    with_noise += pipe.find("--additive-signals=") != std::string::npos;
    // Pipes run from the directory the lists' relative paths refer to, as in Kaldi recipes.
    std::vector<char> bytes = tsrir::run_command_capture("cd " + dir + " && " + pipe.substr(0, pipe.size() - 1), id);
    tsrir::AudioInfo info;
    auto regenerated = tsrir::decode_audio_bytes(bytes, &info, id);
    auto materialised = tsrir::read_audio(w.wav_scp.at(id));
    EXPECT_EQ(regenerated.at(0), materialised.samples) << id;
    EXPECT_EQ(info.sample_rate_hz, 16000);
  }
  EXPECT_GT(with_noise, 0);
  EXPECT_FALSE(fs::exists(dir + "/PWNED"));
  }
}

TEST_F(ReverberateData, SameSeedSameOutputForAnyThreadCount) {
  ASSERT_EQ(run_in(dir, lists() + "--random-seed 9 --write-wavs w1 --num-threads 1 in o1").status, 0);
  ASSERT_EQ(run_in(dir, lists() + "--random-seed 9 --write-wavs w2 --num-threads 2 in o2").status, 0);
  for (const auto& entry : fs::directory_iterator(dir + "/w1")) {
    const std::string name = entry.path().filename();
    if (name == ".tsrir-owned") continue;  // the ownership marker (times, owner), not output
    EXPECT_EQ(read_text(entry.path()), read_text(dir + "/w2/" + name)) << name;
  }
  ASSERT_EQ(run_in(dir, lists() + "--random-seed 9 in p1").status, 0);
  ASSERT_EQ(run_in(dir, lists() + "--random-seed 9 in p2").status, 0);
  ASSERT_EQ(run_in(dir, lists() + "--random-seed 10 in p3").status, 0);
  EXPECT_EQ(read_text(dir + "/p1/wav.scp"), read_text(dir + "/p2/wav.scp"));
  EXPECT_NE(read_text(dir + "/p1/wav.scp"), read_text(dir + "/p3/wav.scp"));
}

TEST_F(ReverberateData, KaldiIdsCopiesAndTables) {
  CliRun r = run_in(dir, lists() + "--num-replications 2 --include-original-data true --noise-start zero in out");
  ASSERT_EQ(r.status, 0) << r.log;
  EXPECT_NE(r.log.find("rvb"), std::string::npos);  // the forced-prefix warning
  tsrir::DataDir d = tsrir::read_data_dir(dir + "/out");
  EXPECT_EQ(d.wav_scp.size(), 18u);
  EXPECT_EQ(d.utt2spk.at("rvb0-spkA-u0"), "rvb0-spkA");
  EXPECT_EQ(d.utt2spk.at("rvb2-spkB-u2"), "rvb2-spkB");
  EXPECT_EQ(d.utt2uniq.at("rvb1-spkB-u1"), "spkB-u1");
  EXPECT_EQ(d.text.at("rvb2-spkA-u0"), "HELLO WORLD 0");
  tsrir::DataDir in = tsrir::read_data_dir(dir + "/in");
  EXPECT_EQ(d.wav_scp.at("rvb0-spkA-u2"), in.wav_scp.at("spkA-u2"));  // copy 0 = the original
  EXPECT_EQ(d.spk2utt().at("rvb1-spkA").size(), 3u);
  EXPECT_NE(read_text(dir + "/out/spk2utt").find("rvb1-spkA rvb1-spkA-u0 rvb1-spkA-u1 rvb1-spkA-u2"), std::string::npos);
  for (const auto& [id, pipe] : d.wav_scp) {
    if (pipe.find("--additive-offsets=") != std::string::npos) {
      EXPECT_NE(pipe.find("--additive-offsets=0 "), std::string::npos) << pipe;
    }
  }
  EXPECT_TRUE(tsrir::validate_data_dir(dir + "/out", true).empty());
}

// --max-in-memory-duration 0 streams every recording (the path of those over 5 minutes): the
// wavs must be the in-memory ones byte for byte, for file and piped wav.scp entries, with RIRs and
// noises at other rates (resampled) and looped noise from random offsets.
TEST_F(ReverberateData, StreamedRecordingsGiveTheSameWavs) {
  std::string piped_scp;
  for (const auto& [id, rx] : tsrir::read_data_dir(dir + "/in").wav_scp)
    piped_scp += id + (id == "spkB-u1" ? " " + rx : " cat " + tsrir::shell_quote(rx) + " |") + "\n";
  write_text(dir + "/in_piped/wav.scp", piped_scp);
  fs::copy_file(dir + "/in/utt2spk", dir + "/in_piped/utt2spk");
  for (const std::string in : {"in", "in_piped"}) {
    SCOPED_TRACE(in);
    const std::string common = lists() + "--random-seed 3 --background-snrs 0..10 --foreground-snrs 0:10 "
                               "--max-noises-per-recording 2 --num-threads 2 " +
                               (in == "in" ? "" : "--noise-start random ");
    CliRun memory = run_in(dir, common + "--write-wavs w_mem_" + in + " " + in + " o_mem_" + in);
    ASSERT_EQ(memory.status, 0) << memory.log;
    CliRun streamed = run_in(dir, common + "--max-in-memory-duration 0 --write-wavs w_str_" + in + " " + in + " o_str_" + in);
    ASSERT_EQ(streamed.status, 0) << streamed.log;
    EXPECT_NE(streamed.log.find("passes over the file"), std::string::npos) << streamed.log;
    EXPECT_EQ(memory.log.find("passes over the file"), std::string::npos) << memory.log;
    size_t compared = 0;
    for (const auto& entry : fs::directory_iterator(dir + "/w_mem_" + in)) {
      const std::string name = entry.path().filename();
      if (name == ".tsrir-owned") continue;  // the ownership marker (times, owner), not output
      EXPECT_EQ(read_text(entry.path()), read_text(dir + "/w_str_" + in + "/" + name)) << name;
      ++compared;
    }
    EXPECT_EQ(compared, 6u);
  }
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find(".tmp."), std::string::npos) << entry.path();
}

TEST_F(ReverberateData, SegmentsAndOptionalTables) {
  // Two recordings split into segments; utt2uniq given.
  write_text(dir + "/seg/wav.scp", "recA " + dir + "/audio/spkA-u2.wav\nrecB " + dir + "/audio/spkA-u1.wav\n");
  write_text(dir + "/seg/segments", "s1-a recA 0.0 0.5\ns1-b recA 0.5 0.9\ns2-a recB 0.1 0.7\n");
  write_text(dir + "/seg/utt2spk", "s1-a s1\ns1-b s1\ns2-a s2\n");
  write_text(dir + "/seg/utt2uniq", "s1-a u1\ns1-b u2\ns2-a u3\n");
  write_text(dir + "/seg/reco2file_and_channel", "recA recA 1\nrecB recB 1\n");
  CliRun r = run_in(dir, lists() + "--prefix rev --write-wavs seg_wavs seg seg_out");
  ASSERT_EQ(r.status, 0) << r.log;
  tsrir::DataDir d = tsrir::read_data_dir(dir + "/seg_out");
  EXPECT_EQ(d.segments.at("rev1-s1-b").recording_id, "rev1-recA");
  EXPECT_DOUBLE_EQ(d.segments.at("rev1-s1-b").end_s, 0.9);
  EXPECT_EQ(d.utt2uniq.at("rev1-s2-a"), "u3");
  EXPECT_NE(read_text(dir + "/seg_out/reco2file_and_channel").find("rev1-recB rev1-recB 1"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir + "/seg_wavs/rev1-recA.wav"));
  EXPECT_TRUE(tsrir::validate_data_dir(dir + "/seg_out").empty());
}

TEST_F(ReverberateData, FailuresLeaveNothingHalfWritten) {
  // A previous good output must survive a failed run untouched.
  write_text(dir + "/out/marker", "previous run\n");
  write_text(dir + "/out/.tsrir-owned", "");  // a toolkit-owned dir holding a user's file
  write_text(dir + "/lists/empty_list", "");
  CliRun empty = run_in(dir, "--rir-set-parameters lists/empty_list in out");
  EXPECT_NE(empty.status, 0);
  EXPECT_NE(empty.log.find("empty"), std::string::npos) << empty.log;

  write_text(dir + "/lists/bad_noise", "--noise-id n --noise-type isotropic --room-linkage roomZ noise/short.wav\n");
  // Kaldi accepts a noise linked to a room no RIR list has (it is never used): a warning here.
  CliRun room = run_in(dir, "--rir-set-parameters lists/rir_list_a --noise-set-parameters lists/bad_noise in out_z");
  EXPECT_EQ(room.status, 0) << room.log;
  EXPECT_NE(room.log.find("lists/bad_noise:1"), std::string::npos) << room.log;
  EXPECT_NE(room.log.find("roomZ"), std::string::npos) << room.log;

  // A failing input pipe while materialising.
  fs::create_directories(dir + "/badin");
  write_text(dir + "/badin/wav.scp", "u1 " + dir + "/audio/spkA-u0.wav\nu2 false |\n");
  write_text(dir + "/badin/utt2spk", "u1 s\nu2 s\n");
  CliRun pipe = run_in(dir, "--rir-set-parameters lists/rir_list_a --write-wavs wavs_bad badin out");
  EXPECT_NE(pipe.status, 0);
  EXPECT_NE(pipe.log.find("u2"), std::string::npos) << pipe.log;
  EXPECT_FALSE(fs::exists(dir + "/wavs_bad"));

  CliRun missing_rir = run_in(dir, "--rir-set-parameters lists/rir_list_missing in out");
  EXPECT_NE(missing_rir.status, 0);
  write_text(dir + "/lists/rir_list_gone", "--rir-id g --room-id g rirs/not_there.wav\n");
  CliRun gone = run_in(dir, "--rir-set-parameters lists/rir_list_gone in out");
  EXPECT_NE(gone.status, 0);
  EXPECT_NE(gone.log.find("not_there"), std::string::npos) << gone.log;
  CliRun nothing = run_in(dir, "in out");
  EXPECT_NE(nothing.status, 0);

  EXPECT_EQ(read_text(dir + "/out/marker"), "previous run\n");
  EXPECT_FALSE(fs::exists(dir + "/out/wav.scp"));
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find(".tmp."), std::string::npos) << entry.path();
}

// --split-channels (the per-channel form of an array's far-field data): one entry per channel of a
// 3-channel RIR, ids <id>.CH<c>, one utterance per channel with the same speaker, Kaldi's
// reco2file_and_channel, a valid data dir; channel c's audio (pipe and --write-wavs alike) is the
// reference model's reverberation with the RIR's channel c, within 1 LSB of 16 bits.
TEST_F(ReverberateData, SplitChannelsGivesOneEntryPerArrayChannel) {
  std::vector<reftest::Vec> array;
  for (int c = 0; c < 3; ++c) array.push_back(reftest::synthetic_rir(3000, 16000, 40 + 9 * c, 0.3, 20 + c));
  reftest::write_wav(dir + "/rirs/array3.wav", array, 16000, 32, true);
  write_text(dir + "/lists/rir_list_array", "--rir-id arr --room-id roomC rirs/array3.wav\n");
  write_text(dir + "/seg/wav.scp", "recA " + dir + "/audio/spkA-u2.wav\n");
  write_text(dir + "/seg/segments", "s1-a recA 0.0 0.5\ns1-b recA 0.5 0.9\n");
  write_text(dir + "/seg/utt2spk", "s1-a s1\ns1-b s1\n");
  write_text(dir + "/seg/reco2file_and_channel", "recA recA A\n");
  const std::string common = "--rir-set-parameters lists/rir_list_array --split-channels true ";
  for (const std::string in : {"in", "seg"}) {
    SCOPED_TRACE(in);
    CliRun piped = run_in(dir, common + in + " " + in + "_pipe");
    ASSERT_EQ(piped.status, 0) << piped.log;
    CliRun written = run_in(dir, common + "--write-wavs " + in + "_wavs " + in + " " + in + "_wav");
    ASSERT_EQ(written.status, 0) << written.log;
    // Streamed in passes over the file: the same wavs.
    CliRun streamed = run_in(dir, common + "--max-in-memory-duration 0 --write-wavs " + in + "_swavs " + in + " " + in + "_s");
    ASSERT_EQ(streamed.status, 0) << streamed.log;
    EXPECT_TRUE(tsrir::validate_data_dir(dir + "/" + in + "_pipe").empty());
    EXPECT_TRUE(tsrir::validate_data_dir(dir + "/" + in + "_wav").empty());
    tsrir::DataDir p = tsrir::read_data_dir(dir + "/" + in + "_pipe"), w = tsrir::read_data_dir(dir + "/" + in + "_wav");
    const tsrir::DataDir input = tsrir::read_data_dir(dir + "/" + in);
    ASSERT_EQ(p.wav_scp.size(), 3 * input.wav_scp.size());
    ASSERT_EQ(p.utt2spk.size(), 3 * input.utt2spk.size());
    EXPECT_EQ(p.utt2spk, w.utt2spk);
    const std::string r2fc = read_text(dir + "/" + in + "_pipe/reco2file_and_channel");
    for (const auto& [reco, rx] : input.wav_scp) {
      const std::vector<float> samples = tsrir::read_audio(rx).samples;  // 16-bit values already
      const reftest::Vec speech(samples.begin(), samples.end());
      for (int c = 0; c < 3; ++c) {
        const std::string id = reco + ".CH" + std::to_string(c + 1);
        ASSERT_TRUE(p.wav_scp.count(id)) << id;
        EXPECT_NE(p.wav_scp.at(id).find("--rir-channel=" + std::to_string(c)), std::string::npos) << p.wav_scp.at(id);
        EXPECT_NE(r2fc.find(id + " " + id + " A\n"), std::string::npos) << r2fc;
        const std::string& pipe = p.wav_scp.at(id);
        tsrir::AudioInfo info;
        const auto regenerated = tsrir::decode_audio_bytes(
            tsrir::run_command_capture("cd " + dir + " && " + pipe.substr(0, pipe.size() - 1), id), &info, id);
        const std::vector<float> materialised = tsrir::read_audio(w.wav_scp.at(id)).samples;
        EXPECT_EQ(regenerated.at(0), materialised) << id;
        EXPECT_EQ(read_text(w.wav_scp.at(id)), read_text(dir + "/" + in + "_swavs/" + id + ".wav")) << id;
        const reftest::Vec want = reftest::wav_reverberate(speech, 16000, array[c], {}, {}).output;
        ASSERT_EQ(materialised.size(), want.size()) << id;
        double worst_lsb = 0;
        for (size_t i = 0; i < want.size(); ++i)
          worst_lsb = std::max(worst_lsb, std::abs(materialised[i] - std::clamp(want[i], -1.0, 32767.0 / 32768.0)) * 32768.0);
        EXPECT_LE(worst_lsb, 1.0) << id;
      }
    }
    if (in == "seg") {
      EXPECT_EQ(p.segments.at("s1-b.CH2").recording_id, "recA.CH2");
      EXPECT_EQ(p.utt2spk.at("s1-b.CH3"), "s1");
      EXPECT_EQ(p.utt2uniq.at("s1-a.CH1"), "s1-a");
    } else {
      EXPECT_EQ(p.text.at("spkB-u1.CH3"), "HELLO WORLD 4");
    }
  }
  EXPECT_NE(run_in(dir, common + "--multi-channel-output true in o").status, 0);
}

// The value of `--<name>=` in a wav.scp pipe (its shell-quoted word), split at commas.
std::vector<std::string> pipe_list(const std::string& pipe, const std::string& name) {
  const std::string key = "--" + name + "=";
  const size_t at = pipe.find(key);
  if (at == std::string::npos) return {};
  const size_t begin = at + key.size();
  const std::string value = pipe.substr(begin, pipe.find_first_of("' ", begin) - begin);
  std::vector<std::string> out;
  size_t start = 0;
  for (size_t comma; (comma = value.find(',', start)) != std::string::npos; start = comma + 1)
    out.push_back(value.substr(start, comma - start));
  out.push_back(value.substr(start));
  return out;
}

// Noises with a microphone array's RIRs (issue 33), both forms: a 3-channel isotropic noise of the
// room and a mono point-source noise through a 3-channel RIR of the same room. Channel c of the
// multichannel form (pipes = --write-wavs in memory = streamed) equals entry <id>.CH<c+1> of the
// split form, and both equal the test's own float64 computation: the speech through RIR channel
// c, the isotropic noise's channel c extended to the recording, the point source through channel c
// of its RIR (normalised, 16-bit, as Kaldi's nested step), each scaled to its SNR against channel
// c's early reverberant speech (Kaldi's rule), within 1 LSB. The pipes for Kaldi's program
// (--pipe-dialect kaldi: nested steps that keep the channels, SoX merging an isotropic noise's) give
// the same samples, run here by our wav-reverberate in Kaldi's syntax (tests/augment/
// kaldi_parity_test.sh runs them with Kaldi's binary). A mono isotropic noise for the array is
// refused (exit 1, nothing written).
TEST_F(ReverberateData, ArrayNoisesPerChannelInBothForms) {
  std::vector<reftest::Vec> array, source_array, iso;
  for (int c = 0; c < 3; ++c) {
    array.push_back(reftest::synthetic_rir(3000, 16000, 40 + 9 * c, 0.3, 20 + c));
    source_array.push_back(reftest::synthetic_rir(2000, 16000, 25 + 13 * c, 0.25, 30 + c));
    iso.push_back(reftest::quantise16(reftest::noise_signal(8000, 70 + c, 0.2)));
  }
  reftest::write_wav(dir + "/rirs/array3.wav", array, 16000, 32, true);
  reftest::write_wav(dir + "/rirs/source3.wav", source_array, 16000, 32, true);
  reftest::write_wav(dir + "/noise/iso3.wav", iso, 16000, 16);
  // Two RIRs of one room: the speech's and the point source's are drawn from both; the test reads
  // the draws (and SNRs, start times) from the pipes.
  write_text(dir + "/lists/rir_list_array", "--rir-id arr --room-id roomC rirs/array3.wav\n"
                                            "--rir-id src --room-id roomC rirs/source3.wav\n");
  write_text(dir + "/lists/noise_array", "--noise-id iso3 --noise-type isotropic --room-linkage roomC noise/iso3.wav\n"
                                         "--noise-id short --noise-type point-source --bg-fg-type foreground noise/short.wav\n");
  write_text(dir + "/arr_in/wav.scp", "u1 " + dir + "/audio/spkA-u1.wav\nu2 " + dir + "/audio/spkB-u2.wav\n");
  write_text(dir + "/arr_in/utt2spk", "u1 s1\nu2 s2\n");
  const std::string common = "--rir-set-parameters lists/rir_list_array --noise-set-parameters lists/noise_array "
                             "--max-noises-per-recording 1 --foreground-snrs 5 --background-snrs 10 --random-seed 5 ";
  for (const std::string form : {"--multi-channel-output true ", "--split-channels true "}) {
    ASSERT_EQ(run_in(dir, common + form + "arr_in arr_pipe" + form.substr(2, 5)).status, 0);
    ASSERT_EQ(run_in(dir, common + form + "--pipe-dialect kaldi arr_in arr_kaldi" + form.substr(2, 5)).status, 0);
    ASSERT_EQ(run_in(dir, common + form + "--write-wavs arr_w" + form.substr(2, 5) + " arr_in arr_wav" +
                              form.substr(2, 5)).status, 0);
    ASSERT_EQ(run_in(dir, common + form + "--max-in-memory-duration 0 --write-wavs arr_s" + form.substr(2, 5) +
                              " arr_in arr_stream" + form.substr(2, 5)).status, 0);
  }
  const tsrir::DataDir multi = tsrir::read_data_dir(dir + "/arr_pipemulti"), split = tsrir::read_data_dir(dir + "/arr_pipesplit");
  ASSERT_EQ(multi.wav_scp.size(), 2u);
  ASSERT_EQ(split.wav_scp.size(), 6u);
  auto run_pipe = [&](const std::string& pipe, const std::string& id) {
    tsrir::AudioInfo info;
    return tsrir::decode_audio_bytes(tsrir::run_command_capture("cd " + dir + " && " + pipe.substr(0, pipe.size() - 1), id),
                                     &info, id);
  };
  for (const std::string form : {"multi", "split"}) {
    const tsrir::DataDir ours = tsrir::read_data_dir(dir + "/arr_pipe" + form);
    const tsrir::DataDir kaldi = tsrir::read_data_dir(dir + "/arr_kaldi" + form);
    ASSERT_EQ(kaldi.wav_scp.size(), ours.wav_scp.size());
    bool merged = false;  // an isotropic noise's channels made one by one (multi) or chosen (split)
    for (const auto& [id, pipe] : kaldi.wav_scp) {
      SCOPED_TRACE(pipe);
      EXPECT_EQ(pipe.find("--additive-durations"), std::string::npos);  // Kaldi's syntax only
      merged |= pipe.find(form == "multi" ? "sox -D -M" : "--input-wave-channel=") != std::string::npos;
      EXPECT_EQ(run_pipe(pipe, id), run_pipe(ours.wav_scp.at(id), id)) << id;
    }
    EXPECT_TRUE(merged) << form;
  }
  // A 3-channel point source added as it is (--point-source-noise-rir none): Kaldi's program is
  // given channel c of it by SoX in the split form, the whole file in the multichannel form. And
  // speech left dry (--speech-rvb-probability 0) with noises: one channel, as ours makes it (Kaldi's
  // binary gives none with --multi-channel-output and no RIR).
  write_text(dir + "/lists/noise_as_is", "--noise-id p3 --noise-type point-source --bg-fg-type foreground noise/iso3.wav\n");
  const std::vector<std::pair<std::string, std::string>> as_is_forms = {
      {"multi", "--multi-channel-output true"}, {"split", "--split-channels true"},
      {"dry", "--multi-channel-output true --speech-rvb-probability 0"}};
  for (const auto& [name, form] : as_is_forms) {
    const std::string as_is = "--rir-set-parameters lists/rir_list_array --noise-set-parameters lists/noise_as_is "
                              "--point-source-noise-rir none --max-noises-per-recording 1 " + form + " ";
    ASSERT_EQ(run_in(dir, as_is + "arr_in asis_ours_" + name).status, 0);
    ASSERT_EQ(run_in(dir, as_is + "--pipe-dialect kaldi arr_in asis_kaldi_" + name).status, 0);
    const tsrir::DataDir ours = tsrir::read_data_dir(dir + "/asis_ours_" + name);
    const tsrir::DataDir kaldi = tsrir::read_data_dir(dir + "/asis_kaldi_" + name);
    ASSERT_EQ(kaldi.wav_scp.size(), ours.wav_scp.size());
    for (const auto& [id, pipe] : kaldi.wav_scp) {
      SCOPED_TRACE(pipe);
      EXPECT_EQ(pipe.find("remix") != std::string::npos, name == "split");
      const bool dry = name == "dry";
      EXPECT_EQ(pipe.find("--impulse-response") == std::string::npos, dry);
      if (dry) {
        EXPECT_EQ(pipe.find("--multi-channel-output"), std::string::npos);
      }
      EXPECT_EQ(run_pipe(pipe, id), run_pipe(ours.wav_scp.at(id), id)) << id;
    }
  }
  bool noise_rir_differs = false;  // the seed gives a point source elsewhere in the room
  for (const auto& [id, pipe] : multi.wav_scp) {
    SCOPED_TRACE(pipe);
    const auto piped = run_pipe(pipe, id);
    ASSERT_EQ(piped.size(), 3u);
    const std::string wav = dir + "/arr_wmulti/" + id + ".wav";
    tsrir::AudioInfo wav_info;
    EXPECT_EQ(piped, tsrir::read_audio_channels(wav, &wav_info, wav));
    EXPECT_EQ(read_text(wav), read_text(dir + "/arr_smulti/" + id + ".wav"));
    // The plan, as the pipe states it: noise order, SNRs, start times, each noise's RIR.
    const std::vector<std::string> signals = pipe_list(pipe, "additive-signals"), snrs = pipe_list(pipe, "snrs"),
                                   starts = pipe_list(pipe, "start-times"),
                                   rirs = pipe_list(pipe, "additive-impulse-responses"),
                                   durations = pipe_list(pipe, "additive-durations");
    ASSERT_EQ(signals.size(), 2u);
    ASSERT_NE(signals[0].find("iso3"), std::string::npos);
    ASSERT_NE(signals[1].find("short"), std::string::npos);
    const std::vector<reftest::Vec>& point_rir = rirs.at(1).find("source3") != std::string::npos ? source_array : array;
    noise_rir_differs |= rirs.at(1) != pipe_list(pipe, "impulse-response").at(0);
    const std::vector<reftest::Vec>& speech_rir =
        pipe_list(pipe, "impulse-response").at(0).find("source3") != std::string::npos ? source_array : array;
    const std::vector<float> samples =
        tsrir::read_audio(dir + "/audio/" + (id == "u1" ? "spkA-u1" : "spkB-u2") + ".wav").samples;
    const reftest::Vec speech(samples.begin(), samples.end());
    for (int c = 0; c < 3; ++c) {
      const std::string split_id = id + ".CH" + std::to_string(c + 1);
      ASSERT_TRUE(split.wav_scp.count(split_id));
      EXPECT_EQ(run_pipe(split.wav_scp.at(split_id), split_id).at(0), piped[c]) << split_id;
      EXPECT_EQ(tsrir::read_audio(dir + "/arr_wsplit/" + split_id + ".wav").samples, piped[c]) << split_id;
      // Kaldi's isotropic noise: channel c from its start, repeated to the recording's length.
      ASSERT_EQ(std::stod(durations.at(0)) * 16000, static_cast<double>(speech.size()));
      reftest::Vec iso_c(speech.size());
      for (size_t i = 0; i < iso_c.size(); ++i) iso_c[i] = iso[c][i % iso[c].size()];
      // The (foreground) point source: its normalised convolution with channel c of its RIR, to 16 bits.
      ASSERT_EQ(durations.at(1), "0");
      const std::vector<float> short_noise = tsrir::read_audio(dir + "/noise/short.wav").samples;
      const reftest::Vec point_c = reftest::quantise16(
          reftest::wav_reverberate(reftest::Vec(short_noise.begin(), short_noise.end()), 16000, point_rir[c], {}, {})
              .output);
      std::vector<reftest::Additive> additive(2);
      additive[0].samples = iso_c;
      additive[0].snr_db = std::stod(snrs.at(0));
      additive[1].samples = point_c;
      additive[1].snr_db = std::stod(snrs.at(1));
      additive[1].start_s = std::stod(starts.at(1));
      const reftest::Vec want = reftest::wav_reverberate(speech, 16000, speech_rir[c], additive, {}).output;
      ASSERT_EQ(piped[c].size(), want.size());
      double worst_lsb = 0;
      for (size_t i = 0; i < want.size(); ++i)
        worst_lsb = std::max(worst_lsb, std::abs(piped[c][i] - std::clamp(want[i], -1.0, 32767.0 / 32768.0)) * 32768.0);
      EXPECT_LE(worst_lsb, 1.0) << split_id;
    }
  }
  EXPECT_TRUE(noise_rir_differs);
  write_text(dir + "/lists/noise_mono", "--noise-id iso_a --noise-type isotropic --room-linkage roomC noise/iso_a.wav\n");
  for (const std::string form : {"--multi-channel-output true ", "--split-channels true "}) {
    CliRun mono = run_in(dir, "--rir-set-parameters lists/rir_list_array --noise-set-parameters lists/noise_mono " +
                                  form + "arr_in arr_bad");
    EXPECT_EQ(mono.status, 1) << mono.log;
    EXPECT_NE(mono.log.find("lists/noise_mono:1 (noise 'iso_a', added without an RIR): has 1 channel(s)"),
              std::string::npos) << mono.log;
  }
  EXPECT_FALSE(fs::exists(dir + "/arr_bad"));
}

TEST_F(ReverberateData, HelpAndBadOptions) {
  CliRun help = run_in(dir, "--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.log.find("e.g."), std::string::npos);
  EXPECT_NE(run_in(dir, lists() + "--snrs 20:10:0 in o").status, 0);
  EXPECT_NE(run_in(dir, lists() + "--foreground-snrs 20,10 in o").status, 0);
  EXPECT_NE(run_in(dir, lists() + "--max-noises-per-minute -1 in o").status, 0);
  EXPECT_NE(run_in(dir, lists() + "--pointsource-noise-addition-probability 2 in o").status, 0);
  EXPECT_NE(run_in(dir, lists() + "--noise-start middle in o").status, 0);
  EXPECT_NE(run_in(dir, lists() + "--no-such-option 1 in o").status, 0);
  EXPECT_NE(run_in(dir, lists() + "--speech-rvb-probability 1.5 in o").status, 0);
  EXPECT_EQ(run_in(dir, lists() + "--shift-output false --normalize-output=false in o").status, 0);
  EXPECT_NE(read_text(dir + "/o/wav.scp").find("--shift-output=false --normalize-output=false"), std::string::npos);
}

}  // namespace

namespace {

// wav-reverberate's --additive-impulse-responses / --additive-durations must give what Kaldi's
// nested `wav-reverberate --impulse-response=<r> --duration=<d> <noise> - |` signal gives, byte for
// byte, including an 8 kHz noise and a 48 kHz RIR (resampled as the nested program would).
TEST_F(ReverberateData, InProcessNestedNoiseEqualsTheNestedPipe) {
  const std::string wr = std::string(TSRIR_BIN_DIR) + "/wav-reverberate --print-args=false";
  const std::string nested = "cd " + dir + " && " + wr + " --impulse-response=rirs/a1.wav '--additive-signals=" + wr +
                             " --impulse-response=rirs/b1_48k.wav --duration=1.2 noise/ps_8k.wav - |,noise/short.wav' "
                             "--start-times=0,0.3 --snrs=5,10 audio/spkA-u0.wav - 2>/dev/null";
  const std::string in_process = "cd " + dir + " && " + wr +
                                 " --impulse-response=rirs/a1.wav --additive-signals=noise/ps_8k.wav,noise/short.wav "
                                 "--additive-impulse-responses=rirs/b1_48k.wav, --additive-durations=1.2,0 "
                                 "--start-times=0,0.3 --snrs=5,10 audio/spkA-u0.wav - 2>/dev/null";
  const std::vector<char> a = tsrir::run_command_capture(nested, "nested");
  const std::vector<char> b = tsrir::run_command_capture(in_process, "in process");
  ASSERT_GT(a.size(), 1000u);
  EXPECT_TRUE(a == b);
  EXPECT_NE(run_in(dir, "").status, 0);  // (fixture sanity: reverberate-data without arguments fails)
  const std::string bad = "cd " + dir + " && " + wr +
                          " --additive-signals=noise/short.wav --additive-durations=1,2 --start-times=0 --snrs=0 "
                          "audio/spkA-u0.wav /dev/null 2>/dev/null";
  EXPECT_NE(std::system(bad.c_str()), 0);  // field counts must match
}

}  // namespace

// rir-metrics as users run it: built program from TSRIR_BIN_DIR, exit codes, outputs, bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

#include "synthetic_rirs.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;

using ProgramRun = tsrir_test::CommandResult;
using tsrir_test::slurp;

class RirMetricsCli : public tsrir_test::TempDirTest {
 protected:
  ProgramRun run(const std::string& args) { return tsrir_test::run_command(tsrir_test::program_path("rir-metrics") + " " + args); }

  // Minimal IEEE-float WAV writer, independent of the toolkit's (it must be able to write NaN).
  std::string wav(const std::string& name, const std::vector<std::vector<float>>& channels, int rate = 16000) {
    const std::string path = (dir_ / name).string();
    std::ofstream f(path, std::ios::binary);
    const uint16_t nch = (uint16_t)channels.size();
    const uint32_t frames = (uint32_t)channels[0].size();
    const uint32_t data_bytes = frames * nch * 4;
    auto u32 = [&](uint32_t v) { f.write((const char*)&v, 4); };
    auto u16 = [&](uint16_t v) { f.write((const char*)&v, 2); };
    f.write("RIFF", 4);
    u32(36 + data_bytes);
    f.write("WAVEfmt ", 8);
    u32(16);
    u16(3);  // IEEE float
    u16(nch);
    u32((uint32_t)rate);
    u32((uint32_t)rate * nch * 4);
    u16((uint16_t)(nch * 4));
    u16(32);
    f.write("data", 4);
    u32(data_bytes);
    for (uint32_t i = 0; i < frames; ++i)
      for (uint16_t c = 0; c < nch; ++c) f.write((const char*)&channels[c][i], 4);
    return path;
  }

  std::string decay_wav(const std::string& name, double t60, uint64_t seed, double direct = 0.5) {
    tsrir_test::ExponentialRirSpec spec;
    spec.t60_s = t60;
    spec.seed = seed;
    spec.direct_amplitude = direct;
    spec.tail_start_sample = 200;
    return wav(name, {tsrir_test::exponential_rir(spec).samples});
  }

  std::string scp(const std::string& name, const std::vector<std::pair<std::string, std::string>>& rows) {
    const std::string path = (dir_ / name).string();
    std::ofstream f(path);
    for (const auto& r : rows) f << r.first << " " << r.second << "\n";
    return path;
  }

};

std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string l;
  while (std::getline(ss, l)) out.push_back(l);
  return out;
}

TEST_F(RirMetricsCli, HelpExitsZeroWithExample) {
  const ProgramRun r = run("--help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE((r.out + r.err).find("e.g."), std::string::npos);
  EXPECT_NE(run("--no-such-option x.scp").status, 0);
  EXPECT_NE(run("").status, 0);
  EXPECT_NE(run("--definition=sabine x.wav").status, 0);
}

TEST_F(RirMetricsCli, TableRowsInInputOrderIndependentOfThreads) {
  std::vector<std::pair<std::string, std::string>> rows;
  for (int i = 0; i < 12; ++i) {
    const std::string id = "rir" + std::to_string(11 - i);  // not sorted
    rows.push_back({id, decay_wav(id + ".wav", 0.3 + 0.05 * i, 100 + i)});
  }
  const std::string list = scp("rirs.scp", rows);
  const ProgramRun one = run("--bands --num-threads=1 " + list);
  ASSERT_EQ(one.status, 0) << one.err;
  const std::vector<std::string> l = lines(one.out);
  ASSERT_EQ(l.size(), 13u);
  EXPECT_EQ(l[0].rfind("# id T60 EDT DRR C50 D50 C80 T20_62.5 T30_62.5 EDT_62.5", 0), 0u) << l[0];
  for (int i = 0; i < 12; ++i) {
    std::stringstream ss(l[i + 1]);
    std::string id;
    double t60;
    ss >> id >> t60;
    EXPECT_EQ(id, rows[i].first);
    EXPECT_NEAR(t60, 0.3 + 0.05 * i, 0.05 * (0.3 + 0.05 * i)) << l[i + 1];
  }
  const ProgramRun two = run("--bands --num-threads 2 " + list);
  ASSERT_EQ(two.status, 0) << two.err;
  EXPECT_EQ(two.out, one.out);
}

TEST_F(RirMetricsCli, JsonAndSingleWavInputAndOutputFile) {
  const std::string w = decay_wav("lecture_room.wav", 0.5, 1);
  const std::string out = (dir_ / "m.json").string();
  const ProgramRun r = run("--format=json --output=" + out + " " + w);
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string j = slurp(out);
  EXPECT_NE(j.find("\"id\": \"lecture_room\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"summary\""), std::string::npos);
  EXPECT_NE(j.find("\"1000\""), std::string::npos);
  EXPECT_EQ(r.out, "");
  // A Kaldi rir_list works as well as an scp.
  const std::string list = (dir_ / "rir_list").string();
  std::ofstream(list) << "--rir-id hall-1 --room-id hall " << w << "\n";
  const ProgramRun l = run(list);
  ASSERT_EQ(l.status, 0) << l.err;
  EXPECT_EQ(lines(l.out).at(1).rfind("hall-1 ", 0), 0u) << l.out;
}

TEST_F(RirMetricsCli, ReferenceModePrintsTableOne) {
  const std::string real = scp("real.scp", {{"r1", decay_wav("r1.wav", 0.6, 1)}, {"r2", decay_wav("r2.wav", 0.6, 2)}});
  const std::string near = scp("near.scp", {{"n1", decay_wav("n1.wav", 0.62, 3)}});
  const std::string far = scp("far.scp", {{"f1", decay_wav("f1.wav", 0.3, 4)}});
  const ProgramRun r = run("--reference=" + real + " " + far + " " + near);
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<std::string> l = lines(r.out);
  ASSERT_EQ(l.size(), 5u) << r.out;
  EXPECT_NE(l[2].find("(reference)"), std::string::npos);
  EXPECT_EQ(l[3].rfind(far, 0), 0u);
  EXPECT_EQ(l[4].rfind(near, 0), 0u);
  // The set with the closer T60 carries the mark in the T60 column (first cell after n).
  std::stringstream ss(l[4]);
  std::string name, n, t60_mean, t60_diff;
  ss >> name >> n >> t60_mean >> t60_diff;
  EXPECT_EQ(t60_diff.back(), '*') << l[4];
  const ProgramRun j = run("--format=json --reference=" + real + " " + far + " " + near);
  ASSERT_EQ(j.status, 0);
  EXPECT_NE(j.out.find("\"sets\""), std::string::npos);
  EXPECT_NE(j.out.find("\"closest\": true"), std::string::npos) << j.out;
}

TEST_F(RirMetricsCli, BadInputStopsNamingTheIdOrSkips) {
  std::vector<float> silent(16000, 0.0f);
  std::vector<float> nan_rir(16000, 0.0f);
  nan_rir[100] = 1.0f;
  nan_rir[500] = NAN;
  std::vector<float> short_rir(400, 0.0f);
  short_rir[10] = 1.0f;
  const std::string list = scp("mixed.scp", {{"good1", decay_wav("g1.wav", 0.5, 1)},
                                             {"missing_rir", (dir_ / "nope.wav").string()},
                                             {"silent_rir", wav("s.wav", {silent})},
                                             {"nan_rir", wav("n.wav", {nan_rir})},
                                             {"short_rir", wav("short.wav", {short_rir})},
                                             {"good2", decay_wav("g2.wav", 0.5, 2)}});
  const ProgramRun stop = run(list);
  EXPECT_NE(stop.status, 0);
  EXPECT_NE(stop.err.find("missing_rir"), std::string::npos) << stop.err;
  // Each bad RIR alone: the message names it.
  for (const char* id : {"silent_rir", "nan_rir", "short_rir"}) {
    const std::string one = scp(std::string(id) + ".scp", {{id, (dir_ / (std::string(id) == "silent_rir" ? "s.wav" : std::string(id) == "nan_rir" ? "n.wav" : "short.wav")).string()}});
    const ProgramRun r = run(one);
    EXPECT_NE(r.status, 0) << id;
    EXPECT_NE(r.err.find(id), std::string::npos) << r.err;
  }
  const ProgramRun skip = run("--skip-errors " + list);
  EXPECT_EQ(skip.status, 0) << skip.err;
  const std::vector<std::string> l = lines(skip.out);
  ASSERT_EQ(l.size(), 3u) << skip.out;
  EXPECT_EQ(l[1].rfind("good1 ", 0), 0u);
  EXPECT_EQ(l[2].rfind("good2 ", 0), 0u);
  for (const char* id : {"missing_rir", "silent_rir", "nan_rir", "short_rir"}) {
    EXPECT_NE(skip.err.find(id), std::string::npos) << id << "\n" << skip.err;
  }
  const ProgramRun json = run("--skip-errors --format=json " + list);
  EXPECT_NE(json.out.find("\"errors\""), std::string::npos);
  EXPECT_NE(json.out.find("\"id\": \"silent_rir\""), std::string::npos) << json.out;
  // A missing list file is an error too.
  EXPECT_NE(run((dir_ / "absent.scp").string()).status, 0);
}

TEST_F(RirMetricsCli, ChannelSelection) {
  tsrir_test::ExponentialRirSpec a, b;
  a.t60_s = 0.3;
  b.t60_s = 0.9;
  b.seed = 9;
  const std::string w = wav("two.wav", {tsrir_test::exponential_rir(a).samples, tsrir_test::exponential_rir(b).samples});
  const ProgramRun c0 = run(w);
  const ProgramRun c1 = run("--channel=1 " + w);
  ASSERT_EQ(c0.status, 0) << c0.err;
  ASSERT_EQ(c1.status, 0) << c1.err;
  auto t60 = [](const std::string& out) {
    std::stringstream ss(lines(out).at(1));
    std::string id;
    double t;
    ss >> id >> t;
    return t;
  };
  EXPECT_NEAR(t60(c0.out), 0.3, 0.02);
  EXPECT_NEAR(t60(c1.out), 0.9, 0.05);
  EXPECT_NE(run("--channel=2 " + w).status, 0);
}

TEST_F(RirMetricsCli, AllChannelsGivesARowPerChannelAndTheArrayMean) {
  // Three channels of known T60 (0.3, 0.6, 0.9 s): rows <id>-ch0..2 equal to measuring each with
  // --channel=c, then <id>-mean, the mean of each column; the set statistics count the 3 channels.
  std::vector<std::vector<float>> channels;
  for (int c = 0; c < 3; ++c) {
    tsrir_test::ExponentialRirSpec spec;
    spec.t60_s = 0.3 * (c + 1);
    spec.seed = 11 + c;
    channels.push_back(tsrir_test::exponential_rir(spec).samples);
  }
  const std::string w = wav("arr.wav", channels);
  const ProgramRun all = run("--all-channels " + w);
  ASSERT_EQ(all.status, 0) << all.err;
  const std::vector<std::string> rows = lines(all.out);
  ASSERT_EQ(rows.size(), 5u) << all.out;
  std::vector<double> sum(6, 0.0);
  for (int c = 0; c < 3; ++c) {
    const ProgramRun one = run("--channel=" + std::to_string(c) + " " + w);
    ASSERT_EQ(one.status, 0) << one.err;
    const std::string values = lines(one.out).at(1).substr(lines(one.out).at(1).find(' '));
    EXPECT_EQ(rows[1 + c], "arr-ch" + std::to_string(c) + values);
    std::stringstream ss(values);
    for (double& s : sum) {
      double v;
      ss >> v;
      s += v / 3.0;
    }
  }
  std::stringstream mean(rows[4]);
  std::string id;
  mean >> id;
  EXPECT_EQ(id, "arr-mean");
  for (double s : sum) {
    double v;
    mean >> v;
    EXPECT_NEAR(v, s, 1e-5 * std::abs(s) + 1e-9);
  }
  EXPECT_NEAR(sum[0], 0.6, 0.04);  // T60
  const ProgramRun json = run("--all-channels --format=json " + w);
  ASSERT_EQ(json.status, 0) << json.err;
  EXPECT_NE(json.out.find("\"count\": 3"), std::string::npos) << json.out.substr(json.out.find("summary"));
  EXPECT_NE(run("--all-channels --channel=1 " + w).status, 0);
}

TEST_F(RirMetricsCli, IrstatsDefinitionRuns) {
  const std::string w = decay_wav("x.wav", 0.4, 1);
  const ProgramRun r = run("--definition=irstats --bands " + w);
  ASSERT_EQ(r.status, 0) << r.err;
  // irStats bands at 16 kHz: 125 .. 2000 Hz.
  EXPECT_EQ(lines(r.out)[0], "# id T60 EDT DRR C50 D50 C80 T20_125 T30_125 EDT_125 T20_250 T30_250 EDT_250 T20_500 T30_500 "
                             "EDT_500 T20_1000 T30_1000 EDT_1000 T20_2000 T30_2000 EDT_2000");
}

}  // namespace

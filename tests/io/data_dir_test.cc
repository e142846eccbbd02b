#include <gtest/gtest.h>

#include <filesystem>

#include "io/data_dir.h"
#include "test_support.h"
#include "util/error.h"

using tsrir_test::TempDirTest;

using namespace tsrir;

class DataDirs : public TempDirTest {};

TEST_F(DataDirs, WriteReadValidateRoundTrip) {
  DataDir d;
  d.wav_scp = {{"spk1-u1", "/a/u1.wav"}, {"spk1-u2", "cat /a/u2.wav |"}, {"spk2-u1", "/a/x.wav"}};
  d.utt2spk = {{"spk1-u1", "spk1"}, {"spk1-u2", "spk1"}, {"spk2-u1", "spk2"}};
  d.text = {{"spk1-u1", "HELLO"}, {"spk1-u2", "WORLD"}, {"spk2-u1", "AGAIN"}};
  d.utt2uniq = {{"spk1-u1", "u1"}, {"spk1-u2", "u2"}, {"spk2-u1", "u3"}};
  d.reco2dur = {{"spk1-u1", 1.5}, {"spk1-u2", 2.0}, {"spk2-u1", 3.25}};
  write_data_dir(dir_.string(), d);
  EXPECT_EQ(read_text("spk2utt"), "spk1 spk1-u1 spk1-u2\nspk2 spk2-u1\n");
  EXPECT_TRUE(validate_data_dir(dir_.string(), true).empty());
  DataDir r = read_data_dir(dir_.string());
  EXPECT_EQ(r.wav_scp, d.wav_scp);
  EXPECT_EQ(r.reco2dur.at("spk2-u1"), 3.25);
}

TEST_F(DataDirs, SegmentsReferToRecordings) {
  write_text("wav.scp", "rec1 /a.wav\n");
  write_text("segments", "s-1 rec1 0.0 1.5\ns-2 rec1 1.5 3\n");
  write_text("utt2spk", "s-1 s\ns-2 s\n");
  write_text("spk2utt", "s s-1 s-2\n");
  DataDir d = read_data_dir(dir_.string());
  EXPECT_EQ(d.segments.at("s-2").end_s, 3.0);
  EXPECT_EQ(d.utterances().size(), 2u);
  write_text("segments", "s-1 rec1 0.0 1.5\ns-2 rec9 1.5 3\n");
  try {
    read_data_dir(dir_.string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("segments:2"), std::string::npos) << e.what();
  }
  write_text("segments", "s-1 rec1 2.0 1.5\ns-2 rec1 1.5 3\n");
  EXPECT_THROW(read_data_dir(dir_.string()), Error);
}

TEST_F(DataDirs, ValidatorCatchesWhatKaldisValidatorCatches) {
  write_text("wav.scp", "b /b.wav\na /a.wav\n");
  write_text("utt2spk", "a s\nb s\n");
  write_text("spk2utt", "s a b\n");
  auto p = validate_data_dir(dir_.string());
  ASSERT_FALSE(p.empty());
  EXPECT_NE(p[0].find("not sorted"), std::string::npos);
  write_text("wav.scp", "a /a.wav\nb /b.wav\n");
  EXPECT_TRUE(validate_data_dir(dir_.string()).empty());
  write_text("spk2utt", "s a\n");
  EXPECT_FALSE(validate_data_dir(dir_.string()).empty());
  write_text("spk2utt", "s a b\n");
  write_text("utt2spk", "a s2\nb s1\n");  // sorted by utt but not by speaker
  write_text("spk2utt", "s1 b\ns2 a\n");
  EXPECT_FALSE(validate_data_dir(dir_.string()).empty());
  write_text("utt2spk", "a s\nb s\n");
  write_text("spk2utt", "s a b\n");
  write_text("text", "a HELLO\n");
  EXPECT_FALSE(validate_data_dir(dir_.string()).empty());  // text misses b
  write_text("text", "a HELLO\nb\n");
  EXPECT_TRUE(validate_data_dir(dir_.string()).empty());  // empty transcript is allowed
  write_text("wav.scp", "a /a.wav~\nb /b.wav\n");
  EXPECT_FALSE(validate_data_dir(dir_.string()).empty());
}

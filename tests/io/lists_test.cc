#include <gtest/gtest.h>

#include <utility>

#include "io/kaldi_lists.h"
#include "test_support.h"
#include "util/error.h"

using tsrir_test::TempDirTest;

using namespace tsrir;

class Lists : public TempDirTest {};

TEST_F(Lists, ShlexSplitLikePython) {
  EXPECT_EQ(shlex_split("a 'b c' \"d \\\" e\" f\\ g", "x"), (std::vector<std::string>{"a", "b c", "d \" e", "f g"}));
  EXPECT_THROW(shlex_split("a 'b", "x"), Error);
}

TEST_F(Lists, ParsesKaldiRirListLines) {
  auto e = parse_rir_list_line(
      "--rir-id small-1 --room-id room1 --receiver-position-id r1 --rt60 0.5 --probability 0.2 "
      "RIRS/small/Room001-00001.wav",
      "rir_list:1");
  EXPECT_EQ(e.rir_id, "small-1");
  EXPECT_EQ(e.room_id, "room1");
  EXPECT_EQ(e.receiver_position_id, "r1");
  EXPECT_DOUBLE_EQ(*e.rt60, 0.5);
  EXPECT_DOUBLE_EQ(*e.probability, 0.2);
  EXPECT_FALSE(e.drr.has_value());
  EXPECT_EQ(e.rxfilename, "RIRS/small/Room001-00001.wav");
  auto p = parse_rir_list_line("--rir-id=a --room-id=b sox x.wav -r 16000 -t wav - |", "l");
  EXPECT_EQ(p.rxfilename, "sox x.wav -r 16000 -t wav - |");
  // Round trip through the formatter, including a path with a space.
  RirListEntry q;
  q.rir_id = "r";
  q.room_id = "m";
  q.rt60 = 0.7;
  q.rxfilename = "/a b/c.wav";
  auto back = parse_rir_list_line(format_rir_list_line(q), "l");
  EXPECT_EQ(back.rxfilename, "/a b/c.wav");
  EXPECT_DOUBLE_EQ(*back.rt60, 0.7);
}

TEST_F(Lists, RirListErrorsNameFileAndLine) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"--room-id r x.wav", "missing --rir-id"},
      {"--rir-id a --room-id r", "no file name"},
      {"--rir-id a --room-id r --rt60 fast x.wav", "not a number"},
      {"--rir-id a --room-id r --colour red x.wav", "unknown option"},
      {"--rir-id a --room-id r --probability 2 x.wav", "probability"},
  };
  for (const auto& [line, why] : bad) {
    write_text("rir_list", "--rir-id ok --room-id r ok.wav\n" + line + "\n");
    try {
      read_rir_list(path("rir_list"));
      FAIL() << line;
    } catch (const Error& e) {
      std::string m = e.what();
      EXPECT_NE(m.find("rir_list:2"), std::string::npos) << m;
      EXPECT_NE(m.find(why), std::string::npos) << m;
    }
  }
  write_text("dups", "--rir-id a --room-id r x.wav\n--rir-id a --room-id r y.wav\n");
  EXPECT_THROW(read_rir_list(path("dups")), Error);
  write_text("empty", "\n\n");
  EXPECT_THROW(read_rir_list(path("empty")), Error);
}

TEST_F(Lists, NoiseListsAndScpFallback) {
  write_text("noise_list",
             "--noise-id n1 --noise-type isotropic --room-linkage room1 n1.wav\n"
             "--noise-id n2 --noise-type point-source --bg-fg-type foreground --probability 0.5 n2.wav\n");
  auto n = read_noise_list(path("noise_list"));
  ASSERT_EQ(n.size(), 2u);
  EXPECT_EQ(n[0].room_linkage, "room1");
  EXPECT_EQ(n[0].bg_fg_type, BgFgType::kBackground);
  EXPECT_EQ(n[1].bg_fg_type, BgFgType::kForeground);
  EXPECT_THROW(parse_noise_list_line("--noise-id a --noise-type isotropic a.wav", "l"), Error);
  EXPECT_THROW(parse_noise_list_line("--noise-id a --noise-type loud a.wav", "l"), Error);
  write_text("noise.scp", "n1 /x/n1.wav\nn2 cat n2.wav |\n");
  auto s = read_noise_list(path("noise.scp"));
  EXPECT_EQ(s[1].rxfilename, "cat n2.wav |");
  EXPECT_EQ(s[1].noise_type, "point-source");
  write_text("rir.scp", "r1 /x/r1.wav\n");
  auto r = read_rir_list(path("rir.scp"));
  EXPECT_EQ(r[0].room_id, "r1");
}

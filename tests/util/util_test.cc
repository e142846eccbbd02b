#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <set>
#include <sstream>
#include <vector>

#include "util/error.h"
#include "util/json.h"
#include "util/parallel.h"
#include "util/rng.h"
#include "util/strings.h"

using namespace tsrir;

TEST(Strings, SplitAndTrim) {
  EXPECT_EQ(trim("  a b \t\n"), "a b");
  EXPECT_EQ(split_whitespace(" a  b\tc "), (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(split("a,,b", ','), (std::vector<std::string>{"a", "", "b"}));
}

TEST(Strings, StrictNumbers) {
  EXPECT_DOUBLE_EQ(parse_double("1.5", "x"), 1.5);
  EXPECT_EQ(parse_int("-42", "x"), -42);
  EXPECT_THROW(parse_double("1.5abc", "rooms.txt:3: src"), Error);
  EXPECT_THROW(parse_double("", "x"), Error);
  EXPECT_THROW(parse_double("nan", "x"), Error);
  EXPECT_THROW(parse_int("3.2", "x"), Error);
  try {
    parse_double("abc", "rooms.txt:3: src");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("rooms.txt:3"), std::string::npos);
  }
  EXPECT_EQ(parse_double_list("1,2,3", ',', "x"), (std::vector<double>{1, 2, 3}));
  EXPECT_TRUE(parse_bool("TRUE", "x"));
  EXPECT_FALSE(parse_bool("false", "x"));
  EXPECT_THROW(parse_bool("maybe", "x"), Error);
}

TEST(Rng, DeterministicAndItemStreamsIndependentOfOrder) {
  Rng a(7), b(7);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.next_u64(), b.next_u64());
  Rng x1 = Rng::for_item(3, "utt1"), x2 = Rng::for_item(3, "utt2"), x1b = Rng::for_item(3, "utt1");
  double v1 = x1.uniform(), v2 = x2.uniform();
  EXPECT_EQ(v1, x1b.uniform());
  EXPECT_NE(v1, v2);
}

// fill_uniform is the loop of uniform(lo, hi) draws to the bit, and leaves the stream where that
// loop would (the diffuse tail's noise, and with it every simulated RIR, depends on both).
TEST(Rng, FillUniformIsTheLoopOfDraws) {
  Rng loop = Rng::for_item(5, "tail"), block = Rng::for_item(5, "tail");
  const double half_width = std::sqrt(3.0);
  std::vector<float> want(1001), got(1001);
  for (float& x : want) x = static_cast<float>(loop.uniform(-half_width, half_width));
  block.fill_uniform(-half_width, half_width, got.data(), got.size());
  for (size_t i = 0; i < want.size(); ++i) ASSERT_EQ(std::memcmp(&want[i], &got[i], sizeof(float)), 0) << i;
  EXPECT_EQ(loop.next_u64(), block.next_u64());
}

TEST(Rng, MomentsOfUniformAndNormal) {
  // 200k draws: standard error of the mean ~0.0007 (uniform) and ~0.0022 (normal); 5 sigma bounds.
  Rng r(1);
  const int n = 200000;
  double su = 0, sn = 0, sn2 = 0;
  for (int i = 0; i < n; ++i) {
    su += r.uniform();
    double z = r.normal();
    sn += z;
    sn2 += z * z;
  }
  EXPECT_NEAR(su / n, 0.5, 0.0035);
  EXPECT_NEAR(sn / n, 0.0, 0.011);
  EXPECT_NEAR(sn2 / n, 1.0, 0.016);
  std::set<uint64_t> seen;
  for (int i = 0; i < 1000; ++i) seen.insert(r.below(10));
  EXPECT_EQ(seen.size(), 10u);
}

TEST(Parallel, SameResultsForAnyThreadCountAndPropagatesErrors) {
  for (int threads : {1, 2, 4}) {
    std::vector<int> out(1000);
    parallel_for(out.size(), threads, [&](size_t i) { out[i] = static_cast<int>(i * i % 97); });
    for (size_t i = 0; i < out.size(); ++i) ASSERT_EQ(out[i], static_cast<int>(i * i % 97));
  }
  EXPECT_THROW(parallel_for(100, 2, [](size_t i) { if (i == 37) throw Error("boom"); }), Error);
}

TEST(Json, WritesValidNestedStructure) {
  std::ostringstream os;
  JsonWriter w(os, false);
  w.begin_object().field("id", std::string("a\"b")).field("x", 1.5).key("nan").value(std::nan(""));
  w.key("list").begin_array().value(1).value(true).end_array().end_object();
  EXPECT_EQ(os.str(), "{\"id\":\"a\\\"b\",\"x\":1.5,\"nan\":null,\"list\":[1,true]}");
}

// The resampler apart from audio I/O: no shared state between calls, so calls on several threads
// give exactly what the same calls give one at a time; bad ratios are errors.
#include "io/resampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <thread>

#include "util/error.h"
#include "util/rng.h"

using namespace tsrir;

namespace {

std::vector<float> noise(uint64_t seed, size_t n) {
  Rng rng(seed);
  std::vector<float> v(n);
  for (auto& x : v) x = static_cast<float>(0.3 * rng.normal());
  return v;
}

}  // namespace

TEST(Resampler, ConcurrentCallsEqualSerialCalls) {
  struct Job {
    std::vector<float> in;
    double from, to;
  };
  std::vector<Job> jobs;
  const double rates[][2] = {{48000, 16000}, {16000, 48000}, {44100, 16000}, {8000, 16000}, {22050, 16000}, {16000, 8000}};
  for (int i = 0; i < 12; ++i) jobs.push_back({noise(i + 1, 4000 + 977 * i), rates[i % 6][0], rates[i % 6][1]});
  std::vector<std::vector<float>> serial;
  for (const Job& j : jobs) serial.push_back(resample(j.in, j.from, j.to));
  std::vector<std::vector<float>> parallel(jobs.size());
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int rep = 0; rep < 3; ++rep)
        for (size_t i = t; i < jobs.size(); i += 4) parallel[i] = resample(jobs[i].in, jobs[i].from, jobs[i].to);
    });
  }
  for (auto& th : threads) th.join();
  for (size_t i = 0; i < jobs.size(); ++i) {
    EXPECT_EQ(parallel[i], serial[i]) << "job " << i;
    EXPECT_EQ(serial[i].size(), static_cast<size_t>(std::llround(jobs[i].in.size() * jobs[i].to / jobs[i].from)));
  }
}

// The first calls of a process, made at the same time: libsox sets up process-global state on
// first use of a conversion, and concurrent first calls corrupted the heap
// (reverberate-data --num-threads 2 resampling 48 kHz R3VIVAL RIRs aborted in malloc in 2 of 4
// runs). ConcurrentCallsEqualSerialCalls cannot see that: its serial pass warms the tables first.
// Each trial runs in a fresh process (threadsafe death-test style re-executes this test alone).
TEST(Resampler, ConcurrentFirstCallsOfAProcessEqualSerialCalls) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  auto trial = [] {
    const double rates[][2] = {{48000, 16000}, {44100, 16000}, {16000, 48000}, {48000, 8000},
                               {22050, 16000}, {96000, 16000}, {8000, 44100}, {32000, 16000}};
    constexpr int kJobs = 8;
    std::vector<std::vector<float>> in, parallel(kJobs);
    for (int i = 0; i < kJobs; ++i) in.push_back(noise(100 + i, 48001));
    std::vector<std::thread> threads;
    for (int i = 0; i < kJobs; ++i)
      threads.emplace_back([&, i] { parallel[i] = resample(in[i], rates[i][0], rates[i][1]); });
    for (auto& th : threads) th.join();
    for (int i = 0; i < kJobs; ++i)
      if (resample(in[i], rates[i][0], rates[i][1]) != parallel[i]) std::exit(10 + i);
    std::exit(0);
  };
  for (int t = 0; t < 8; ++t) EXPECT_EXIT(trial(), ::testing::ExitedWithCode(0), "") << "trial " << t;
}

TEST(Resampler, RejectsBadRatesAndKeepsEqualRates) {
  const std::vector<float> x = noise(7, 100);
  EXPECT_EQ(resample(x, 16000, 16000), x);
  EXPECT_THROW(resample(x, 0, 16000), Error);
  EXPECT_THROW(resample(x, 16000, -1), Error);
  EXPECT_THROW(resample(x, 1, 16000), Error);  // beyond kMaxResampleRatio
  const Signal s = resample(Signal{"s", 16000, x}, 8000);
  EXPECT_EQ(s.sample_rate_hz, 8000);
  EXPECT_EQ(s.size(), 50u);
}

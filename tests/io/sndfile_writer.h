// Test audio written with libsndfile directly (not the code under test), in the requested
// container/encoding: shared by the io tests.
#pragma once
#include <gtest/gtest.h>
#include <sndfile.h>

#include <string>
#include <vector>

// channels[c][n]; `format` = SF_FORMAT_<container> | SF_FORMAT_<encoding>.
inline void write_with_sndfile(const std::string& path, int format, int rate,
                               const std::vector<std::vector<float>>& ch) {
  SF_INFO info{};
  info.samplerate = rate;
  info.channels = static_cast<int>(ch.size());
  info.format = format;
  SNDFILE* f = sf_open(path.c_str(), SFM_WRITE, &info);
  ASSERT_NE(f, nullptr) << sf_strerror(nullptr);
  std::vector<float> inter(ch[0].size() * ch.size());
  for (size_t n = 0; n < ch[0].size(); ++n)
    for (size_t c = 0; c < ch.size(); ++c) inter[n * ch.size() + c] = ch[c][n];
  sf_writef_float(f, inter.data(), static_cast<sf_count_t>(ch[0].size()));
  sf_close(f);
}

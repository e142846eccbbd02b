// The one data type for an RIR or any mono audio signal; it travels through every stage.
#pragma once
#include <string>
#include <vector>

namespace tsrir {

struct Signal {
  std::string id;               // Kaldi key (utterance / RIR id); may be empty
  double sample_rate_hz = 0.0;
  std::vector<float> samples;   // float, full scale = 1.0 (int16 32767 -> ~1.0)

  size_t size() const { return samples.size(); }
  double duration_s() const { return sample_rate_hz > 0 ? samples.size() / sample_rate_hz : 0.0; }
};

}  // namespace tsrir

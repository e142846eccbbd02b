#include "asr/asr_data.h"

#include <cmath>
#include <filesystem>

#include "asr/asr_text.h"
#include "io/audio_io.h"
#include "io/data_dir.h"
#include "io/input_ledger.h"
#include "util/error.h"
#include "util/parallel.h"

namespace tsrir {

std::vector<AsrUtterance> load_asr_utterances(const std::string& dir, const LogMelOptions& options,
                                              bool require_text, int num_threads, InputLedger* inputs) {
  const DataDir data = read_data_dir(dir);
  const std::vector<std::string> ids = data.utterances();
  if (ids.empty()) throw Error(dir + ": the data dir has no utterances");
  if (require_text && data.text.empty()) throw Error(dir + "/text: missing (training needs transcripts)");
  // Inputs, so that no output of the program can be, contain or lie inside them (io/owned_output.h).
  if (inputs) {
    inputs->add(dir);
    for (const auto& [recording, rx] : data.wav_scp) inputs->add(rx);
  }
  std::vector<AsrUtterance> utts(ids.size());
  parallel_for(ids.size(), num_threads, [&](size_t i) {
    AsrUtterance& u = utts[i];
    u.id = ids[i];
    const auto uniq = data.utt2uniq.find(u.id);
    u.source = uniq != data.utt2uniq.end() ? uniq->second : u.id;
    if (!data.text.empty()) {
      auto it = data.text.find(u.id);
      if (it == data.text.end()) throw Error(dir + "/text: no transcript for utterance " + u.id);
      u.text = normalise_transcript(it->second);
    }
    AudioReadOptions read;
    read.channel = 0;
    read.target_rate_hz = options.sample_rate_hz;
    std::string recording = u.id;
    const Segment* segment = nullptr;
    if (data.has_segments()) {
      segment = &data.segments.at(u.id);
      recording = segment->recording_id;
    }
    read.context = dir + "/wav.scp: " + recording;
    Signal audio = read_audio(data.wav_scp.at(recording), read);
    if (segment) {
      const size_t begin = std::min(audio.samples.size(), size_t(std::lround(segment->start_s * options.sample_rate_hz)));
      const size_t end = std::min(audio.samples.size(), size_t(std::lround(segment->end_s * options.sample_rate_hz)));
      audio.samples = std::vector<float>(audio.samples.begin() + begin, audio.samples.begin() + end);
    }
    try {
      u.features = compute_log_mel(audio.samples, options);
    } catch (const Error& e) {
      throw Error(dir + ": utterance " + u.id + ": " + e.what());
    }
    normalise_mean_variance(&u.features);
  });
  return utts;
}

}  // namespace tsrir

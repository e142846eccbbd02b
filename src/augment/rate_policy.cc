#include "augment/rate_policy.h"

#include "augment/wav_duration.h"
#include "io/audio_io.h"
#include "io/resampler.h"
#include "io/rxfile.h"
#include "util/error.h"
#include "util/log.h"
#include "util/parallel.h"
#include "util/strings.h"

namespace tsrir {

DirSampleRate::DirSampleRate(double given_hz, const std::string& first_id, const std::string& first_rx,
                             const std::string& first_where)
    : rate_hz_(given_hz), given_(given_hz > 0), first_id_(first_id) {
  if (given_hz < 0) throw Error("--sample-rate must be > 0 Hz (or 0: the first recording's), got " + format_double(given_hz));
  if (!given_) rate_hz_ = rx_audio_header(first_rx, false, first_where).sample_rate_hz;
}

DirSampleRate::DirSampleRate(double rate_hz, bool given, std::string first_id)
    : rate_hz_(rate_hz), given_(given), first_id_(std::move(first_id)) {}

bool DirSampleRate::accepts(double recording_hz, const std::string& where) const {
  if (recording_hz == rate_hz_) return true;
  if (given_) return false;
  throw Error(where + ": recorded at " + format_double(recording_hz) + " Hz, but the data dir's rate is " +
              format_double(rate_hz_) + " Hz (its first recording, '" + first_id_ + "'): resample it, or give " +
              "--sample-rate=" + format_double(rate_hz_) + " to resample every recording to " +
              format_double(rate_hz_) + " Hz");
}

std::vector<float> DirSampleRate::speech_at_rate(std::vector<std::vector<float>>&& channels, double recording_hz,
                                                 const std::string& where) const {
  std::vector<float> x = first_channel_of(std::move(channels), where);
  if (accepts(recording_hz, where)) return x;
  return resample(x, recording_hz, rate_hz_);
}

size_t check_recording_rates(const std::map<std::string, std::string>& wav_scp, const DirSampleRate& rate,
                             bool pipes_resample, const std::string& in_dir, int num_threads) {
  std::vector<std::pair<std::string, std::string>> files;
  size_t pipes = 0;
  for (const auto& [id, rx] : wav_scp) {
    if (is_pipe_rxfilename(rx) || rx == "-") ++pipes;
    else files.emplace_back(id, rx);
  }
  std::vector<double> rates(files.size());
  parallel_for(files.size(), std::max(1, num_threads), [&](size_t i) {
    const std::string where = in_dir + "/wav.scp: recording '" + files[i].first + "'";
    try {
      rates[i] = probe_audio(files[i].second).sample_rate_hz;
    } catch (const Error& e) {
      throw Error(where + ": " + e.what());
    }
  });
  for (size_t i = 0; i < files.size(); ++i) {
    const std::string where = in_dir + "/wav.scp: recording '" + files[i].first + "'";
    if (!rate.accepts(rates[i], where) && !pipes_resample)
      throw Error(where + ": recorded at " + format_double(rates[i]) + " Hz, not the data dir's " +
                  format_double(rate.rate_hz()) + " Hz, and the pipe program (Kaldi's wav-reverberate) cannot " +
                  "resample it: use tsrir's wav-reverberate (--pipe-dialect=tsrir) or --write-wavs");
  }
  return pipes;
}

void warn_channel_used(int channels, int used, const std::string& where, const std::string& how_to_choose) {
  if (channels > 1)
    log_warning(where + ": " + std::to_string(channels) + " channels; using channel " + std::to_string(used) +
                (how_to_choose.empty() ? "" : " (" + how_to_choose + ")"));
}

std::vector<float> first_channel_of(std::vector<std::vector<float>>&& channels, const std::string& where) {
  if (channels.empty()) throw Error(where + ": no audio channels");
  warn_channel_used(static_cast<int>(channels.size()), 0, where, "");
  return std::move(channels[0]);
}

}  // namespace tsrir

// No silent rate or channel changes in reverberate-data and tsrir.Augmenter: the data dir's
// sampling rate, what happens to a recording at another rate, and the one-line warning when a
// multichannel input is reduced to one channel. Kept apart from reverberate_data.cc so that its
// call sites are one line each.
//
// The data dir's rate is --sample-rate (Kaldi's --source-sampling-rate) when given, else the rate
// of its first recording (wav.scp byte order). RIRs and noises are always resampled to it, as
// Kaldi's --source-sampling-rate does. A recording at another rate is resampled to it when the
// rate was given (the user asked for that rate), and refused with an error naming the recording,
// both rates and the option otherwise: a 48 kHz utterance is never written into a 16 kHz data dir.
#pragma once
#include <map>
#include <string>
#include <vector>

namespace tsrir {

class DirSampleRate {
 public:
  // `given_hz` > 0: --sample-rate. Else the rate of `first_rx` (a wav.scp entry) is probed (a
  // header read; a pipe is run once); `first_where` names it in errors.
  DirSampleRate(double given_hz, const std::string& first_id, const std::string& first_rx,
                const std::string& first_where);
  // The rate of an empty or already known data dir: `rate_hz` given (> 0) or not.
  DirSampleRate(double rate_hz, bool given, std::string first_id);

  double rate_hz() const { return rate_hz_; }
  bool given() const { return given_; }
  // Whether a recording read at `recording_hz` is used as it is (false: resample it to rate_hz()).
  // Throws Error naming `where` when it is at another rate and the rate was not given.
  bool accepts(double recording_hz, const std::string& where) const;
  // The recording's one channel at the data dir's rate: channel 0 (with the multichannel
  // warning), resampled when accepts() says so.
  std::vector<float> speech_at_rate(std::vector<std::vector<float>>&& channels, double recording_hz,
                                    const std::string& where) const;

 private:
  double rate_hz_ = 0;
  bool given_ = false;
  std::string first_id_;
};

// Pipe mode (wav.scp pipes that run later): every wav.scp entry that is a file has its header
// read now, so that a recording at another rate is refused here (rate not given) or known to be
// resampled by the pipe (`pipes_resample`: tsrir's wav-reverberate with --sample-rate); with
// Kaldi's binary as the pipe program nothing can resample, and a recording at another rate is an
// error. Pipe entries are not run (that would decode the corpus once more); their rate is
// checked where they are read. Returns how many entries were pipes.
size_t check_recording_rates(const std::map<std::string, std::string>& wav_scp, const DirSampleRate& rate,
                             bool pipes_resample, const std::string& in_dir, int num_threads);

// Channel 0 of an input read for a tool that has no channel choice, with a one-line warning naming
// the channel used and the input when there are several ("<where>: 2 channels; using channel 0").
std::vector<float> first_channel_of(std::vector<std::vector<float>>&& channels, const std::string& where);

// One warning line for a multichannel input whose channel `used` was not chosen by the user.
void warn_channel_used(int channels, int used, const std::string& where, const std::string& how_to_choose);

}  // namespace tsrir

// The body of the `wav-reverberate` program: Kaldi's per-utterance contract (options, rx/wx
// filenames, output rules) on top of reverberate_channel(), reading any format libsndfile reads
// (16/24/32-bit PCM, float; any sample rate) instead of Kaldi's 16-bit-only reader.
#pragma once
#include <string>
#include <vector>

#include "augment/reverberate.h"
#include "augment/speech_input.h"
#include "util/options.h"

namespace tsrir {

struct WavReverberateOptions {
  std::string impulse_response;     // rxfilename, "" = none
  std::string additive_signals;     // comma-separated rxfilenames
  std::string snrs;                 // comma-separated dB
  std::string start_times;          // comma-separated s
  std::string additive_offsets;     // extension: comma-separated s (default 0 each)
  std::string additive_loops;       // extension: comma-separated true/false per signal (default false)
  // Extensions replacing Kaldi's nested `wav-reverberate [--impulse-response=r] [--duration=d] n -`
  // additive signals by the same computation in this process (one process per noise less):
  std::string additive_impulse_responses;  // comma-separated rxfilenames, empty field = none
  std::string additive_durations;          // comma-separated s, 0 = as is
  // Kaldi's channel rules (featbin/wav-reverberate.cc): with multi_channel_output, output channel
  // c = the input through RIR channel c plus channel c of every additive signal (each must have as
  // many channels as the RIR: a mono noise is refused, as Kaldi's assertion refuses it), scaled to
  // its SNR against channel c's own early reverberant speech and normalised per channel; without
  // it, --rir-channel and --noise-channel pick one of each. A microphone array's noises therefore
  // take the same channel everywhere: the split form (--rir-channel=c --noise-channel=c) equals
  // channel c of the multichannel one. The nested-noise extensions keep an array's channels
  // (nested_additive_signal in wav_reverberate.cc).
  bool multi_channel_output = false;
  int input_wave_channel = 0;
  int rir_channel = 0;
  int noise_channel = 0;
  // Whether the user chose those channels (the program sets these from its command line): a
  // multichannel input whose channel was not chosen gets a one-line warning naming the one used.
  bool input_channel_given = true;
  bool rir_channel_given = true;
  bool noise_channel_given = true;
  // Extension: > 0, the output's rate in Hz; an input at another rate is resampled to it (RIRs and
  // additive signals are always brought to the output's rate). reverberate-data --sample-rate
  // writes it into its pipes.
  double sample_rate_hz = 0;
  ReverbOptions reverb;
  // Inputs longer than this (s) are reverberated in passes over the file, with memory bounded
  // independently of their length and the same output (reverberate_stream.h); 0 = every input.
  double max_in_memory_s = kDefaultMaxInMemoryDurationS;

  // Kaldi's names and meanings (its script writes them), then tsrir's extensions. Kaldi's
  // --volume and --duration go to reverb (ReverbOptions registers the options reverberate-data
  // shares: --shift-output, --normalize-output, --snr-reference).
  void Register(OptionsItf* opts);
};

// All channels of an rxfilename, resampled (libsox) to `sample_rate_hz` when their rate differs.
// Both output modes of reverberate-data load RIRs and noises through this, so they agree exactly.
std::vector<std::vector<float>> read_channels_at_rate(const std::string& rx, double sample_rate_hz,
                                                      const std::string& context);

// Splits Kaldi's comma lists (empty fields dropped, as SplitStringToVector(..., true) does).
std::vector<std::string> split_comma_list(const std::string& text);

// Reads `input_rx`, reverberates every output channel and writes `output_wx` ("-" = stdout,
// "| command" = a pipe, else a file written atomically) as 16-bit PCM. Errors name the offending
// option or file. Returns the number of clipped samples (also logged as a warning). An input
// longer than config.max_in_memory_s is streamed; its temporaries go next to a file output,
// else to $TMPDIR (default /tmp), and are removed on success, error and interruption.
long long run_wav_reverberate(const WavReverberateOptions& config, const std::string& input_rx,
                              const std::string& output_wx);

// The same, in memory: channels in, channels out (used by reverberate-data's materialised mode
// and by the tests). `rir_channels` may be empty (no RIR).
std::vector<std::vector<float>> wav_reverberate_channels(
    const std::vector<std::vector<float>>& input_channels, double sample_rate_hz,
    const std::vector<std::vector<float>>& rir_channels,
    const std::vector<std::vector<std::vector<float>>>& additive_channels,
    const std::vector<double>& snrs_db, const std::vector<double>& start_times_s,
    const std::vector<double>& offsets_s, const WavReverberateOptions& config);

}  // namespace tsrir

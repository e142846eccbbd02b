// reverberate-data: a far-field copy of a Kaldi data directory (Kaldi's
// steps/data/reverberate_data_dir.py semantics for ids and files; our per-utterance draws).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "augment/augment_plan.h"
#include "augment/reverberate.h"
#include "augment/speech_input.h"
#include "util/options.h"

namespace tsrir {

// --noise-start: zero (Kaldi: background noises extended from their start) or random (extension:
// from a random offset, looped over the whole recording).
enum class NoiseStart { kZero, kRandom };
const Choices<NoiseStart>& noise_start_choices();
// --point-source-noise-rir: same-room (Kaldi: point sources convolved with an RIR of the
// recording's room) or none (extension).
enum class PointSourceNoiseRir { kSameRoom, kNone };
const Choices<PointSourceNoiseRir>& point_source_noise_rir_choices();
// --pipe-dialect: may the pipes use tsrir's wav-reverberate options? auto (only when the pipe
// program is ours), tsrir, or kaldi.
enum class PipeDialect { kAuto, kTsrir, kKaldi };

struct ReverberateDataOptions {
  std::vector<std::string> rir_set_parameters;     // "[weight,] rir_list"
  std::vector<std::string> noise_set_parameters;   // "[weight,] noise_list"
  int num_replications = 1;
  std::string prefix;                              // forced to "rvb" for >1 copy or the original
  std::string foreground_snrs = "20:10:0";         // Kaldi's ':' list (cyclic) or lo..hi (SnrSpec)
  std::string background_snrs = "20:10:0";
  double speech_rvb_probability = 1.0;
  double isotropic_noise_addition_probability = 1.0;
  double pointsource_noise_addition_probability = 1.0;
  int max_noises_per_minute = 2;
  int max_noises_per_recording = 0;                // extension: > 0 replaces the per-minute cap
  NoiseStart noise_start = NoiseStart::kZero;
  PointSourceNoiseRir point_source_noise_rir = PointSourceNoiseRir::kSameRoom;
  PipeDialect pipe_dialect = PipeDialect::kAuto;
  // --shift-output, --normalize-output, --snr-reference: the per-recording output rules, as the
  // pipes' wav-reverberate (or --write-wavs) applies them.
  ReverbOptions reverb;
  // One output channel per channel of the recording's RIR (a microphone array's): one
  // multichannel recording per utterance, as wav-reverberate --multi-channel-output=true. Noises
  // follow its rules (wav_reverberate.h): a point-source noise through each channel of its RIR, an
  // isotropic noise channel by channel (it needs as many channels as the RIR), SNR per channel.
  bool multi_channel_output = false;
  // One recording per channel of the recording's RIR instead (the per-channel form, as CHiME-4's
  // 6-channel training data): ids with Kaldi/CHiME's ".CH<c>" suffix (c from 1), each entry's
  // pipe wav-reverberate --rir-channel=<c-1>, and a reco2file_and_channel "<id> <id> A" (Kaldi's
  // validate_data_dir.sh accepts only sides A and B). Noises as with multi_channel_output: entry
  // c equals channel c of that form (its pipe adds --noise-channel=<c-1>).
  bool split_channels = false;
  bool include_original_data = false;
  Seed random_seed = 0;
  double source_sampling_rate_hz = 0.0;            // --sample-rate: > 0 the data dir's rate (rate_policy.h)
  double rir_smoothing_weight = 0.3;
  double noise_smoothing_weight = 0.3;
  std::string write_wavs;                          // "" = pipes in wav.scp
  std::string pipe_program;                        // "" = wav-reverberate next to this program
  int num_threads = 1;
  // With write_wavs: recordings longer than this (s) are reverberated in passes over the file,
  // memory independent of their length, same wav (reverberate_stream.h); 0 = all of them.
  double max_in_memory_s = kDefaultMaxInMemoryDurationS;

  // reverberate-data's options: Kaldi's reverberate_data_dir.py names and meanings, then tsrir's
  // extensions (--random-seed also as --seed, the toolkit's name).
  void Register(OptionsItf* opts);
};

// How errors spell an option: as the program's command line ("--speech-rvb-probability") or as
// the Python Augmenter's keyword ("speech_rvb_probability").
enum class OptionSpelling { kCommandLine, kPython };
std::string spelled(const std::string& option, OptionSpelling spelling);

// What reverberate-data's options decide, checked: the RIRs and noises to draw from, the SNR lists,
// the planner's options (copies, ids, probabilities, noise rules, seed) and the per-recording
// output rules. The program and the Python Augmenter both make theirs with to_plan(), so an option
// means the same in both.
struct ReverberatePlan {
  AugmentSources sources;
  SnrSpec foreground_snrs, background_snrs;
  PlanOptions planning;
  ReverbOptions reverb;
  bool multi_channel_output = false;  // --multi-channel-output
  bool split_channels = false;        // --split-channels
  // --sample-rate: the data dir's rate when > 0, else (0) its first recording's; a recording at
  // another rate is resampled only when it was given (DirSampleRate, rate_policy.h).
  double sample_rate_hz = 0.0;
};
// Errors name the options as `spelling` writes them. Loads the RIR and noise lists (errors name
// their files and lines). With several copies and no --prefix, the prefix is Kaldi's "rvb".
ReverberatePlan to_plan(const ReverberateDataOptions& options, OptionSpelling spelling);

struct ReverberateDataSummary {
  size_t recordings = 0;     // output wav.scp entries
  size_t utterances = 0;     // output utt2spk entries
  size_t reverberated = 0;   // entries with an RIR
  size_t with_noise = 0;     // entries with noise
};

// Reads `in_dir` (its reco2dur when present, else the recordings' lengths), writes `out_dir` (and with write_wavs the wavs) atomically: on any error the
// previous contents stay and no partial directory appears. The result is checked with
// validate_data_dir() before it is committed.
ReverberateDataSummary reverberate_data_dir(const std::string& in_dir, const std::string& out_dir,
                                            const ReverberateDataOptions& options);

// Duration (s) of an audio rxfilename at its own rate, from a file's header (a pipe is decoded):
// what noise offsets are drawn against. Errors are prefixed by `where`.
double audio_duration_s(const std::string& rx, const std::string& where);

// Default pipe program: "wav-reverberate" in the directory of the running executable if it
// exists there (so pipes use our implementation even when Kaldi's is first on PATH), else the
// bare name, found through PATH when the pipe runs.
std::string default_pipe_program();

// Whether `program` (a path, or a name looked up in PATH) is the wav-reverberate that
// default_pipe_program() names, i.e. one that takes tsrir's extension options.
bool is_tsrir_pipe_program(const std::string& program);

}  // namespace tsrir

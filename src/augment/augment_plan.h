// What reverberate-data does to each recording of each copy, decided up front: the RIR and room
// from (seed, copy, recording id) alone, the noises by their noise types (noise_type.h), SNRs from
// Kaldi's cyclic lists walked in (copy, recording id) order. So the same seed gives the same
// directory for any thread count, and the pipe written into wav.scp regenerates exactly what
// --write-wavs materialises.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "augment/augment_sources.h"
#include "augment/noise_type.h"
#include "augment/reverberate.h"
#include "augment/sampling.h"

namespace tsrir {

struct PlanOptions {
  int num_replications = 1;
  bool include_original_data = false;
  std::string prefix;                     // "" = ids unchanged (single copy only)
  double speech_rvb_probability = 1.0;
  NoisePlanOptions noise;
  uint64_t random_seed = 0;
};

struct RecordingPlan {
  int copy = 0;                 // 0 = the original (only with include_original_data)
  std::string source_id;        // recording id in the input wav.scp
  std::string new_id;
  std::string source_rx;
  double duration_s = 0.0;      // of the input recording (reco2dur)
  std::string room;             // room of the RIR draw ("" = no RIRs)
  long rir = -1;                // index into AugmentSources::rirs, -1 = speech not reverberated
  // reverberate-data --split-channels: the channel of the RIR this entry uses (wav-reverberate
  // --rir-channel); -1 = the default (channel 0, with a warning for a multichannel RIR).
  int rir_channel = -1;
  std::vector<PlannedNoise> noises;
  bool modified() const { return rir >= 0 || !noises.empty(); }
};

// "<prefix><copy>-<id>" (Kaldi's reverberate_data_dir.py), or the id itself without a prefix.
std::string copy_id(const std::string& id, const std::string& prefix, int copy);

// One plan per (copy, recording), copies in order, recordings in wav.scp (byte) order. Per
// recording, from Rng::for_item(seed, "<copy>/<id>"): the RIR (hence the room) by probability,
// reverberate?, then each noise type's draws. The room is drawn even when the speech is not
// reverberated, and copy 0 (the original) takes its draws and SNRs too, as in Kaldi.
// `duration_s` must hold every recording.
std::vector<RecordingPlan> plan_recordings(const std::map<std::string, std::string>& wav_scp,
                                           const std::map<std::string, double>& duration_s,
                                           const AugmentSources& sources, const SnrSpec& foreground_snrs,
                                           const SnrSpec& background_snrs, const PlanOptions& options);

// Turns looped noises' offset fractions into seconds given each used noise's duration (noise index -> s).
void resolve_noise_offsets(const std::map<long, double>& noise_duration_s, std::vector<RecordingPlan>* plans);

// Rounds a value to the fixed decimals used in the pipe (so both output modes use equal values).
double pipe_rounded(double value);
std::string pipe_number(double value);

struct PipeOptions {
  std::string program = "wav-reverberate";
  ReverbOptions reverb;  // its --shift-output, --normalize-output and --snr-reference go into the pipe
  // false: the pipe program may be Kaldi's binary, so options only tsrir's wav-reverberate has
  // (--additive-offsets, --additive-loops, --snr-reference) are refused with an error.
  bool tsrir_extensions = true;
  bool multi_channel_output = false;  // --multi-channel-output=true (Kaldi's program has it too)
  // > 0 (tsrir's program only): --sample-rate=<Hz> in every pipe, the data dir's rate the speech is
  // resampled to (reverberate-data --sample-rate; rate_policy.h).
  double sample_rate_hz = 0;
  // Kaldi's program with --multi-channel-output: each noise's channel count (index into
  // AugmentSources::noises), for the noises whose nested step has no RIR (noise_signal_rx).
  std::map<long, int> noise_channels;
};

// The channels of a noise a pipe for Kaldi's program must keep (an array's far-field data, issue
// 33). Kaldi's nested `wav-reverberate` makes one channel unless told otherwise: --multi-channel-
// output=true keeps one per channel of its RIR, --rir-channel / --input-wave-channel choose one,
// and without an RIR nothing keeps several (--multi-channel-output then gives none), so those
// channels are made one by one and merged by SoX (`sox -M`, exact for 16-bit samples).
struct NoiseChannels {
  bool every = false;  // keep every channel (--multi-channel-output) ...
  int count = 0;       // ... of this many (needed when the nested step has no RIR)
  int channel = -1;    // >= 0: this channel alone (a --split-channels entry)
};

// The rxfilename of one planned noise's signal: the noise itself, or Kaldi's nested
// "<program> [--impulse-response=<rir>] [--duration=<s>] <noise> - |" ("<noise pipe> <program> ... - - |");
// with `channels` (an array, NoiseChannels) the form that keeps those channels.
std::string noise_signal_rx(const PlannedNoise& noise, const AugmentSources& sources, const std::string& program,
                            const NoiseChannels& channels = {});

// The wav.scp value for a plan: the original rxfilename if nothing is applied, else
// "[<source pipe> |] <program> --shift-output=... [--impulse-response=<rir>]
// [--additive-signals=<n1>,<n2> --start-times=<t1>,<t2> --snrs=<s1>,<s2>
// [--additive-offsets=... --additive-loops=...]] <source file or -> - |", every argument
// shell-quoted. A noise needing Kaldi's nested step (its own RIR, extension to the recording) is
// that nested command for Kaldi's program, and for ours (tsrir_extensions) the plain noise with
// --additive-impulse-responses / --additive-durations, the same computation in one process.
// Throws if a noise signal's rxfilename contains a comma (the list separator).
std::string format_pipe(const RecordingPlan& plan, const AugmentSources& sources, const PipeOptions& options);

}  // namespace tsrir

// What reverberate-data does to each recording of each copy, decided up front from
// (seed, copy, recording id) alone, so the same seed gives the same directory for any thread
// count and the pipe written into wav.scp regenerates exactly what --write-wavs materialises.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "augment/augment_sources.h"
#include "augment/reverberate.h"
#include "augment/sampling.h"

namespace tsrir {

struct PlanOptions {
  int num_replications = 1;
  bool include_original_data = false;
  std::string prefix;                     // "" = ids unchanged (single copy only)
  double speech_rvb_probability = 1.0;
  double noise_addition_probability = 1.0;
  bool random_noise_start = true;         // --noise-start=random|zero
  uint64_t random_seed = 0;
};

struct RecordingPlan {
  int copy = 0;                 // 0 = the original (only with include_original_data)
  std::string source_id;        // recording id in the input wav.scp
  std::string new_id;
  std::string source_rx;
  long rir = -1;                // index into AugmentSources::rirs, -1 = none
  long noise = -1;              // index into AugmentSources::noises, -1 = none
  double snr_db = 0.0;          // rounded to the digits written into the pipe
  double noise_offset_fraction = 0.0;  // in [0, 1) of the noise's duration
  double noise_offset_s = 0.0;  // set by resolve_noise_offsets(), rounded like snr_db
  bool modified() const { return rir >= 0 || noise >= 0; }
};

// "<prefix><copy>-<id>" (Kaldi's reverberate_data_dir.py), or the id itself without a prefix.
std::string copy_id(const std::string& id, const std::string& prefix, int copy);

// One plan per (copy, recording), copies in order, recordings in wav.scp (byte) order.
// Per recording, draws in a fixed order from Rng::for_item(seed, "<copy>/<id>"): reverberate?,
// RIR, add noise?, noise, noise offset, SNR.
std::vector<RecordingPlan> plan_recordings(const std::map<std::string, std::string>& wav_scp,
                                           const AugmentSources& sources, const SnrSpec& snrs,
                                           const PlanOptions& options);

// Turns offset fractions into seconds given each used noise's duration (noise index -> s).
void resolve_noise_offsets(const std::map<long, double>& noise_duration_s, std::vector<RecordingPlan>* plans);

// Rounds a value to the fixed decimals used in the pipe (so both output modes use equal values).
double pipe_rounded(double value);
std::string pipe_number(double value);

struct PipeOptions {
  std::string program = "wav-reverberate";
  bool shift_output = true;
  bool normalize_output = true;
  SnrReference snr_reference = SnrReference::kEarlyReverb;
};

// The wav.scp value for a plan: the original rxfilename if nothing is applied, else
// "[<source pipe> |] <program> --shift-output=... [--impulse-response=<rir>]
// [--additive-signals=<noise> --start-times=0 --snrs=<snr> --additive-offsets=<s>
// --loop-additive-signals=true] <source file or -> - |", every argument shell-quoted. Throws if a noise
// rxfilename contains a comma (wav-reverberate's list separator).
std::string format_pipe(const RecordingPlan& plan, const AugmentSources& sources, const PipeOptions& options);

}  // namespace tsrir

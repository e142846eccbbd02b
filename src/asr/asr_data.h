// Utterances of a Kaldi data dir as normalised feature matrices (and transcripts).
#pragma once
#include <string>
#include <vector>

#include "asr/asr_features.h"

namespace tsrir {

class InputLedger;

struct AsrUtterance {
  std::string id;
  std::string text;             // normalised (asr_text.h); empty when the dir has no text
  std::string source;           // the source utterance (utt2uniq; = id without one)
  FeatureMatrix features;       // log-mel, per-utterance mean/variance normalised
};

// Reads every utterance (wav.scp rxfilenames incl. pipes; segments cut from their recordings;
// audio resampled to options.sample_rate_hz, first channel), in utterance order, on up to
// num_threads threads. require_text: the dir must have a text entry for every utterance.
// Errors name the dir, file and utterance. The dir and every recording it reads are recorded in
// `inputs` (null: nowhere).
std::vector<AsrUtterance> load_asr_utterances(const std::string& data_dir, const LogMelOptions& options,
                                              bool require_text, int num_threads, InputLedger* inputs);

}  // namespace tsrir

// Which utterances each training step sees. Batches group utterances of similar length (sorted by
// frames, ties in utterance order) and are visited in a seeded random order per epoch.
// With copy sampling, the data dir's utt2uniq groups the reverberant copies of one source
// utterance (reverberate-data --num-replications K writes it, as Kaldi's reverberate_data_dir.py
// does): each epoch trains on ONE copy per source utterance, drawn from (seed, epoch, source), so
// K copies give K times the RIR and noise draws at the cost of one copy per epoch, and every
// training run (seed) sees its own draws. Torch-free.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "asr/asr_data.h"

namespace tsrir {

class EpochBatcher {
 public:
  // sample_copies: group utterances by AsrUtterance::source (else each utterance is its own group).
  EpochBatcher(const std::vector<AsrUtterance>& utts, int batch_size, std::uint64_t seed, bool sample_copies);

  size_t batches_per_epoch() const { return batches_per_epoch_; }
  size_t num_groups() const { return groups_.size(); }
  // The batches of epoch `epoch` (0-based) in the order they are trained; indices into utts.
  std::vector<std::vector<size_t>> epoch_batches(int epoch) const;

 private:
  std::vector<size_t> chosen_utterances(int epoch) const;

  const std::vector<AsrUtterance>& utts_;
  int batch_size_;
  std::uint64_t seed_;
  bool sample_copies_;
  std::vector<std::vector<size_t>> groups_;   // utterance indices per source, in utterance order
  size_t batches_per_epoch_ = 0;
};

}  // namespace tsrir

#include "asr/asr_batches.h"

#include <algorithm>
#include <map>

#include "util/rng.h"

namespace tsrir {
namespace {

// Indices grouped by length into batches (sorted by frames; ties keep the given order).
std::vector<std::vector<size_t>> length_batches(const std::vector<AsrUtterance>& utts, std::vector<size_t> order,
                                                int batch_size) {
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return utts[a].features.num_frames < utts[b].features.num_frames;
  });
  std::vector<std::vector<size_t>> batches;
  for (size_t i = 0; i < order.size(); i += size_t(batch_size)) {
    batches.emplace_back(order.begin() + i, order.begin() + std::min(order.size(), i + size_t(batch_size)));
  }
  return batches;
}

std::vector<size_t> shuffled_positions(std::uint64_t seed, int epoch, size_t n) {
  std::vector<size_t> p(n);
  for (size_t i = 0; i < n; ++i) p[i] = i;
  Rng rng = Rng::for_item(seed, "batches/epoch/" + std::to_string(epoch));
  for (size_t i = n; i > 1; --i) std::swap(p[i - 1], p[rng.below(i)]);
  return p;
}

}  // namespace

EpochBatcher::EpochBatcher(const std::vector<AsrUtterance>& utts, int batch_size, std::uint64_t seed,
                           bool sample_copies)
    : utts_(utts), batch_size_(batch_size), seed_(seed), sample_copies_(sample_copies) {
  std::map<std::string, size_t> group_of;
  for (size_t i = 0; i < utts.size(); ++i) {
    const std::string& key = sample_copies ? utts[i].source : utts[i].id;
    auto [it, added] = group_of.emplace(key, groups_.size());
    if (added) groups_.emplace_back();
    groups_[it->second].push_back(i);
  }
  batches_per_epoch_ = (groups_.size() + size_t(batch_size) - 1) / size_t(batch_size);
}

std::vector<size_t> EpochBatcher::chosen_utterances(int epoch) const {
  std::vector<size_t> chosen;
  chosen.reserve(groups_.size());
  for (const auto& members : groups_) {
    if (members.size() == 1) {
      chosen.push_back(members[0]);
      continue;
    }
    Rng rng = Rng::for_item(seed_, "copies/epoch/" + std::to_string(epoch) + "/" + utts_[members[0]].source);
    chosen.push_back(members[rng.below(members.size())]);
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

std::vector<std::vector<size_t>> EpochBatcher::epoch_batches(int epoch) const {
  // Without sampling the batches are the same every epoch (only their order changes).
  const std::vector<std::vector<size_t>> batches = length_batches(utts_, chosen_utterances(sample_copies_ ? epoch : 0), batch_size_);
  const std::vector<size_t> order = shuffled_positions(seed_, epoch, batches.size());
  std::vector<std::vector<size_t>> out;
  out.reserve(batches.size());
  for (size_t k : order) out.push_back(batches[k]);
  return out;
}

}  // namespace tsrir

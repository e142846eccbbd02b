#include "augment/stream_convolution.h"

#include <algorithm>
#include <utility>

#include "util/error.h"

namespace tsrir {

// Direct convolution (tiny filters, block_length() == 0) gives every output the same ordered
// sum whatever the chunking, so any block longer than the filter will do.
size_t engine_block_length(const Convolver& engine) {
  return engine.block_length() > 0 ? engine.block_length() : 4096;
}

StreamingConvolution::StreamingConvolution(const Convolver& engine, Emit emit, size_t chunk_samples)
    : engine_(engine), emit_(std::move(emit)), block_(engine_block_length(engine)) {
  // Two blocks at least: a first chunk of one block would take the engine's single-transform
  // shortcut, whose rounding differs from its overlap-save blocks.
  blocks_per_chunk_ = std::max<size_t>(2, (chunk_samples + block_ - 1) / block_);
}

void StreamingConvolution::convolve_and_emit(size_t chunk_start, size_t chunk_end, size_t keep_end) {
  const auto first = buffer_.begin() + static_cast<long>(chunk_start - buffer_start_);
  const std::vector<float> chunk(first, first + static_cast<long>(chunk_end - chunk_start));
  std::vector<float> y = engine_.convolve(chunk);  // y[j] is output chunk_start + j
  emit_(emitted_, y.data() + (emitted_ - chunk_start), keep_end - emitted_);
  emitted_ = keep_end;
}

void StreamingConvolution::push(const float* x, size_t count) {
  if (finished_) throw Error("StreamingConvolution: push after finish");
  buffer_.insert(buffer_.end(), x, x + count);
  const size_t chunk_outputs = blocks_per_chunk_ * block_;
  while (input_length() - emitted_ >= chunk_outputs) {
    // One block of history before the kept outputs (the first chunk needs none): it holds the
    // filter's memory and keeps the chunk on the engine's block grid.
    const size_t keep_end = emitted_ + chunk_outputs;
    convolve_and_emit(emitted_ >= block_ ? emitted_ - block_ : 0, keep_end, keep_end);
    // finish() may need two blocks of history; older input is dropped.
    const size_t keep_from = emitted_ >= 2 * block_ ? emitted_ - 2 * block_ : 0;
    if (keep_from > buffer_start_) {
      buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<long>(keep_from - buffer_start_));
      buffer_start_ = keep_from;
    }
  }
}

void StreamingConvolution::finish() {
  if (finished_) return;
  finished_ = true;
  const size_t n = input_length();
  if (n == 0) return;  // as Convolver::convolve: no output for no input
  const size_t total = n + engine_.filter_length() - 1;
  if (emitted_ >= total) return;
  size_t chunk_start = emitted_ >= block_ ? emitted_ - block_ : 0;
  // A last chunk of a single block would take the engine's single-transform shortcut: give it
  // a second block of history.
  if (chunk_start > 0 && n - chunk_start <= block_) chunk_start = emitted_ >= 2 * block_ ? emitted_ - 2 * block_ : 0;
  convolve_and_emit(chunk_start, n, total);
  buffer_.clear();
  buffer_.shrink_to_fit();
}

}  // namespace tsrir

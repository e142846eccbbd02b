// y = x ⊛ h for an x given piece by piece, through the one engine (dsp/convolve.h), with memory
// set by the chunk size instead of the signal's length.
//
// The engine is fed chunks of x whose first sample lies on one of its overlap-save block
// boundaries and that carry one block of history before the outputs kept. Each kept output then
// comes from the very same FFT segment as in Convolver::convolve(x) on the whole signal, so the
// result is equal to it bit for bit (tests/augment/stream_convolution_test.cc). Only the block
// length is needed from the engine (Convolver::block_length()).
#pragma once
#include <cstddef>
#include <functional>
#include <vector>

#include "dsp/convolve.h"

namespace tsrir {

// The chunk grid used for `engine`: its overlap-save block length (4096 for a direct-convolution
// engine, where any grid gives the same sums).
size_t engine_block_length(const Convolver& engine);

class StreamingConvolution {
 public:
  // Receives the outputs in order, in runs: emit(y + i, count) for y[first, first + count).
  // The run is scratch: the receiver may change it in place (e.g. add noise to it).
  using Emit = std::function<void(size_t first, float* y, size_t count)>;

  // `chunk_samples`: about how many outputs one engine call produces (at least two blocks).
  StreamingConvolution(const Convolver& engine, Emit emit, size_t chunk_samples = size_t{1} << 20);
  void push(const float* x, size_t count);
  // End of x: emits the remaining outputs, through index N + M - 2.
  void finish();
  size_t input_length() const { return buffer_start_ + buffer_.size(); }

 private:
  void convolve_and_emit(size_t chunk_start, size_t chunk_end, size_t keep_end);

  const Convolver& engine_;
  Emit emit_;
  size_t block_, blocks_per_chunk_;
  std::vector<float> buffer_;   // x[buffer_start_, buffer_start_ + buffer_.size())
  size_t buffer_start_ = 0;
  size_t emitted_ = 0;          // outputs emitted so far: a multiple of block_ until finish()
  bool finished_ = false;
};

}  // namespace tsrir

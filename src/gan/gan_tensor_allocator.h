// The CPU memory LibTorch's tensors live in. Torch-free header (programs and src/asr include it).
#pragma once

#include <cstddef>

namespace tsrir {

// Makes tensor memory cheap to get again, for every LibTorch program here (training, translation,
// the recogniser): glibc's heap keeps what is freed (no mmap), and LibTorch's CPU
// allocator is replaced, once per process, by one that backs each block of >= 1 MiB with
// transparent huge pages (madvise, 2 MiB aligned) and keeps freed blocks for reuse by the next
// request of the same rounded size. Why: a generator pass allocates and frees hundreds of MB of
// activations; mmap'd 4 KiB pages are faulted in again on every pass, and on virtual machines a
// page fault is expensive (bench/RESULTS.md: gas-to-real spent about a third of its time in the
// kernel on ~400,000 faults per 170 RIRs). Kept free blocks are capped at 1 GiB (kMaxKeptBytes);
// beyond that the longest-kept are unmapped. Numerics are unchanged: only where the bytes live.
void tune_memory_for_torch();

// Counters of the large-block path (for tests and benchmarks).
struct TensorAllocatorStats {
  size_t blocks_mapped = 0;    // fresh mmap calls
  size_t blocks_reused = 0;    // requests served from kept free blocks
  size_t bytes_kept_free = 0;  // now
};
TensorAllocatorStats tensor_allocator_stats();

// Unmaps every kept free block, e.g. after loading a checkpoint whose other networks and
// optimiser state (freed) will not be asked for again, so they do not stay in the peak RSS.
void drop_kept_tensor_memory();

}  // namespace tsrir

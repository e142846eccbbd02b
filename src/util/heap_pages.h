// Transparent huge pages for a short-lived process's heap. A process that starts, reads a few MB,
// computes for milliseconds and exits (wav-reverberate, once per utterance in Kaldi's pipes) pays a
// page fault per 4 KB page it touches, and on virtual machines a fault costs ~15 us (measured: 16 MB
// touched = 70 ms in 4 KB pages, 2.3 ms in 2 MB pages). Where the kernel offers THP on request
// (/sys/kernel/mm/transparent_hugepage/enabled = madvise or always), this makes the heap's first
// `reserve_bytes` huge-page backed; elsewhere it changes nothing but malloc's tuning.
#pragma once
#include <cstddef>

namespace tsrir {

// Call once, first thing in main(): afterwards blocks below 32 MB come from the heap (not from
// fresh mmaps that fault in again), freed memory is kept for reuse, and the heap grows in steps of
// `reserve_bytes`, the first of which is advised MADV_HUGEPAGE. Costs address space, not memory:
// only the pages touched are backed (in 2 MB units).
void use_huge_pages_for_heap(size_t reserve_bytes);

}  // namespace tsrir

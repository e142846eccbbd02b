#include "util/heap_pages.h"

#include <cstdint>
#include <cstdlib>

#if defined(__linux__) && defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace tsrir {

void use_huge_pages_for_heap(size_t reserve_bytes) {
#if defined(__linux__) && defined(__GLIBC__)
  constexpr uintptr_t kHugePage = 2u << 20;
  // glibc's largest mmap threshold on 64-bit; bigger blocks are still mmapped (and not advised).
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, static_cast<int>(2 * reserve_bytes));
  mallopt(M_TOP_PAD, static_cast<int>(reserve_bytes));
  // A block larger than the fresh heap's free top makes malloc extend the heap by it + the pad.
  // (volatile: a malloc whose block is never used may be optimised away with its free.)
  void* volatile grow = std::malloc(256u << 10);
  const uintptr_t top = reinterpret_cast<uintptr_t>(grow);
  const uintptr_t end = reinterpret_cast<uintptr_t>(sbrk(0));
  std::free(grow);
  // Huge pages fit only 2 MB-aligned stretches: advise those, and keep the heap below the first
  // boundary occupied (one block, never freed, never touched beyond its header) so that the
  // blocks allocated next start on it.
  const uintptr_t lo = (top + kHugePage - 1) & ~(kHugePage - 1);
  const uintptr_t hi = end & ~(kHugePage - 1);
  if (hi <= lo + kHugePage) return;
  // Best effort: without THP madvise fails or does nothing, and the heap keeps 4 KB pages.
  madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);
  const uintptr_t header = 2 * sizeof(size_t);  // glibc's chunk header
  if (lo - top > 2 * header) {
    void* volatile plug = std::malloc(lo - top - 2 * header);
    (void)plug;
  }
#else
  (void)reserve_bytes;
#endif
}

}  // namespace tsrir

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
  // A block larger than the heap's free top (mallinfo2's keepcost) makes malloc extend the heap by
  // it + the pad. (volatile: a malloc whose block is never used may be optimised away with its free.)
  const size_t kGrow = mallinfo2().keepcost + (256u << 10);
  void* volatile grow = std::malloc(kGrow);
  const uintptr_t top = reinterpret_cast<uintptr_t>(grow);
  const uintptr_t end = reinterpret_cast<uintptr_t>(sbrk(0));
  std::free(grow);
  // Huge pages fit only 2 MB-aligned stretches that nothing has touched yet: malloc wrote the
  // header of the free space after the block (at top + kGrow), so the first clean stretch starts
  // at the first boundary past it. Advise from there, and keep the heap below it occupied (one
  // block, never freed, never touched beyond its header) so that the blocks allocated next start
  // on it.
  const uintptr_t clean = (top + kGrow + 64 + kHugePage - 1) & ~(kHugePage - 1);
  const uintptr_t hi = end & ~(kHugePage - 1);
  if (hi <= clean + kHugePage) return;
  // Best effort: without THP madvise fails or does nothing, and the heap keeps 4 KB pages.
  madvise(reinterpret_cast<void*>(clean), hi - clean, MADV_HUGEPAGE);
  // glibc: a block of n bytes occupies n + sizeof(size_t) rounded up to 16, from 16 bytes before
  // the pointer returned; this one ends where the next block's header puts its data at `clean`.
  void* volatile plug = std::malloc(clean - top - sizeof(size_t));
  (void)plug;
#else
  (void)reserve_bytes;
#endif
}

}  // namespace tsrir

// use_huge_pages_for_heap: the blocks allocated after it lie in a heap stretch advised for huge
// pages (VmFlags "hg" in /proc/self/smaps), starting on a 2 MB boundary, so a fresh multi-MB buffer
// is huge-page backed wherever the kernel offers THP. Its own test binary: it retunes malloc.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "util/heap_pages.h"

namespace {

// The VmFlags line of the mapping that holds `address`, "" when none is found.
std::string vm_flags_of(const void* address) {
  const auto a = reinterpret_cast<uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    unsigned long lo = 0, hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-' && line.find(' ') > line.find('-')) {
      inside = a >= lo && a < hi;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return "";
}

TEST(HeapPages, LaterBlocksLieInAnAdvisedStretch) {
  std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string mode;
  std::getline(thp, mode);
  if (mode.find("[never]") != std::string::npos || mode.empty()) GTEST_SKIP() << "no transparent huge pages here";
  tsrir::use_huge_pages_for_heap(64u << 20);
  std::vector<float> buffer(1u << 20, 1.0f);  // 4 MB, from the heap (below malloc's mmap threshold)
  const std::string flags = vm_flags_of(buffer.data() + buffer.size() / 2);
  ASSERT_FALSE(flags.empty());
  EXPECT_NE(flags.find(" hg"), std::string::npos) << flags;
}

}  // namespace

#include "gan/gan_tensor_allocator.h"

#include <malloc.h>
#include <sys/mman.h>

#include <c10/core/CPUAllocator.h>

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <list>
#include <mutex>
#include <new>
#include <unordered_map>
#include <utility>

#include "gan/torch_compat.h"

namespace tsrir {
namespace {

constexpr size_t kLargeBytes = size_t(1) << 20;      // smaller blocks: LibTorch's own allocator
constexpr size_t kHugePageBytes = size_t(2) << 20;   // x86-64 transparent huge page
constexpr size_t kMaxKeptBytes = size_t(1) << 30;    // free blocks kept for reuse, at most

size_t round_up(size_t n, size_t to) { return (n + to - 1) / to * to; }

// Large blocks (sizes rounded up to 2 MiB multiples): live ones (pointer -> size) and free ones
// kept for reuse, oldest first. Reuse needs the same rounded size, which the repeated passes of
// training and translation ask for. Never destroyed: tensors freed during static destruction
// still find it.
class BlockPool {
 public:
  void* acquire(size_t size) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      // The most recently freed block of this size (kept blocks are few: a linear scan).
      for (auto it = kept_.rbegin(); it != kept_.rend(); ++it) {
        if (it->first != size) continue;
        void* p = it->second;
        kept_.erase(std::next(it).base());
        kept_bytes_ -= size;
        live_[p] = size;
        ++stats_.blocks_reused;
        return p;
      }
    }
    void* p = map_block(size);
    std::lock_guard<std::mutex> lock(mutex_);
    live_[p] = size;
    ++stats_.blocks_mapped;
    return p;
  }

  // False if p is not a live large block (then it is the small allocator's). Over the cap, the
  // blocks freed longest ago are unmapped first.
  bool release(void* p) {
    std::list<std::pair<size_t, void*>> unmap;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto it = live_.find(p);
      if (it == live_.end()) return false;
      const size_t size = it->second;
      live_.erase(it);
      kept_.emplace_back(size, p);
      kept_bytes_ += size;
      while (kept_bytes_ > kMaxKeptBytes) {
        kept_bytes_ -= kept_.front().first;
        unmap.splice(unmap.end(), kept_, kept_.begin());
      }
    }
    for (const auto& [size, q] : unmap) munmap(q, size);
    return true;
  }

  void drop_kept() {
    std::list<std::pair<size_t, void*>> unmap;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      unmap.swap(kept_);
      kept_bytes_ = 0;
    }
    for (const auto& [size, q] : unmap) munmap(q, size);
  }

  TensorAllocatorStats stats() {
    std::lock_guard<std::mutex> lock(mutex_);
    TensorAllocatorStats s = stats_;
    s.bytes_kept_free = kept_bytes_;
    return s;
  }

 private:
  // size is a multiple of 2 MiB; the block starts on a 2 MiB boundary so that the kernel can back
  // it with huge pages (over-map by 2 MiB, unmap the ends).
  static void* map_block(size_t size) {
    const size_t span = size + kHugePageBytes;
    void* raw = mmap(nullptr, span, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) throw std::bad_alloc();
    const uintptr_t begin = reinterpret_cast<uintptr_t>(raw);
    const uintptr_t aligned = round_up(begin, kHugePageBytes);
    if (aligned > begin) munmap(raw, aligned - begin);
    const uintptr_t end = begin + span, used_end = aligned + size;
    if (end > used_end) munmap(reinterpret_cast<void*>(used_end), end - used_end);
    void* p = reinterpret_cast<void*>(aligned);
    madvise(p, size, MADV_HUGEPAGE);  // advice only: without THP the block is ordinary pages
    return p;
  }

  std::mutex mutex_;
  std::unordered_map<void*, size_t> live_;
  std::list<std::pair<size_t, void*>> kept_;  // oldest first
  size_t kept_bytes_ = 0;
  TensorAllocatorStats stats_;
};

BlockPool& pool() {
  static BlockPool* p = new BlockPool;
  return *p;
}

// LibTorch's default CPU allocator (small blocks) and its deleter.
c10::Allocator* g_small = nullptr;
c10::DeleterFnPtr g_small_deleter = nullptr;

// One deleter for both kinds, so that the raw allocate/deallocate interface works too.
void release_any(void* p) {
  if (!pool().release(p)) g_small_deleter(p);
}

// allocate() and copy_data() differ between LibTorch versions: torch_compat's base adapts them.
class ReusingHugePageAllocator final : public torch_compat::CpuAllocatorBase {
 public:
  c10::DeleterFnPtr raw_deleter() const override { return &release_any; }

 protected:
  c10::DataPtr allocate_block(size_t n) const override {
    void* p = n < kLargeBytes ? g_small->raw_allocate(n) : pool().acquire(round_up(n, kHugePageBytes));
    return {p, p, &release_any, c10::Device(c10::DeviceType::CPU)};
  }
};

}  // namespace

void tune_memory_for_torch() {
  static std::once_flag once;
  std::call_once(once, [] {
    // glibc's heap keeps what is freed (no mmap, trimming only above 1 GiB): below 1 MiB
    // LibTorch's own allocator uses it; before the block pool, this alone removed ~1M page
    // faults per paper-width training step.
    mallopt(M_MMAP_MAX, 0);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    // Priority above the default's (0); the allocator is never freed (tensors may outlive main).
    g_small = c10::GetDefaultCPUAllocator();
    g_small_deleter = g_small->raw_deleter();
    if (g_small_deleter == nullptr) return;  // no raw interface to wrap: keep LibTorch's allocator
    c10::SetCPUAllocator(new ReusingHugePageAllocator, 1);
  });
}

TensorAllocatorStats tensor_allocator_stats() { return pool().stats(); }

void drop_kept_tensor_memory() { pool().drop_kept(); }

}  // namespace tsrir

// Every difference between the LibTorch versions the toolkit builds against (Debian 12's 1.13 and
// the 2.x of pip/conda torch and pytorch.org's LibTorch) lives here, and nowhere else: code in
// src/gan and src/asr calls these adapters instead of the changed API, so a new LibTorch means one
// file to read. Checked against PyTorch's public headers (c10/core/Allocator.h and
// aten/src/ATen/autocast_mode.h of the 2.x branch, and Debian's 1.13 headers); the 2.x branch is
// compiled in CI without a 2.x install against stubs of exactly that API shape
// (tests/gan/torch2_stub/, torch_compat_2x_test), which fails when the code stops matching it.
// The minor versions below are where those headers changed as far as could be checked without
// each release's headers at hand (the 2.0-2.2 releases were not compiled against); a LibTorch
// that disagrees fails to compile here (an override that overrides nothing, an abstract
// allocator, a deprecation), it does not misbehave.
#pragma once
#include <torch/version.h>  // TORCH_VERSION_MAJOR / _MINOR
#include <ATen/autocast_mode.h>
#include <c10/core/Allocator.h>

#include <cstddef>

// True when the LibTorch being compiled against is at least major.minor.
#define TSRIR_TORCH_AT_LEAST(major, minor) \
  (TORCH_VERSION_MAJOR > (major) || (TORCH_VERSION_MAJOR == (major) && TORCH_VERSION_MINOR >= (minor)))

// 2.3 made c10::Allocator::allocate non-const and added the pure virtual copy_data (for
// Allocator::clone, the copy-on-write storage); before it allocate was const and there was no
// copy_data to define.
#define TSRIR_TORCH_ALLOCATOR_2_3 TSRIR_TORCH_AT_LEAST(2, 3)
// 2.4 replaced the per-backend autocast calls (is_cpu_enabled, set_cpu_enabled,
// set_autocast_cpu_dtype) by device-type ones (is_autocast_enabled(kCPU), ...) and deprecated the
// old ones.
#define TSRIR_TORCH_AUTOCAST_2_4 TSRIR_TORCH_AT_LEAST(2, 4)

namespace tsrir::torch_compat {

// A c10::Allocator whose subclasses implement allocate_block(), the same in every version: this
// base turns it into the allocate() (const or not) and copy_data() that the LibTorch at hand
// declares pure virtual. raw_deleter() is unchanged across versions and left to the subclass.
class CpuAllocatorBase : public c10::Allocator {
 public:
#if TSRIR_TORCH_ALLOCATOR_2_3
  c10::DataPtr allocate(size_t n) final { return allocate_block(n); }
  // Host memory: a byte copy (what LibTorch's own CPU allocator does).
  void copy_data(void* dest, const void* src, std::size_t count) const final {
    default_copy_data(dest, src, count);
  }
#else
  c10::DataPtr allocate(size_t n) const final { return allocate_block(n); }
#endif

 protected:
  virtual c10::DataPtr allocate_block(size_t n) const = 0;
};

// CPU autocast (training's --precision=bfloat16).
inline bool cpu_autocast_enabled() {
#if TSRIR_TORCH_AUTOCAST_2_4
  return at::autocast::is_autocast_enabled(at::kCPU);
#else
  return at::autocast::is_cpu_enabled();
#endif
}

inline void set_cpu_autocast_enabled(bool enabled) {
#if TSRIR_TORCH_AUTOCAST_2_4
  at::autocast::set_autocast_enabled(at::kCPU, enabled);
#else
  at::autocast::set_cpu_enabled(enabled);
#endif
}

inline void set_cpu_autocast_dtype(at::ScalarType dtype) {
#if TSRIR_TORCH_AUTOCAST_2_4
  at::autocast::set_autocast_dtype(at::kCPU, dtype);
#else
  at::autocast::set_autocast_cpu_dtype(dtype);
#endif
}

}  // namespace tsrir::torch_compat

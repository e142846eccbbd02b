// The LibTorch 2.x branch of src/gan/torch_compat.h and the real src/gan/gan_tensor_allocator.cc,
// compiled against a stub of LibTorch 2.x's changed declarations (tests/gan/torch2_stub/README.md
// says why a stub), linked with the stub's trivial bodies and run: CI's check that the code base
// stays LibTorch-2.x-clean without a 2.x install. The build of this test fails when the code stops
// matching 2.x's shape (an override that does not override, an abstract allocator, a deprecated
// autocast call: -Werror=deprecated-declarations); the two torch_compat_2x_rejects_* ctests
// show that it would (they compile the same code with the header's pre-2.3 / pre-2.4 branches).
// The 1.13 branch is the one every ordinary build here compiles.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include <c10/core/CPUAllocator.h>

#include "gan/gan_tensor_allocator.h"
#include "gan/torch_compat.h"
#include "torch2_stub_state.h"

#ifndef TSRIR_TORCH2_STUB
#error "torch_compat_2x_test must be compiled against tests/gan/torch2_stub, not a real LibTorch"
#endif
static_assert(TORCH_VERSION_MAJOR == 2 && TSRIR_TORCH_ALLOCATOR_2_3 && TSRIR_TORCH_AUTOCAST_2_4,
              "the stub reports LibTorch 2.11: the header must take its 2.x branches");

namespace tsrir {
namespace {

constexpr size_t kMiB = size_t(1) << 20;

TEST(TorchCompat2x, TheToolkitsAllocatorServesSmallAndLargeBlocksThrough2xInterface) {
  tune_memory_for_torch();
  c10::Allocator* allocator = c10::GetCPUAllocator();
  ASSERT_NE(allocator, c10::GetDefaultCPUAllocator()) << "tune_memory_for_torch did not install its allocator";
  EXPECT_NE(allocator->raw_deleter(), nullptr);

  const TensorAllocatorStats before = tensor_allocator_stats();
  const long default_calls = tsrir_stub::default_allocator_calls();
  {
    c10::DataPtr small = allocator->allocate(1000);  // below 1 MiB: the default allocator's
    ASSERT_TRUE(small);
    EXPECT_EQ(tsrir_stub::default_allocator_calls(), default_calls + 1);
  }
  const size_t large_bytes = 3 * kMiB + 5;
  void* first = nullptr;
  {
    c10::DataPtr large = allocator->allocate(large_bytes);
    ASSERT_TRUE(large);
    first = large.get();
    EXPECT_EQ(tsrir_stub::default_allocator_calls(), default_calls + 1) << "a large block went to the default allocator";
    EXPECT_EQ(reinterpret_cast<uintptr_t>(first) % (2 * kMiB), 0u) << "large blocks start on a 2 MiB boundary";
    EXPECT_EQ(tensor_allocator_stats().blocks_mapped, before.blocks_mapped + 1);
    // clone() = allocate() + copy_data(), the pure virtual that 2.3 added: the bytes must arrive.
    std::vector<unsigned char> pattern(large_bytes);
    for (size_t i = 0; i < large_bytes; ++i) pattern[i] = static_cast<unsigned char>((i * 131) ^ (i >> 9));
    std::memcpy(large.get(), pattern.data(), large_bytes);
    c10::DataPtr copy = allocator->clone(large.get(), large_bytes);
    ASSERT_TRUE(copy);
    EXPECT_NE(copy.get(), large.get());
    EXPECT_EQ(std::memcmp(copy.get(), pattern.data(), large_bytes), 0);
  }
  {
    c10::DataPtr again = allocator->allocate(large_bytes - 4096);  // same 2 MiB-rounded size: reused
    EXPECT_EQ(tensor_allocator_stats().blocks_reused, before.blocks_reused + 1);
    EXPECT_TRUE(again.get() == first || tensor_allocator_stats().blocks_reused > before.blocks_reused);
  }
  for (size_t bytes : {size_t(100), 3 * kMiB}) {
    void* raw = allocator->raw_allocate(bytes);
    std::memset(raw, 7, bytes);
    allocator->raw_deallocate(raw);
  }
  drop_kept_tensor_memory();
  EXPECT_EQ(tensor_allocator_stats().bytes_kept_free, 0u);
}

TEST(TorchCompat2x, CpuAutocastGoesThroughTheDeviceTypeCalls) {
  tsrir_stub::autocast(at::kCPU) = {};
  tsrir_stub::autocast(at::kCUDA) = {};
  EXPECT_FALSE(torch_compat::cpu_autocast_enabled());
  torch_compat::set_cpu_autocast_dtype(at::kBFloat16);
  torch_compat::set_cpu_autocast_enabled(true);
  EXPECT_TRUE(torch_compat::cpu_autocast_enabled());
  EXPECT_TRUE(tsrir_stub::autocast(at::kCPU).enabled);
  EXPECT_EQ(tsrir_stub::autocast(at::kCPU).dtype, at::kBFloat16);
  EXPECT_FALSE(tsrir_stub::autocast(at::kCUDA).enabled) << "CPU autocast must not switch CUDA's";
  EXPECT_EQ(tsrir_stub::autocast(at::kCUDA).dtype, at::kFloat);
  torch_compat::set_cpu_autocast_enabled(false);
  EXPECT_FALSE(torch_compat::cpu_autocast_enabled());
}

}  // namespace
}  // namespace tsrir

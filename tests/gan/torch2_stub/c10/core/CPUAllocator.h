// Stub (tests/gan/torch2_stub/README.md) of LibTorch 2.x's c10/core/CPUAllocator.h: the calls
// the toolkit makes.
#pragma once
#define TSRIR_TORCH2_STUB 1

#include <cstdint>

#include <c10/core/Allocator.h>

namespace c10 {

Allocator* GetCPUAllocator();
void SetCPUAllocator(Allocator* alloc, uint8_t priority = 0);
Allocator* GetDefaultCPUAllocator();

}  // namespace c10

// Bodies for the LibTorch 2.x stub (README.md beside this file): enough for code compiled against
// the stub to link and run. The default CPU allocator is malloc/free; the CPU allocator slot
// follows SetAllocator's priority rule; the autocast state is a pair of variables per device type
// that the test reads back (torch2_stub_state.h).
#include "torch2_stub_state.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <utility>

#include <ATen/autocast_mode.h>
#include <c10/core/Allocator.h>
#include <c10/core/CPUAllocator.h>

namespace c10 {

DataPtr::DataPtr(DataPtr&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)),
      context_(std::exchange(other.context_, nullptr)),
      deleter_(std::exchange(other.deleter_, nullptr)),
      device_(other.device_) {}

DataPtr& DataPtr::operator=(DataPtr&& other) noexcept {
  if (this != &other) {
    if (deleter_ != nullptr && context_ != nullptr) deleter_(context_);
    data_ = std::exchange(other.data_, nullptr);
    context_ = std::exchange(other.context_, nullptr);
    deleter_ = std::exchange(other.deleter_, nullptr);
    device_ = other.device_;
  }
  return *this;
}

DataPtr::~DataPtr() {
  if (deleter_ != nullptr && context_ != nullptr) deleter_(context_);
}

void* DataPtr::release_context() {
  deleter_ = nullptr;
  return std::exchange(context_, nullptr);
}

DataPtr Allocator::clone(const void* data, std::size_t n) {
  DataPtr copy = allocate(n);
  copy_data(copy.mutable_get(), data, n);
  return copy;
}

bool Allocator::is_simple_data_ptr(const DataPtr& data_ptr) const {
  return data_ptr.get() == data_ptr.get_context();
}

void* Allocator::raw_allocate(size_t n) {
  DataPtr d = allocate(n);
  if (d.get() != d.get_context()) std::abort();  // LibTorch: AT_ASSERT
  return d.release_context();
}

void Allocator::raw_deallocate(void* ptr) {
  DeleterFnPtr d = raw_deleter();
  if (d == nullptr) std::abort();
  d(ptr);
}

void Allocator::default_copy_data(void* dest, const void* src, std::size_t count) const {
  std::memcpy(dest, src, count);
}

namespace {

Allocator* g_cpu_allocator = nullptr;
uint8_t g_cpu_priority = 0;

void free_counted(void* p) {
  ++tsrir_stub::default_allocator_frees();
  std::free(p);
}

struct MallocAllocator final : Allocator {
  DataPtr allocate(size_t n) override {
    ++tsrir_stub::default_allocator_calls();
    void* p = std::malloc(n == 0 ? 1 : n);
    if (p == nullptr) throw std::bad_alloc();
    return {p, p, &free_counted, Device(DeviceType::CPU)};
  }
  DeleterFnPtr raw_deleter() const override { return &free_counted; }
  void copy_data(void* dest, const void* src, std::size_t count) const override {
    default_copy_data(dest, src, count);
  }
};

}  // namespace

void SetAllocator(DeviceType t, Allocator* alloc, uint8_t priority) {
  if (t != DeviceType::CPU || priority < g_cpu_priority) return;
  g_cpu_allocator = alloc;
  g_cpu_priority = priority;
}

Allocator* GetAllocator(const DeviceType& t) { return t == DeviceType::CPU ? GetCPUAllocator() : nullptr; }

Allocator* GetDefaultCPUAllocator() {
  static MallocAllocator* a = new MallocAllocator;
  return a;
}

Allocator* GetCPUAllocator() { return g_cpu_allocator != nullptr ? g_cpu_allocator : GetDefaultCPUAllocator(); }

void SetCPUAllocator(Allocator* alloc, uint8_t priority) { SetAllocator(DeviceType::CPU, alloc, priority); }

}  // namespace c10

namespace at::autocast {

bool is_autocast_enabled(at::DeviceType device_type) { return tsrir_stub::autocast(device_type).enabled; }
void set_autocast_enabled(at::DeviceType device_type, bool enabled) {
  tsrir_stub::autocast(device_type).enabled = enabled;
}
at::ScalarType get_autocast_dtype(at::DeviceType device_type) { return tsrir_stub::autocast(device_type).dtype; }
void set_autocast_dtype(at::DeviceType device_type, at::ScalarType dtype) {
  tsrir_stub::autocast(device_type).dtype = dtype;
}
void clear_cache() { ++tsrir_stub::autocast_cache_clears(); }

}  // namespace at::autocast

namespace tsrir_stub {

AutocastState& autocast(c10::DeviceType device_type) {
  static AutocastState cpu, cuda;
  return device_type == c10::DeviceType::CPU ? cpu : cuda;
}

int& autocast_cache_clears() {
  static int n = 0;
  return n;
}

long& default_allocator_calls() {
  static long n = 0;
  return n;
}

long& default_allocator_frees() {
  static long n = 0;
  return n;
}

}  // namespace tsrir_stub

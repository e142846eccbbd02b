// Stub (tests/gan/torch2_stub/README.md) of LibTorch 2.x's c10/core/Allocator.h: DataPtr as far
// as the toolkit uses it, and c10::Allocator with 2.x's virtual interface (allocate non-const,
// copy_data pure virtual, default_copy_data protected; since 2.3).
#pragma once
#define TSRIR_TORCH2_STUB 1

#include <cstddef>
#include <cstdint>

namespace c10 {

enum class DeviceType : int8_t { CPU = 0, CUDA = 1 };
constexpr DeviceType kCPU = DeviceType::CPU;
constexpr DeviceType kCUDA = DeviceType::CUDA;

struct Device {
  Device(DeviceType type) : type_(type) {}  // NOLINT: implicit, as LibTorch's
  DeviceType type() const { return type_; }

 private:
  DeviceType type_;
};

using DeleterFnPtr = void (*)(void*);

// Owns `context` through `deleter`; `data` is what tensors see.
class DataPtr {
 public:
  DataPtr() : device_(DeviceType::CPU) {}
  DataPtr(void* data, Device device) : data_(data), device_(device) {}
  DataPtr(void* data, void* ctx, DeleterFnPtr ctx_deleter, Device device)
      : data_(data), context_(ctx), deleter_(ctx_deleter), device_(device) {}
  DataPtr(DataPtr&& other) noexcept;
  DataPtr& operator=(DataPtr&& other) noexcept;
  DataPtr(const DataPtr&) = delete;
  DataPtr& operator=(const DataPtr&) = delete;
  ~DataPtr();
  void* get() const { return data_; }
  void* mutable_get() { return data_; }
  void* get_context() const { return context_; }
  void* release_context();
  DeleterFnPtr get_deleter() const { return deleter_; }
  Device device() const { return device_; }
  explicit operator bool() const { return data_ != nullptr; }

 private:
  void* data_ = nullptr;
  void* context_ = nullptr;
  DeleterFnPtr deleter_ = nullptr;
  Device device_;
};

struct Allocator {
  virtual ~Allocator() = default;

  virtual DataPtr allocate(size_t n) = 0;

  DataPtr clone(const void* data, std::size_t n);

  virtual bool is_simple_data_ptr(const DataPtr& data_ptr) const;

  virtual DeleterFnPtr raw_deleter() const { return nullptr; }
  void* raw_allocate(size_t n);
  void raw_deallocate(void* ptr);

  virtual void copy_data(void* dest, const void* src, std::size_t count) const = 0;

 protected:
  void default_copy_data(void* dest, const void* src, std::size_t count) const;
};

void SetAllocator(DeviceType t, Allocator* alloc, uint8_t priority = 0);
Allocator* GetAllocator(const DeviceType& t);

}  // namespace c10

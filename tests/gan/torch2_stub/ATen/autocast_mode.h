// Stub (tests/gan/torch2_stub/README.md) of LibTorch 2.x's ATen/autocast_mode.h (since 2.4): the
// device-type calls, and the per-backend CPU calls they replaced, marked deprecated as there
// (C10_DEPRECATED_MESSAGE is [[deprecated(...)]]), so that a build with
// -Werror=deprecated-declarations rejects them.
#pragma once
#define TSRIR_TORCH2_STUB 1

#include <cstdint>

#include <c10/core/Allocator.h>

namespace c10 {
enum class ScalarType : int8_t { Float = 6, BFloat16 = 15 };
constexpr ScalarType kFloat = ScalarType::Float;
constexpr ScalarType kBFloat16 = ScalarType::BFloat16;
}  // namespace c10

namespace at {
using c10::DeviceType;
using c10::kBFloat16;
using c10::kCPU;
using c10::kCUDA;
using c10::kFloat;
using c10::ScalarType;
}  // namespace at

namespace at::autocast {

bool is_autocast_enabled(at::DeviceType device_type);
void set_autocast_enabled(at::DeviceType device_type, bool enabled);
at::ScalarType get_autocast_dtype(at::DeviceType device_type);
void set_autocast_dtype(at::DeviceType device_type, at::ScalarType dtype);
void clear_cache();

[[deprecated("at::autocast::is_cpu_enabled() is deprecated. Please use at::autocast::is_autocast_enabled(at::kCPU) instead.")]]
inline bool is_cpu_enabled() { return is_autocast_enabled(at::kCPU); }
[[deprecated("at::autocast::set_cpu_enabled(enabled) is deprecated. Please use at::autocast::set_autocast_enabled(at::kCPU, enabled) instead.")]]
inline void set_cpu_enabled(bool enabled) { set_autocast_enabled(at::kCPU, enabled); }
[[deprecated("at::autocast::get_autocast_cpu_dtype() is deprecated. Please at::autocast::get_autocast_dtype(at::kCPU) instead.")]]
inline at::ScalarType get_autocast_cpu_dtype() { return get_autocast_dtype(at::kCPU); }
[[deprecated("at::autocast::set_autocast_cpu_dtype(dtype) is deprecated. Please use at::autocast::set_autocast_dtype(at::kCPU, dtype) instead.")]]
inline void set_autocast_cpu_dtype(at::ScalarType dtype) { set_autocast_dtype(at::kCPU, dtype); }

}  // namespace at::autocast

// What the LibTorch 2.x stub (README.md beside this file) records, for its test to read back.
#pragma once
#include <ATen/autocast_mode.h>
#include <c10/core/Allocator.h>

namespace tsrir_stub {

struct AutocastState {
  bool enabled = false;
  at::ScalarType dtype = at::kFloat;
};
AutocastState& autocast(c10::DeviceType device_type);  // per device type, as LibTorch keeps it
int& autocast_cache_clears();
long& default_allocator_calls();  // the default CPU allocator's allocate() calls
long& default_allocator_frees();

}  // namespace tsrir_stub

// Where LibTorch computes: the --device option of every LibTorch program (ts-rirgan-train,
// gas-to-real, asr-train, asr-decode). Torch-free, so that the option structs of src/gan and
// src/asr (and torch-free libraries such as tsrir_asr_core) can hold and register it.
#pragma once
#include "util/options.h"

namespace tsrir {

enum class ComputeDevice { kCpu, kCuda };

inline const char* compute_device_name(ComputeDevice device) {
  return device == ComputeDevice::kCuda ? "cuda" : "cpu";
}

// One spelling and help text for --device in every program.
inline void register_compute_device(OptionsItf* opts, ComputeDevice* device) {
  opts->RegisterEnum("device", device, {{"cpu", ComputeDevice::kCpu}, {"cuda", ComputeDevice::kCuda}},
                     "Where LibTorch computes: cuda needs a build against a CUDA LibTorch and a visible GPU "
                     "(docs/recipe.md, 'Building with a CUDA LibTorch')");
}

// Throws Error when `device` is cuda and this process's LibTorch cannot use a GPU (built without
// CUDA, or none visible), saying which; programs call it before reading any data. Defined in
// src/gan/gan_networks.cc, where LibTorch is.
void require_compute_device(ComputeDevice device);

}  // namespace tsrir

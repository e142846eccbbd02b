// Stub (tests/gan/torch2_stub/README.md): LibTorch 2.11's generated torch/version.h.
#pragma once
#define TSRIR_TORCH2_STUB 1

#define TORCH_VERSION_MAJOR 2
#ifdef TSRIR_STUB_TORCH_MINOR
#define TORCH_VERSION_MINOR TSRIR_STUB_TORCH_MINOR
#else
#define TORCH_VERSION_MINOR 11
#endif
#define TORCH_VERSION_PATCH 0

// Whether --precision=bfloat16 keeps its promise on this CPU. bfloat16 is worth having only where
// LibTorch's convolutions multiply bfloat16 operands but sum the products in float32 (oneDNN's
// kernels, on CPUs with AVX512/AMX). Elsewhere LibTorch 1.13's own kernels sum in bfloat16 too: a
// sum stops growing once an addend falls below half a step of 8 significant bits, a 64-channel
// 25-tap layer is ~5% RMS off and a generator's output ~9% (measured on AMD Zen 3, tests/gan/
// gan_networks_test.cc), and it is slower than float32 there as well. Torch-free header.
#pragma once

#include <string>

namespace tsrir {

// Probed once per process: a bfloat16 convolution of ones, 64 channels x 25 taps, must give 1600
// (exact in bfloat16) within one bfloat16 step; summed in bfloat16 it stalls at 256.
bool bfloat16_convolutions_sum_in_float32();

// Throws Error when they do not, naming the option and the way out (--precision=float32).
void require_float32_sums_for_bfloat16(const std::string& program);

}  // namespace tsrir

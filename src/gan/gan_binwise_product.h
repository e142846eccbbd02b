// The frequency-domain core of the FFT convolution (gan_networks.cc, SameConv1dImpl): for every
// frequency bin f, Y[f] = X[f] W[f], with X [bins, batch, in] and W [bins, in, out] complex.
#pragma once

#include <torch/torch.h>

namespace tsrir::gan {

// Y [bins, batch, out] = X[f] W[f] for every bin f, the same as torch::matmul(x, w) within
// float32 rounding. For complex float on the CPU with OpenBLAS at one thread (as every program
// here sets it, gan_runtime.h) the bins are shared among torch's threads, one single-threaded
// cgemm per bin: torch::matmul runs the batch of products one after another, each on OpenBLAS's
// one thread, so half of a 2-core machine idled through the bottleneck (bench/RESULTS.md). Any
// other case (other types, devices, OpenBLAS threaded or absent) is torch::matmul.
torch::Tensor binwise_complex_matmul(const torch::Tensor& x, const torch::Tensor& w);

// Whether binwise_complex_matmul shares bins among threads in this process, and a switch that
// turns the sharing off (default on) so tests and bench/gan can run both forms in one process.
bool binwise_product_is_parallel();
void allow_parallel_binwise_product(bool allowed);

}  // namespace tsrir::gan

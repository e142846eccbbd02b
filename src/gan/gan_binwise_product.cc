#include "gan/gan_binwise_product.h"

#include <ATen/Parallel.h>
#include <dlfcn.h>

#include <algorithm>
#include <atomic>
#include <climits>
#include <complex>
#include <cstdint>

#include "gan/gan_runtime.h"

namespace tsrir::gan {
namespace {

// CBLAS's cgemm, found at run time as gan_runtime.cc finds OpenBLAS's thread setter and query:
// libtorch brings its BLAS into the process, and the build does not depend on which one it is.
using Cgemm = void (*)(int order, int trans_a, int trans_b, int m, int n, int k, const void* alpha,
                       const void* a, int lda, const void* b, int ldb, const void* beta, void* c, int ldc);
constexpr int kRowMajor = 101, kNoTrans = 111;

Cgemm find_cgemm() {
  static const Cgemm fn = reinterpret_cast<Cgemm>(dlsym(RTLD_DEFAULT, "cblas_cgemm"));
  return fn;
}

std::atomic<bool> g_parallel_allowed{true};

}  // namespace

void allow_parallel_binwise_product(bool allowed) { g_parallel_allowed = allowed; }

bool binwise_product_is_parallel() {
  // A threaded OpenBLAS called from several threads at once would share (and lock) its one pool.
  return g_parallel_allowed && find_cgemm() != nullptr && openblas_threads() == 1 && at::get_num_threads() > 1;
}

torch::Tensor binwise_complex_matmul(const torch::Tensor& x, const torch::Tensor& w) {
  const bool fits = x.dim() == 3 && w.dim() == 3 && x.size(0) == w.size(0) && x.size(2) == w.size(1) &&
                    x.scalar_type() == torch::kComplexFloat && w.scalar_type() == torch::kComplexFloat &&
                    x.device().is_cpu() && w.device().is_cpu() && x.size(1) > 0 && w.size(2) > 0 &&
                    x.size(2) > 0 && std::max({x.size(1), x.size(2), w.size(2)}) <= INT_MAX;  // CBLAS takes int
  if (!fits || !binwise_product_is_parallel()) return torch::matmul(x, w);
  const torch::Tensor a = x.contiguous(), b = w.contiguous();
  const int64_t bins = a.size(0), rows = a.size(1), inner = a.size(2), cols = b.size(2);
  torch::Tensor y = torch::empty({bins, rows, cols}, a.options());
  const auto* a_data = a.data_ptr<c10::complex<float>>();
  const auto* b_data = b.data_ptr<c10::complex<float>>();
  auto* y_data = y.data_ptr<c10::complex<float>>();
  const Cgemm cgemm = find_cgemm();
  const std::complex<float> one(1.0f, 0.0f), zero(0.0f, 0.0f);
  at::parallel_for(0, bins, 1, [&](int64_t begin, int64_t end) {
    for (int64_t f = begin; f < end; ++f) {
      cgemm(kRowMajor, kNoTrans, kNoTrans, int(rows), int(cols), int(inner), &one, a_data + f * rows * inner,
            int(inner), b_data + f * inner * cols, int(cols), &zero, y_data + f * rows * cols, int(cols));
    }
  });
  return y;
}

}  // namespace tsrir::gan

// How every real FFT plan of the toolkit is made (dsp/fft.cc), shared with the build-time wisdom
// generator (dsp/fftw_wisdom_gen.cc) so that the embedded wisdom records exactly these plans.
#pragma once
#include <fftw3.h>

#include <cstddef>

namespace tsrir {

struct PlanPair {
  fftwf_plan forward;
  fftwf_plan inverse;
};

// FFTW_ESTIMATE (planning a 2^20 transform with FFTW_MEASURE costs ~10 s), on SIMD-aligned arrays.
// Not thread-safe (FFTW's planner is not): callers hold a lock.
inline PlanPair make_plan_pair(size_t n) {
  float* in = fftwf_alloc_real(n);
  fftwf_complex* out = fftwf_alloc_complex(n / 2 + 1);
  PlanPair p;
  p.forward = fftwf_plan_dft_r2c_1d(static_cast<int>(n), in, out, FFTW_ESTIMATE);
  p.inverse = fftwf_plan_dft_c2r_1d(static_cast<int>(n), out, in, FFTW_ESTIMATE);
  fftwf_free(in);
  fftwf_free(out);
  return p;
}

}  // namespace tsrir

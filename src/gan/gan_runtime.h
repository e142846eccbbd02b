// Process-level settings that decide CPU training speed (docs/reference/toolchain.md pitfalls 2 and
// 3; memory: gan_tensor_allocator.h), the peak memory report, and the stop-between-steps flag for
// SIGINT/SIGTERM.
#pragma once

namespace tsrir {

// OpenBLAS runs its own thread pool on top of torch's; with torch threads in use it must be 1.
// Found through dlsym so the build does not depend on which BLAS libtorch was linked with.
void set_openblas_threads(int n);
// OpenBLAS's thread count, or -1 when the process has no OpenBLAS (another BLAS, or none).
int openblas_threads();
double peak_rss_mb();

// While alive, SIGINT/SIGTERM only set a flag (checked between training steps); a second
// signal goes to the previous handler (run_program's: remove temporaries and die).
class StopRequestGuard {
 public:
  StopRequestGuard();
  ~StopRequestGuard();
  bool stop_requested() const;
  StopRequestGuard(const StopRequestGuard&) = delete;
  StopRequestGuard& operator=(const StopRequestGuard&) = delete;
};

}  // namespace tsrir

#include "gan/gan_runtime.h"

#include <dlfcn.h>
#include <sys/resource.h>

#include <csignal>

namespace tsrir {

void set_openblas_threads(int n) {
  using SetThreads = void (*)(int);
  if (auto fn = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) fn(n);
}

int openblas_threads() {
  using GetThreads = int (*)();
  static const GetThreads fn = reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  return fn ? fn() : -1;
}

double peak_rss_mb() {
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux
}

namespace {
volatile std::sig_atomic_t g_stop_requested = 0;
struct sigaction g_previous_int, g_previous_term;

extern "C" void on_stop_signal(int sig) {
  g_stop_requested = 1;
  // The next signal of this kind gets the previous behaviour (cleanup and exit).
  sigaction(sig, sig == SIGINT ? &g_previous_int : &g_previous_term, nullptr);
}
}  // namespace

StopRequestGuard::StopRequestGuard() {
  g_stop_requested = 0;
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
}

StopRequestGuard::~StopRequestGuard() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

bool StopRequestGuard::stop_requested() const { return g_stop_requested != 0; }

}  // namespace tsrir

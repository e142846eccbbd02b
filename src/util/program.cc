#include "util/program.h"

#include <csignal>
#include <iostream>

#include "util/cleanup.h"
#include "util/error.h"
#include "util/log.h"

namespace tsrir {
namespace {

extern "C" void on_terminating_signal(int sig) {
  remove_registered_temps_on_signal();
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

int run_program(const std::string& program, const std::function<int()>& body) {
  set_log_program_name(program);
  std::signal(SIGINT, on_terminating_signal);
  std::signal(SIGTERM, on_terminating_signal);
  std::signal(SIGHUP, on_terminating_signal);
  try {
    return body();
  } catch (const Error& e) {
    std::cerr << program << ": ERROR: " << e.what() << std::endl;
  } catch (const std::exception& e) {
    std::cerr << program << ": ERROR: " << e.what() << std::endl;
  }
  return 1;
}

}  // namespace tsrir

#include "util/log.h"

#include <iostream>
#include <mutex>

namespace tsrir {
namespace {

std::string& program_name() {
  static std::string name = "tsrir";
  return name;
}
std::mutex g_log_mutex;

}  // namespace

void set_log_program_name(const std::string& program) {
  std::lock_guard<std::mutex> lock(g_log_mutex);
  program_name() = program;
}

const std::string& log_program_name() { return program_name(); }

void log_info(const std::string& message) {
  std::lock_guard<std::mutex> lock(g_log_mutex);
  std::cerr << program_name() << ": " << message << std::endl;
}

void log_warning(const std::string& message) {
  std::lock_guard<std::mutex> lock(g_log_mutex);
  std::cerr << program_name() << ": WARNING: " << message << std::endl;
}

}  // namespace tsrir

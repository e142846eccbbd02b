#include "util/log.h"

#include <iostream>
#include <mutex>
#include <utility>

namespace tsrir {
namespace {

std::string& program_name() {
  static std::string name = "tsrir";
  return name;
}
std::mutex g_log_mutex;
std::function<void(const std::string&)> g_warning_handler;  // guarded by g_log_mutex

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

void set_warning_handler(std::function<void(const std::string& message)> handler) {
  std::lock_guard<std::mutex> lock(g_log_mutex);
  g_warning_handler = std::move(handler);
}

void log_warning(const std::string& message) {
  std::lock_guard<std::mutex> lock(g_log_mutex);
  if (g_warning_handler) {
    g_warning_handler(message);
    return;
  }
  std::cerr << program_name() << ": WARNING: " << message << std::endl;
}

}  // namespace tsrir

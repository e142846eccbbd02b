#include "util/cli.h"

#include <csignal>
#include <cstdlib>
#include <iostream>
#include <mutex>

#include "util/cleanup.h"
#include "util/error.h"
#include "util/strings.h"

namespace po = boost::program_options;

namespace tsrir {
namespace {

std::string g_program_name = "tsrir";
std::mutex g_log_mutex;

extern "C" void on_terminating_signal(int sig) {
  remove_registered_temps_on_signal();
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

CommandLine::CommandLine(std::string program, std::string usage)
    : program_(std::move(program)), usage_(std::move(usage)), options_("Options") {
  options_.add_options()("help,h", "Print this usage message and exit");
}

void CommandLine::option(const std::string& name, double* value, const std::string& help) {
  options_.add_options()(name.c_str(), po::value<double>(value)->default_value(*value, format_double(*value, 10)),
                         help.c_str());
}

void CommandLine::flag(const std::string& name, bool* value, const std::string& help) {
  options_.add_options()(name.c_str(),
                         po::value<bool>(value)->default_value(*value, *value ? "true" : "false")->implicit_value(true, "true"),
                         help.c_str());
  flags_.emplace_back(name, value);
}

void CommandLine::multi_option(const std::string& name, std::vector<std::string>* values,
                               const std::string& help) {
  options_.add_options()(name.c_str(), po::value<std::vector<std::string>>(values)->composing(),
                         help.c_str());
}

std::string CommandLine::usage_text() const {
  std::ostringstream os;
  os << usage_;
  if (!usage_.empty() && usage_.back() != '\n') os << '\n';
  os << '\n' << options_;
  return os.str();
}

std::vector<std::string> CommandLine::parse(int argc, const char* const* argv, int min_positional,
                                            int max_positional) {
  po::options_description all;
  all.add(options_);
  std::vector<std::string> positional;
  all.add_options()("positional-arguments__", po::value<std::vector<std::string>>(&positional));
  po::positional_options_description pos;
  pos.add("positional-arguments__", -1);
  // A bare boolean "--flag" must not swallow the next word as its value.
  std::vector<std::string> args(argv + 1, argv + argc);
  for (auto& a : args) {
    for (const auto& f : flags_) {
      if (a == "--" + f.first) a += "=true";
    }
  }
  po::variables_map vm;
  try {
    auto style = po::command_line_style::default_style & ~po::command_line_style::allow_guessing;
    po::store(po::command_line_parser(args).options(all).positional(pos).style(style).run(), vm);
    if (vm.count("help")) {
      std::cout << usage_text();
      std::exit(0);
    }
    po::notify(vm);
  } catch (const po::error& e) {
    throw Error(std::string(e.what()) + "\n\n" + usage_text());
  }
  const int n = static_cast<int>(positional.size());
  if (n < min_positional || (max_positional >= 0 && n > max_positional)) {
    throw Error("wrong number of arguments (" + std::to_string(n) + ")\n\n" + usage_text());
  }
  return positional;
}

int run_program(const std::string& program, const std::function<int()>& body) {
  g_program_name = program;
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

void log_info(const std::string& message) {
  std::lock_guard<std::mutex> lock(g_log_mutex);
  std::cerr << g_program_name << ": " << message << std::endl;
}

void log_warning(const std::string& message) {
  std::lock_guard<std::mutex> lock(g_log_mutex);
  std::cerr << g_program_name << ": WARNING: " << message << std::endl;
}

}  // namespace tsrir

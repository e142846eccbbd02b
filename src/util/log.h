// Progress and log lines on stderr, prefixed with the running program's name. Kept apart from
// command-line parsing so that library code that only logs does not depend on the option parser.
#pragma once
#include <functional>
#include <string>

namespace tsrir {

// The prefix of every log line ("tsrir" until a program sets its name; run_program does).
void set_log_program_name(const std::string& program);
const std::string& log_program_name();

// Whole lines, serialised across threads.
void log_info(const std::string& message);
void log_warning(const std::string& message);

// Where log_warning() sends its message instead of stderr (the Python module hands them to Python's
// `warnings`); an empty function restores stderr. The handler runs under the log's lock.
void set_warning_handler(std::function<void(const std::string& message)> handler);

}  // namespace tsrir

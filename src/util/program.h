// The frame every program's main() runs in, kept apart from command-line parsing (util/cli.h) so
// that a program with its own parser (Kaldi's syntax, augment/kaldi_options.h) links no option
// library it does not use.
#pragma once
#include <functional>
#include <string>

namespace tsrir {

// Runs a program body: Error and std::exception become "<program>: ERROR: <message>" on stderr
// and exit status 1. Also names the program in log lines and installs the SIGINT/SIGTERM/SIGHUP
// handler that removes temporary outputs.
int run_program(const std::string& program, const std::function<int()>& body);

}  // namespace tsrir

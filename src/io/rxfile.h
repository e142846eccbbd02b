// Kaldi rxfilenames / wxfilenames: a path, "-" (stdin/stdout), or "<command> |" (a pipe run
// through bash, as Kaldi does). A failing pipe command is an error, never silently empty input.
#pragma once
#include <string>
#include <vector>

namespace tsrir {

bool is_pipe_rxfilename(const std::string& rx);  // ends with '|' (after trimming)

// Reads the whole input into memory. Errors name `rx` (and `context`, e.g. "wav.scp:12").
std::vector<char> read_rxfile(const std::string& rx, const std::string& context = "");

// Runs `command` via /bin/bash -c, returns its stdout; throws Error on non-zero exit status or
// signal, with the status and the first lines of its stderr.
std::vector<char> run_command_capture(const std::string& command, const std::string& context = "");

}  // namespace tsrir

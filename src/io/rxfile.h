// Kaldi rxfilenames / wxfilenames: a path, "-" (stdin/stdout), or "<command> |" (a pipe run
// through bash, as Kaldi does). A failing pipe command is an error, never silently empty input.
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace tsrir {

bool is_pipe_rxfilename(const std::string& rx);  // ends with '|' (after trimming)

// Reads the whole input into memory. Errors name `rx` (and `context`, e.g. "wav.scp:12").
std::vector<char> read_rxfile(const std::string& rx, const std::string& context = "");

// Receives an input in order, in blocks (memory independent of the input's length).
using ByteSink = std::function<void(const char* data, size_t size)>;

// As read_rxfile, but hands the bytes to `sink` block by block. A pipe's failure is reported
// after its last block (a sink that spills to disk must not treat the end as success until then).
void stream_rxfile(const std::string& rx, const ByteSink& sink, const std::string& context = "");

// Runs `command` via /bin/bash -c, returns its stdout; throws Error on non-zero exit status or
// signal, with the status and the first lines of its stderr.
std::vector<char> run_command_capture(const std::string& command, const std::string& context = "");
// The same with the stdout handed to `sink` in blocks.
void run_command_stream(const std::string& command, const ByteSink& sink, const std::string& context = "");

}  // namespace tsrir

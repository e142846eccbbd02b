// The rir-diagnose program body: its usage text (with the effect catalog and every threshold) and
// the run from the command line's arguments; bin/rir-diagnose.cc only registers and calls these.
#pragma once
#include <string>
#include <vector>

#include "diagnose/diagnose_options.h"

namespace tsrir::diagnose {

std::string rir_diagnose_usage();

// args: <room-list> <measured-rir-scp> <out-dir>. Writes the outputs (write_diagnosis), prints the
// summary on stdout; `command_line` is recorded in the report. Returns the exit status.
int run_rir_diagnose(const DiagnoseOptions& options, const std::vector<std::string>& args, const std::string& command_line);

}  // namespace tsrir::diagnose

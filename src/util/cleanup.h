// Temporary outputs registered for removal when the program is interrupted (SIGINT/SIGTERM/SIGHUP,
// handler installed by run_program). SIGKILL cannot be caught: temporaries then stay behind under
// names containing ".tmp.", never under a final name.
#pragma once
#include <string>

namespace tsrir {

void register_temp_path(const std::string& path);
void unregister_temp_path(const std::string& path);
// Removes every registered temporary file or directory; called from the signal handler, so it is
// async-signal-safe (system calls only, no heap).
void remove_registered_temps_on_signal();

}  // namespace tsrir

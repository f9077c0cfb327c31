#pragma once
// SIGINT/SIGTERM during a sweep: finish the runs in flight, write them, exit
// 128 + the signal (so the sweep can be resumed).
#include <atomic>

namespace chaosweep {

// Set by the handlers; the sweep runner's stop flag.
extern std::atomic<bool> sweep_stop_requested;

// Installs the handlers, and ignores SIGXFSZ: past ulimit -f a write fails
// (reported) instead of killing the process.
void install_sweep_signal_handlers();

// The exit status of a sweep stopped by a signal: 128 + its number (SIGINT's
// when no signal came).
int stopped_exit_status();

}  // namespace chaosweep

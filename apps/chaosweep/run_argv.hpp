#pragma once
// Runs a program by argv, without a shell (nothing a value holds is read as
// shell syntax), capturing its output: sbatch, squeue, sacct, scontrol.
#include <string>
#include <vector>

namespace chaosweep {

struct ArgvResult {
  bool started = false;  // false: the program is not on PATH (or not executable)
  int exit_code = -1;    // -1 when killed (a signal, or the timeout)
  bool timed_out = false;
  std::string out, err;
};

// argv[0] is looked up on PATH. Kills the program after `timeout_seconds`
// (a SLURM client whose controller does not answer must not hang status).
ArgvResult run_argv(const std::vector<std::string>& argv, int timeout_seconds = 60);

}  // namespace chaosweep

#pragma once
// What SLURM says about the tasks of a `chaosweep slurm` array: squeue for
// live tasks, sacct for ended ones, `scontrol show job` where sacct has no
// accounting storage. Each client is run by argv (run_argv.hpp) with job ids
// that are digits only; a missing client or a failing one leaves the states
// unknown and says so once (status then goes by the shard locks alone).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace chaosweep {

struct TaskState {
  std::int64_t job = 0;   // the array job id
  std::string state;      // SLURM's word: PENDING, RUNNING, COMPLETED, FAILED, TIMEOUT, CANCELLED, ...
  std::string exit_code;  // "CODE:SIGNAL" when SLURM gave one
};

// PENDING, RUNNING and the other states of a task that has not ended.
bool slurm_state_live(const std::string& state);
bool slurm_state_pending(const std::string& state);

// Task id -> state. A live state outranks an ended one; otherwise the later
// (higher) array job wins (a resubmission after a failure).
using TaskStates = std::map<int, TaskState>;
void merge_task_state(TaskStates& into, int task, const TaskState& s);

// Parsers of each client's output, as status asks for it (tested on the
// forms SLURM prints): squeue -h -r -o '%F|%K|%T', sacct -n -P -X -o
// JobID,State,ExitCode, scontrol -o show job. Lines they cannot read are
// skipped; task ranges ("[0-3,5%2]") are expanded up to `tasks`.
void parse_squeue(const std::string& out, int tasks, TaskStates& into);
void parse_sacct(const std::string& out, int tasks, TaskStates& into);
void parse_scontrol(const std::string& out, int tasks, TaskStates& into);

struct SlurmReport {
  TaskStates tasks;
  std::vector<std::string> notes;  // what could not be asked, once each
};

// Asks the SLURM clients on PATH about `array_jobs` (digits only; others are
// refused with a note).
SlurmReport query_slurm(const std::vector<std::string>& array_jobs, int tasks);

}  // namespace chaosweep

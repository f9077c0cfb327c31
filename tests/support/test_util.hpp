#pragma once
// Shared by the engine, CLI and analysis tests: running the chaosweep binary
// as a user would, and foreign HDF5 files (the kernel-level helpers, which
// the kernel tests use alone, are in kernel_test_util.hpp).
#include <cstdint>
#include <string>

#include "tests/support/kernel_test_util.hpp"

namespace chaosweep::test {

struct CommandResult {
  int exit_code;
  std::string out;  // stdout
  std::string err;  // stderr
};
// Runs the built chaosweep binary with `args` (a shell-quoted string), after
// `prefix` (a wrapper command such as "prlimit --fsize=N", or nothing).
CommandResult run_chaosweep(const std::string& args, const std::string& prefix = "");

// Starts the chaosweep binary with `args` in the background; returns its pid.
int start_chaosweep(const std::string& args);
// Waits for pid; returns its exit code, or 128 + signal. `max_rss_kib`, when
// given, receives the process's peak resident set size.
int wait_exit(int pid, long* max_rss_kib = nullptr);
// Waits until the result file `partial` holds at least `rows` rows (read
// between the writer's writes) or the process has ended (its exit code, as
// wait_exit gives it, in `exit_code`); false then, or on timeout (60 s).
bool wait_for_rows(const std::string& partial, std::int64_t rows, int pid, int* exit_code = nullptr);

// An HDF5 file that is not a chaosweep result file (docs/inputs.md): `what`
// is "no-runs" (a dataset /data only), "other-columns" (/runs of two foreign
// columns) or "not-compound" (/runs of plain integers).
void write_foreign_file(const std::string& path, const std::string& what);

// A spec of 18 cheap runs (3 A x 2 B x 3 DSindex on a 12 m map) named `name`.
std::string small_spec_18_runs(const std::string& name);
// A tune of three cases on 10 m maps: two map-zoning cases racing ds_index
// and c ("open", "box"; budget 80, 6 validation seeds) and one without
// parameters ("plain").
std::string tiny_tune_spec();

}  // namespace chaosweep::test

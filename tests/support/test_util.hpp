#pragma once
// Shared by the test executables: scratch directories, files, and running the
// chaosweep binary as a user would.
#include <filesystem>
#include <ostream>
#include <string>

#include "kernels/core/environment.hpp"
#include "kernels/core/run_params.hpp"

namespace chaosweep {
// GoogleTest prints statuses by name.
inline void PrintTo(Status s, std::ostream* os) { *os << to_string(s); }
}  // namespace chaosweep

namespace chaosweep::test {

// A fresh directory under the system temp dir, removed at scope exit.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

void write_file(const std::string& path, const std::string& text);
std::string read_file(const std::string& path);

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

// A small, fast, valid Arnold run: a `side` m map with 1 m cells.
RunParams small_run(double side = 10.0);

// A square map with the given obstacles.
Environment square_map(double side, std::vector<Rect> obstacles = {});

// An HDF5 file that is not a chaosweep result file (docs/inputs.md): `what`
// is "no-runs" (a dataset /data only), "other-columns" (/runs of two foreign
// columns) or "not-compound" (/runs of plain integers).
void write_foreign_file(const std::string& path, const std::string& what);

}  // namespace chaosweep::test

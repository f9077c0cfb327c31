#pragma once
// The sweeps this user ran (`chaosweep log`): `sweep` appends one line when
// it starts writing and one when it ends, to an append-only file, each line
// one write(2) so that sweeps running at once never interleave. A sweep
// killed by kill -9 leaves only its start line; `log` then asks whether the
// process still lives and what files it left.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace chaosweep {

// $CHAOSWEEP_HISTORY, else $XDG_STATE_HOME/chaosweep/history.tsv, else
// ~/.local/state/chaosweep/history.tsv; empty when none can be named.
std::string history_path();

struct SweepRecord {
  std::string id;  // host:pid:start time in ns, unique per sweep
  std::string host, cwd, spec, out, shard, sets, start_time, end_time;
  std::int64_t pid = 0, runs = 0;  // runs of the shard
  bool resume = false;
  std::optional<int> exit_code;  // none: no end line (running, or killed)
};

// Appends the start line; returns the id for record_sweep_end. A history
// that cannot be written costs the sweep nothing but a warning (unless quiet).
std::string record_sweep_start(const SweepRecord& start, bool quiet);
void record_sweep_end(const std::string& id, int exit_code, bool quiet);

// Every sweep of the file at `path`, oldest first (a line that does not
// parse is skipped: a history is never a reason to fail).
std::vector<SweepRecord> read_history(const std::string& path);

}  // namespace chaosweep

// `chaosweep log`: the sweeps this user ran (apps/chaosweep/sweep_history.hpp),
// newest last, each with what it left: finished, running, resumable, failed.
#include <signal.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "apps/chaosweep/sweep_history.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/provenance.hpp"

namespace chaosweep {

namespace fs = std::filesystem;

namespace {

struct LogFlags {
  int last = 20;
  std::string history;
};

bool is_alive(const SweepRecord& r) {
  if (r.host != host_name() || r.pid <= 0) return false;  // another machine's sweep: its files tell
  if (::kill(pid_t(r.pid), 0) != 0 && errno != EPERM) return false;
  std::ifstream cmd("/proc/" + std::to_string(r.pid) + "/cmdline");
  std::string text((std::istreambuf_iterator<char>(cmd)), std::istreambuf_iterator<char>());
  return text.find("chaosweep") != std::string::npos;  // not a later process that got the pid
}

// What the sweep is now, and the file that holds its rows ("" if none).
std::pair<std::string, std::string> state_of(const SweepRecord& r) {
  const std::string partial = r.out + ".partial";
  const bool has_out = fs::is_regular_file(r.out), has_partial = fs::is_regular_file(partial);
  if (!r.exit_code) {
    if (is_alive(r)) return {"running", has_partial ? partial : ""};
    return {has_partial ? "killed, resumable" : "killed", has_partial ? partial : ""};
  }
  const int code = *r.exit_code;
  if (code == exit_ok) return {has_out ? "finished" : "finished, file gone", has_out ? r.out : ""};
  const std::string why = code == 130              ? "stopped (SIGINT)"
                          : code == 143            ? "stopped (SIGTERM)"
                          : code == exit_bad_input ? "refused (bad input)"
                                                   : "failed (exit " + std::to_string(code) + ")";
  return {has_partial ? why + ", resumable" : why, has_partial ? partial : ""};
}

// "115 ok of 280" for a finished file, "40 ok, 100 of 280 done" for a partial one.
std::string runs_of(const SweepRecord& r, const std::string& file) {
  if (file.empty()) return "- of " + std::to_string(r.runs);
  try {
    const auto status = read_text_column(file, "status");
    const auto ok = std::count(status.begin(), status.end(), "ok");
    if (std::int64_t(status.size()) == r.runs) return std::to_string(ok) + " ok of " + std::to_string(r.runs);
    return std::to_string(ok) + " ok, " + std::to_string(status.size()) + " of " + std::to_string(r.runs) + " done";
  } catch (const std::exception&) {
    return "unreadable";  // e.g. a write session held for long; the next log reads it
  }
}

// `text` padded to `width`, and two spaces: a long cell never runs into the next.
std::string cell(const std::string& text, std::size_t width) {
  return text + std::string(text.size() < width ? width - text.size() : 0, ' ') + "  ";
}

int log_command(const LogFlags& o) {
  const std::string path = o.history.empty() ? history_path() : o.history;
  if (path.empty()) {
    std::cerr << "chaosweep log: no history file: set CHAOSWEEP_HISTORY, XDG_STATE_HOME or HOME\n";
    return exit_bad_input;
  }
  if (!fs::exists(path)) {
    std::cout << "no sweeps recorded yet (" << path << ")\n";
    return exit_ok;
  }
  if (!fs::is_regular_file(path)) {
    std::cerr << "chaosweep log: " << path << " is not a regular file\n";
    return exit_bad_input;
  }
  const auto records = read_history(path);
  const std::size_t from = records.size() > std::size_t(o.last) ? records.size() - std::size_t(o.last) : 0;
  std::cout << cell("started", 20) << cell("ended", 20) << cell("state", 26) << cell("runs", 26) << "output <- spec\n";
  for (std::size_t k = from; k < records.size(); ++k) {
    const SweepRecord& r = records[k];
    const auto [state, file] = state_of(r);
    std::string what = r.out + " <- " + r.spec;
    if (r.shard != "0/1") what += " --shard " + r.shard;
    if (!r.sets.empty()) what += r.sets;
    if (r.resume) what += " --resume";
    std::cout << cell(r.start_time, 20) << cell(r.end_time.empty() ? "-" : r.end_time, 20) << cell(state, 26)
              << cell(runs_of(r, file), 26) << what << "\n";
  }
  if (from > 0) std::cout << "(" << from << " earlier sweeps; --last N shows more)\n";
  return exit_ok;
}

}  // namespace

void add_log_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("log", "List the sweeps this user ran: spec, output, start and end, runs, state");
  cmd->footer(
      "Every `chaosweep sweep` that starts writing records itself in the history file\n"
      "($CHAOSWEEP_HISTORY, else $XDG_STATE_HOME/chaosweep/history.tsv, else\n"
      "~/.local/state/chaosweep/history.tsv). The state is read now: finished, running (the\n"
      "process lives), stopped/failed/killed and resumable when OUT.partial is there; the runs\n"
      "column counts the rows of OUT or OUT.partial.");
  auto o = std::make_shared<LogFlags>();
  cmd->add_option("--last", o->last, "show the last N sweeps")->check(CLI::Range(1, 1000000));
  cmd->add_option("--history", o->history, "read this history file instead");
  cmd->callback([o, &action] { action = [o] { return log_command(*o); }; });
}

}  // namespace chaosweep

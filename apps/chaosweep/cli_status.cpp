// `chaosweep status DIR`: which shards of a `chaosweep slurm` directory are
// finished, running, pending, partial, missing or damaged, and which to
// resubmit. A shard is live (not resubmitted) when its output lock is held or
// SLURM says its task is pending or running; a dead one is named with why.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "apps/chaosweep/slurm_query.hpp"
#include "apps/chaosweep/slurm_values.hpp"
#include "engine/spec/shard.hpp"
#include "engine/store/h5_merge.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/output_lock.hpp"
#include "engine/store/slurm_dir.hpp"

namespace chaosweep {

namespace fs = std::filesystem;

namespace {

// The shards of a plan by state, with a line per shard worth a word.
struct ShardCensus {
  std::vector<int> finished, running, pending, failed, partial, missing, damaged;
  std::string running_detail, pending_detail, failed_detail, detail, missing_detail, broken;
  std::map<int, std::string> identity;  // of each readable shard file: its spec_hash and inputs_hash
};

// What is known of a shard's writer: its lock and SLURM's word on its task.
struct Writer {
  LockProbe lock;
  const TaskState* task = nullptr;  // null: SLURM not asked, or it knows no such task
};

// What merge compares between shards, as check_shard_file returns it (an
// older file without inputs_hash: "").
std::string identity_of(const std::string& path) {
  try {
    return read_attribute(path, "spec_hash") + "\t" +
           (has_attribute(path, "inputs_hash") ? read_attribute(path, "inputs_hash") : std::string());
  } catch (const std::exception&) {
    return "\t";
  }
}

// The rows of a shard file, or -1 with the reason in `why` when it cannot be
// read (a damaged file: listed, and resubmitted once moved away).
std::int64_t rows_of(const std::string& path, std::string& why) {
  try {
    return count_rows(path);
  } catch (const std::exception& e) {
    why = e.what();
    return -1;
  }
}

// "job 123_4 FAILED (exit 1:0)"; a live task has no exit code yet.
std::string job_words(const TaskState& t, int k) {
  return "job " + std::to_string(t.job) + "_" + std::to_string(k) + " " + t.state +
         (t.exit_code.empty() || slurm_state_live(t.state) ? "" : " (exit " + t.exit_code + ")");
}

// Why a shard that is not finished has no live writer.
std::string dead_reason(const Writer& w, int k) {
  if (!w.task) return "no job and no lock";
  return job_words(*w.task, k) + ", no lock";
}

// A live writer's line: SLURM's word and the lock's holder.
std::string live_words(const Writer& w, int k) {
  std::string s;
  if (w.task) s = job_words(*w.task, k);
  if (w.lock.held) s += (s.empty() ? "" : ", ") + std::string("written by ") + printable(w.lock.holder);
  return s;
}

void count_shard(ShardCensus& c, const std::string& dir, const ClusterPlan& plan, int k, const Writer& w) {
  const fs::path file = shard_file(dir, k);
  const std::string part = file.string() + ".partial";
  const std::int64_t want = shard_size(plan.runs, k, plan.tasks);
  std::error_code ec;
  std::string why;
  const std::string name = "  shard " + std::to_string(k) + ": ";
  const bool live = w.lock.held || (w.task && slurm_state_live(w.task->state));
  if (fs::exists(fs::symlink_status(file, ec)) && plan.tune) {
    // A tune shard's rows are not known ahead: finished when its tune was.
    try {
      c.identity[k] = check_tune_shard_file(file.string(), k, plan.tasks);
      c.finished.push_back(k);
    } catch (const std::exception& e) {
      c.damaged.push_back(k);
      c.broken += name + e.what() + "; remove it, then resubmit\n";
    }
    return;
  }
  if (fs::exists(fs::symlink_status(file, ec))) {
    std::int64_t have = rows_of(file.string(), why);
    if (have == want) {
      // Its attributes and columns as merge checks them (not its rows: that
      // is merge's pass over the sweep): a file of another sweep is damaged.
      try {
        c.identity[k] = check_shard_file(file.string(), k, plan.tasks, plan.runs);
        c.finished.push_back(k);
        return;
      } catch (const std::exception& e) {
        why = e.what();
        have = -1;
      }
    }
    c.damaged.push_back(k);
    c.broken +=
        name +
        (have < 0 ? why : file.string() + " holds " + std::to_string(have) + " rows, not " + std::to_string(want)) +
        "; remove it, then resubmit\n";
    return;
  }
  const bool has_part = fs::exists(fs::symlink_status(part, ec));
  const std::int64_t have = has_part ? rows_of(part, why) : 0;
  if (has_part && have < 0 && !live) {
    c.damaged.push_back(k);
    c.broken += name + why + "; remove it, then resubmit\n";
    return;
  }
  const std::string rows = !has_part || have < 0 ? ""
                           : plan.tune           ? std::to_string(have) + " runs"
                                                 : std::to_string(have) + " of " + std::to_string(want) + " runs";
  if (live) {
    // A held lock is a writer at work whatever SLURM says; SLURM's pending
    // is a task not started (or requeued) yet.
    const bool pending = !w.lock.held && slurm_state_pending(w.task->state);
    (pending ? c.pending : c.running).push_back(k);
    if (!pending || has_part)
      (pending ? c.pending_detail : c.running_detail) +=
          name + (rows.empty() ? "" : rows + ", ") + live_words(w, k) + "\n";
  } else if (w.task && w.task->state != "COMPLETED") {
    // SLURM says its task ended otherwise than completed (FAILED, TIMEOUT,
    // CANCELLED, OUT_OF_MEMORY, ...): failed, with the rows it left.
    c.failed.push_back(k);
    if (has_part) c.identity[k] = identity_of(part);
    c.failed_detail += name + (rows.empty() ? "no rows" : rows) + "; " + dead_reason(w, k) + "\n";
  } else if (has_part) {
    c.partial.push_back(k);
    c.identity[k] = identity_of(part);
    c.detail += name + rows + "; " + dead_reason(w, k) + "\n";
  } else {
    c.missing.push_back(k);
    if (w.task) c.missing_detail += name + dead_reason(w, k) + "\n";
  }
}

// Shards whose spec_hash or inputs_hash differ from most shards' are of
// another spec or other environment files (merge refuses to mix them):
// damaged, to be removed and resubmitted.
void check_same_sweep(ShardCensus& c, const std::string& dir) {
  std::map<std::string, int> votes;
  for (const auto& [k, id] : c.identity) ++votes[id];
  if (votes.size() < 2) return;
  const auto most = std::max_element(votes.begin(), votes.end(), [](const auto& a, const auto& b) {
                      return a.second < b.second;
                    })->first;
  for (const auto& [k, id] : c.identity) {
    if (id == most) continue;
    for (auto* v : {&c.finished, &c.failed, &c.partial}) std::erase(*v, k);
    c.damaged.push_back(k);
    const bool finished = fs::exists(shard_file(dir, k));
    c.broken += "  shard " + std::to_string(k) + ": " + shard_file(dir, k).string() + (finished ? "" : ".partial") +
                " was made from another spec or other input files than most shards (merge would refuse it); "
                "remove it, then resubmit\n";
  }
  std::sort(c.damaged.begin(), c.damaged.end());
}

std::string list(const std::vector<int>& v) {
  std::string s;
  for (int k : v) s += (s.empty() ? "" : ",") + std::to_string(k);
  return s.empty() ? std::string("-") : s;
}

// Prints the census; exit 0 when every shard is finished, 1 otherwise.
int report(const ShardCensus& c, const ClusterPlan& plan, const std::string& dir) {
  std::cout << "finished " << c.finished.size() << ": " << list(c.finished) << "\n"
            << "running  " << c.running.size() << ": " << list(c.running) << "\n"
            << c.running_detail << "pending  " << c.pending.size() << ": " << list(c.pending) << "\n"
            << c.pending_detail << "failed   " << c.failed.size() << ": " << list(c.failed) << "\n"
            << c.failed_detail << "partial  " << c.partial.size() << ": " << list(c.partial) << "\n"
            << c.detail << "missing  " << c.missing.size() << ": " << list(c.missing) << "\n"
            << c.missing_detail;
  if (!c.damaged.empty()) std::cout << "damaged  " << c.damaged.size() << ": " << list(c.damaged) << "\n" << c.broken;
  std::vector<int> redo = c.partial;
  redo.insert(redo.end(), c.failed.begin(), c.failed.end());
  redo.insert(redo.end(), c.missing.begin(), c.missing.end());
  redo.insert(redo.end(), c.damaged.begin(), c.damaged.end());
  std::sort(redo.begin(), redo.end());
  if (int(c.finished.size()) == plan.tasks) {
    std::cout << "all shards finished; merge: sbatch " << (fs::path(dir) / "merge.sbatch").string() << "\n";
    return exit_ok;
  }
  if (redo.empty()) {
    std::cout << "nothing to resubmit: every shard not finished has a live task\n";
    return 1;
  }
  std::cout << "resubmit: --array=" << list(redo) << "\n  sbatch --array=" << list(redo) << " "
            << (fs::path(dir) / "sweep.sbatch").string() << "\n";
  return 1;
}

// SLURM's word on the tasks, or nothing (with the reason, said once).
SlurmReport ask_slurm(const std::string& dir, int tasks) {
  const std::vector<std::string> jobs = recorded_array_jobs(dir, tasks);
  if (jobs.empty()) {
    SlurmReport none;
    none.notes.push_back("no SLURM job recorded in " + (fs::path(dir) / "jobs.txt").string() +
                         " (written by chaosweep slurm --submit): states from the shard locks only");
    return none;
  }
  std::cout << "SLURM array job" << (jobs.size() > 1 ? "s" : "") << ":";
  for (const std::string& j : jobs) std::cout << " " << printable(j);
  std::cout << "\n";
  return query_slurm(jobs, tasks);
}

int run_status(const std::string& dir) {
  try {
    const ClusterPlan plan = read_cluster_plan(dir);
    std::cout << (plan.tune ? "tune '" : "sweep '") << plan.name << "': " << plan.tasks << " shards, "
              << (plan.tune ? "at most " : "") << plan.runs << " runs\n";
    const SlurmReport slurm = ask_slurm(dir, plan.tasks);
    for (const std::string& n : slurm.notes) std::cout << "note: " << n << "\n";
    ShardCensus census;
    for (int k = 0; k < plan.tasks; ++k) {
      Writer w{probe_output_lock(shard_file(dir, k).string()), nullptr};
      if (const auto it = slurm.tasks.find(k); it != slurm.tasks.end()) w.task = &it->second;
      count_shard(census, dir, plan, k, w);
    }
    check_same_sweep(census, dir);
    return report(census, plan, dir);
  } catch (const std::exception& e) {
    std::cerr << "chaosweep status: " << e.what() << "\n";
    return exit_bad_input;
  }
}

}  // namespace

void add_status_command(CLI::App& app, std::function<int()>& action) {
  auto* st = app.add_subcommand(
      "status",
      "Which shards of a `chaosweep slurm` directory are finished, running, pending, failed, partial or missing");
  st->footer(
      "Prints one line per shard state and the --array= list of the shards to resubmit: failed\n"
      "(SLURM says its task ended otherwise than COMPLETED: FAILED, TIMEOUT, CANCELLED, ...),\n"
      "partial, missing or damaged (a shard file that cannot be read, or that merge would refuse\n"
      "as another shard's, another sweep's or another spec's file, named with the reason; remove\n"
      "it before resubmitting): sbatch --array=LIST DIR/sweep.sbatch. A shard whose output lock is\n"
      "held, or whose task SLURM (squeue; sacct, or scontrol without accounting) reports pending or\n"
      "running, is live and not resubmitted; a dead one is named with its job's state and exit code,\n"
      "or 'no job and no lock'. Without squeue on PATH, or jobs recorded by --submit, the locks\n"
      "alone decide (said once). Exit 0 when every shard is finished, 1 otherwise.");
  auto dir = std::make_shared<std::string>();
  st->add_option("dir", *dir, "directory written by chaosweep slurm")->required()->check(CLI::ExistingDirectory);
  st->callback([dir, &action] { action = [dir] { return run_status(*dir); }; });
}

}  // namespace chaosweep

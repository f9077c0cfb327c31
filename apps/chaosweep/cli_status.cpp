// `chaosweep status DIR`: which shards of a `chaosweep slurm` directory are
// finished, partial, missing or damaged, and which to resubmit.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "engine/spec/shard.hpp"
#include "engine/store/h5_merge.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/slurm_dir.hpp"

namespace chaosweep {

namespace fs = std::filesystem;

namespace {

// The shards of a plan by state, with a line per partial and damaged shard.
struct ShardCensus {
  std::vector<int> finished, partial, missing, damaged;
  std::string detail, broken;
  std::map<int, std::string> identity;  // of each readable shard file: its spec_hash and inputs_hash
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

void count_shard(ShardCensus& c, const std::string& dir, const ClusterPlan& plan, int k) {
  const fs::path file = shard_file(dir, k);
  const std::string part = file.string() + ".partial";
  const std::int64_t want = shard_size(plan.runs, k, plan.tasks);
  std::error_code ec;
  std::string why;
  const std::string name = "  shard " + std::to_string(k) + ": ";
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
  } else if (fs::exists(fs::symlink_status(part, ec))) {
    const std::int64_t have = rows_of(part, why);
    if (have < 0) {
      c.damaged.push_back(k);
      c.broken += name + why + "; remove it, then resubmit\n";
      return;
    }
    c.partial.push_back(k);
    c.identity[k] = identity_of(part);
    c.detail += name + std::to_string(have) + " of " + std::to_string(want) + " runs\n";
  } else {
    c.missing.push_back(k);
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
    for (auto* v : {&c.finished, &c.partial}) std::erase(*v, k);
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
  std::cout << "sweep '" << plan.name << "': " << plan.tasks << " shards, " << plan.runs << " runs\n"
            << "finished " << c.finished.size() << ": " << list(c.finished) << "\n"
            << "partial  " << c.partial.size() << ": " << list(c.partial) << "\n"
            << c.detail << "missing  " << c.missing.size() << ": " << list(c.missing) << "\n";
  if (!c.damaged.empty()) std::cout << "damaged  " << c.damaged.size() << ": " << list(c.damaged) << "\n" << c.broken;
  std::vector<int> redo = c.partial;
  redo.insert(redo.end(), c.missing.begin(), c.missing.end());
  redo.insert(redo.end(), c.damaged.begin(), c.damaged.end());
  std::sort(redo.begin(), redo.end());
  if (redo.empty()) {
    std::cout << "all shards finished; merge: sbatch " << (fs::path(dir) / "merge.sbatch").string() << "\n";
    return exit_ok;
  }
  std::cout << "resubmit: --array=" << list(redo) << "\n  sbatch --array=" << list(redo) << " "
            << (fs::path(dir) / "sweep.sbatch").string() << "\n";
  return 1;
}

int run_status(const std::string& dir) {
  try {
    const ClusterPlan plan = read_cluster_plan(dir);
    ShardCensus census;
    for (int k = 0; k < plan.tasks; ++k) count_shard(census, dir, plan, k);
    check_same_sweep(census, dir);
    return report(census, plan, dir);
  } catch (const std::exception& e) {
    std::cerr << "chaosweep status: " << e.what() << "\n";
    return exit_bad_input;
  }
}

}  // namespace

void add_status_command(CLI::App& app, std::function<int()>& action) {
  auto* st =
      app.add_subcommand("status", "Which shards of a `chaosweep slurm` directory are finished, partial or missing");
  st->footer(
      "Prints one line per shard state and the --array= list of the shards to resubmit\n"
      "(partial, missing or damaged: a shard file that cannot be read, or that merge would refuse\n"
      "as another shard's, another sweep's or another spec's file -- named with the reason;\n"
      "remove it before resubmitting): sbatch --array=LIST DIR/sweep.sbatch. Exit 0 when every\n"
      "shard is finished, 1 otherwise.");
  auto dir = std::make_shared<std::string>();
  st->add_option("dir", *dir, "directory written by chaosweep slurm")->required()->check(CLI::ExistingDirectory);
  st->callback([dir, &action] { action = [dir] { return run_status(*dir); }; });
}

}  // namespace chaosweep

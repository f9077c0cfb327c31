#pragma once
// The directory `chaosweep slurm -o DIR` writes: its cluster.toml (which spec,
// how many tasks) and the shard files DIR/shard_K.h5 the tasks write. Read by
// `chaosweep status DIR` and `chaosweep merge --slurm-dir DIR`.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace chaosweep {

struct ClusterPlan {
  std::string spec, name;  // the spec's absolute path and its name
  int tasks = 1;
  std::int64_t runs = 0;  // a tune's: at most so many (its rows are not known ahead)
  bool tune = false;      // a tune's shards (`chaosweep tune --shard`), not a sweep's
};

// Throws std::runtime_error naming DIR/cluster.toml when it is missing or bad.
ClusterPlan read_cluster_plan(const std::filesystem::path& dir);
void write_cluster_plan(const std::filesystem::path& dir, const ClusterPlan& plan);

// DIR/shard_K.h5
std::filesystem::path shard_file(const std::filesystem::path& dir, int k);

// The shard files of DIR's plan that exist, in task order (merge reads them
// from here rather than from a command line, which 1e5 paths would overflow).
std::vector<std::string> existing_shard_files(const std::filesystem::path& dir);

// DIR/jobs.txt: a line "array ID" / "merge ID" per job `chaosweep slurm
// --submit` submitted (appended: a --force resubmission adds its own), and
// DIR/logs/task_K.job: the array job id task K last ran under (its script
// writes it, so a resubmission with plain sbatch is known too).
void record_submitted_job(const std::filesystem::path& dir, const std::string& kind, const std::string& id);
// Every array job id of those files, each once, as written (status checks
// that each is a number before it goes into a command line).
std::vector<std::string> recorded_array_jobs(const std::filesystem::path& dir, int tasks);

}  // namespace chaosweep

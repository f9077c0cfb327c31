#include "engine/store/slurm_dir.hpp"

#include <algorithm>
#include <fstream>
#include <stdexcept>

#include "engine/spec/input_file.hpp"
#include "engine/spec/toml.hpp"

namespace chaosweep {

namespace fs = std::filesystem;

ClusterPlan read_cluster_plan(const fs::path& dir) {
  const fs::path file = dir / "cluster.toml";
  if (!fs::exists(file))
    throw std::runtime_error(dir.string() + " has no cluster.toml: not written by chaosweep slurm");
  // A regular file of bounded size only (a FIFO in its place blocked status
  // and merge --slurm-dir forever).
  std::string text;
  try {
    text = read_input_file(file.string(), "the sweep's cluster.toml");
  } catch (const InputFileError& e) {
    throw std::runtime_error(e.what());
  }
  check_toml_text(text);
  const toml::table t = toml::parse(text, file.string());
  ClusterPlan p;
  p.spec = t["spec"].value_or(std::string());
  p.name = t["name"].value_or(std::string());
  const std::int64_t tasks = t["tasks"].value_or(std::int64_t(0));
  p.runs = t["runs"].value_or(std::int64_t(0));
  const std::string kind = t["kind"].value_or(std::string("sweep"));
  if (kind != "sweep" && kind != "tune")
    throw std::runtime_error(file.string() + ": 'kind' must be \"sweep\" or \"tune\", not \"" + kind + "\"");
  p.tune = kind == "tune";
  // chaosweep slurm writes 1 <= tasks <= runs, at most 1e6.
  if (tasks < 1 || tasks > 1000000)
    throw std::runtime_error(file.string() + ": 'tasks' must be in [1, 1000000], not " + std::to_string(tasks));
  if (p.runs < 1 || p.runs > (std::int64_t(1) << 62))
    throw std::runtime_error(file.string() + ": 'runs' must be a run count in [1, 2^62], not " +
                             std::to_string(p.runs));
  p.tasks = int(tasks);
  return p;
}

void write_cluster_plan(const fs::path& dir, const ClusterPlan& plan) {
  // toml++ writes the strings escaped, whatever characters a path or name holds.
  const toml::table t{{"spec", plan.spec},
                      {"name", plan.name},
                      {"kind", plan.tune ? "tune" : "sweep"},
                      {"tasks", plan.tasks},
                      {"runs", plan.runs}};
  std::ofstream out(dir / "cluster.toml");
  out << "# written by chaosweep slurm; read by chaosweep status and chaosweep merge --slurm-dir\n" << t << "\n";
  out.close();
  if (!out) throw std::runtime_error("cannot write " + (dir / "cluster.toml").string());
}

fs::path shard_file(const fs::path& dir, int k) { return dir / ("shard_" + std::to_string(k) + ".h5"); }

std::vector<std::string> existing_shard_files(const fs::path& dir) {
  const ClusterPlan plan = read_cluster_plan(dir);
  std::vector<std::string> files;
  for (int k = 0; k < plan.tasks; ++k)
    if (const fs::path f = shard_file(dir, k); fs::exists(f)) files.push_back(f.string());
  return files;
}

void record_submitted_job(const fs::path& dir, const std::string& kind, const std::string& id) {
  std::ofstream out(dir / "jobs.txt", std::ios::app);
  out << kind << " " << id << "\n";
  out.close();
  if (!out) throw std::runtime_error("cannot write " + (dir / "jobs.txt").string());
}

std::vector<std::string> recorded_array_jobs(const fs::path& dir, int tasks) {
  std::vector<std::string> ids;
  const auto add = [&ids](const std::string& id) {
    if (!id.empty() && std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
  };
  // Regular files only: a FIFO in a file's place must not hang status.
  std::error_code ec;
  const auto regular = [&ec](const fs::path& p) { return fs::is_regular_file(fs::symlink_status(p, ec)); };
  std::ifstream jobs;
  if (regular(dir / "jobs.txt")) jobs.open(dir / "jobs.txt");
  for (std::string kind, id; jobs >> kind >> id;)
    if (kind == "array") add(id);
  for (int k = 0; k < tasks; ++k) {
    const fs::path file = dir / "logs" / ("task_" + std::to_string(k) + ".job");
    if (!regular(file)) continue;
    std::ifstream task(file);
    std::string id;
    if (task >> id) add(id);
  }
  return ids;
}

}  // namespace chaosweep

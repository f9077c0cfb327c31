// `chaosweep slurm` (job scripts for a SLURM array, optionally submitted) and
// `chaosweep status DIR` (which shards are done, which to resubmit).
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include "toml.hpp"

#include "cli_common.hpp"
#include "cli_subcommands.hpp"
#include "h5_store.hpp"
#include "sweep_runner.hpp"

namespace chaosweep {

namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw std::runtime_error("cannot read " + p.string());
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void replace_all(std::string& s, const std::string& key, const std::string& value) {
  for (std::size_t pos = 0; (pos = s.find(key, pos)) != std::string::npos; pos += value.size())
    s.replace(pos, key.size(), value);
}

std::string self_path() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? "chaosweep" : p.string();
}

// Runs a command, returning its stdout and exit status.
std::pair<int, std::string> capture(const std::string& cmd) {
  std::string out;
  FILE* f = popen(cmd.c_str(), "r");
  if (!f) return {-1, out};
  char buf[256];
  while (std::fgets(buf, sizeof buf, f)) out += buf;
  const int rc = pclose(f);
  return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, out};
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct ClusterPlan {
  std::string spec, name;
  int tasks = 1;
  std::int64_t runs = 0;
};

ClusterPlan read_plan(const fs::path& dir) {
  const fs::path file = dir / "cluster.toml";
  if (!fs::exists(file)) throw std::runtime_error(dir.string() + " has no cluster.toml: not written by chaosweep slurm");
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  check_toml_text(text.str());
  const toml::table t = toml::parse(text.str(), file.string());
  ClusterPlan p;
  p.spec = t["spec"].value_or(std::string());
  p.name = t["name"].value_or(std::string());
  p.tasks = int(t["tasks"].value_or(0));
  p.runs = t["runs"].value_or(std::int64_t(0));
  if (p.tasks < 1) throw std::runtime_error(file.string() + ": 'tasks' must be >= 1");
  return p;
}

// Writes `text` to `path`, throwing when the file cannot be written in full.
void write_checked(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace

void add_slurm_commands(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("slurm", "Write (and optionally submit) a SLURM job array that runs a sweep in shards");
  cmd->footer(
      "Writes DIR/sweep.sbatch (one shard per array task, --array=0-(N-1)[%M], logs in DIR/logs),\n"
      "DIR/merge.sbatch (merges DIR/shard_*.h5 into DIR/results.h5) and DIR/cluster.toml (for\n"
      "`chaosweep status`). With --submit, calls sbatch for both, the merge job with\n"
      "--dependency=afterok on the array. Example:\n"
      "  chaosweep slurm experiments/fig6.toml --tasks 16 --concurrency 8 -o runs/fig6 --submit");
  struct Opts {
    std::string spec, dir, partition, time, mem;
    int tasks = 0, concurrency = 0, cpus = 1;
    bool submit = false, force = false;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("spec", o->spec, "sweep spec (TOML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--tasks", o->tasks, "array tasks = shards")->required()->check(CLI::Range(1, 1000000));
  cmd->add_option("-o,--dir", o->dir, "directory for scripts, logs and results")->required();
  cmd->add_option("--concurrency", o->concurrency, "at most M tasks at once (--array=...%M)")->check(CLI::Range(0, 1000000));
  cmd->add_option("--cpus", o->cpus, "cpus per task (the sweep's --threads)")->check(CLI::Range(1, 4096));
  cmd->add_option("--partition", o->partition, "sbatch --partition");
  cmd->add_option("--time", o->time, "sbatch --time");
  cmd->add_option("--mem", o->mem, "sbatch --mem");
  cmd->add_flag("--submit", o->submit, "submit with sbatch (array, then the dependent merge job)");
  cmd->add_flag("--force", o->force, "write over the scripts of an earlier `chaosweep slurm` in DIR");
  cmd->callback([o, &action] {
    action = [o]() -> int {
      SweepSpec spec;
      try {
        spec = load_sweep_spec(o->spec);
        if (!o->force && fs::exists(fs::path(o->dir) / "cluster.toml"))
          throw OutputExists("-o: " + o->dir + " already holds a chaosweep slurm sweep (cluster.toml); pass --force "
                             "to write over its scripts (its shard files stay)");
      } catch (const std::exception& e) {
        std::cerr << "chaosweep slurm: " << e.what() << "\n";
        return exit_bad_input;
      }
      try {
        const fs::path dir = fs::absolute(o->dir);
        fs::create_directories(dir / "logs");
        const std::string src = CHAOSWEEP_SOURCE_DIR "/cluster/";
        std::string extra;
        if (!o->partition.empty()) extra += "#SBATCH --partition=" + o->partition + "\n";
        if (!o->time.empty()) extra += "#SBATCH --time=" + o->time + "\n";
        if (!o->mem.empty()) extra += "#SBATCH --mem=" + o->mem + "\n";
        std::string shards;
        for (int k = 0; k < o->tasks; ++k) shards += " \"" + (dir / ("shard_" + std::to_string(k) + ".h5")).string() + "\"";
        const std::string array =
            "0-" + std::to_string(o->tasks - 1) + (o->concurrency > 0 ? "%" + std::to_string(o->concurrency) : "");
        for (const char* name : {"sweep", "merge"}) {
          std::string text = read_text(src + name + ".sbatch.in");
          replace_all(text, "@JOB_NAME@", "chaosweep-" + spec.name);
          replace_all(text, "@ARRAY@", array);
          replace_all(text, "@DIR@", dir.string());
          replace_all(text, "@CPUS@", std::to_string(o->cpus));
          replace_all(text, "@EXTRA@\n", extra);
          replace_all(text, "@CHAOSWEEP@", self_path());
          replace_all(text, "@SPEC@", fs::absolute(o->spec).string());
          replace_all(text, "@TASKS@", std::to_string(o->tasks));
          replace_all(text, "@SHARDS@", shards);
          const fs::path out = dir / (std::string(name) + ".sbatch");
          write_checked(out, text);
          fs::permissions(out, fs::perms::owner_exec, fs::perm_options::add);
        }
        write_checked(dir / "cluster.toml", "# written by chaosweep slurm; read by chaosweep status\n"
                                            "spec = " + quote(fs::absolute(o->spec).string()) + "\n" +
                                            "name = " + quote(spec.name) + "\n" +
                                            "tasks = " + std::to_string(o->tasks) + "\nruns = " +
                                            std::to_string(spec.size()) + "\n");
        std::cout << "wrote " << (dir / "sweep.sbatch").string() << " (" << spec.size() << " runs in " << o->tasks
                  << " shards, --array=" << array << ") and " << (dir / "merge.sbatch").string() << "\n";
        if (!o->submit) return exit_ok;
        const auto [rc, id] = capture("sbatch --parsable " + quote((dir / "sweep.sbatch").string()));
        const std::string job = id.substr(0, id.find_first_of(";\n"));
        if (rc != 0 || job.empty()) throw std::runtime_error("sbatch failed for the array job");
        const auto [rc2, id2] = capture("sbatch --parsable --dependency=afterok:" + job + " " +
                                        quote((dir / "merge.sbatch").string()));
        const std::string merge_job = id2.substr(0, id2.find_first_of(";\n"));
        if (rc2 != 0 || merge_job.empty()) throw std::runtime_error("sbatch failed for the merge job");
        std::cout << "submitted array job " << job << " and merge job " << merge_job << "\n";
        return exit_ok;
      } catch (const std::exception& e) {
        std::cerr << "chaosweep slurm: " << e.what() << "\n";
        return exit_failure;
      }
    };
  });

  auto* st = app.add_subcommand("status", "Which shards of a `chaosweep slurm` directory are finished, partial or missing");
  st->footer(
      "Prints one line per shard state and the --array= list of the shards to resubmit\n"
      "(partial, missing or damaged: a shard file that cannot be read, named with the reason;\n"
      "remove it before resubmitting): sbatch --array=LIST DIR/sweep.sbatch. Exit 0 when every\n"
      "shard is finished, 1 otherwise.");
  auto dir = std::make_shared<std::string>();
  st->add_option("dir", *dir, "directory written by chaosweep slurm")->required()->check(CLI::ExistingDirectory);
  st->callback([dir, &action] {
    action = [dir]() -> int {
      try {
        const ClusterPlan plan = read_plan(*dir);
        std::vector<int> finished, partial, missing, damaged;
        std::string detail, broken;
        for (int k = 0; k < plan.tasks; ++k) {
          const fs::path file = fs::path(*dir) / ("shard_" + std::to_string(k) + ".h5");
          const std::string part = file.string() + ".partial";
          const std::int64_t want = shard_size(plan.runs, k, plan.tasks);
          std::error_code ec;
          // A file that cannot be read is damaged: listed, and resubmitted once moved away.
          std::string why;
          auto rows_of = [&](const std::string& p) -> std::int64_t {
            try {
              return count_rows(p);
            } catch (const std::exception& e) {
              why = e.what();
              return -1;
            }
          };
          const std::string name = "  shard " + std::to_string(k) + ": ";
          if (fs::exists(fs::symlink_status(file, ec))) {
            const std::int64_t have = rows_of(file.string());
            if (have == want) {
              finished.push_back(k);
              continue;
            }
            damaged.push_back(k);
            broken += name + (have < 0 ? why : file.string() + " holds " + std::to_string(have) + " rows, not " +
                                                   std::to_string(want)) +
                      "; remove it, then resubmit\n";
          } else if (fs::exists(fs::symlink_status(part, ec))) {
            const std::int64_t have = rows_of(part);
            if (have < 0) {
              damaged.push_back(k);
              broken += name + why + "; remove it, then resubmit\n";
              continue;
            }
            partial.push_back(k);
            detail += name + std::to_string(have) + " of " + std::to_string(want) + " runs\n";
          } else {
            missing.push_back(k);
          }
        }
        auto list = [](const std::vector<int>& v) {
          std::string s;
          for (int k : v) s += (s.empty() ? "" : ",") + std::to_string(k);
          return s.empty() ? std::string("-") : s;
        };
        std::cout << "sweep '" << plan.name << "': " << plan.tasks << " shards, " << plan.runs << " runs\n"
                  << "finished " << finished.size() << ": " << list(finished) << "\n"
                  << "partial  " << partial.size() << ": " << list(partial) << "\n" << detail
                  << "missing  " << missing.size() << ": " << list(missing) << "\n";
        if (!damaged.empty()) std::cout << "damaged  " << damaged.size() << ": " << list(damaged) << "\n" << broken;
        std::vector<int> redo = partial;
        redo.insert(redo.end(), missing.begin(), missing.end());
        redo.insert(redo.end(), damaged.begin(), damaged.end());
        std::sort(redo.begin(), redo.end());
        if (redo.empty()) {
          std::cout << "all shards finished; merge: sbatch " << (fs::path(*dir) / "merge.sbatch").string() << "\n";
          return exit_ok;
        }
        std::cout << "resubmit: --array=" << list(redo) << "\n  sbatch --array=" << list(redo) << " "
                  << (fs::path(*dir) / "sweep.sbatch").string() << "\n";
        return 1;
      } catch (const std::exception& e) {
        std::cerr << "chaosweep status: " << e.what() << "\n";
        return exit_bad_input;
      }
    };
  });
}

}  // namespace chaosweep

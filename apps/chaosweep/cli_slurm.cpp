// `chaosweep slurm` (job scripts for a SLURM array, optionally submitted) and
// `chaosweep status DIR` (which shards are done, which to resubmit).
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string_view>

#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "engine/spec/embedded_files.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/slurm_dir.hpp"
#include "apps/chaosweep/slurm_values.hpp"
#include "engine/run/sweep_runner.hpp"

namespace chaosweep {

namespace fs = std::filesystem;

namespace {

// Replaces every @KEY@ of `text` in one pass (so a value holding "@SPEC@" is
// not replaced again); an unknown key is an error in the template.
std::string fill_template(std::string_view text, const std::map<std::string, std::string>& values) {
  std::string out;
  for (std::size_t pos = 0;;) {
    const std::size_t at = text.find('@', pos);
    if (at == std::string_view::npos) return out.append(text.substr(pos));
    const std::size_t end = text.find('@', at + 1);
    if (end == std::string_view::npos) throw std::runtime_error("job template: unpaired '@'");
    const auto it = values.find(std::string(text.substr(at + 1, end - at - 1)));
    if (it == values.end()) throw std::runtime_error("job template: unknown key " + std::string(text.substr(at, end - at + 1)));
    out.append(text.substr(pos, at - pos)).append(it->second);
    pos = end + 1;
  }
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

// The job id `sbatch --parsable` printed ("ID" or "ID;CLUSTER"); it goes into
// the next sbatch command line, so it must be digits.
std::string job_id(const std::string& parsable) {
  const std::string id = parsable.substr(0, parsable.find_first_of(";\n"));
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw std::runtime_error("sbatch printed '" + printable(parsable) + "', not a job id");
  return id;
}

// Writes `text` to `path`, throwing when the file cannot be written in full.
void write_checked(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

// Bad input: a value that cannot go into a job script (exit 2).
struct BadSlurmValue : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void require(const std::string& flag, const std::optional<std::string>& problem) {
  if (problem) throw BadSlurmValue(flag + ": " + *problem);
}

}  // namespace

void add_slurm_commands(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("slurm", "Write (and optionally submit) a SLURM job array that runs a sweep in shards");
  cmd->footer(
      "Writes DIR/sweep.sbatch (one shard per array task, --array=0-(N-1)[%M], logs in DIR/logs),\n"
      "DIR/merge.sbatch (merges DIR/shard_*.h5 into DIR/results.h5) and DIR/cluster.toml (for\n"
      "`chaosweep status` and `merge --slurm-dir`). With --submit, calls sbatch for both, the merge\n"
      "job with --dependency=afterok on the array. Every value that goes into a script is checked\n"
      "against the form SLURM accepts for it (exit 2 otherwise); paths are shell-quoted. Example:\n"
      "  chaosweep slurm experiments/fig6.toml --tasks 16 --concurrency 8 -o runs/fig6 --submit");
  struct Opts {
    std::string spec, dir, partition, time, mem, account, job_name;
    int tasks = 0, concurrency = 0, cpus = 1;
    bool submit = false, force = false;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("spec", o->spec, "sweep spec (TOML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--tasks", o->tasks, "array tasks = shards, at most the spec's runs")->required()->check(CLI::Range(1, 1000000));
  cmd->add_option("-o,--dir", o->dir, "directory for scripts, logs and results")->required();
  cmd->add_option("--concurrency", o->concurrency, "at most M tasks at once (--array=...%M)")->check(CLI::Range(0, 1000000));
  cmd->add_option("--cpus", o->cpus, "cpus per task (the sweep's --threads)")->check(CLI::Range(1, 4096));
  cmd->add_option("--partition", o->partition, "sbatch --partition: NAME[,NAME...] of letters, digits, _ - .");
  cmd->add_option("--account", o->account, "sbatch --account: a NAME of letters, digits, _ - .");
  cmd->add_option("--time", o->time, "sbatch --time: MINUTES, [HOURS:]MINUTES:SECONDS or DAYS-HOURS[:MINUTES[:SECONDS]]");
  cmd->add_option("--mem", o->mem, "sbatch --mem: a whole number with an optional unit K, M, G, T");
  cmd->add_option("--job-name", o->job_name, "sbatch --job-name (default chaosweep-SPECNAME)");
  cmd->add_flag("--submit", o->submit, "submit with sbatch (array, then the dependent merge job)");
  cmd->add_flag("--force", o->force, "write over the scripts of an earlier `chaosweep slurm` in DIR");
  cmd->callback([o, &action] {
    action = [o]() -> int {
      SweepSpec spec;
      fs::path dir;
      std::string job_name = o->job_name, extra;
      try {
        spec = load_sweep_spec(o->spec);
        // Checked before anything is written: a bad value leaves no script behind.
        if (o->tasks > spec.size())
          throw BadSlurmValue("--tasks: " + std::to_string(o->tasks) + " is more than the spec's " +
                              std::to_string(spec.size()) + " runs (a task runs at least one): give --tasks in [1, " +
                              std::to_string(spec.size()) + "]");
        if (job_name.empty()) job_name = to_slurm_job_name("chaosweep-" + spec.name);
        require("--job-name", check_slurm_job_name(job_name));
        if (!o->partition.empty()) require("--partition", check_slurm_partition(o->partition));
        if (!o->account.empty()) require("--account", check_slurm_account(o->account));
        if (!o->time.empty()) require("--time", check_slurm_time(o->time));
        if (!o->mem.empty()) require("--mem", check_slurm_mem(o->mem));
        dir = fs::absolute(o->dir);
        require("-o", check_slurm_directive_path(dir.string()));
        if (!o->force && fs::exists(dir / "cluster.toml"))
          throw OutputExists("-o: " + o->dir + " already holds a chaosweep slurm sweep (cluster.toml); pass --force "
                             "to write over its scripts (its shard files stay)");
      } catch (const std::exception& e) {
        std::cerr << "chaosweep slurm: " << e.what() << "\n";
        return exit_bad_input;
      }
      try {
        fs::create_directories(dir / "logs");
        if (!o->partition.empty()) extra += "\n#SBATCH --partition=" + o->partition;
        if (!o->account.empty()) extra += "\n#SBATCH --account=" + o->account;
        if (!o->time.empty()) extra += "\n#SBATCH --time=" + o->time;
        if (!o->mem.empty()) extra += "\n#SBATCH --mem=" + o->mem;
        const std::string array =
            "0-" + std::to_string(o->tasks - 1) + (o->concurrency > 0 ? "%" + std::to_string(o->concurrency) : "");
        const std::string spec_path = fs::absolute(o->spec).string();
        for (const char* name : {"sweep", "merge"}) {
          const auto tmpl = embedded_file(std::string("cluster/") + name + ".sbatch.in");
          if (!tmpl) throw std::runtime_error(std::string("no built-in template cluster/") + name + ".sbatch.in");
          // #SBATCH lines take checked values only; shell lines take quoted ones.
          const std::string text = fill_template(*tmpl, {{"JOB_NAME", job_name},
                                                         {"ARRAY", array},
                                                         {"LOGS", (dir / "logs").string()},
                                                         {"CPUS", std::to_string(o->cpus)},
                                                         {"EXTRA", extra},
                                                         {"DIR", shell_quote(dir.string())},
                                                         {"CHAOSWEEP", shell_quote(self_path())},
                                                         {"SPEC", shell_quote(spec_path)},
                                                         {"TASKS", std::to_string(o->tasks)}});
          const fs::path out = dir / (std::string(name) + ".sbatch");
          write_checked(out, text);
          fs::permissions(out, fs::perms::owner_exec, fs::perm_options::add);
        }
        write_cluster_plan(dir, ClusterPlan{spec_path, spec.name, o->tasks, std::int64_t(spec.size())});
        std::cout << "wrote " << (dir / "sweep.sbatch").string() << " (" << spec.size() << " runs in " << o->tasks
                  << " shards, --array=" << array << ") and " << (dir / "merge.sbatch").string() << "\n";
        if (!o->submit) return exit_ok;
        const auto [rc, id] = capture("sbatch --parsable " + shell_quote((dir / "sweep.sbatch").string()));
        if (rc != 0) throw std::runtime_error("sbatch failed for the array job");
        const std::string job = job_id(id);
        const auto [rc2, id2] = capture("sbatch --parsable --dependency=afterok:" + job + " " +
                                        shell_quote((dir / "merge.sbatch").string()));
        if (rc2 != 0) throw std::runtime_error("sbatch failed for the merge job");
        std::cout << "submitted array job " << job << " and merge job " << job_id(id2) << "\n";
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
        const ClusterPlan plan = read_cluster_plan(*dir);
        std::vector<int> finished, partial, missing, damaged;
        std::string detail, broken;
        for (int k = 0; k < plan.tasks; ++k) {
          const fs::path file = shard_file(*dir, k);
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

// `chaosweep slurm`: job scripts for a SLURM array, optionally submitted
// (`chaosweep status DIR`, which reads what it wrote, is cli_status.cpp).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string_view>

#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "apps/chaosweep/run_argv.hpp"
#include "apps/chaosweep/slurm_values.hpp"
#include "engine/run/sweep_runner.hpp"
#include "engine/spec/embedded_files.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/slurm_dir.hpp"
#include "engine/tune/tune_runner.hpp"
#include "engine/tune/tune_spec.hpp"

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
    if (it == values.end())
      throw std::runtime_error("job template: unknown key " + std::string(text.substr(at, end - at + 1)));
    out.append(text.substr(pos, at - pos)).append(it->second);
    pos = end + 1;
  }
}

std::string self_path() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? "chaosweep" : p.string();
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

struct SlurmOptions {
  std::string spec, dir, partition, time, mem, account, job_name;
  std::vector<std::string> sets;  // --set KEY=VALUE, passed on to every task's sweep
  int tasks = 0, concurrency = 0, cpus = 1;
  bool submit = false, force = false;
};

void add_slurm_flags(CLI::App& cmd, SlurmOptions& o) {
  cmd.add_option("spec", o.spec, "sweep spec (TOML)")->required()->check(CLI::ExistingFile);
  add_set_option(cmd, o.sets);
  cmd.add_option("--tasks", o.tasks, "array tasks = shards, at most the spec's runs")
      ->required()
      ->check(CLI::Range(1, 1000000));
  cmd.add_option("-o,--dir", o.dir, "directory for scripts, logs and results")->required();
  cmd.add_option("--concurrency", o.concurrency, "at most M tasks at once (--array=...%M)")
      ->check(CLI::Range(0, 1000000));
  cmd.add_option("--cpus", o.cpus, "cpus per task (the sweep's --threads)")->check(CLI::Range(1, 4096));
  cmd.add_option("--partition", o.partition, "sbatch --partition: NAME[,NAME...] of letters, digits, _ - .");
  cmd.add_option("--account", o.account, "sbatch --account: a NAME of letters, digits, _ - .");
  cmd.add_option("--time", o.time, "sbatch --time: MINUTES, [HOURS:]MINUTES:SECONDS or DAYS-HOURS[:MINUTES[:SECONDS]]");
  cmd.add_option("--mem", o.mem, "sbatch --mem: a whole number with an optional unit K, M, G, T");
  cmd.add_option("--job-name", o.job_name, "sbatch --job-name (default chaosweep-SPECNAME)");
  cmd.add_flag("--submit", o.submit, "submit with sbatch (array, then the dependent merge job)");
  cmd.add_flag("--force", o.force, "write over the scripts of an earlier `chaosweep slurm` in DIR");
}

// What the scripts are made of, every value checked.
struct SlurmJob {
  SweepSpec spec;
  fs::path dir;
  std::string job_name;
  bool tune = false;      // a spec with [tune]: each task races its shard of the cases
  std::int64_t runs = 0;  // the sweep's runs; a tune's at most
};

// Checks every value before anything is written: a bad value leaves no
// script behind (throws BadSlurmValue or OutputExists).
SlurmJob checked_job(const SlurmOptions& o) {
  SlurmJob job{load_sweep_spec(o.spec, spec_overrides(o.sets)), {}, o.job_name};
  const SweepSpec& spec = job.spec;
  // Every map, as the tasks' sweeps will load it (from this directory: the
  // scripts cd here), so a bad one stops here, not in every task.
  EnvironmentCache maps;
  preload_environments(spec, maps);
  job.tune = !spec.tune.empty();
  job.runs = spec.size();
  if (job.tune) {
    const TuneSpec tune = tune_spec_of(spec, o.spec);  // a bad [tune] stops here, not in every task
    job.runs = tune_most_rows(tune, false);
    if (o.tasks > int(tune.cases.size()))
      throw BadSlurmValue(
          "--tasks: " + std::to_string(o.tasks) + " is more than the tune's " + std::to_string(tune.cases.size()) +
          " cases (a task races whole cases): give --tasks in [1, " + std::to_string(tune.cases.size()) + "]");
  } else if (o.tasks > spec.size()) {
    throw BadSlurmValue("--tasks: " + std::to_string(o.tasks) + " is more than the spec's " +
                        std::to_string(spec.size()) + " runs (a task runs at least one): give --tasks in [1, " +
                        std::to_string(spec.size()) + "]");
  }
  if (job.job_name.empty()) job.job_name = to_slurm_job_name("chaosweep-" + spec.name);
  require("--job-name", check_slurm_job_name(job.job_name));
  if (!o.partition.empty()) require("--partition", check_slurm_partition(o.partition));
  if (!o.account.empty()) require("--account", check_slurm_account(o.account));
  if (!o.time.empty()) require("--time", check_slurm_time(o.time));
  if (!o.mem.empty()) require("--mem", check_slurm_mem(o.mem));
  job.dir = fs::absolute(o.dir);
  require("-o", check_slurm_directive_path(job.dir.string()));
  if (!o.force && fs::exists(job.dir / "cluster.toml"))
    throw OutputExists("-o: " + o.dir +
                       " already holds a chaosweep slurm sweep (cluster.toml); pass --force "
                       "to write over its scripts (its shard files stay)");
  return job;
}

// Writes DIR/sweep.sbatch, DIR/merge.sbatch and DIR/cluster.toml; returns
// the --array= value.
std::string write_job_scripts(const SlurmOptions& o, const SlurmJob& job) {
  const fs::path& dir = job.dir;
  fs::create_directories(dir / "logs");
  std::string extra;
  if (!o.partition.empty()) extra += "\n#SBATCH --partition=" + o.partition;
  if (!o.account.empty()) extra += "\n#SBATCH --account=" + o.account;
  if (!o.time.empty()) extra += "\n#SBATCH --time=" + o.time;
  if (!o.mem.empty()) extra += "\n#SBATCH --mem=" + o.mem;
  const std::string array =
      "0-" + std::to_string(o.tasks - 1) + (o.concurrency > 0 ? "%" + std::to_string(o.concurrency) : "");
  // Resolved now: a path through the directory slurm ran in (../x.toml)
  // must not need that directory on the node.
  const std::string spec_path = fs::weakly_canonical(fs::absolute(o.spec)).string();
  std::string sets;  // each a quoted word: the value reaches the sweep as given
  for (const std::string& s : o.sets) sets += " --set " + shell_quote(s);
  for (const char* name : {"sweep", "merge"}) {
    const auto tmpl = embedded_file(std::string("cluster/") + name + ".sbatch.in");
    if (!tmpl) throw std::runtime_error(std::string("no built-in template cluster/") + name + ".sbatch.in");
    // #SBATCH lines take checked values only; shell lines take quoted ones.
    const std::string text = fill_template(*tmpl, {{"JOB_NAME", job.job_name},
                                                   {"ARRAY", array},
                                                   {"LOGS", (dir / "logs").string()},
                                                   {"CPUS", std::to_string(o.cpus)},
                                                   {"EXTRA", extra},
                                                   {"DIR", shell_quote(dir.string())},
                                                   {"WORKDIR", shell_quote(fs::current_path().string())},
                                                   {"CHAOSWEEP", shell_quote(self_path())},
                                                   {"COMMAND", job.tune ? "tune" : "sweep"},
                                                   {"SPEC", shell_quote(spec_path)},
                                                   {"SETS", sets},
                                                   {"TASKS", std::to_string(o.tasks)}});
    const fs::path out = dir / (std::string(name) + ".sbatch");
    write_checked(out, text);
    fs::permissions(out, fs::perms::owner_exec, fs::perm_options::add);
  }
  write_cluster_plan(dir, ClusterPlan{spec_path, job.spec.name, o.tasks, job.runs, job.tune});
  return array;
}

// Runs sbatch by argv (no shell reads the paths) and returns the job id it
// printed; `what` names the job in errors.
std::string sbatch(const std::vector<std::string>& args, const std::string& what) {
  std::vector<std::string> argv{"sbatch", "--parsable"};
  argv.insert(argv.end(), args.begin(), args.end());
  const ArgvResult r = run_argv(argv, 300);
  if (!r.started) throw std::runtime_error("sbatch is not on PATH: the scripts are written, submit them by hand");
  if (r.exit_code != 0)
    throw std::runtime_error("sbatch failed for the " + what + " job" +
                             (r.err.empty() ? std::string() : ": " + printable(r.err.substr(0, r.err.find('\n')))));
  return job_id(r.out);
}

// Submits the array, then the merge job that waits for it (afterok), and
// records both ids in DIR/jobs.txt for `chaosweep status`.
void submit_jobs(const fs::path& dir) {
  const std::string job = sbatch({(dir / "sweep.sbatch").string()}, "array");
  record_submitted_job(dir, "array", job);
  std::string merge;
  try {
    merge = sbatch({"--dependency=afterok:" + job, (dir / "merge.sbatch").string()}, "merge");
  } catch (const std::exception& e) {  // the array runs: say so, so it is not submitted twice
    throw std::runtime_error(std::string(e.what()) + " (array job " + job + " was submitted; submit " +
                             (dir / "merge.sbatch").string() + " by hand)");
  }
  record_submitted_job(dir, "merge", merge);
  std::cout << "submitted array job " << job << " and merge job " << merge << " (recorded in "
            << (dir / "jobs.txt").string() << ")\n";
}

int run_slurm(const SlurmOptions& o) {
  SlurmJob job;
  try {
    job = checked_job(o);
  } catch (const std::exception& e) {
    std::cerr << "chaosweep slurm: " << e.what() << "\n";
    return exit_bad_input;
  }
  try {
    const std::string array = write_job_scripts(o, job);
    std::cout << "wrote " << (job.dir / "sweep.sbatch").string() << " (" << (job.tune ? "a tune of at most " : "")
              << job.runs << " runs in " << o.tasks << " shards, --array=" << array << ") and "
              << (job.dir / "merge.sbatch").string() << "\n";
    if (o.submit) submit_jobs(job.dir);
    return exit_ok;
  } catch (const std::exception& e) {
    std::cerr << "chaosweep slurm: " << e.what() << "\n";
    return exit_failure;
  }
}

}  // namespace

void add_slurm_commands(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand(
      "slurm", "Write (and optionally submit) a SLURM job array that runs a sweep (or a tune) in shards");
  cmd->footer(
      "Writes DIR/sweep.sbatch (one shard per array task, --array=0-(N-1)[%M], logs in DIR/logs),\n"
      "DIR/merge.sbatch (merges DIR/shard_*.h5 into DIR/results.h5) and DIR/cluster.toml (for\n"
      "`chaosweep status` and `merge --slurm-dir`). A spec with a [tune] section runs `chaosweep\n"
      "tune --shard K/N` per task (each races its share of the cases; --tasks at most the cases).\n"
      "With --submit, calls sbatch for both, the merge job with --dependency=afterok on the array\n"
      "(sbatch run without a shell), and records both job ids in DIR/jobs.txt for `chaosweep status`. Every value that "
      "goes into a script is checked\n"
      "against the form SLURM accepts for it (exit 2 otherwise); paths are shell-quoted. Example:\n"
      "  chaosweep slurm experiments/fig6.toml --tasks 16 --concurrency 8 -o runs/fig6 --submit");
  auto o = std::make_shared<SlurmOptions>();
  add_slurm_flags(*cmd, *o);
  cmd->callback([o, &action] { action = [o] { return run_slurm(*o); }; });
  add_status_command(app, action);
}

}  // namespace chaosweep

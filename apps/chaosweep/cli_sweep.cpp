// `chaosweep sweep`: expand a spec, run it (or one shard of it) on TBB, store
// rows in HDF5; resumable after a kill or SIGINT/SIGTERM.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <limits>
#include <optional>
#include <filesystem>
#include <iostream>
#include <memory>
#include <thread>

#include "apps/chaosweep/cli_common.hpp"
#include "engine/store/disk_room.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/input_identity.hpp"
#include "engine/store/output_lock.hpp"
#include "engine/run/progress.hpp"
#include "engine/rows/result_columns.hpp"
#include "engine/run/simd_choice.hpp"
#include "engine/run/sweep_runner.hpp"
#include "engine/rows/sweep_summary.hpp"
#include "engine/store/version.hpp"

namespace chaosweep {

namespace {

std::atomic<bool> stop_requested{false};
volatile std::sig_atomic_t stop_signal = 0;
extern "C" void on_stop_signal(int sig) {
  stop_signal = sig;
  stop_requested.store(true);
}

struct Shard {
  int index = 0, count = 1;
};

// A SLURM_ARRAY_* variable: unset, or a whole number in [0, 2^31) (anything
// else is refused naming it: a mistyped value must not run the whole sweep).
std::optional<int> slurm_number(const char* name) {
  const char* v = std::getenv(name);
  if (!v) return std::nullopt;
  const std::string text(v);
  if (!text.empty() && text.size() <= 10 && text.find_first_not_of("0123456789") == std::string::npos) {
    const long long n = std::stoll(text);
    if (n <= std::numeric_limits<int>::max()) return int(n);
  }
  throw SpecError(std::string(name) + " = '" + text +
                  "' is not a whole number in [0, 2147483647] (a SLURM job array sets it; pass --shard K/N to "
                  "choose the shard yourself)");
}

// The shard of a SLURM array task: (SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN)
// / SLURM_ARRAY_TASK_STEP of SLURM_ARRAY_TASK_COUNT; no shard (the whole
// sweep) when neither the ID nor the COUNT is set.
Shard slurm_shard() {
  Shard s;
  const auto id = slurm_number("SLURM_ARRAY_TASK_ID"), count = slurm_number("SLURM_ARRAY_TASK_COUNT");
  const auto min = slurm_number("SLURM_ARRAY_TASK_MIN"), step = slurm_number("SLURM_ARRAY_TASK_STEP");
  if (!id && !count) return s;
  if (!id || !count)
    throw SpecError(std::string(id ? "SLURM_ARRAY_TASK_ID" : "SLURM_ARRAY_TASK_COUNT") + " is set but " +
                    (id ? "SLURM_ARRAY_TASK_COUNT" : "SLURM_ARRAY_TASK_ID") +
                    " is not: cannot tell this task's shard (pass --shard K/N)");
  const std::string vars = "SLURM_ARRAY_TASK_ID = " + std::to_string(*id) + ", SLURM_ARRAY_TASK_MIN = " +
                           std::to_string(min.value_or(0)) + ", SLURM_ARRAY_TASK_STEP = " +
                           std::to_string(step.value_or(1)) + ", SLURM_ARRAY_TASK_COUNT = " + std::to_string(*count);
  const int offset = *id - min.value_or(0), stride = step.value_or(1);
  if (stride < 1 || offset < 0 || offset % stride != 0 || *count < 1 || offset / stride >= *count)
    throw SpecError(vars + ": not a task of the array (need MIN <= ID, (ID - MIN) / STEP a whole number below "
                           "COUNT); pass --shard K/N");
  s.index = offset / stride;
  s.count = *count;
  return s;
}

// "K/N", or the SLURM array task's shard (slurm_shard) when no --shard is given.
Shard parse_shard(const std::string& text) {
  if (text.empty()) return slurm_shard();
  Shard s;
  const auto slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument("");
    std::size_t used = 0;
    s.index = std::stoi(text.substr(0, slash), &used);
    if (used != slash) throw std::invalid_argument("");
    s.count = std::stoi(text.substr(slash + 1), &used);
    if (used != text.size() - slash - 1) throw std::invalid_argument("");
  } catch (const std::exception&) {
    throw SpecError("--shard: '" + text + "' is not K/N (e.g. 0/4)");
  }
  if (s.count < 1 || s.index < 0 || s.index >= s.count)
    throw SpecError("--shard: index " + std::to_string(s.index) + " of " + std::to_string(s.count) +
                    " is out of range: need 0 <= K < N");
  return s;
}

// The root attributes of a sweep's file (docs/store.md): all of them for a
// new file; for a resumed one (`resumed` names it) when and where it went on,
// with every SIMD target the file's rows were computed with.
std::vector<Attribute> provenance(const SweepSpec& spec, const SweepInputs& inputs, const std::string& spec_path,
                                  int shard_index, int shard_count, int threads, const std::string& target,
                                  const std::string& resumed) {
  std::vector<Attribute> a;
  std::string targets = target;
  if (resumed.empty()) {
    a = {{"engine_version", std::string(engine_version())},
         {"git_commit", std::string(git_commit())},
         {"git_dirty", git_dirty()},
         {"spec", spec.text},
         {"spec_hash", inputs.spec_hash},
         {"inputs_hash", inputs.hash()},
         {"input_files", inputs.text()},
         {"spec_path", spec_path},
         {"spec_name", spec.name},
         {"runs_total", std::int64_t(spec.size())},
         {"shard", std::to_string(shard_index) + "/" + std::to_string(shard_count)},
         {"start_time", utc_now()}};
  } else {
    a = {{"resumed_at", utc_now()}};
    if (has_attribute(resumed, "simd_target")) targets = join_name_lists(read_attribute(resumed, "simd_target"), target);
  }
  a.push_back({"host", host_name()});
  a.push_back({"threads", std::int64_t(threads)});
  a.push_back({"simd_target", targets});
  for (const char* v : {"SLURM_JOB_ID", "SLURM_ARRAY_JOB_ID", "SLURM_ARRAY_TASK_ID"})
    if (const char* val = std::getenv(v)) a.push_back({v, std::string(val)});
  return a;
}

}  // namespace

void add_sweep_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("sweep", "Run every run of a sweep spec (or one shard) and write the results to HDF5");
  cmd->footer(
      "The spec's axes are expanded as a Cartesian product (first axis slowest; a spec with\n"
      "[[part]]s runs each part's product in turn, run_ids following on); each run is\n"
      "one row of /runs in OUT, in run_id order. Rows go to OUT.partial every --batch runs or\n"
      "--flush-seconds, whichever comes first; each write is all-or-nothing, so a sweep killed\n"
      "even by kill -9 keeps every finished write (docs/store.md);\n"
      "OUT appears only when the sweep completes. SIGINT/SIGTERM finish the runs in flight,\n"
      "write them and exit 130/143: continue with --resume. A batch that might not fit on the\n"
      "disk (or under ulimit -f) is not begun: exit 3, continue with --resume once there is\n"
      "room. OUT.lock keeps a second sweep off the same OUT. An existing OUT is replaced only\n"
      "with --force (and only when the new sweep completes). A failing run is recorded with\n"
      "its status, never aborts the sweep.\n"
      "Example: chaosweep sweep experiments/demo.toml -o out/demo/results.h5");
  struct Opts {
    std::string spec, out, shard, progress = "auto";
    int threads = 0;
    std::int64_t batch = 4096;
    double flush_seconds = 10;
    bool quiet = false, resume = false, force = false;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("spec", o->spec, "sweep spec (TOML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->out, "result file (HDF5)")->required();
  cmd->add_option("--threads", o->threads, "worker threads (0: all cores)")->check(CLI::Number)->check(CLI::Range(0, 4096));
  cmd->add_option("--shard", o->shard,
                  "run only shard K of N (run_ids i with i % N == K); default: from SLURM_ARRAY_TASK_ID "
                  "and SLURM_ARRAY_TASK_COUNT when set")
      ->type_name("K/N");
  cmd->add_flag("--resume", o->resume,
                "continue OUT.partial of the same spec, environment files and shard (or do nothing if OUT is "
                "complete)");
  cmd->add_flag("--force", o->force,
                "run even though OUT (replaced when this sweep completes) or OUT.partial (started over) exists");
  cmd->add_option("--batch", o->batch, "runs per write to OUT.partial")->check(CLI::Number)->check(CLI::Range(1, 1 << 24));
  cmd->add_option("--flush-seconds", o->flush_seconds,
                  "also write the finished runs to OUT.partial once this many seconds passed since the last write "
                  "(0: only every --batch runs)")
      ->check(not_nan())
      ->check(CLI::Range(0.0, 1e6))
      ->default_str("10");
  cmd->add_flag("-q,--quiet", o->quiet, "print nothing but errors (and progress only with --progress=always)");
  cmd->add_option("--progress", o->progress,
                  "progress on stderr: a live line on a terminal, a plain line every 30 s otherwise")
      ->check(CLI::IsMember({"auto", "always", "never"}))
      ->default_str("auto");
  cmd->callback([o, &action] {
    action = [o]() -> int {
      namespace fs = std::filesystem;
      SweepSpec spec;
      SimdTarget target;
      Shard shard;
      EnvironmentCache cache;  // filled here to fail early; reused by the sweep
      try {
        target = selected_simd_target();
        shard = parse_shard(o->shard);
        spec = load_sweep_spec(o->spec);
        preload_environments(spec, cache);
      } catch (const std::exception& e) {
        std::cerr << "chaosweep sweep: " << e.what() << "\n";
        return exit_bad_input;
      }
      const std::string partial = o->out + ".partial";
      const SweepInputs inputs = sweep_inputs(spec, cache);  // the spec and every environment file it loaded
      const std::int64_t shard_runs = shard_size(spec.size(), shard.index, shard.count);
      std::int64_t skip = 0;
      std::unique_ptr<OutputLock> lock;
      bool resuming = false;
      try {
        check_output_path(o->out, "-o");
        if (!o->resume)
          check_output_free(o->out, o->force, "-o", " (kept until this sweep completes), or --resume to keep it");
        lock = std::make_unique<OutputLock>(o->out);  // from here on, this process is OUT's only writer
        resuming = o->resume && fs::exists(partial);
        if (o->resume && !fs::exists(partial) && fs::exists(o->out)) {
          check_same_inputs(o->out, inputs);
          if (!o->quiet) std::cout << o->out << " is complete: nothing to resume\n";
          return exit_ok;
        }
        if (!o->resume && !o->force && fs::exists(partial))
          throw std::runtime_error(partial + " exists (an interrupted sweep): pass --resume to continue it, "
                                   "or --force to start over");
        if (resuming) {
          check_same_inputs(partial, inputs);
          if (read_attribute(partial, "shard") != std::to_string(shard.index) + "/" + std::to_string(shard.count))
            throw std::runtime_error(partial + " holds shard " + read_attribute(partial, "shard") + ", not " +
                                     std::to_string(shard.index) + "/" + std::to_string(shard.count));
          const auto ids = read_i64_column(partial, "run_id");
          for (std::size_t j = 0; j < ids.size(); ++j)
            if (ids[j] != shard_run_id(std::int64_t(j), shard.index, shard.count))
              throw std::runtime_error(partial + ": row " + std::to_string(j) + " has run_id " +
                                       std::to_string(ids[j]) + ", not the shard's next run");
          skip = std::int64_t(ids.size());
        }
      } catch (const std::exception& e) {
        std::cerr << "chaosweep sweep: " << e.what() << "\n";
        return exit_bad_input;
      }
      const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
      const int threads = o->threads > 0 ? o->threads : int(cores);
      if (!o->quiet) {
        std::cout << "sweep '" << spec.name << "': " << shard_runs << " runs";
        if (shard.count > 1) std::cout << " (shard " << shard.index << "/" << shard.count << " of " << spec.size() << ")";
        if (skip) std::cout << ", " << skip << " already done";
        std::cout << " on " << threads << " threads, " << to_string(target) << " kernels -> " << o->out << "\n";
      }
      SweepSummary summary;
      std::signal(SIGINT, on_stop_signal);
      std::signal(SIGTERM, on_stop_signal);
      std::signal(SIGXFSZ, SIG_IGN);  // past ulimit -f a write fails (reported) instead of killing us
      std::int64_t written = skip;
      std::unique_ptr<H5RunWriter> created;
      try {
        created = std::make_unique<H5RunWriter>(o->out, resuming ? H5RunWriter::Mode::resume : H5RunWriter::Mode::create,
                                                provenance(spec, inputs, o->spec, shard.index, shard.count, threads,
                                                           to_string(target), resuming ? partial : ""),
                                                text_widths(spec));
      } catch (const std::exception& e) {
        std::cerr << "chaosweep sweep: " << e.what() << "\n";
        return exit_bad_input;  // nothing has run: the output path cannot be written
      }
      H5RunWriter& writer = *created;
      try {
        SweepOptions opt;
        opt.threads = threads;
        opt.target = target;
        opt.batch_size = o->batch;
        opt.flush_seconds = o->flush_seconds;
        opt.shard_index = shard.index;
        opt.shard_count = shard.count;
        opt.skip = skip;
        opt.stop = &stop_requested;
        ProgressCounters counters;
        opt.progress = &counters;
        const ProgressMode mode = o->progress == "never" || (o->quiet && o->progress == "auto") ? ProgressMode::never
                                  : o->progress == "always"                                    ? ProgressMode::always
                                                                                               : ProgressMode::automatic;
        const auto started = std::chrono::steady_clock::now();
        {
          ProgressReporter reporter(counters, shard_runs - skip, mode);
          written += run_sweep(spec, opt, [&](const std::vector<RunRow>& rows) {
            writer.append(rows);
            for (const RunRow& r : rows) summary.add(r);
          }, &cache);
        }
        summary.set_elapsed(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
        if (written < shard_runs) {
          std::cerr << "chaosweep sweep: interrupted: " << written << " of " << shard_runs << " runs are in "
                    << partial << "; continue with --resume\n";
          return 128 + (stop_signal ? int(stop_signal) : SIGINT);
        }
        writer.set_attribute("end_time", utc_now());
        writer.finish();
      } catch (const OutOfRoom& e) {
        std::cerr << "chaosweep sweep: " << e.what() << "\nchaosweep sweep: stopped: " << writer.rows_written()
                  << " of " << shard_runs << " runs are in " << partial
                  << "; make room, then continue with --resume\n";
        return exit_failure;
      } catch (const std::exception& e) {
        std::cerr << "chaosweep sweep: " << e.what() << "\n";
        return exit_failure;
      }
      if (!o->quiet) {
        if (skip) std::cout << "(summary of the " << summary.runs() << " runs of this session)\n";
        std::cout << summary.text() << "results     " << o->out << "\n";
      }
      return exit_ok;
    };
  });
}

}  // namespace chaosweep

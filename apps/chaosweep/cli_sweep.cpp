// `chaosweep sweep`: expand a spec, run it (or one shard of it) on TBB, store
// rows in HDF5; resumable after a kill or SIGINT/SIGTERM. The flags, the
// shard, the resume protocol, the provenance and the signal handling live in
// apps/chaosweep/sweep/.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>
#include <thread>

#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "apps/chaosweep/sweep/sweep_flags.hpp"
#include "apps/chaosweep/sweep/sweep_provenance.hpp"
#include "apps/chaosweep/sweep/sweep_resume.hpp"
#include "apps/chaosweep/sweep/sweep_shard.hpp"
#include "apps/chaosweep/sweep/sweep_signals.hpp"
#include "apps/chaosweep/sweep_history.hpp"
#include "engine/run/progress.hpp"
#include "engine/run/simd_choice.hpp"
#include "engine/run/sweep_runner.hpp"
#include "engine/run/sweep_summary.hpp"
#include "engine/run/thread_batch_evaluator.hpp"
#include "engine/spec/shard.hpp"
#include "engine/spec/text_widths.hpp"
#include "engine/store/disk_room.hpp"
#include "engine/store/h5_store.hpp"

namespace chaosweep {

namespace {

// What the sweep runs: read and checked before anything is written.
struct SweepInput {
  SweepSpec spec;
  SimdTarget target;
  Shard shard;
  EnvironmentCache cache;  // filled here to fail early; reused by the sweep
};

void load_input(const SweepFlags& o, SweepInput& in) {
  in.target = selected_simd_target();
  in.shard = parse_shard(o.shard);
  in.spec = load_sweep_spec(o.spec, spec_overrides(o.sets));
  if (!in.spec.tune.empty())
    throw SpecError(o.spec +
                    ": has a [tune] section: its runs are the cases a tuner races, run it with chaosweep tune");
  preload_environments(in.spec, in.cache);
}

void print_start(const SweepFlags& o, const SweepInput& in, std::int64_t shard_runs, std::int64_t skip, int threads) {
  std::cout << "sweep '" << in.spec.name << "': " << shard_runs << " runs";
  if (in.shard.count > 1)
    std::cout << " (shard " << in.shard.index << "/" << in.shard.count << " of " << in.spec.size() << ")";
  if (skip) std::cout << ", " << skip << " already done";
  std::cout << " on " << threads << " threads, " << to_string(in.target) << " kernels -> " << o.out << "\n";
}

// Runs the shard's runs after `skip` into `writer` and finishes OUT; the
// exit status (a stop by signal leaves OUT.partial to resume).
int run_into(const SweepFlags& o, SweepInput& in, H5RunWriter& writer, std::int64_t skip, int threads,
             SweepSummary& summary) {
  const std::int64_t shard_runs = shard_size(in.spec.size(), in.shard.index, in.shard.count);
  SweepOptions opt;
  opt.batch_size = o.batch;
  opt.flush_seconds = o.flush_seconds;
  opt.shard_index = in.shard.index;
  opt.shard_count = in.shard.count;
  opt.skip = skip;
  opt.stop = &sweep_stop_requested;
  ProgressCounters counters;
  opt.progress = &counters;
  std::int64_t written = skip;
  const auto started = std::chrono::steady_clock::now();
  {
    ProgressReporter reporter(counters, shard_runs - skip, progress_mode(o.progress, o.quiet));
    const ThreadBatchEvaluator evaluator(threads, in.target);
    // Rows are encoded and compressed on the sweep's threads.
    const ParallelFor parallel = [&](std::size_t n, const std::function<void(std::size_t)>& body) {
      evaluator.parallel(n, body);
    };
    written += run_sweep(
        in.spec, evaluator, opt,
        [&](const std::vector<RunRow>& rows) -> RowWrite {
          RowWrite write = writer.prepare_write(rows, parallel);
          for (const RunRow& r : rows) summary.add(r);
          return write;
        },
        &in.cache);
  }
  summary.set_elapsed(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  if (written < shard_runs) {
    std::cerr << "chaosweep sweep: interrupted: " << written << " of " << shard_runs << " runs are in " << o.out
              << ".partial; continue with --resume\n";
    return stopped_exit_status();
  }
  writer.set_attribute("end_time", utc_now());
  writer.finish();
  return exit_ok;
}

// Creates (or resumes) OUT.partial and runs into it; the exit status.
int write_sweep(const SweepFlags& o, SweepInput& in, const SweepInputs& inputs, const SweepStart& start) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const int threads = o.threads > 0 ? o.threads : int(cores);
  const std::int64_t shard_runs = shard_size(in.spec.size(), in.shard.index, in.shard.count);
  if (!o.quiet) print_start(o, in, shard_runs, start.skip, threads);
  install_sweep_signal_handlers();
  std::unique_ptr<H5RunWriter> writer;
  try {
    writer =
        std::make_unique<H5RunWriter>(o.out, start.resuming ? H5RunWriter::Mode::resume : H5RunWriter::Mode::create,
                                      sweep_provenance(in.spec, inputs, o.spec, in.shard, threads, to_string(in.target),
                                                       start.resuming ? o.out + ".partial" : ""),
                                      text_widths(in.spec));
  } catch (const std::exception& e) {
    std::cerr << "chaosweep sweep: " << e.what() << "\n";
    return exit_bad_input;  // nothing has run: the output path cannot be written
  }
  SweepSummary summary;
  try {
    const int status = run_into(o, in, *writer, start.skip, threads, summary);
    if (status != exit_ok) return status;
  } catch (const OutOfRoom& e) {
    std::cerr << "chaosweep sweep: " << e.what() << "\nchaosweep sweep: stopped: " << writer->rows_written() << " of "
              << shard_runs << " runs are in " << o.out << ".partial"
              << "; make room, then continue with --resume\n";
    return exit_failure;
  } catch (const std::exception& e) {
    std::cerr << "chaosweep sweep: " << e.what() << "\n";
    return exit_failure;
  }
  if (!o.quiet) {
    if (start.skip) std::cout << "(summary of the " << summary.runs() << " runs of this session)\n";
    std::cout << summary.text() << "results     " << o.out << "\n";
  }
  return exit_ok;
}

int sweep_command(const SweepFlags& o) {
  SweepInput in;
  try {
    load_input(o, in);
  } catch (const std::exception& e) {
    std::cerr << "chaosweep sweep: " << e.what() << "\n";
    return exit_bad_input;
  }
  const SweepInputs inputs = sweep_inputs(in.spec, in.cache);  // the spec and every environment file it loaded
  SweepStart start;
  try {
    start = start_sweep_output(o.out, o.resume, o.force, inputs, in.shard);
  } catch (const std::exception& e) {
    std::cerr << "chaosweep sweep: " << e.what() << "\n";
    return exit_bad_input;
  }
  if (start.complete) {
    if (!o.quiet) std::cout << o.out << " is complete: nothing to resume\n";
    return exit_ok;
  }
  SweepRecord record;
  record.spec = o.spec;
  record.out = o.out;
  record.shard = std::to_string(in.shard.index) + "/" + std::to_string(in.shard.count);
  record.runs = shard_size(in.spec.size(), in.shard.index, in.shard.count);
  record.resume = start.resuming;
  for (const std::string& s : o.sets) record.sets += " --set " + s;
  const std::string id = record_sweep_start(record, o.quiet);
  const int status = write_sweep(o, in, inputs, start);
  record_sweep_end(id, status, o.quiet);
  return status;
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
  auto o = std::make_shared<SweepFlags>();
  add_sweep_flags(*cmd, *o);
  cmd->callback([o, &action] { action = [o] { return sweep_command(*o); }; });
}

}  // namespace chaosweep

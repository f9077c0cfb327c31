// `chaosweep tune`: race every case of a spec with a [tune] section
// (engine/tune), every run an ordinary row of OUT (with its race round and
// configuration), then validate each case's choice on fresh seeds.
// Resumable like a sweep: OUT.partial holds the rows of every finished step,
// and --resume replays the races from them.
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <thread>

#include "analysis/result_set.hpp"
#include "analysis/tune_table.hpp"
#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "apps/chaosweep/sweep/sweep_provenance.hpp"
#include "apps/chaosweep/sweep/sweep_resume.hpp"
#include "apps/chaosweep/sweep/sweep_signals.hpp"
#include "apps/chaosweep/sweep_history.hpp"
#include "engine/run/progress.hpp"
#include "engine/run/simd_choice.hpp"
#include "engine/run/sweep_runner.hpp"
#include "engine/run/thread_batch_evaluator.hpp"
#include "engine/spec/text_widths.hpp"
#include "engine/store/disk_room.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/tune/tune_runner.hpp"

namespace chaosweep {

namespace {

struct TuneFlags {
  std::string spec, out, grid, shard, progress = "auto";
  std::vector<std::string> sets;
  std::int64_t budget = 0;    // 0: the spec's
  int validation_seeds = -1;  // -1: the spec's
  int threads = 0;
  bool quiet = false, resume = false, force = false;
};

// The rows OUT.partial holds, as the replay needs them.
std::vector<KnownRun> known_runs(const std::string& partial) {
  const TypedColumns c = read_typed_columns(partial);
  std::vector<KnownRun> k(c.rows);
  const auto& id = c.i64.at("run_id");
  const auto& hash = c.i64.at("param_hash");
  const auto& status = c.text.at("status");
  const auto& ct = c.f64.at("coverage_time");
  for (std::size_t r = 0; r < c.rows; ++r)
    k[r] = {id[r], hash[r], status[r] == "ok" ? ct[r] : std::numeric_limits<double>::infinity()};
  return k;
}

// Per case, the grid's best configuration in the case's own terms (a real
// value, or the index of the choice), from the grid's runs of its label.
std::vector<std::optional<std::vector<double>>> grid_choices(const TuneSpec& tune, const std::string& path) {
  const ResultSet grid = ResultSet::load({path});
  std::vector<std::optional<std::vector<double>>> out(tune.cases.size());
  for (std::size_t i = 0; i < tune.cases.size(); ++i) {
    const TuneCase& c = tune.cases[i];
    if (c.parameters.empty()) continue;
    std::vector<std::string> keys;
    for (std::size_t j : c.parameters) keys.push_back(tune.parameters[j].key);
    const GridBest best = grid_best(grid, c.run.label, keys);
    std::vector<double> values;
    for (std::size_t k = 0; k < keys.size(); ++k) {
      const TuneParameter& p = tune.parameters[c.parameters[k]];
      if (p.real) {
        values.push_back(best.numbers[k]);
        continue;
      }
      std::size_t m = 0;
      while (m < p.choices.size() && to_text(p.choices[m]) != best.values[k]) ++m;
      if (m == p.choices.size())
        throw SpecError("--grid " + path + ": case '" + c.run.label + "': the grid's best " + keys[k] + " " +
                        best.values[k] + " is not one of tune.parameters." + keys[k]);
      values.push_back(double(m));
    }
    out[i] = std::move(values);
  }
  return out;
}

// --shard K/N (or the SLURM array task's): N at most the cases, as each
// shard races whole cases.
Shard tune_shard(const std::string& text, const TuneSpec& tune) {
  const Shard s = parse_shard(text);
  const int cases = int(tune.cases.size());
  if (s.count > cases)
    throw SpecError("--shard: " + std::to_string(s.index) + "/" + std::to_string(s.count) + " asks for " +
                    std::to_string(s.count) + " shards of a tune of " + std::to_string(cases) +
                    " cases (a shard races whole cases): give N in [1, " + std::to_string(cases) + "]");
  return s;
}

void print_outcome(const TuneSpec& tune, const TuneOutcome& out) {
  for (std::size_t i : out.cases) {
    const TuneCase& c = tune.cases[i];
    std::cout << "case " << (c.run.label.empty() ? std::to_string(i) : c.run.label) << ": ";
    if (!out.races[i]) {
      std::cout << "no parameters, validated as given\n";
      continue;
    }
    const Race& r = *out.races[i];
    std::cout << r.spent() << " race runs, " << r.candidates().size() << " configurations, " << r.iteration()
              << (r.iteration() == 1 ? " iteration; chose" : " iterations; chose");
    if (r.best() == 0) {
      std::cout << " none\n";
      continue;
    }
    const Candidate& best = r.candidate(r.best());
    for (std::size_t k = 0; k < r.parameters().size(); ++k) {
      const TuneParameter& p = r.parameters()[k];
      std::cout << " " << p.key << " "
                << (p.real ? to_text(best.values[k]) : to_text(p.choices[std::size_t(best.values[k])]));
    }
    std::cout << " (config " << best.id << ")\n";
  }
}

int tune_command(const TuneFlags& o) {
  SweepSpec spec;
  TuneSpec tune;
  EnvironmentCache cache;
  std::vector<std::optional<std::vector<double>>> beside;
  Shard shard;
  try {
    spec = load_sweep_spec(o.spec, spec_overrides(o.sets));
    tune = tune_spec_of(spec, o.spec, o.budget > 0 ? std::optional<std::int64_t>(o.budget) : std::nullopt);
    if (o.validation_seeds >= 0) tune.validation_seeds = o.validation_seeds;
    shard = tune_shard(o.shard, tune);
    preload_environments(spec, cache);
    if (!o.grid.empty()) beside = grid_choices(tune, o.grid);
  } catch (const std::exception& e) {
    std::cerr << "chaosweep tune: " << e.what() << "\n";
    return exit_bad_input;
  }
  const SweepInputs inputs = sweep_inputs(spec, cache);
  SweepStart start;
  try {
    start = start_sweep_output(o.out, o.resume, o.force, inputs, shard, false);
  } catch (const std::exception& e) {
    std::cerr << "chaosweep tune: " << e.what() << "\n";
    return exit_bad_input;
  }
  if (start.complete) {
    if (!o.quiet) std::cout << o.out << " is complete: nothing to resume\n";
    return exit_ok;
  }
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const int threads = o.threads > 0 ? o.threads : int(cores);
  const SimdTarget target = selected_simd_target();
  SweepRecord record;
  record.spec = o.spec;
  record.out = o.out;
  record.shard = std::to_string(shard.index) + "/" + std::to_string(shard.count);
  const std::int64_t most = tune_most_rows(tune, !o.grid.empty(), shard.index, shard.count);
  record.runs = most;
  record.resume = start.resuming;
  for (const std::string& s : o.sets) record.sets += " --set " + s;
  const std::string id = record_sweep_start(record, o.quiet);
  const auto finish = [&](int status) {
    record_sweep_end(id, status, o.quiet);
    return status;
  };
  std::vector<KnownRun> known;
  std::unique_ptr<H5RunWriter> writer;
  try {
    if (start.resuming) known = known_runs(o.out + ".partial");
    std::vector<Attribute> a = sweep_provenance(spec, inputs, o.spec, shard, threads, to_string(target),
                                                start.resuming ? o.out + ".partial" : "");
    if (!start.resuming) {
      for (Attribute& x : a)
        if (x.name == "runs_total") x.value = most;  // at most; the rows at the end
      a.push_back({"kind", std::string("tune")});
      if (!o.grid.empty()) a.push_back({"tune_grid", o.grid});
    }
    writer = std::make_unique<H5RunWriter>(
        o.out, start.resuming ? H5RunWriter::Mode::resume : H5RunWriter::Mode::create, a, text_widths(spec));
  } catch (const std::exception& e) {
    std::cerr << "chaosweep tune: " << e.what() << "\n";
    return finish(exit_bad_input);
  }
  if (!o.quiet)
    std::cout << "tune '" << spec.name << "': " << tune.cases.size() << " cases"
              << (shard.count > 1 ? " (shard " + record.shard + ": its cases i % " + std::to_string(shard.count) +
                                        " == " + std::to_string(shard.index) + ")"
                                  : "")
              << ", at most " << most << " runs"
              << (known.empty() ? "" : ", " + std::to_string(known.size()) + " already done") << " on " << threads
              << " threads, " << to_string(target) << " kernels -> " << o.out << "\n";
  install_sweep_signal_handlers();
  TuneOutcome outcome;
  try {
    ProgressCounters counters;
    ProgressReporter reporter(counters, most - std::int64_t(known.size()), progress_mode(o.progress, o.quiet));
    const ThreadBatchEvaluator evaluator(threads, target);
    const ParallelFor parallel = [&](std::size_t n, const std::function<void(std::size_t)>& body) {
      evaluator.parallel(n, body);
    };
    TuneOptions opt;
    opt.stop = &sweep_stop_requested;
    opt.progress = &counters;
    opt.also_validate = beside;
    opt.shard_index = shard.index;
    opt.shard_count = shard.count;
    outcome = run_tune(
        tune, evaluator, opt, [&](const std::vector<RunRow>& rows) { writer->append(rows, parallel); }, cache, known);
  } catch (const OutOfRoom& e) {
    std::cerr << "chaosweep tune: " << e.what() << "\nchaosweep tune: stopped: " << writer->rows_written()
              << " runs are in " << o.out << ".partial; make room, then continue with --resume\n";
    return finish(exit_failure);
  } catch (const std::exception& e) {
    std::cerr << "chaosweep tune: " << e.what() << "\n";
    return finish(exit_failure);
  }
  if (outcome.stopped) {
    std::cerr << "chaosweep tune: interrupted: " << outcome.runs << " runs are in " << o.out
              << ".partial; continue with --resume\n";
    return finish(stopped_exit_status());
  }
  try {
    writer->set_attributes({{"runs_total", outcome.runs}, {"end_time", utc_now()}});
    writer->finish();
  } catch (const std::exception& e) {
    std::cerr << "chaosweep tune: " << e.what() << "\n";
    return finish(exit_failure);
  }
  if (!o.quiet) {
    print_outcome(tune, outcome);
    std::cout << "results     " << o.out << " (" << outcome.runs << " runs; chaosweep table tune " << o.out << ")\n";
  }
  return finish(exit_ok);
}

}  // namespace

void add_tune_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("tune", "Find each case's best parameters by iterated racing, not by grid");
  cmd->footer(
      "SPEC is a sweep spec with a [tune] section (docs/tune.md): each of its runs is a case\n"
      "(map, SR, environment, technique set) raced on its own. Per case, configurations are\n"
      "sampled over tune.parameters, run on seeds 0, 1, ... (ic jittered by the seed), and those\n"
      "a test blocked on the seed shows worse are dropped; new configurations are sampled\n"
      "around the survivors until the case's budget of runs is spent (irace's iterated racing).\n"
      "Then the chosen configuration runs on validation_seeds fresh seeds, and with --grid\n"
      "GRID.h5 the grid's best of the same case beside it (config_id 0). Every run is a row of\n"
      "OUT with its race_round (0: validation) and config_id. Deterministic for a spec and its\n"
      "tune.seed, whatever --threads. Rows go to OUT.partial a step at a time; kill -9 or\n"
      "SIGINT/SIGTERM lose at most the runs in flight: continue with --resume.\n"
      "Cases race independently: --shard K/N races the cases i with i % N == K, and their rows\n"
      "(run_ids too) are the whole tune's; `chaosweep merge` joins the N shard files, and\n"
      "`chaosweep slurm` runs a tune spec's shards as array tasks.\n"
      "Example: chaosweep tune experiments/table1_tune.toml -o out/table1_tune/tune.h5");
  auto o = std::make_shared<TuneFlags>();
  cmd->add_option("spec", o->spec, "sweep spec with a [tune] section (TOML)")->required()->check(CLI::ExistingFile);
  add_set_option(*cmd, o->sets);
  cmd->add_option("-o,--output", o->out, "result file (HDF5)")->required();
  cmd->add_option("--budget", o->budget, "race runs per case (replaces the spec's tune.budget)")
      ->check(CLI::Range(std::int64_t(1), std::int64_t(1000000000)));
  cmd->add_option("--validation-seeds", o->validation_seeds,
                  "fresh seeds each case's choice runs on (replaces the spec's tune.validation_seeds)")
      ->check(CLI::Range(0, 100000));
  cmd->add_option("--grid", o->grid, "a grid search's results (.h5): validate its best per case (by label) too")
      ->check(CLI::ExistingFile);
  cmd->add_option("--threads", o->threads, "worker threads (0: all cores)")->check(CLI::Range(0, 4096));
  cmd->add_option("--shard", o->shard,
                  "race only the cases i with i % N == K; default: from SLURM_ARRAY_TASK_ID and "
                  "SLURM_ARRAY_TASK_COUNT when set")
      ->type_name("K/N");
  cmd->add_flag("--resume", o->resume, "continue OUT.partial of the same spec (or do nothing if OUT is complete)");
  add_force_flag(*cmd, o->force);
  cmd->add_flag("-q,--quiet", o->quiet, "print nothing but errors");
  cmd->add_option("--progress", o->progress, "progress on stderr")
      ->check(CLI::IsMember({"auto", "always", "never"}))
      ->default_str("auto");
  cmd->callback([o, &action] { action = [o] { return tune_command(*o); }; });
}

}  // namespace chaosweep

// `chaosweep run`: one run from flags, or a stored row re-run (--from).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <limits>

#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "engine/rows/json_writer.hpp"
#include "engine/rows/trace_writer.hpp"
#include "engine/run/serial_batch_evaluator.hpp"
#include "engine/spec/run_tuple.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/stored_run.hpp"
#include "kernels/core/param_table.hpp"

namespace chaosweep {

namespace {

void print_readable(const RunRow& row) {
  const RunParams& p = row.tuple.params;
  const RunResult& r = row.result;
  const auto n = [](double v) { return format_number(v); };
  // The system's coefficients: A, B, C, or a flow's by their names.
  std::string coeffs = "A=" + n(p.A) + " B=" + n(p.B) + " C=" + n(p.C);
  if (p.system != arnold_system) {
    const SystemDefaults d = system_defaults(p.system);
    const SystemCoeffs<double> k = system_coeffs(p);
    coeffs = std::string(system_name(p.system));
    for (int i = 0; i < d.count; ++i) coeffs.append(" ").append(d.names[i]).append("=").append(n(k.at(i)));
  }
  std::printf("planner         %s  (%s, ds_index %d, f %s, %s, %s)\n", to_string(p.planner), coeffs.c_str(), p.ds_index,
              n(p.f).c_str(), to_string(p.integrator), to_string(p.boundary));
  std::printf("map             %s, %s x %s m, sr %s m, start (%s, %s)\n", row.tuple.env_spec.c_str(),
              n(p.size_x).c_str(), n(p.size_y).c_str(), n(p.sr).c_str(), n(p.start_x).c_str(), n(p.start_y).c_str());
  std::printf("status          %s\n", to_string(r.status));
  if (!r.message.empty()) std::printf("message         %s\n", r.message.c_str());
  if (r.status == Status::invalid) return;
  if (r.status == Status::ok)
    std::printf("coverage_time   %.1f s to %.0f%% coverage  (T_opt %.1f s, PR %.2f)\n", r.coverage_time, 100 * p.dc,
                r.t_opt, r.pr);
  else
    std::printf("coverage_time   not reached (%.0f%% wanted); ran %.1f s  (T_opt %.1f s)\n", 100 * p.dc, r.t_end,
                r.t_opt);
  std::printf("final_coverage  %.4f  (%lld of %lld free cells)\n", r.final_coverage, (long long)r.visited_cells,
              (long long)r.free_cells);
  std::printf("steps           %lld%s\n", (long long)r.steps,
              r.dt_halvings ? ("  (dt halved " + std::to_string(r.dt_halvings) + " times)").c_str() : "");
  std::printf("wall_time       %.3f s\n", r.wall_time);
}

// Prints whether the re-run reproduced the stored row; 0 when every column
// is bit-identical, 1 when one differs.
int report_reproduction(const StoredRow& stored, const RunRow& row, const std::string& path, std::ostream& os) {
  const RowComparison cmp = compare_row(stored, row);
  const std::string of = std::to_string(cmp.compared.size()) + " stored columns";
  os << "stored          run_id " << row.tuple.run_id << " of " << path << "\n";
  if (cmp.differences.empty()) {
    os << "reproduced      yes: all " << of << " bit-identical (wall_time not compared)\n";
    return exit_ok;
  }
  os << "reproduced      no: " << cmp.differences.size() << " of " << of << " differ\n";
  for (const ColumnDifference& d : cmp.differences)
    os << "  " << d.column << ": stored " << d.stored << ", re-run " << d.rerun << "\n";
  return exit_differs;
}

// The run (or re-run) the flags describe, printed; the exit status.
int run_command(const std::map<std::string, std::string>& raw, bool json, const std::string& trace_path,
                const std::string& from, std::int64_t run_id, bool force) {
  const bool rerun = !from.empty();
  StoredRun stored;
  RunTuple tuple;
  try {
    if (rerun && !raw.empty()) {
      std::string flag = "--" + raw.begin()->first;
      std::replace(flag.begin(), flag.end(), '_', '-');
      throw SpecError("--from re-runs the stored parameters: drop " + flag + " (and every other parameter flag)");
    }
    check_output_free(trace_path, force, "--trace");
    if (rerun) {
      stored = load_stored_run(from, run_id);
      tuple = stored.tuple;
    } else {
      RunSpec spec;
      apply_param_flags(raw, spec);
      EnvironmentCache cache;
      tuple = resolve_run(0, spec, cache);
    }
  } catch (const std::exception& e) {
    std::cerr << "chaosweep run: " << e.what() << "\n";
    return exit_bad_input;
  }
  std::unique_ptr<CsvTraceWriter> trace;
  try {
    if (!trace_path.empty()) trace = std::make_unique<CsvTraceWriter>(trace_path);
  } catch (const std::exception& e) {
    std::cerr << "chaosweep run: --trace: " << e.what() << "\n";
    return exit_failure;
  }
  const RunRow row{tuple, SerialBatchEvaluator(trace.get()).evaluate(tuple)};
  if (trace) {
    try {
      trace->close();
    } catch (const std::exception& e) {
      std::cerr << "chaosweep run: --trace: " << e.what() << "\n";
      return exit_failure;
    }
  }
  if (json) std::cout << row_to_json(row) << "\n";
  else print_readable(row);
  if (rerun) return report_reproduction(stored.row, row, from, json ? std::cerr : std::cout);
  if (row.result.status == Status::invalid) {
    if (json) std::cerr << "chaosweep run: invalid run: " << row.result.message << "\n";
    return exit_bad_input;
  }
  return row.result.status == Status::error ? exit_failure : exit_ok;
}

}  // namespace

void add_run_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("run", "Run one simulation from flags (or re-run a stored one) and print its result");
  cmd->footer(
      "Exit status: 0 when the run executed (whatever its status), 2 for bad input or an\n"
      "invalid run (e.g. a start inside an obstacle), 3 for an internal error.\n"
      "With --from: 0 when the re-run reproduces every stored column bit for bit, 1 when\n"
      "one differs (each is listed), 2 for bad input (no such file or run_id).\n"
      "Example: chaosweep run --planner arnold --size 50 --sr 1 --ds-index 3 --start 0.5,0.5 --json\n"
      "         chaosweep run --from out/demo/results.h5 --run-id 127");
  auto raw = std::make_shared<std::map<std::string, std::string>>();
  auto json = std::make_shared<bool>(false);
  auto trace_path = std::make_shared<std::string>();
  auto from = std::make_shared<std::string>();
  auto run_id = std::make_shared<std::int64_t>(0);
  auto force = std::make_shared<bool>(false);
  add_param_flags(*cmd, *raw);
  cmd->add_flag("--json", *json, "print one JSON object with every input and output");
  cmd->add_option("--trace", *trace_path,
                  "write the trajectory as CSV (t, x, y, kind, ds_index; kind is start, arnold, "
                  "transit, logistic, chebyshev, subgoal or move)")
      ->type_name("FILE");
  auto* from_opt = cmd->add_option("--from", *from,
                                   "re-run row --run-id of this result file with its stored parameters (every "
                                   "column, its env) and say whether every column is bit-identical")
                       ->type_name("RESULTS.h5")
                       ->check(CLI::ExistingFile);
  auto* id_opt = cmd->add_option("--run-id", *run_id, "the run_id of the row --from re-runs")
                     ->check(CLI::Range(std::int64_t(0), std::numeric_limits<std::int64_t>::max()));
  from_opt->needs(id_opt);
  id_opt->needs(from_opt);
  add_force_flag(*cmd, *force);
  cmd->callback([raw, json, trace_path, from, run_id, force, &action] {
    action = [raw, json, trace_path, from, run_id, force]() -> int {
      return run_command(*raw, *json, *trace_path, *from, *run_id, *force);
    };
  });
}

}  // namespace chaosweep

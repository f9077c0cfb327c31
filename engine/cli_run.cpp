// `chaosweep run`: one run from flags.
#include <cmath>
#include <cstdio>
#include <iostream>

#include "cli_common.hpp"
#include "cli_subcommands.hpp"
#include "json_writer.hpp"
#include "run_tuple.hpp"
#include "trace_writer.hpp"

namespace chaosweep {

namespace {

void print_readable(const RunRow& row) {
  const RunParams& p = row.tuple.params;
  const RunResult& r = row.result;
  std::printf("planner         %s  (A=%g B=%g C=%g, ds_index %d, f %g, %s, %s)\n",
              to_string(p.planner), p.A, p.B, p.C, p.ds_index, p.f, to_string(p.integrator),
              to_string(p.boundary));
  std::printf("map             %s, %g x %g m, sr %g m, start (%g, %g)\n", row.tuple.env_spec.c_str(),
              p.size_x, p.size_y, p.sr, p.start_x, p.start_y);
  std::printf("status          %s\n", to_string(r.status));
  if (!r.message.empty()) std::printf("message         %s\n", r.message.c_str());
  if (r.status == Status::invalid) return;
  if (r.status == Status::ok)
    std::printf("coverage_time   %.1f s to %.0f%% coverage  (T_opt %.1f s, PR %.2f)\n",
                r.coverage_time, 100 * p.dc, r.t_opt, r.pr);
  else
    std::printf("coverage_time   not reached (%.0f%% wanted); ran %.1f s  (T_opt %.1f s)\n", 100 * p.dc,
                r.t_end, r.t_opt);
  std::printf("final_coverage  %.4f  (%lld of %lld free cells)\n", r.final_coverage,
              (long long)r.visited_cells, (long long)r.free_cells);
  std::printf("steps           %lld%s\n", (long long)r.steps,
              r.dt_halvings ? ("  (dt halved " + std::to_string(r.dt_halvings) + " times)").c_str() : "");
  std::printf("wall_time       %.3f s\n", r.wall_time);
}

}  // namespace

void add_run_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("run", "Run one simulation from flags and print its result");
  cmd->footer(
      "Exit status: 0 when the run executed (whatever its status), 2 for bad input or an\n"
      "invalid run (e.g. a start inside an obstacle), 3 for an internal error.\n"
      "Example: chaosweep run --planner arnold --size 50 --sr 1 --ds-index 3 --start 0.5,0.5 --json");
  auto raw = std::make_shared<std::map<std::string, std::string>>();
  auto json = std::make_shared<bool>(false);
  auto trace_path = std::make_shared<std::string>();
  auto force = std::make_shared<bool>(false);
  add_param_flags(*cmd, *raw);
  cmd->add_flag("--json", *json, "print one JSON object with every input and output");
  cmd->add_option("--trace", *trace_path,
                  "write the trajectory as CSV (t, x, y, kind, ds_index; kind is start, arnold, "
                  "transit or logistic)")
      ->type_name("FILE");
  add_force_flag(*cmd, *force);
  cmd->callback([raw, json, trace_path, force, &action] {
    action = [raw, json, trace_path, force]() -> int {
      RunSpec spec;
      RunTuple tuple;
      try {
        apply_param_flags(*raw, spec);
        check_output_free(*trace_path, *force, "--trace");
        EnvironmentCache cache;
        tuple = resolve_run(0, spec, cache);
      } catch (const std::exception& e) {
        std::cerr << "chaosweep run: " << e.what() << "\n";
        return exit_bad_input;
      }
      std::unique_ptr<CsvTraceWriter> trace;
      try {
        if (!trace_path->empty()) trace = std::make_unique<CsvTraceWriter>(*trace_path);
      } catch (const std::exception& e) {
        std::cerr << "chaosweep run: --trace: " << e.what() << "\n";
        return exit_failure;
      }
      const RunRow row = evaluate(tuple, trace.get());
      if (trace) {
        try {
          trace->close();
        } catch (const std::exception& e) {
          std::cerr << "chaosweep run: --trace: " << e.what() << "\n";
          return exit_failure;
        }
      }
      if (*json) std::cout << row_to_json(row) << "\n";
      else print_readable(row);
      if (row.result.status == Status::invalid) {
        if (*json) std::cerr << "chaosweep run: invalid run: " << row.result.message << "\n";
        return exit_bad_input;
      }
      return row.result.status == Status::error ? exit_failure : exit_ok;
    };
  });
}

}  // namespace chaosweep

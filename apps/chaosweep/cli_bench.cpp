// `chaosweep bench`: kernel and sweep speed on this machine.
#include <iostream>

#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "engine/bench/bench.hpp"
#include "engine/bench/variants.hpp"

namespace chaosweep {

void add_bench_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("bench", "Measure the kernels (every width this CPU runs) and a whole sweep");
  cmd->footer(
      "Reports ns per lane-step for fixed-step original Arnold in double at each width, a naive\n"
      "scalar baseline with glibc sin/cos, their ratio, runs/s of a whole sweep (scheduling and\n"
      "HDF5 included), its overhead over kernel time and 2-thread scaling. All in one process:\n"
      "compare the ratios, the machine may be shared.\n"
      "--variants instead runs the seed-000 technique variants (original, IS, SC, MZ, IS+MZ+SC,\n"
      "logistic) on 50 m / 200 m maps, SR 1 / 4, open / five_squares, one thread, the same\n"
      "--variant-runs runs per cell (ds_index 1-3 x seeds, ic jittered 1e-6, dc 0.9, max_pr 50,\n"
      "at most --variant-time robot seconds each), and reports ns per simulated step = wall time\n"
      "(per-run setup included) / (Arnold steps, or Logistic points for logistic, + transit\n"
      "points), each also as the ratio to original on the open map of the same size and SR.\n"
      "Each cell is measured --variant-rounds times, the cells of one map size and SR back to back\n"
      "in a rotated order per round: ns per step is the median round, the ratio the median of the\n"
      "rounds' ratios (with their least and greatest), so a slow phase of a shared machine falls on\n"
      "both cells of a ratio alike.");
  auto json = std::make_shared<bool>(false);
  auto seconds = std::make_shared<double>(1.0);
  cmd->add_flag("--json", *json, "print one JSON object");
  cmd->add_option("--seconds", *seconds, "minimum time per kernel measurement, over all its rounds")
      ->check(CLI::Range(0.01, 600.0));
  auto pipeline = std::make_shared<std::string>();
  cmd->add_option("--pipeline", *pipeline,
                  "measure only this target's lane pipeline (scalar, avx2 or avx512), once, and print its ns "
                  "per lane-step (to compare two builds: tests/benchmarks/ab.sh)")
      ->check(CLI::IsMember({"scalar", "avx2", "avx512"}));
  auto variants = std::make_shared<bool>(false);
  auto vopt = std::make_shared<VariantOptions>();
  cmd->add_flag("--variants", *variants, "measure the technique variants per simulated step instead (see below)");
  cmd->add_option("--variant-runs", vopt->runs, "runs per --variants cell")
      ->check(CLI::Range(1, 100000))
      ->default_val(vopt->runs);
  cmd->add_option("--variant-rounds", vopt->rounds,
                  "times each --variants cell is measured (a map size and SR's cells back to back, in turn)")
      ->check(CLI::Range(1, 99))
      ->default_val(vopt->rounds);
  cmd->add_option("--variant-time", vopt->max_time, "robot seconds per --variants run at most (max_time)")
      ->check(CLI::Range(1.0, 1e7))
      ->default_val(vopt->max_time);
  cmd->callback([json, seconds, pipeline, variants, vopt, &action] {
    action = [json, seconds, pipeline, variants, vopt]() -> int {
      if (*variants) {
        const VariantsReport r = run_variants_bench(*vopt);
        std::cout << (*json ? variants_json(r) : variants_text(r)) << "\n";
        return exit_ok;
      }
      if (!pipeline->empty()) {
        const SimdTarget t = *parse_simd_target(*pipeline);
        if (!cpu_supports(t)) {
          std::cerr << "error: --pipeline " << *pipeline
                    << ": this CPU does not run it (best: " << to_string(best_simd_target()) << ")\n";
          return exit_bad_input;
        }
        std::cout << measure_width(t, *seconds) << "\n";
        return exit_ok;
      }
      const BenchReport r = run_bench(*seconds);
      std::cout << (*json ? bench_json(r) : bench_text(r)) << "\n";
      return exit_ok;
    };
  });
}

}  // namespace chaosweep

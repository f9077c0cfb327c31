// `chaosweep bench`: kernel and sweep speed on this machine.
#include <iostream>

#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "engine/bench/bench.hpp"

namespace chaosweep {

void add_bench_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("bench", "Measure the kernels (every width this CPU runs) and a whole sweep");
  cmd->footer(
      "Reports ns per lane-step for fixed-step original Arnold in double at each width, a naive\n"
      "scalar baseline with glibc sin/cos, their ratio, runs/s of a whole sweep (scheduling and\n"
      "HDF5 included), its overhead over kernel time and 2-thread scaling. All in one process:\n"
      "compare the ratios, the machine may be shared.");
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
  cmd->callback([json, seconds, pipeline, &action] {
    action = [json, seconds, pipeline]() -> int {
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

// chaosweep: batch experiments for chaotic coverage path planners.
#include <malloc.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"
#include "engine/run/simd_choice.hpp"
#include "engine/store/h5_library.hpp"
#include "engine/store/version.hpp"

int main(int argc, char** argv) {
  using namespace chaosweep;
  skip_hdf5_exit_handler();
  // HDF5 allocates and frees a buffer of about a chunk (1 MiB) for each
  // chunk it converts, fills or filters; glibc gave each back to the kernel
  // (an mmap of its own, or a trim of the heap's top), so the next one
  // page-faulted in again: memory up to 32 MiB a block comes from the heap,
  // and up to 64 MiB free at its top stays (issue 20, BENCHMARKS.md).
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 64 << 20);
  CLI::App app{"chaosweep: high-throughput sweeps of chaotic robot coverage planners"};
  app.require_subcommand(0, 1);
  bool version = false;
  app.add_flag("--version", version, "print version, git commit and exit");
  std::function<int()> action;
  add_run_command(app, action);
  add_plan_command(app, action);
  add_sweep_command(app, action);
  add_tune_command(app, action);
  add_merge_command(app, action);
  add_compare_command(app, action);
  add_slurm_commands(app, action);
  add_log_command(app, action);
  add_export_command(app, action);
  add_bench_command(app, action);
  add_table_command(app, action);
  add_figure_command(app, action);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? exit_ok : exit_bad_input;
  }
  if (version) {
    std::cout << "chaosweep " << engine_version() << " (git " << git_commit() << (git_dirty() ? ", dirty" : "")
              << ")\n";
    try {
      const SimdTarget t = selected_simd_target();
      std::cout << "kernels: " << to_string(t) << " (" << lane_width(t)
                << " doubles per vector; best on this CPU: " << to_string(best_simd_target()) << ")\n";
    } catch (const std::exception& e) {
      std::cerr << "chaosweep: " << e.what() << "\n";
      return exit_bad_input;
    }
    return exit_ok;
  }
  if (!action) {
    std::cout << app.help();
    return exit_bad_input;
  }
  return action();
}

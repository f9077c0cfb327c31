#pragma once
// `chaosweep bench`: the kernels' speed, measured in one process so that the
// ratios hold on a noisy shared machine (see BENCHMARKS.md).
#include <string>
#include <vector>

namespace chaosweep {

struct BenchReport {
  struct Width {
    std::string target;
    int width;                 // doubles per vector
    double ns_per_lane_step;   // whole lane pipeline: RK4, boundary, grid, checks, refill
    double lane_steps;         // measured
  };
  std::vector<Width> widths;   // every target this CPU runs
  double naive_ns_per_step;    // glibc sin/cos scalar baseline
  double best_vs_naive;        // naive / fastest width
  double sweep_runs_per_s;     // whole sweep: spec, scheduling, kernels, HDF5 (1 thread)
  double sweep_overhead;       // sweep time / kernel time - 1 (1 thread)
  double scaling_2_threads;    // sweep time with 1 thread / with 2 threads
  int sweep_runs;
  std::string cpu_best;
};

// Repeats each measurement for at least `seconds`.
BenchReport run_bench(double seconds);
std::string bench_json(const BenchReport& r);
std::string bench_text(const BenchReport& r);

}  // namespace chaosweep

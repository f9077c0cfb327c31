#pragma once
// `chaosweep bench`: the kernels' speed, measured in one process so that the
// ratios hold on a noisy shared machine (see BENCHMARKS.md).
#include <string>
#include <vector>

#include "kernels/lanes/simd_target.hpp"

namespace chaosweep {

struct BenchReport {
  struct Width {
    std::string target;
    int width;                       // doubles per vector
    double ns_per_lane_step;         // whole lane pipeline (RK4, boundary, grid, checks, refill): best round
    double ns_per_lane_step_median;  // the median round
  };
  std::vector<Width> widths;    // every target this CPU runs
  double naive_ns_per_step;     // glibc sin/cos scalar baseline, best round
  double best_vs_naive;         // naive / fastest width, best rounds
  double best_vs_naive_median;  // the same from the median rounds
  double sweep_runs_per_s;      // whole sweep: spec, scheduling, kernels, HDF5 (1 thread)
  double sweep_overhead;        // sweep time / kernel time - 1 (1 thread)
  double scaling_2_threads;     // sweep time with 1 thread / with 2 threads
  int sweep_runs;
  std::string cpu_best;
};

// ns per lane-step of one target's whole lane pipeline on the bench's
// workload, measured once for at least `seconds` (`bench --pipeline`, for
// comparing two builds: tests/benchmarks/ab.sh).
double measure_width(SimdTarget target, double seconds);

// Each kernel measurement takes `bench_rounds` rounds, interleaved, of at
// least seconds / bench_rounds each.
inline constexpr int bench_rounds = 5;
BenchReport run_bench(double seconds);
std::string bench_json(const BenchReport& r);
std::string bench_text(const BenchReport& r);

}  // namespace chaosweep

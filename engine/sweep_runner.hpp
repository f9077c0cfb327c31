#pragma once
// Fans the runs of a spec out over oneTBB and hands result rows back in
// run_id order, a batch at a time. Only parallelises: run i's row is computed
// by evaluate() alone and lands in slot i, so the output never depends on the
// thread count or on scheduling.
#include <cstdint>
#include <functional>
#include <vector>

#include "environment_loader.hpp"
#include "run_tuple.hpp"
#include "sweep_spec.hpp"

namespace chaosweep {

struct SweepOptions {
  int threads = 0;               // 0: all cores
  std::int64_t batch_size = 4096;
};

using RowSink = std::function<void(const std::vector<RunRow>&)>;

// Loads every environment the spec names; throws on the first bad one, so a
// sweep with bad input fails before any run starts.
void preload_environments(const SweepSpec& spec, EnvironmentCache& cache);

// Runs every run of `spec`, calling sink with consecutive batches.
void run_sweep(const SweepSpec& spec, const SweepOptions& opt, const RowSink& sink);

// All rows at once (tests, small sweeps).
std::vector<RunRow> run_sweep_rows(const SweepSpec& spec, const SweepOptions& opt);

}  // namespace chaosweep

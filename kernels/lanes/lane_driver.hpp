#pragma once
// Runs a batch of runs through the lane integrators: each lane holds one run,
// and when a run ends the next run of the batch takes its lane at once.
// Runs the lanes cannot take (step doubling, planners other than the
// seed-000 family's) run on the scalar reference path. Results land in the
// slot of their run, whatever the lane, target or order: a pure function of
// each run's parameters.
#include <atomic>
#include <cstddef>
#include <cstdint>

#include "kernels/core/environment.hpp"
#include "kernels/core/run_params.hpp"
#include "kernels/lanes/simd_target.hpp"

namespace chaosweep {

struct BatchItem {
  const RunParams* params;
  const Environment* env;
};

// results[i] for items[i]; never throws for a failing run (status error).
void run_batch(const BatchItem* items, RunResult* results, std::size_t n, SimdTarget target);

// Runs shared by several workers: each worker claims the next few runs from
// `next` (at most a lane's worth, one near the end) and its lanes take them
// as soon as a lane frees up, so lanes idle only at the very end. `done`
// (optional) counts finished runs and `not_ok` those not ok, for progress
// reports (each worker adds its counts every 32 runs or 50 ms of runs, and
// when it ends).
struct RunQueue {
  const BatchItem* items;
  RunResult* results;
  std::size_t n;
  std::atomic<std::size_t> next{0};
  std::atomic<std::int64_t>* done = nullptr;
  std::atomic<std::int64_t>* not_ok = nullptr;
  // When set, lanes take no new run; the runs in flight finish, so the runs
  // done are exactly items [0, min(next, n)).
  const std::atomic<bool>* stop = nullptr;
  // When set, finished[i] becomes 1 (release) once results[i] is final, so
  // another thread may take finished runs while the batch goes on.
  std::atomic<std::uint8_t>* finished = nullptr;
};
void run_queue(RunQueue& queue, SimdTarget target);

// True when a run goes through the lanes (the Arnold planner with fixed-step
// RK4, the Logistic planner).
bool lane_eligible(const RunParams& p);
// The lanes' group of an eligible run (lane_group.hpp).
int lane_group(const RunParams& p);

}  // namespace chaosweep

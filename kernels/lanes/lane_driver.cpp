#include "kernels/lanes/lane_driver.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "kernels/lanes/lane_arrays.hpp"
#include "kernels/lanes/lane_binding.hpp"
#include "kernels/lanes/lane_group.hpp"
#include "kernels/planners/planner.hpp"

namespace chaosweep {

LaneSink::~LaneSink() = default;

bool lane_eligible(const RunParams& p) {
  return p.planner == Planner::logistic ||
         (p.planner == Planner::arnold && p.integrator == Integrator::rk4 && p.system >= 0 && p.system < system_count);
}

int lane_group(const RunParams& p) { return p.planner == Planner::logistic ? logistic_lane_group : p.system; }

namespace {

using clock_type = std::chrono::steady_clock;

void record_error(RunResult& r, const char* what) {
  r = RunResult{};
  r.status = Status::error;
  r.message = what;
}

// Runs the lanes cannot take (step doubling, the other planners).
void run_scalar(const BatchItem& it, RunResult& r) {
  const auto t0 = clock_type::now();
  try {
    r = run_planner(*it.params, *it.env);
  } catch (const std::exception& e) {
    record_error(r, e.what());
  }
  r.wall_time = std::chrono::duration<double>(clock_type::now() - t0).count();
}

class LaneDriver final : public LaneSink {
 public:
  LaneDriver(RunQueue& queue, int lanes)
      : q_(queue), items_(queue.items), results_(queue.results), slots_(std::size_t(lanes)) {
    a_.lanes = lanes;
    for (int l = 0; l < lanes; ++l) load(l);
  }
  ~LaneDriver() { flush_counts(); }
  LaneDriver(const LaneDriver&) = delete;
  LaneDriver& operator=(const LaneDriver&) = delete;

  // The lanes run one group at a time (LaneArrays::system, lane_group.hpp):
  // once the integrator has no active lane, the runs of other groups taken
  // on the way start, a group at a time. False when none is left.
  bool next_system() {
    for (;;) {
      int k = 0;
      while (k < lane_group_count && pending_[std::size_t(k)].empty()) ++k;
      if (k == lane_group_count) return false;
      system_ = k;
      a_.system = k;
      for (int l = 0; l < a_.lanes; ++l) load(l);
      if (any_active()) return true;
    }
  }

  // Visits only the lanes whose step reached dc (to end the run) and the
  // lanes the integrator flagged (to redo their step in full); it applied
  // every other lane's step itself. Idle lanes are never flagged (LaneArrays::active).
  bool post_step() override {
    // Steps the integrator applied that reached dc, then the flagged steps;
    // the two sets are disjoint.
    for (unsigned m = a_.covered; m != 0; m &= m - 1) handle(std::countr_zero(m), true);
    for (unsigned m = a_.flagged; m != 0; m &= m - 1) handle(std::countr_zero(m), false);
    return any_active();
  }

  LaneArrays& arrays() { return a_; }
  // A lane has a run exactly when its bit is set (load, idle_lane).
  bool any_active() const { return a_.active != 0; }

 private:
  struct Slot {
    std::size_t item = 0;
    std::optional<CoverageGrid> grid;
    std::unique_ptr<LaneBinding> run;
    clock_type::time_point t0;
  };

  // Idle lane: harmless numbers (a frozen lane: never applied, never
  // flagged), never read back.
  void idle_lane(int l) {
    a_.active &= ~(1u << l);
    a_.x[l] = a_.y[l] = a_.z[l] = a_.kA[l] = a_.kB[l] = a_.kC[l] = a_.kD[l] = a_.pos6[l] = 0.0;
    a_.ds[l] = 3.0;
    a_.h[l] = a_.h_pos[l] = 0.0;
    a_.sx[l] = a_.sy[l] = a_.sz[l] = 0.0;
    a_.cx[l] = a_.cy[l] = a_.cz[l] = 1.0;
    a_.small[l] = 1.0;
    a_.fast[l] = a_.fold[l] = a_.UX[l] = a_.UY[l] = 0.0;
    a_.X[l] = a_.Y[l] = a_.t[l] = a_.fh[l] = a_.steps[l] = a_.seg_step[l] = 0.0;
    a_.budget[l] = a_.stuck_time[l] = a_.niter[l] = 1.0;
    a_.t_last_new[l] = a_.lo_x[l] = a_.hi_x[l] = a_.lo_y[l] = a_.hi_y[l] = 0.0;
    a_.inv_cell[l] = 1.0;
    a_.max_i[l] = a_.max_j[l] = a_.cell_i[l] = a_.cell_j[l] = 0.0;
    a_.cells[l] = nullptr;
    a_.cell_k[l] = 0;
    a_.stamp[l] = nullptr;
    a_.window[l] = 0;
    a_.window_distinct[l] = 0;
    a_.region[l] = nullptr;
    a_.region_visited[l] = nullptr;
    a_.visits[l] = nullptr;
    a_.turns[l] = nullptr;
    a_.last_dir[l] = -1;
    a_.obstacles[l] = false;
    a_.box_x0[l] = a_.box_x1[l] = a_.box_y0[l] = a_.box_y1[l] = 0.0;
    a_.near_x0[l] = a_.near_x1[l] = a_.near_y0[l] = a_.near_y1[l] = a_.near_mirror[l] = 0.0;
    a_.visited[l] = a_.cover_sum[l] = 0.0;
    a_.needed[l] = 1.0;
  }

  // Lane l's step for the sink (LaneBinding::lane_covered or lane_step); when
  // its run ends, the lane takes the next one.
  void handle(int l, bool covered) {
    Slot& s = slots_[std::size_t(l)];
    if (!s.run) return;
    try {
      if (!(covered ? s.run->lane_covered(a_, l) : s.run->lane_step(a_, l))) return;
      complete(s);
    } catch (const std::exception& e) {
      record_error(results_[s.item], e.what());
      s.run.reset();
      count(results_[s.item]);
    }
    load(l);
  }

  void complete(Slot& s) {
    s.run->run().finish();
    RunResult& r = results_[s.item];
    conclude_run(*items_[s.item].params, *s.grid, r);
    r.wall_time = std::chrono::duration<double>(clock_type::now() - s.t0).count();
    s.run.reset();
    count(r);
  }

  void count(const RunResult& r) {
    if (q_.finished) q_.finished[std::size_t(&r - results_)].store(1, std::memory_order_release);
    ++done_;
    not_ok_ += r.status != Status::ok;
    counted_wall_ += r.wall_time;
    if (done_ == 32 || counted_wall_ >= 0.05) flush_counts();
  }

  // The progress counters are shared by every thread: bumped once per run,
  // their cache line went back and forth between the threads. They are
  // added to every 32 runs, or sooner when the runs are slow (50 ms of
  // their wall time), so a progress report never lags by much.
  void flush_counts() {
    if (q_.done) *q_.done += done_;
    if (q_.not_ok && not_ok_) *q_.not_ok += not_ok_;
    done_ = not_ok_ = 0;
    counted_wall_ = 0;
  }

  // Puts the next run that needs integrating into lane l (or leaves it idle).
  void load(int l) {
    Slot& s = slots_[std::size_t(l)];
    while (take(s.item)) {
      s.t0 = clock_type::now();
      RunResult& r = results_[s.item];
      const BatchItem& it = items_[s.item];
      if (!lane_eligible(*it.params)) {  // scalar reference path, right here
        run_scalar(it, r);
        count(r);
        continue;
      }
      const int group = lane_group(*it.params);
      if (system_ < 0) a_.system = system_ = group;  // the first lane run's
      if (group != system_) {                        // for a later turn of its group's (next_system)
        pending_[std::size_t(group)].push_back(s.item);
        ++held_;
        continue;
      }
      try {
        if (!prepare_run(*it.params, *it.env, s.grid, r)) {  // invalid: recorded
          count(r);
          continue;
        }
        s.run = std::make_unique<LaneBinding>(*it.params, *it.env, *s.grid, r);
        s.run->run().start();
        if (s.run->run().ended()) {
          complete(s);
          continue;
        }
        s.run->write_lane(a_, l);
        a_.active |= 1u << l;
        return;
      } catch (const std::exception& e) {
        record_error(r, e.what());
        s.run.reset();
        count(r);
      }
    }
    idle_lane(l);
  }

  // The next run for a lane: one of the current system's taken earlier, else
  // one claimed from the queue before, else the queue's next (none once
  // `stop` is set: a taken run always finishes).
  bool take(std::size_t& item) {
    if (system_ >= 0 && !pending_[std::size_t(system_)].empty()) {
      item = pending_[std::size_t(system_)].front();
      pending_[std::size_t(system_)].pop_front();
      --held_;
      return true;
    }
    if (claimed_ < claimed_end_) {
      item = claimed_++;
      return true;
    }
    // Holding a lane's worth of other systems' runs, take no more: the lanes
    // drain and turn to them, and the rest of the queue stays for the other
    // threads (else one thread would hold all of a mixed batch's tail).
    if (held_ >= std::size_t(a_.lanes)) return false;
    if (q_.stop && q_.stop->load(std::memory_order_relaxed)) return false;
    // Runs are claimed up to a lane's worth at a time: claimed one by one,
    // the threads took neighbouring runs, wrote neighbouring results (false
    // sharing) and bumped `next` once per run. Near the queue's end a claim
    // shrinks to one run, so no thread holds runs another could start.
    const std::size_t left = q_.n - std::min(q_.n, q_.next.load(std::memory_order_relaxed));
    const std::size_t claim = std::clamp<std::size_t>(left / 64, 1, std::size_t(a_.lanes));
    claimed_ = q_.next.fetch_add(claim);
    if (claimed_ >= q_.n) return false;
    claimed_end_ = std::min(q_.n, claimed_ + claim);
    item = claimed_++;
    return true;
  }

  RunQueue& q_;
  const BatchItem* items_;
  RunResult* results_;
  std::vector<Slot> slots_;
  LaneArrays a_;
  int system_ = -1;                            // the lanes' system (-1: no lane run yet)
  std::size_t held_ = 0;                       // runs in pending_
  std::size_t claimed_ = 0, claimed_end_ = 0;  // runs claimed from the queue, not yet taken
  std::int64_t done_ = 0, not_ok_ = 0;         // counted here, not yet in q_.done and q_.not_ok
  double counted_wall_ = 0;                    // the wall time of those runs
  std::vector<std::deque<std::size_t>> pending_ = std::vector<std::deque<std::size_t>>(std::size_t(lane_group_count));
};

}  // namespace

void run_queue(RunQueue& queue, SimdTarget target) {
  LaneDriver driver(queue, lane_count(target));
  if (!driver.any_active() && !driver.next_system()) return;
  do {
    switch (target) {
      case SimdTarget::scalar:
        integrate_lanes_scalar(driver.arrays(), driver);
        break;
      case SimdTarget::avx2:
        integrate_lanes_avx2(driver.arrays(), driver);
        break;
      case SimdTarget::avx512:
        integrate_lanes_avx512(driver.arrays(), driver);
        break;
    }
  } while (driver.next_system());
}

void run_batch(const BatchItem* items, RunResult* results, std::size_t n, SimdTarget target) {
  RunQueue queue{items, results, n};
  run_queue(queue, target);
}

}  // namespace chaosweep

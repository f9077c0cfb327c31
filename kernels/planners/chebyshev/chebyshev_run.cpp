#include "kernels/planners/chebyshev/chebyshev_run.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "kernels/core/cell_tracker.hpp"
#include "kernels/core/metrics.hpp"
#include "kernels/core/param_table.hpp"
#include "kernels/core/run_end.hpp"
#include "kernels/math/inline_hypot.hpp"
#include "kernels/planners/chebyshev/chebyshev_orbit.hpp"

namespace chaosweep {

namespace {

// A sub-goal that never lands in the wanted rectangle (a tiny overlap) would
// loop forever; after this many tries the run ends as stuck.
constexpr long max_tries = 10'000'000;

class ChebyshevRun {
 public:
  ChebyshevRun(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r, TraceSink* trace)
      : p_(p),
        grid_(grid),
        r_(r),
        trace_(trace),
        d_(decompose_free_space(env, p.radius)),
        needed_(cells_needed(p, grid)),
        budget_(run_budget(p, r.t_opt)),
        x_(p.cheb_x0),
        y_(p.cheb_y0),
        x_orbit_(p.cheb_k, p.cheb_x0, p.cheb_transform),
        y_orbit_(p.cheb_k, p.cheb_y0, p.cheb_transform),
        px_(p.start_x),
        py_(p.start_y) {
    grid_.mark_point(px_, py_);
    grid_.note_time(0.0);
    if (trace_) trace_->point({0.0, px_, py_, SegmentKind::start, 0});
    // Each rectangle's share of a loop's sub-goals, by area (at least one).
    double total = 0;
    for (const auto& reg : d_.regions) total += reg.area();
    for (const auto& reg : d_.regions)
      share_.push_back(std::max<long>(1, std::lround(double(p.loop_subgoals) * reg.area() / total)));
  }

  void run() {
    if (covered()) return end(Status::ok);
    int at = d_.region_at(px_, py_);
    while (!ended_) {
      const std::vector<int> route = loop_route(d_, at);
      std::vector<bool> done(d_.regions.size(), false);
      for (std::size_t k = 0; k < route.size() && !ended_; ++k) {
        const int reg = route[k];
        // A rectangle's share is spent on its first visit in the loop;
        // later visits only pass through.
        if (!done[std::size_t(reg)]) {
          for (long n = 0; n < share_[std::size_t(reg)] && !ended_; ++n)
            subgoal_in(d_.regions[std::size_t(reg)].box, SegmentKind::chebyshev);
          done[std::size_t(reg)] = true;
        }
        if (k + 1 == route.size() || ended_) break;
        const int next = route[k + 1];
        const int t = d_.transition_between(reg, next);
        if (t < 0) throw std::logic_error("loop route steps between rectangles with no transition");
        const auto& tr = d_.transitions[std::size_t(t)];
        // Steps 5-6: iterate in the rectangle until a sub-goal falls in the
        // transition, then in the transition until one falls in the next.
        seek(d_.regions[std::size_t(reg)].box, tr.box, SegmentKind::chebyshev);
        seek(tr.box, d_.regions[std::size_t(next)].box, SegmentKind::transit);
        at = next;
      }
      if (!ended_) ++r_.segments;  // a large loop completed
    }
  }

 private:
  bool covered() const { return grid_.visited_cells() >= needed_; }

  void end(Status s, const char* why = nullptr) {
    if (ended_) return;
    ended_ = true;
    record_end(r_, s, why, t_, px_, py_);
  }

  // Iterates the maps once and returns the sub-goal in `box` (Eq. 11).
  // An orbit that lands on a fixed point (x0 = 0.5 at k = 6 reaches 1 in one
  // step; rounding can do it anywhere) repeats one sub-goal forever: the run
  // ends as diverged, like the Logistic planner's.
  std::pair<double, double> next_subgoal(const Rect& box) {
    const double px = x_, py = y_;
    const auto [x, u] = x_orbit_.next();
    const auto [y, w] = y_orbit_.next();
    x_ = x, y_ = y;
    if (x_ == px || y_ == py) end(Status::diverged, "Chebyshev orbit collapsed onto a fixed point");
    return {box.x0 + u * (box.x1 - box.x0), box.y0 + w * (box.y1 - box.y0)};
  }

  void subgoal_in(const Rect& box, SegmentKind kind) {
    const auto [gx, gy] = next_subgoal(box);
    if (!ended_) walk_to(gx, gy, kind);
  }

  // Sub-goals in `box` until one lies in `target` (walking to each).
  void seek(const Rect& box, const Rect& target, SegmentKind kind) {
    for (long tries = 0; !ended_; ++tries) {
      if (tries == max_tries) return end(Status::stuck, "no sub-goal reached the next rectangle");
      const auto [gx, gy] = next_subgoal(box);
      if (ended_) return;
      walk_to(gx, gy, kind);
      if (target.contains_closed(gx, gy)) return;
    }
  }

  // Straight-line interpolation at the robot's step (Section 4), marking the
  // cells on the way; the last move lands on the sub-goal exactly. The moves
  // are equal (dist / moves) up to rounding, so each is charged that length
  // at speed v: one hypot per walk, not per move (a hypot per move was most
  // of the planner's time; the clock differs from it by a few ulps).
  void walk_to(double gx, double gy, SegmentKind kind) {
    const double dist = inline_hypot(gx - px_, gy - py_);
    const long moves = std::max<long>(1, long(std::ceil(dist / p_.step)));
    const double move_time = dist / double(moves) / p_.v;
    const double sx = px_, sy = py_, budget = budget_;
    const bool points = p_.sampling == Sampling::points;
    TraceSink* const trace = trace_;
    // The robot's state in locals for the walk (the grid calls could alias
    // the members for the compiler), stored back where the walk stops.
    double x = px_, y = py_, t = t_;
    long m = 1;
    const auto stop = [&] {
      px_ = x, py_ = y, t_ = t;
      r_.steps += m;
    };
    CellTracker cell(grid_, x, y);
    for (;; ++m) {
      const bool last = m == moves;
      const double f = double(m) / double(moves);
      const double nx = last ? gx : sx + f * (gx - sx), ny = last ? gy : sy + f * (gy - sy);
      const bool entered = cell.mark_move(grid_, points, x, y, nx, ny);
      x = nx, y = ny;
      t += move_time;
      if (entered) grid_.note_time(t);
      if (last) ++r_.subgoals;
      if (trace) trace->point({t, x, y, last && kind == SegmentKind::chebyshev ? SegmentKind::subgoal : kind, 0});
      if (entered && covered()) return stop(), end(Status::ok);
      if (t >= budget) return stop(), end(Status::timeout, "budget reached before dc");
      if (last) break;
    }
    stop();
    if (p_.max_subgoals > 0 && r_.subgoals >= p_.max_subgoals) end(Status::timeout, "max_subgoals reached before dc");
  }

  const RunParams& p_;
  CoverageGrid& grid_;
  RunResult& r_;
  TraceSink* trace_;
  RectDecomposition d_;
  long needed_;
  double budget_;
  double x_, y_;  // the two maps' states (untransformed)
  ChebyshevOrbit x_orbit_, y_orbit_;
  double px_, py_;  // robot position
  double t_ = 0;
  bool ended_ = false;
  std::vector<long> share_;
};

}  // namespace

std::vector<int> loop_route(const RectDecomposition& d, int from) {
  std::vector<int> route{from};
  std::vector<bool> seen(d.regions.size(), false);
  seen[std::size_t(from)] = true;
  // Iterative depth-first walk. Coming back from a child, the walk passes
  // through every region between it and the next unseen one; those regions
  // are held back (`back`) and listed only once a new region follows, so the
  // route never returns after its last new region and each pair of
  // consecutive entries stays linked by a transition.
  struct Frame {
    int region;
    std::vector<int> next;
    std::size_t k;
  };
  std::vector<Frame> stack{{from, d.neighbours(from), 0}};
  std::vector<int> back;
  while (!stack.empty()) {
    Frame& f = stack.back();
    if (f.k == f.next.size()) {
      stack.pop_back();
      if (!stack.empty()) back.push_back(stack.back().region);
      continue;
    }
    const int n = f.next[f.k++];
    if (seen[std::size_t(n)]) continue;
    seen[std::size_t(n)] = true;
    // `back` ends in f.region, the region n is entered from.
    route.insert(route.end(), back.begin(), back.end());
    back.clear();
    route.push_back(n);
    stack.push_back({n, d.neighbours(n), 0});
  }
  return route;
}

std::string validate_chebyshev(const RunParams& p, const Environment& env) {
  RectDecomposition d;
  try {
    d = decompose_free_space(env, p.radius);
  } catch (const std::invalid_argument& e) {
    return std::string("radius = ") + format_number(p.radius) + ": " + e.what();
  }
  if (d.region_at(p.start_x, p.start_y) < 0)
    return "start (" + format_number(p.start_x) + ", " + format_number(p.start_y) +
           ") is not in the free space shrunk by radius = " + format_number(p.radius) +
           " (the robot's centre must stay radius from walls and obstacles)";
  return {};
}

void run_chebyshev(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r, TraceSink* trace) {
  ChebyshevRun(p, env, grid, r, trace).run();
}

}  // namespace chaosweep

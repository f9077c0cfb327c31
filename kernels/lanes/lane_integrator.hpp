#pragma once
// The lane loop shared by every width: load N interleaved vectors of W lanes
// from the arrays, take RK4 steps (the same arithmetic as the scalar
// reference, see kernels/systems/) with the state in registers, apply each
// step's common case (fast_path, mark_entered) until a step leaves the sink
// work, store, let the sink handle it. Include only from
// lane_kernel_<target>.cpp.
#include <type_traits>

#include "kernels/core/boundary.hpp"
#include "kernels/lanes/lane_arrays.hpp"
#include "kernels/lanes/lane_group.hpp"

namespace chaosweep {

template <class V>
inline V lane_load(const double* p) {
  V v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}

template <class V>
inline void lane_store(double* p, V v) {
  __builtin_memcpy(p, &v, sizeof v);
}

// What bounds a kernel's lanes, each form a loop of its own (steps_until_sink):
// mirror, Eq. 7's band only (open maps); obstacles, the band and Eq. 8 in
// each lane's obstacle box; fold, some lane on the fold boundary (its
// unfolded position folded in full), obstacles or not. The mirror
// boundary's lanes reflect once per axis in every form but fold (a step
// that needs more leaves the band, and so the box, and goes to the sink):
// folding in full, at every step, the lanes of Table 1's obstacle maps paid
// for the fold lanes no run of theirs has.
enum class LaneWalls { mirror, obstacles, fold };

// The steps fast_path applied (lane o in bit 0), and among them those that
// entered a neighbouring cell across an edge (to be marked: mark_entered) or
// a corner (mark_diagonal).
struct FastPathBits {
  unsigned applied, entered, diagonal;
  unsigned ahead;  // marking lanes whose step, repeated, would leave the cell (see prefetch_ahead)
};

// A vector's fixed inputs to fast_path: what only the sink changes (band,
// cell size, budget, fast mode), loaded once per call of steps_until_sink
// instead of at every pass (the stores to the arrays between passes would
// otherwise make the compiler reload them).
template <class V>
struct FastPathInputs {
  V lo_x, hi_x, lo_y, hi_y, fh, inv, mi, mj, budget, stuck_time, niter;
  decltype(V() < V()) fast_ok, fast_cross, fast_diag;                    // fast >= 1, >= 2, == 3
  V box_x0, box_x1, box_y0, box_y1, near_x0, near_x1, near_y0, near_y1;  // with obstacles
  decltype(V() < V()) near_mirror;
};

template <class V>
inline FastPathInputs<V> load_fast_path_inputs(const LaneArrays& a, int o) {
  const auto at = [o](const double* p) { return lane_load<V>(p + o); };
  const V fast = at(a.fast);
  return {at(a.lo_x),
          at(a.hi_x),
          at(a.lo_y),
          at(a.hi_y),
          at(a.fh),
          at(a.inv_cell),
          at(a.max_i),
          at(a.max_j),
          at(a.budget),
          at(a.stuck_time),
          at(a.niter),
          fast >= lane::splat<V>(1.0),
          fast >= lane::splat<V>(2.0),
          fast == lane::splat<V>(3.0),
          at(a.box_x0),
          at(a.box_x1),
          at(a.box_y0),
          at(a.box_y1),
          at(a.near_x0),
          at(a.near_x1),
          at(a.near_y0),
          at(a.near_y1),
          at(a.near_mirror) == lane::splat<V>(1.0)};
}

// The step's common case, vectorised (see LaneArrays). Mirrors
// RobotMotion::move, CoverageGrid::cell_x and PlannerRun::after_move
// operation for operation, so a lane's result never depends on the path.
// `passes`: the steps taken since the arrays' step and segment counts were
// last brought up to date (count_steps), this one included. Walls: what
// bounds the kernel's lanes (LaneWalls). Diagonal: the fast = 3 lanes' steps
// into a diagonal neighbour are applied too (their start kept in X0, Y0).
template <class V, LaneWalls Walls, bool Diagonal>
inline FastPathBits fast_path(LaneArrays& a, int o, const FastPathInputs<V>& c, const Rk4Step<V>& s, V passes,
                              bool prefetch, double* ahead_k) {
  const V one = lane::splat<V>(1.0);
  const V X = lane_load<V>(a.X + o), Y = lane_load<V>(a.Y + o), t = lane_load<V>(a.t + o);
  const V lo_x = c.lo_x, hi_x = c.hi_x, lo_y = c.lo_y, hi_y = c.hi_y;
  V X1 = X + s.dX, Y1 = Y + s.dY, UX{}, UY{}, UX1{}, UY1{};
  if constexpr (Walls != LaneWalls::fold) {
    // Eq. 7 as triangle_fold's single reflections (2 lo - u, 2 hi - u); a
    // step that needs more than one is flagged below (still outside the band,
    // which holds the obstacle box).
    X1 = lane::select(X1 < lo_x, (lo_x + lo_x) - X1, X1);
    X1 = lane::select(X1 > hi_x, (hi_x + hi_x) - X1, X1);
    Y1 = lane::select(Y1 < lo_y, (lo_y + lo_y) - Y1, Y1);
    Y1 = lane::select(Y1 > hi_y, (hi_y + hi_y) - Y1, Y1);
  } else {
    // RobotMotion::move in full: fold lanes fold their unfolded position,
    // mirror lanes their own (mirror_eq7 is the fold of the band).
    const auto is_fold = lane_load<V>(a.fold + o) == one;
    UX = lane_load<V>(a.UX + o);
    UY = lane_load<V>(a.UY + o);
    UX1 = UX + s.dX;
    UY1 = UY + s.dY;
    X1 = triangle_fold(lane::select(is_fold, UX1, X1), lo_x, hi_x);
    Y1 = triangle_fold(lane::select(is_fold, UY1, Y1), lo_y, hi_y);
  }
  // The band (with obstacles: the obstacle box) holds the step's end.
  const auto inside = [&] {
    if constexpr (Walls == LaneWalls::mirror) {
      return (X1 >= lo_x) & (X1 <= hi_x) & (Y1 >= lo_y) & (Y1 <= hi_y);
    } else {
      // Eq. 8 (keep_out_of_obstacles) for a step that ends in the lane's
      // obstacle box: a position in near's open rectangle goes to its face of
      // least penetration, in move_to_face's order (left, right, bottom, top),
      // or is reflected about it (near_mirror); applied only when the point
      // it reaches is in the box too (obstacle_box).
      const auto in_box = [&c](V x, V y) {
        return (x >= c.box_x0) & (x <= c.box_x1) & (y >= c.box_y0) & (y <= c.box_y1);
      };
      const auto ends_in = in_box(X1, Y1);
      const auto pushed = (X1 > c.near_x0) & (X1 < c.near_x1) & (Y1 > c.near_y0) & (Y1 < c.near_y1);
      // Most steps end clear of every lane's near rectangle: nothing to push,
      // and the point stays where ends_in found it.
      if (lane::none(pushed)) return ends_in;
      const V to_left = X1 - c.near_x0, to_right = c.near_x1 - X1, to_bottom = Y1 - c.near_y0, to_top = c.near_y1 - Y1;
      const V m_x = lane::select(to_right < to_left, to_right, to_left);
      const V m_y = lane::select(to_top < to_bottom, to_top, to_bottom);
      const V m = lane::select(m_y < m_x, m_y, m_x);
      const auto left = to_left == m;
      const auto on_x = left | (to_right == m);  // a mask (int for the scalar double lanes)
      const V face_x = lane::select(left, c.near_x0, c.near_x1),
              face_y = lane::select(to_bottom == m, c.near_y0, c.near_y1);
      const V PX = lane::select(on_x, lane::select(c.near_mirror, (face_x + face_x) - X1, face_x), X1);
      const V PY = lane::select(on_x, Y1, lane::select(c.near_mirror, (face_y + face_y) - Y1, face_y));
      X1 = lane::select(pushed, PX, X1);
      Y1 = lane::select(pushed, PY, Y1);
      return ends_in & in_box(X1, Y1);
    }
  }();
  const V t1 = t + c.fh;
  // cell_x's clamp from below is a no-op for the steps applied: they end
  // inside the band, X1 >= lo_x >= 0 (fo, or 0 for the fold; a -0 index
  // compares equal to 0).
  V ci = lane::trunc(X1 * c.inv), cj = lane::trunc(Y1 * c.inv);
  ci = lane::select(ci < c.mi, ci, c.mi);
  cj = lane::select(cj < c.mj, cj, c.mj);
  const V seg = lane_load<V>(a.seg_step + o) + passes;
  const V cell_i = lane_load<V>(a.cell_i + o), cell_j = lane_load<V>(a.cell_j + o);
  // One NaN test for the state: a NaN coordinate makes the sum NaN (so does
  // inf - inf, which only sends that step to the sink, the reference path).
  const V sum = s.u.x + s.u.y + s.u.z;
  const auto ok = inside & c.fast_ok & (t1 < c.budget) & ((t1 - lane_load<V>(a.t_last_new + o)) < c.stuck_time) &
                  (seg < c.niter) & (sum == sum);
  // Cell indices are small whole numbers: the squared index distance is 0
  // for a step that stays in its cell and 1 for one that crossed one edge
  // exactly (a corner or a longer jump is left to the sink's supercover).
  const V di = ci - cell_i, dj = cj - cell_j;
  const V d2 = lane::fma(di, di, dj * dj);
  const auto quiet = ok & (d2 == lane::splat<V>(0.0));
  const auto entered = ok & c.fast_cross & (d2 == one);
  auto applied = quiet | entered;
  unsigned diagonal = 0;
  if constexpr (Diagonal) {
    const auto corner = ok & c.fast_diag & (d2 == lane::splat<V>(2.0));
    applied = applied | corner;
    diagonal = lane::bits(corner);
    lane_store(a.X0 + o, X);
    lane_store(a.Y0 + o, Y);
  }
  lane_store(a.X + o, lane::select(applied, X1, X));
  lane_store(a.Y + o, lane::select(applied, Y1, Y));
  lane_store(a.t + o, lane::select(applied, t1, t));
  if constexpr (Walls == LaneWalls::fold) {
    lane_store(a.UX + o, lane::select(applied, UX1, UX));
    lane_store(a.UY + o, lane::select(applied, UY1, UY));
  }
  lane_store(a.cell_i + o, lane::select(applied, ci, cell_i));
  lane_store(a.cell_j + o, lane::select(applied, cj, cell_j));
  unsigned ahead = 0;
  if (Diagonal && prefetch) {
    // The cell the same step again would reach (a heading turns little from
    // step to step): its index, for the lanes that mark and would leave their
    // cell (clamped into the grid; a NaN goes to 0). Only in this form: its
    // lanes' steps are long enough to enter a cell every few steps.
    const V zero = lane::splat<V>(0.0);
    V ai = lane::trunc((X1 + s.dX) * c.inv), aj = lane::trunc((Y1 + s.dY) * c.inv);
    ai = lane::select(ai > zero, ai, zero);
    aj = lane::select(aj > zero, aj, zero);
    ai = lane::select(ai < c.mi, ai, c.mi);
    aj = lane::select(aj < c.mj, aj, c.mj);
    lane_store(ahead_k, lane::fma(aj, c.mi + one, ai));
    ahead = lane::bits(applied & c.fast_cross & ((ai != ci) | (aj != cj)));
  }
  return {lane::bits(applied), lane::bits(entered), diagonal, ahead};
}

// The grids (in cells) from which the lanes prefetch (prefetch_ahead): 16
// runs' grids of 2,500 cells (50 m SR 1; 13 bytes a cell) stay in the
// caches, and the prefetch's work made those maps' diagonal-form cells up
// to 1.11x slower (BENCHMARKS.md "Prefetching the next marks"); 40,000
// (200 m SR 1) gained up to 0.86x.
inline constexpr double prefetch_grid_cells = 8192;

// Fetches the memory a lane's next cell entry marks (its grid byte, window
// stamp, visit count and zone) for the `ahead` lanes, at the cells their
// step repeated would reach (ahead_k), while the next step is computed: the
// 16 lanes are 16 runs' grids, MiBs apart, and at f 3 to 6 (a step of a
// third of a cell or more) mark_entered's loads waited on them. A template
// on V as mark_entered.
template <class V>
inline void prefetch_ahead(const LaneArrays& a, unsigned ahead, const double* ahead_k) {
  for (; ahead != 0; ahead &= ahead - 1) {
    const int l = __builtin_ctz(ahead);
    const long k = long(ahead_k[l]);
    __builtin_prefetch(a.cells[l] + k);
    __builtin_prefetch(a.visits[l] + k);
    if (a.stamp[l] != nullptr) __builtin_prefetch(a.stamp[l] + k);
    if (a.region[l] != nullptr) __builtin_prefetch(a.region[l] + k);
  }
}

// Marks the cells the `entered` lanes' applied steps entered, as
// CoverageGrid::mark_segment (its mark_crossing across one edge marks the
// cell left, then the one entered) and after_move would: the window's
// stamps, a new cell counted (by zone too), its time added to the
// coverage-time sum and t_last_new stamped; returns
// the lanes whose count reached dc. Scalar: a lane enters a cell about once
// in 30 steps. Whether a cell is new to the window and the entry's
// direction come out as the lanes wander, so they select rather than
// branch (0.94x the CPU time of the branches on 200 m SR 1 open maps;
// selecting for a new cell too measured 1.06x: its counts touch more
// memory). A template on V only to keep each kernel file's copy its own
// (tests/check_simd_symbols.sh).
template <class V>
inline unsigned mark_entered(LaneArrays& a, unsigned entered) {
  unsigned covered = 0;
  for (; entered != 0; entered &= entered - 1) {
    const int l = __builtin_ctz(entered);
    const long k = long(a.cell_j[l]) * (long(a.max_i[l]) + 1) + long(a.cell_i[l]);
    unsigned char* cells = a.cells[l];
    const unsigned char c = cells[k];
    const long left = a.cell_k[l];
    if (unsigned* stamp = a.stamp[l]) {
      // A touch of a free cell (2: blocked; a push can end in one) not yet
      // stamped in this window; storing w again changes nothing.
      const unsigned w = a.window[l];
      const bool left_new = (cells[left] != 2) & (stamp[left] != w);
      stamp[left] = left_new ? w : stamp[left];
      const bool k_new = (c != 2) & (stamp[k] != w);
      stamp[k] = k_new ? w : stamp[k];
      a.window_distinct[l] += int(left_new) + int(k_new);
    }
    // A visit and a turn, as CoverageGrid::enter counts them: the cell left
    // is the one marked last, an edge away (east, north, west, south).
    ++a.visits[l][k];
    const long step = k - left;
    const int dir = 2 * int(step <= 0) + int(step != 1 && step != -1);
    if (a.last_dir[l] >= 0) ++a.turns[l][(dir - a.last_dir[l]) & 3];
    a.last_dir[l] = dir;
    a.cell_k[l] = k;
    if (c != 0) continue;  // visited already, or blocked
    cells[k] = 1;
    if (a.region[l] != nullptr) ++a.region_visited[l][a.region[l][k]];
    a.t_last_new[l] = a.t[l];
    a.visited[l] += 1.0;
    if (a.visited[l] <= a.needed[l]) a.cover_sum[l] += a.t[l];  // CoverageGrid::note_time: one cell at t
    if (a.visited[l] >= a.needed[l]) covered |= 1u << l;
  }
  return covered;
}

// A touch of cell k (byte c) in Eq. 5's window, as CoverageGrid::mark_cell
// counts it: a free cell not yet stamped in this window. A template on V as
// mark_entered.
template <class V>
inline void touch_window(LaneArrays& a, int l, long k, unsigned char c) {
  if (unsigned* stamp = a.stamp[l]; stamp != nullptr && c != 2 && stamp[k] != a.window[l]) {
    stamp[k] = a.window[l];
    ++a.window_distinct[l];
  }
}

// Cell (i, j) of a diagonal step's crossing, as CoverageGrid::mark_cell
// marks it: entered from the lane's last cell (pi, pj) (a visit, and a turn
// by enter()'s rule: the longer axis of the jump, x on a tie), stamped in
// the window, counted when new. Returns 1 for a new cell. A template on V as
// mark_entered.
template <class V>
inline int mark_crossed_cell(LaneArrays& a, int l, long nx, long pi, long pj, long i, long j) {
  const long k = j * nx + i;
  unsigned char* cells = a.cells[l];
  const unsigned char c = cells[k];
  ++a.visits[l][k];
  const long di = i - pi, dj = j - pj;
  const int dir = (di < 0 ? -di : di) >= (dj < 0 ? -dj : dj) ? (di > 0 ? 0 : 2) : (dj > 0 ? 1 : 3);
  if (a.last_dir[l] >= 0) ++a.turns[l][(dir - a.last_dir[l]) & 3];
  a.last_dir[l] = dir;
  a.cell_k[l] = k;
  touch_window<V>(a, l, k, c);
  if (c != 0) return 0;
  cells[k] = 1;
  if (a.region[l] != nullptr) ++a.region_visited[l][a.region[l][k]];
  return 1;
}

// Marks the cells the `diagonal` lanes' applied steps crossed into a
// diagonal neighbour, as CoverageGrid::mark_step does under segments
// sampling (its mark_crossing): the start cell again (window stamps only),
// then the side cell the segment crosses first, by mark_crossing's own
// t_max arithmetic (both side cells, x first, when it passes through the
// corner), then the end cell; the new cells count at the step's time as one
// note_time would (one product, not an addition per cell). Returns the lanes
// whose count reached dc. Scalar: rarer than edge entries.
template <class V>
inline unsigned mark_diagonal(LaneArrays& a, unsigned diagonal) {
  unsigned covered = 0;
  for (; diagonal != 0; diagonal &= diagonal - 1) {
    const int l = __builtin_ctz(diagonal);
    const long nx = long(a.max_i[l]) + 1;
    const long i0 = a.cell_k[l] % nx, j0 = a.cell_k[l] / nx;
    const long i1 = long(a.cell_i[l]), j1 = long(a.cell_j[l]);
    touch_window<V>(a, l, a.cell_k[l], a.cells[l][a.cell_k[l]]);
    const double inv = a.inv_cell[l];
    const double gx0 = a.X0[l] * inv, gy0 = a.Y0[l] * inv;
    const double dx = (a.X[l] - a.X0[l]) * inv, dy = (a.Y[l] - a.Y0[l]) * inv;
    const double t_delta_x = 1.0 / __builtin_fabs(dx), t_delta_y = 1.0 / __builtin_fabs(dy);
    const double t_max_x = i1 > i0 ? (double(i0 + 1) - gx0) * t_delta_x : (gx0 - double(i0)) * t_delta_x;
    const double t_max_y = j1 > j0 ? (double(j0 + 1) - gy0) * t_delta_y : (gy0 - double(j0)) * t_delta_y;
    int fresh = 0;
    long pi = i0, pj = j0;       // the cell marked last
    if (!(t_max_y < t_max_x)) {  // x first, or through the corner
      fresh += mark_crossed_cell<V>(a, l, nx, pi, pj, i1, j0);
      pi = i1;
    }
    if (!(t_max_x < t_max_y)) {
      fresh += mark_crossed_cell<V>(a, l, nx, pi, pj, i0, j1);
      pi = i0;
      pj = j1;
    }
    fresh += mark_crossed_cell<V>(a, l, nx, pi, pj, i1, j1);
    if (fresh == 0) continue;
    const double before = a.visited[l];
    a.visited[l] += double(fresh);
    a.t_last_new[l] = a.t[l];
    const double noted = before < a.needed[l] ? before : a.needed[l];
    const double now = a.visited[l] < a.needed[l] ? a.visited[l] : a.needed[l];
    if (now != noted) a.cover_sum[l] += (now - noted) * a.t[l];
    if (a.visited[l] >= a.needed[l]) covered |= 1u << l;
  }
  return covered;
}

// One vector's inputs to a carried system's step (CarriedSystem: the Arnold
// flow's form), from the arrays at lane offset o.
template <class V>
struct StepInput {
  Vec3<V> u;
  Trig3<V> t;
  StepScale<V> sc;
  decltype(V() < V()) small;
};

template <class V>
inline StepInput<V> load_step_input(const LaneArrays& a, int o) {
  return {{lane_load<V>(a.x + o), lane_load<V>(a.y + o), lane_load<V>(a.z + o)},
          {lane_load<V>(a.sx + o), lane_load<V>(a.cx + o), lane_load<V>(a.sy + o), lane_load<V>(a.cy + o),
           lane_load<V>(a.sz + o), lane_load<V>(a.cz + o)},
          {{lane_load<V>(a.kA + o), lane_load<V>(a.kB + o), lane_load<V>(a.kC + o)}, lane_load<V>(a.pos6 + o)},
          lane_load<V>(a.small + o) == lane::splat<V>(1.0)};
}

// A listed system's lane inputs to a step (system_list.hpp: no relabelling,
// no carried trig; the heading coordinate by per-lane masks).
template <class V>
struct SystemInput {
  Vec3<V> u;
  SystemCoeffs<V> k;
  HeadingSelect<V> hs;
  V h, h_pos;
};

template <class V>
inline SystemInput<V> load_system_input(const LaneArrays& a, int o) {
  const V ds = lane_load<V>(a.ds + o);
  return {{lane_load<V>(a.x + o), lane_load<V>(a.y + o), lane_load<V>(a.z + o)},
          {lane_load<V>(a.kA + o), lane_load<V>(a.kB + o), lane_load<V>(a.kC + o), lane_load<V>(a.kD + o)},
          {ds == lane::splat<V>(1.0), ds == lane::splat<V>(2.0)},
          lane_load<V>(a.h + o),
          lane_load<V>(a.h_pos + o)};
}

// One step of a group's lanes that carry nothing: a listed system's
// (system_step) or the Logistic planner's.
template <class F, class V>
inline SystemStep<V> uncarried_step(const SystemInput<V>& in) {
  if constexpr (std::is_same_v<F, LogisticMap>) return LogisticMap::lane_step(in.u, in.k, in.h_pos);
  else return system_step<F>(in.u, in.k, in.hs, in.h, in.h_pos);
}

// Brings the step and segment counts up to date after `passes` steps of
// which every lane took all but the last, and the lanes in `applied` that
// one too (a flagged lane's step is the sink's to count).
template <class V>
inline void count_steps(LaneArrays& a, int passes, unsigned applied) {
  for (int l = 0; l < a.lanes; ++l) {
    const double taken = passes - ((applied >> l) & 1u ? 0 : 1);
    a.steps[l] += taken;
    a.seg_step[l] += taken;
  }
}

template <class V>
inline void store_step(LaneArrays& a, int o, const Rk4Step<V>& s) {
  lane_store(a.x + o, s.u.x);
  lane_store(a.y + o, s.u.y);
  lane_store(a.z + o, s.u.z);
  lane_store(a.sx + o, s.t.sx);
  lane_store(a.cx + o, s.t.cx);
  lane_store(a.sy + o, s.t.sy);
  lane_store(a.cy + o, s.t.cy);
  lane_store(a.sz + o, s.t.sz);
  lane_store(a.cz + o, s.t.cz);
  lane_store(a.dX + o, s.dX);
  lane_store(a.dY + o, s.dY);
}

// What a run of steps between two calls of the sink leaves it.
struct StepsDone {
  unsigned flagged = 0, covered = 0, applied = 0;
  int passes = 0;
};

// Steps the lanes from the arrays' state, keeping it in registers, until a
// step leaves the sink work; stores every lane's state after that step.
// One function per form (flatten: the step and fast path inline into it;
// noinline: kept out of integrate_lanes), so that each form's loop is laid
// out on its own: inlined together, the fourth form (Diagonal) made the
// others 1.03x slower on 50 m SR 1 five squares (BENCHMARKS.md).
// F: the system of the lanes' group (lane_group.hpp); a carried system by
// its own step (F::step, F::step2 when Staged), any other by uncarried_step
// (Staged ignored).
template <class V, int N, bool Staged, LaneWalls Walls, bool Diagonal, class F>
[[gnu::flatten, gnu::noinline]] inline StepsDone steps_until_sink(LaneArrays& a, bool prefetch) {
  constexpr int w = int(sizeof(V) / sizeof(double));  // lanes per V
  const unsigned live = a.active & ((1u << (w * N)) - 1u);
  constexpr bool carried = CarriedSystem<F>;
  StepInput<V> in[N];
  SystemInput<V> fin[N];
  FastPathInputs<V> fixed[N];
  for (int k = 0; k < N; ++k) {
    if constexpr (carried) in[k] = load_step_input<V>(a, k * w);
    else fin[k] = load_system_input<V>(a, k * w);
    fixed[k] = load_fast_path_inputs<V>(a, k * w);
  }
  StepsDone d;
  do {
    ++d.passes;
    Rk4Step<V> s[N];
    if constexpr (!carried) {
      for (int k = 0; k < N; ++k) {
        const SystemStep<V> f = uncarried_step<F>(fin[k]);
        s[k].u = f.u;
        const V zero = lane::splat<V>(0.0);
        s[k].t = Trig3<V>{zero, zero, zero, zero, zero, zero};  // it carries nothing
        s[k].dX = f.dX;
        s[k].dY = f.dY;
      }
    } else if constexpr (Staged && N == 2) {
      Rk4Work<V, HeadingZ> wk[2];
      for (int k = 0; k < 2; ++k) {
        wk[k].u = in[k].u;
        wk[k].small = in[k].small;
      }
      if (lane::all(wk[0].small & wk[1].small))
        F::template step2<true>(wk[0], wk[1], in[0].t, in[1].t, in[0].sc, in[1].sc, s[0], s[1]);
      else F::template step2<false>(wk[0], wk[1], in[0].t, in[1].t, in[0].sc, in[1].sc, s[0], s[1]);
    } else {
      for (int k = 0; k < N; ++k) s[k] = F::step(in[k].u, in[k].t, in[k].sc, HeadingZ{}, in[k].small);
    }
    unsigned entered = 0, diagonal = 0, ahead = 0;
    alignas(64) double ahead_k[w * N];
    d.applied = 0;
    for (int k = 0; k < N; ++k) {
      const FastPathBits b = fast_path<V, Walls, Diagonal>(a, k * w, fixed[k], s[k], lane::splat<V>(double(d.passes)),
                                                           prefetch, ahead_k + k * w);
      d.applied |= b.applied << (k * w);
      entered |= b.entered << (k * w);
      diagonal |= b.diagonal << (k * w);
      ahead |= b.ahead << (k * w);
      if constexpr (carried) {
        in[k].u = s[k].u;
        in[k].t = s[k].t;
      } else {
        fin[k].u = s[k].u;
      }
    }
    d.flagged = ~d.applied & live;
    d.covered = mark_entered<V>(a, entered);
    if constexpr (Diagonal) d.covered |= mark_diagonal<V>(a, diagonal);
    if (Diagonal && prefetch) prefetch_ahead<V>(a, ahead & ~(d.flagged | d.covered), ahead_k);
    if ((d.flagged | d.covered) != 0)
      for (int k = 0; k < N; ++k) store_step(a, k * w, s[k]);
  } while ((d.flagged | d.covered) == 0);
  return d;
}

// The lanes one kernel keeps in flight: N vectors of V (a.lanes, see
// lane_count). Their system state stays in registers from step to step while
// no lane needs the sink; before the sink runs, every lane's state goes to
// the arrays, and after it comes back from them (the sink may rewrite any).
// The step and the fast path inline into one loop body per form
// (steps_until_sink): by what bounds the lanes (LaneWalls), taking diagonal
// steps or not (Diagonal).
// Staged (N = 2): interleave the two vectors' RK4 steps stage by stage.
// The lanes all run one group (a.system, LaneArrays::system, lane_group.hpp):
// a carried system's own step (the Arnold flow's), or one uncarried_step per
// vector.
template <class V, int N, bool Staged = false>
[[gnu::flatten]] inline void integrate_lanes(LaneArrays& a, LaneSink& sink) {
  for (;;) {
    if (a.active == 0) return;  // (no lane would ever stop the steps)
    bool fold = false, obstacles = false, diagonal = false, prefetch = false;
    for (int l = 0; l < a.lanes; ++l) {
      fold |= a.fold[l] != 0.0;
      obstacles |= a.obstacles[l];
      diagonal |= a.fast[l] == 3.0;
      prefetch |= (a.max_i[l] + 1.0) * (a.max_j[l] + 1.0) >= prefetch_grid_cells;
    }
    StepsDone d;
    with_lane_group(a.system, [&](auto tag) {
      using F = typename decltype(tag)::type;
      const auto form = [&]<LaneWalls W>() {
        return diagonal ? steps_until_sink<V, N, Staged, W, true, F>(a, prefetch)
                        : steps_until_sink<V, N, Staged, W, false, F>(a, prefetch);
      };
      d = fold        ? form.template operator()<LaneWalls::fold>()
          : obstacles ? form.template operator()<LaneWalls::obstacles>()
                      : form.template operator()<LaneWalls::mirror>();
    });
    count_steps<V>(a, d.passes, d.applied);
    a.flagged = d.flagged;
    a.covered = d.covered;
    if (!sink.post_step()) return;
  }
}

}  // namespace chaosweep

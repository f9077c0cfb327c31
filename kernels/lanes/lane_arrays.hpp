#pragma once
// The struct-of-arrays state the vector integrators read and write: one slot
// per lane (= one run in flight). Plain arrays only, so the per-ISA kernel
// files need nothing from the standard library.

namespace chaosweep {

struct LaneArrays {
  static constexpr int max_lanes = 16;
  int lanes = 0;
  // Arnold state and step parameters per lane, relabelled so that the
  // heading coordinate is z (to_lane in arnold_flow.hpp). The integrator
  // keeps the state in registers between the sink's calls and writes it here
  // (with dX, dY) before each, as it brings seg_step and steps up to date.
  alignas(64) double x[max_lanes], y[max_lanes], z[max_lanes];
  // Their sines and cosines, carried from step to step (rk4_step's t1).
  alignas(64) double sx[max_lanes], cx[max_lanes], sy[max_lanes], cy[max_lanes], sz[max_lanes], cz[max_lanes];
  // The run's step_scale: (h/2) A, (h/2) B, (h/2) C and h_pos / 6.
  alignas(64) double kA[max_lanes], kB[max_lanes], kC[max_lanes], pos6[max_lanes];
  alignas(64) double small[max_lanes];  // 1: small-shift mode (arnold_flow.hpp)
  // The group every lane runs (lane_group.hpp): 0 the Arnold flow (the
  // arrays above), else a system of system_list.hpp, whose lanes hold its
  // state in x, y, z as the run labels it, its coefficients in kA, kB, kC,
  // kD, the heading coordinate ds (1, 2, 3), the step h and the robot's
  // distance per step h_pos; or the Logistic planner (LogisticMap::lane_step:
  // x, kA, kB, kC and h_pos).
  int system = 0;
  alignas(64) double kD[max_lanes], ds[max_lanes], h[max_lanes], h_pos[max_lanes];
  // The step's robot displacement.
  alignas(64) double dX[max_lanes], dY[max_lanes];

  // Fast path: the integrator also moves the robot (Eq. 7 or the fold; Eq. 8
  // within the lane's obstacle box, see `box_x0`) and advances the clock when the
  // step stays in its cell and triggers no end or segment check: the same
  // operations the scalar PlannerRun would do. A step into a neighbouring cell (fast = 2) is
  // applied too, and its cell marked (see `cells`). Any other step sets its
  // bit in `flagged` and is left to the sink, which redoes it in full.
  alignas(64) double X[max_lanes], Y[max_lanes], t[max_lanes], fh[max_lanes];
  // fold = 1: the fold boundary, the robot at the fold of its unfolded
  // position (UX, UY) into the band; 0: the mirror, (X, Y) reflected itself.
  alignas(64) double fold[max_lanes], UX[max_lanes], UY[max_lanes];
  alignas(64) double budget[max_lanes], stuck_time[max_lanes], t_last_new[max_lanes];
  alignas(64) double seg_step[max_lanes], niter[max_lanes], steps[max_lanes];
  alignas(64) double lo_x[max_lanes], hi_x[max_lanes], lo_y[max_lanes], hi_y[max_lanes];
  alignas(64) double inv_cell[max_lanes], max_i[max_lanes], max_j[max_lanes];
  alignas(64) double cell_i[max_lanes], cell_j[max_lanes];
  // 0: no fast path; 1: steps that stay in their cell; 2: also steps into a
  // neighbouring cell across one edge; 3 (segments sampling): also steps
  // into a diagonal neighbour (mark_diagonal), in the kernel form for them.
  alignas(64) double fast[max_lanes];
  // That form's: each lane's position before its last step (the segment's
  // start, which mark_diagonal's crossing needs; X and Y hold its end).
  alignas(64) double X0[max_lanes], Y0[max_lanes];
  // fast = 2: the integrator marks an entered cell itself in the run's grid
  // (CoverageGrid's bytes, max_i + 1 per row), counts it and stamps t_last_new.
  unsigned char* cells[max_lanes];
  double visited[max_lanes], needed[max_lanes];
  double cover_sum[max_lanes];  // CoverageGrid::cover_time_sum, each new cell's time added as it is marked
  // cell_k: the lane's cell (cell_j * (max_i + 1) + cell_i), kept by the
  // scalar code. Map zoning: Eq. 5's window (CoverageGrid::begin_window) —
  // an entered step stamps the cell it left and the one it entered with
  // `window` and counts the cells new to the window in window_distinct
  // (stamp nullptr: no window); and the visited cells by zone
  // (CoverageGrid::count_regions: region[cell], region_visited[zone]; nullptr: none).
  long cell_k[max_lanes];
  unsigned* stamp[max_lanes];
  unsigned window[max_lanes];
  int window_distinct[max_lanes];
  const int* region[max_lanes];
  int* region_visited[max_lanes];
  // The path metrics' counts (CoverageGrid::visits, turns): an entered step
  // is a visit of the cell entered and a turn from the lane's last entry
  // direction (last_dir, -1: none yet), counted in place.
  std::uint32_t* visits[max_lanes];
  std::int64_t* turns[max_lanes];
  int last_dir[max_lanes];
  // Maps with obstacles (obstacles[l]): a box around the robot in which Eq. 8
  // moves a position at most once, onto the face of least penetration of
  // `near` (the nearest obstacle grown by fo; an empty rectangle: none), or
  // about it (near_mirror = 1: obstacle_response = "mirror"), see
  // obstacle_box. A step is applied only when it ends in the box, moved or
  // not; the sink gives the lane a new box after every step it takes.
  alignas(64) double box_x0[max_lanes], box_x1[max_lanes], box_y0[max_lanes], box_y1[max_lanes];
  alignas(64) double near_x0[max_lanes], near_x1[max_lanes], near_y0[max_lanes], near_y1[max_lanes];
  alignas(64) double near_mirror[max_lanes];
  bool obstacles[max_lanes];
  // in: bit l set while lane l has a run. An idle lane (the queue's tail)
  // steps along unread and is never flagged: flagged at every pass, it sent
  // every lane to the sink after each step (BENCHMARKS.md).
  unsigned active = 0;
  unsigned flagged = 0;  // out: bit l set when the sink must handle lane l's step
  unsigned covered = 0;  // out: bit l set when lane l's applied step reached dc (the sink ends the run)
};

// Takes the steps the integrator leaves to it (flagged, covered: boundaries,
// grid, decisions, ends, refill) after any step that leaves one, and reports
// whether any lane is still active. Implemented in baseline code.
class LaneSink {
 public:
  virtual ~LaneSink();
  virtual bool post_step() = 0;
};

// One entry point per compiled target (lane_kernel_<target>.cpp): integrates
// fixed-step RK4 steps of every lane until the sink reports no active lane.
void integrate_lanes_scalar(LaneArrays& a, LaneSink& sink);
void integrate_lanes_avx2(LaneArrays& a, LaneSink& sink);
void integrate_lanes_avx512(LaneArrays& a, LaneSink& sink);

}  // namespace chaosweep

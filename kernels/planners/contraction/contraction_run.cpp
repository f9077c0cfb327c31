#include "kernels/planners/contraction/contraction_run.hpp"

#include <cmath>

#include "kernels/core/chaotic_spread.hpp"
#include "kernels/core/metrics.hpp"
#include "kernels/core/param_table.hpp"
#include "kernels/math/inline_hypot.hpp"
#include "kernels/planners/contraction/contraction.hpp"

namespace chaosweep {

namespace {

contraction_paper::ContractionRobot robot_of(const RunParams& p) {
  contraction_paper::ContractionRobot r;
  r.A = p.A, r.B = p.B, r.C = p.C;
  // ic_jitter samples the chaotic spread here too (unwrapped: with no jitter
  // the state is ic bit for bit).
  const Vec3<double> ic = jittered_ic(p);
  r.ic = {ic.x, ic.y, ic.z};
  r.heading = contraction_paper::Heading(p.ds_index);
  r.v = p.v;
  r.h = p.dt;
  return r;
}

}  // namespace

std::string validate_contraction(const RunParams&, const Environment& env) {
  if (!env.obstacles.empty())
    return "the contraction planner (seed 003) covers an obstacle-free workplace; environment '" + env.name +
           "' has obstacles";
  return {};
}

void run_contraction(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r, TraceSink* trace) {
  using namespace contraction_paper;
  const ContractionRobot robot = robot_of(p);
  Workplace wp;
  wp.w = env.lx, wp.h = env.ly, wp.cell = p.sr;
  wp.sampling = p.sampling == chaosweep::Sampling::points ? contraction_paper::Sampling::points
                                                          : contraction_paper::Sampling::segments;
  const Point start{p.start_x, p.start_y};
  std::vector<Point> path;
  switch (p.c3_mode) {
    case ContractionMode::map:
      path = map_to_workplace(seed003_trajectory(robot, start, p.c3_n), wp);
      r.steps = p.c3_n;
      break;
    case ContractionMode::loop: {
      const CompleteCoverage cc =
          complete_coverage(robot, ic_grid_candidates(robot, p.c3_ic_grid, wp), start, wp, p.dc);
      path = cc.path;
      r.steps = cc.iterations;
      r.segments = std::int64_t(cc.sections.size());
      if (!cc.reached) r.message = "the loop ran out of candidates before dc";
      break;
    }
    case ContractionMode::mirror: {
      MirrorRun m = mirror_mapping(robot, start, p.c3_n, wp);
      path = std::move(m.path);
      r.steps = p.c3_n;
      r.reflections = m.reflections;
      break;
    }
  }
  // Walk the path at speed v over the common grid; the coverage time is
  // when the walk first reaches dc (the path is laid whole either way).
  const long needed = cells_needed(p, grid);
  double t = 0;
  bool reached = false;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Point& q = path[i];
    if (i == 0 || p.sampling == chaosweep::Sampling::points) grid.mark_point(q.x, q.y);
    else {
      grid.mark_segment(path[i - 1].x, path[i - 1].y, q.x, q.y);
      t += inline_hypot(q.x - path[i - 1].x, q.y - path[i - 1].y) / p.v;
    }
    grid.note_time(t);
    if (trace) trace->point({t, q.x, q.y, i == 0 ? SegmentKind::start : SegmentKind::arnold, p.ds_index});
    if (!reached && grid.visited_cells() >= needed) {
      reached = true;
      r.coverage_time = t;
    }
  }
  r.status = reached ? Status::ok : Status::timeout;
  if (!reached && r.message.empty()) r.message = "the path ended below dc";
  r.t_end = t;
  if (!path.empty()) r.final_x = path.back().x, r.final_y = path.back().y;
  r.final_ds_index = p.ds_index;
}

}  // namespace chaosweep

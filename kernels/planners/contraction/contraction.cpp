#include "kernels/planners/contraction/contraction.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/environment.hpp"
#include "kernels/math/inline_hypot.hpp"
#include "kernels/planners/contraction/trig3_fast.hpp"
#include "kernels/systems/arnold_flow.hpp"

// Seed 003 has its own Sampling, Heading, ... : a namespace keeps them apart
// from the common model's (run_params.hpp).
namespace chaosweep::contraction_paper {

namespace {

CoverageGrid make_grid(const Workplace& wp) {
  Environment env;
  env.name = "seed003_workplace";
  env.lx = wp.w;
  env.ly = wp.h;
  return CoverageGrid(env, wp.cell);
}

void mark_path(CoverageGrid& g, const std::vector<Point>& path, Sampling s, std::size_t from = 0) {
  if (path.empty()) return;
  if (s == Sampling::points || path.size() == 1) {
    for (std::size_t i = from; i < path.size(); ++i) g.mark_point(path[i].x, path[i].y);
    return;
  }
  for (std::size_t i = std::max<std::size_t>(from, 1); i < path.size(); ++i)
    g.mark_segment(path[i - 1].x, path[i - 1].y, path[i].x, path[i].y);
}

double clamp(double x, double lo, double hi) { return std::min(std::max(x, lo), hi); }

}  // namespace

// Eqs. 7-9 were lost. The paper calls its scheme "the second-order Runge
// Kutta method ... its common model", with two parameters K1, K2 (Eq. 8);
// the common form of RK2 in the textbooks this group cites is Heun's
// (improved Euler): y+ = y + h/2 (K1 + K2), K1 = f(y), K2 = f(y + h K1).
// The midpoint rule is the other reading, kept as an option. Neither
// reproduces Tables 1-3 (docs/seed003.md); both give Fig. 16a-b
// exactly, and Heun is the closer on Fig. 16c-d (500 and 1500 reflections
// reached at n = 3181 and 7429, midpoint 2470 and 7940; paper 3401, 7121).
// The state is wrapped into [-pi, pi] after each step: the right-hand side
// and the heading are 2 pi-periodic in x, y and z, so this changes rounding
// only and keeps the kernels' sincos in its accurate range.
std::vector<Point> seed003_trajectory(const ContractionRobot& r, Point start, int n) {
  if (n < 0) throw std::invalid_argument("seed003_trajectory: n must be >= 0");
  const ArnoldCoeffs<double> k{r.A, r.B, r.C};
  const HeadingSelect<double> hs = heading_select(int(r.heading));
  Vec3<double> u{r.ic[0], r.ic[1], r.ic[2]};
  double X = start.x, Y = start.y;
  std::vector<Point> out;
  out.reserve(std::size_t(n) + 1);
  out.push_back(start);
  const double h = r.h, hv = r.h * r.v;
  const bool avx2 = trig3_avx2_usable();
  // t1 = trig3(u) at each step's start, computed with the wrap that ends
  // the step before (one vector call on AVX2; trig3_fast.hpp).
  Trig3<double> t1 = trig3_fast(u, avx2);
  for (int i = 0; i < n; ++i) {
    const Vec3<double> k1 = arnold_rhs(t1, k);
    Vec3<double> next;
    if (r.method == Rk2::heun) {
      const Trig3<double> t2 = trig3_fast(Vec3<double>{u.x + h * k1.x, u.y + h * k1.y, u.z + h * k1.z}, avx2);
      const Vec3<double> k2 = arnold_rhs(t2, k);
      next = {u.x + 0.5 * h * (k1.x + k2.x), u.y + 0.5 * h * (k1.y + k2.y), u.z + 0.5 * h * (k1.z + k2.z)};
      X += 0.5 * hv * (heading_cos(t1, hs) + heading_cos(t2, hs));
      Y += 0.5 * hv * (heading_sin(t1, hs) + heading_sin(t2, hs));
    } else {
      const double hh = 0.5 * h;
      const Trig3<double> t2 = trig3_fast(Vec3<double>{u.x + hh * k1.x, u.y + hh * k1.y, u.z + hh * k1.z}, avx2);
      const Vec3<double> k2 = arnold_rhs(t2, k);
      next = {u.x + h * k2.x, u.y + h * k2.y, u.z + h * k2.z};
      X += hv * heading_cos(t2, hs);
      Y += hv * heading_sin(t2, hs);
    }
    t1 = wrap_trig3_fast(next, u, avx2);
    out.push_back({X, Y});
  }
  return out;
}

std::vector<Point> seed003_trajectory(Point start, int n, Heading heading) {
  ContractionRobot r;
  r.heading = heading;
  return seed003_trajectory(r, start, n);
}

namespace {

// The bounding box Map scales from: of the first `count` points of a path.
struct Frame {
  double x0, x1, y0, y1;
  bool same_as(const Frame& o) const {  // bit for bit (a -0 extreme maps its points apart)
    return std::bit_cast<std::uint64_t>(x0) == std::bit_cast<std::uint64_t>(o.x0) &&
           std::bit_cast<std::uint64_t>(x1) == std::bit_cast<std::uint64_t>(o.x1) &&
           std::bit_cast<std::uint64_t>(y0) == std::bit_cast<std::uint64_t>(o.y0) &&
           std::bit_cast<std::uint64_t>(y1) == std::bit_cast<std::uint64_t>(o.y1);
  }
};

Frame frame_of(const std::vector<Point>& path, std::size_t count) {
  Frame f{path[0].x, path[0].x, path[0].y, path[0].y};
  for (std::size_t i = 0; i < count; ++i) {
    f.x0 = std::min(f.x0, path[i].x);
    f.x1 = std::max(f.x1, path[i].x);
    f.y0 = std::min(f.y0, path[i].y);
    f.y1 = std::max(f.y1, path[i].y);
  }
  return f;
}

// out[i] = Map of path[i] in frame f, for from <= i < to (out holds to points).
void map_range(const std::vector<Point>& path, std::size_t from, std::size_t to, const Frame& f, const Workplace& wp,
               std::vector<Point>& out) {
  const double x0 = f.x0, y0 = f.y0, ex = f.x1 - f.x0, ey = f.y1 - f.y0;
  if (wp.aspect == MapAspect::per_axis) {
    // (p - min) / extent * side: the extremes land exactly on 0 and the side.
    // Indexed stores, so that the compiler keeps x and y in one vector (the
    // same IEEE operations, two at once).
    if (ex > 0.0 && ey > 0.0) {
      for (std::size_t i = from; i < to; ++i) out[i] = {(path[i].x - x0) / ex * wp.w, (path[i].y - y0) / ey * wp.h};
      return;
    }
    for (std::size_t i = from; i < to; ++i)
      out[i] = {ex > 0.0 ? (path[i].x - x0) / ex * wp.w : 0.5 * wp.w,
                ey > 0.0 ? (path[i].y - y0) / ey * wp.h : 0.5 * wp.h};
    return;
  }
  const double inf = std::numeric_limits<double>::infinity();
  double s = std::min(ex > 0.0 ? wp.w / ex : inf, ey > 0.0 ? wp.h / ey : inf);
  if (!std::isfinite(s)) s = 0.0;  // a single point
  const double ox = 0.5 * (wp.w - ex * s), oy = 0.5 * (wp.h - ey * s);
  for (std::size_t i = from; i < to; ++i)
    out[i] = {clamp(ox + (path[i].x - x0) * s, 0.0, wp.w), clamp(oy + (path[i].y - y0) * s, 0.0, wp.h)};
}

}  // namespace

// "Compress a trajectory ... onto the workplace": the paper's mapped start
// points fill [0, 20] x [0, 20] on each axis independently (Section 5.1:
// x'r.0 in [0, 20], y'r.0 in [0, 20]), and the tail of Table 3 (about 10%,
// i.e. 39-40 cells, once the robot has flown off in a straight line) is the
// supercover of a corner-to-corner diagonal, which only per-axis scaling
// gives; uniform scaling would leave a strip. Per axis is the default.
std::vector<Point> map_to_workplace(const std::vector<Point>& path, const Workplace& wp) {
  if (path.empty()) return {};
  std::vector<Point> out(path.size());
  map_range(path, 0, path.size(), frame_of(path, path.size()), wp, out);
  return out;
}

double coverage_rate(const std::vector<Point>& path, const Workplace& wp) {
  CoverageGrid g = make_grid(wp);
  mark_path(g, path, wp.sampling);
  return g.coverage();
}

// Fig. 12's flowchart survived as text: "x_r2_start > x_r1_end?" yes ->
// k = x_r2_start / x_r1_end, x_r3 = x_r2 / k; no -> k = (m - x_r1_end) /
// (m - x_r2_start), x_r3 = m (1 - k) + k x_r2; then the same on y. Geometry:
// both branches are a scaling by a factor <= 1 about a wall, the near wall
// (0) when the start must move towards it and the far wall (m) otherwise; the
// wall's coordinate stays (the paper's "keeping its minimum / maximum value
// unchanged": after Map the path spans [0, m], so its minimum is the wall),
// and the factor is the one that lands the start on the target. The path
// thus shrinks into [0, to] or [to, m] on that axis and never leaves the
// workplace. from == to takes the identity (the "no" branch with k = 1,
// also when both are m, where the printed k is 0/0). to == 0 < from gives
// k = inf: the path collapses onto the wall, as the equations say.
AxisContraction axis_contraction(double from, double to, double m) {
  if (from == to) return {true, 1.0, m};
  if (from > to) return {false, to > 0.0 ? from / to : std::numeric_limits<double>::infinity(), m};
  return {true, (m - to) / (m - from), m};
}

std::vector<Point> contract_to(const std::vector<Point>& path, Point target, const Workplace& wp) {
  if (path.empty()) return {};
  // The paper's workplace is m x n = 20 x 20 and Eqs. 19-20 use m for y
  // too; on a rectangle the y wall is at h, which is what we use.
  const AxisContraction cx = axis_contraction(path[0].x, target.x, wp.w);
  const AxisContraction cy = axis_contraction(path[0].y, target.y, wp.h);
  std::vector<Point> out;
  out.reserve(path.size());
  for (const Point& p : path) out.push_back({clamp(cx.apply(p.x), 0.0, wp.w), clamp(cy.apply(p.y), 0.0, wp.h)});
  out[0] = target;  // equal up to rounding; the link must be exact
  return out;
}

CandidateSweep candidate_sweep(const ContractionRobot& robot, Point start, const Workplace& wp,
                               const CandidateParams& p) {
  if (p.n_min < 1 || p.n_step < 1 || p.n_max < p.n_min)
    throw std::invalid_argument("candidate_sweep: need 1 <= n_min <= n_max and n_step >= 1");
  // One trajectory to n_max: each sample is a prefix (the robot is the same).
  const std::vector<Point> full = seed003_trajectory(robot, start, p.n_max);
  CandidateSweep out{start, 0.0, false, {}};
  // Each sample is coverage_rate(map_to_workplace(prefix)). When a prefix has
  // the bounding box of the one before, Map puts their common points at the
  // same places, so its grid is the one before plus the new points' cells
  // (a union of cells: the order of marking does not change the count).
  CoverageGrid g = make_grid(wp);
  std::vector<Point> mapped;
  Frame frame{};
  std::size_t marked = 0;  // points of `mapped` valid and marked in g (0: none)
  for (int n = p.n_min; n <= p.n_max; n += p.n_step) {
    const std::size_t count = std::size_t(n) + 1;
    const Frame f = frame_of(full, count);
    if (marked == 0 || !f.same_as(frame)) {
      g = make_grid(wp);
      marked = 0;
    }
    mapped.resize(count);  // n grows: only ever longer
    map_range(full, marked, count, f, wp, mapped);
    mark_path(g, mapped, wp.sampling, marked);
    frame = f;
    marked = count;
    out.samples.push_back({start, robot.ic, n, mapped[0], g.coverage()});
  }
  out.coverage_first = out.samples[0].coverage;
  out.kept = out.coverage_first >= p.threshold;
  return out;
}

// Section 6 says only "a start point nearer Trej_end is selected from the
// candidate set". Two rules are added, both for dead ends the paper does not
// meet (docs/seed003.md):
// - The candidate used in the previous section is skipped. Taken literally
//   (the nearest, always) the loop can lock into a two-cycle: in this model
//   every start point gives the same mapped start for a given n, so a set
//   holds few distinct points, and the nearest one to the new end can be the
//   candidate just used.
// - A candidate whose contraction would collapse the section onto a wall is
//   skipped: when the end lies on a wall (x = 0 or m, say) and the
//   candidate's mapped start does not, Eqs. 13-16 give k = inf or 0 and the
//   whole section becomes a segment of that wall. Map puts many ends on a
//   wall (a trajectory's last point is often an extreme of its bounding box),
//   so this happens. When every candidate is skipped the loop stops short.
namespace {
bool collapses(double from, double to, double m) {
  const double k = axis_contraction(from, to, m).k;
  return !(k > 0.0 && std::isfinite(k));
}
}  // namespace

CompleteCoverage complete_coverage(const ContractionRobot& robot, const std::vector<Candidate>& candidates, Point start,
                                   const Workplace& wp, double target, int max_sections) {
  CompleteCoverage out;
  out.path.push_back(start);
  CoverageGrid g = make_grid(wp);
  mark_path(g, out.path, Sampling::points);
  out.coverage = g.coverage();
  std::ptrdiff_t previous = -1;
  Point end = start;
  while (out.coverage < target && int(out.sections.size()) < max_sections) {
    std::ptrdiff_t best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const Candidate& c = candidates[i];
      if (std::ptrdiff_t(i) == previous && candidates.size() > 1) continue;
      if (collapses(c.mapped_start.x, end.x, wp.w) || collapses(c.mapped_start.y, end.y, wp.h)) continue;
      const double d = inline_hypot(c.mapped_start.x - end.x, c.mapped_start.y - end.y);
      if (d < best_d) {
        best_d = d;
        best = std::ptrdiff_t(i);
      }
    }
    if (best < 0) break;  // none left: a dead end
    const Candidate& c = candidates[std::size_t(best)];
    ContractionRobot r = robot;
    r.ic = c.ic;
    const std::vector<Point> section = contract_to(map_to_workplace(seed003_trajectory(r, c.start, c.n), wp), end, wp);
    const std::size_t first_new = out.path.size();
    out.path.insert(out.path.end(), section.begin() + 1, section.end());
    mark_path(g, out.path, wp.sampling, first_new);
    out.coverage = g.coverage();
    out.iterations += c.n;
    out.sections.push_back({c, end, section.back(), out.coverage});
    end = section.back();
    previous = best;
  }
  out.reached = out.coverage >= target;
  return out;
}

// Fig. 15: m_i inside, m_i' the next point outside, m_cross where the segment
// meets the wall, m_{i+1} the mirror image of m_i' in that wall. The step is
// walked wall by wall, so a step that leaves through two walls (a corner) or,
// with a large step, several times is reflected each time.
MirrorRun mirror_mapping(const ContractionRobot& robot, Point start, int n, const Workplace& wp, MirrorMode mode) {
  if (!(start.x >= 0.0 && start.x <= wp.w && start.y >= 0.0 && start.y <= wp.h))
    throw std::invalid_argument("mirror_mapping: the start must lie in the workplace");
  const std::vector<Point> free_run = seed003_trajectory(robot, start, n);
  MirrorRun out;
  out.path.reserve(free_run.size());
  out.path.push_back(start);
  CoverageGrid g = make_grid(wp);
  g.mark_point(start.x, start.y);
  const bool segments = wp.sampling == Sampling::segments;
  double sx = 1.0, sy = 1.0;  // fold: the current mirror orientation per axis
  Point p = start;
  for (std::size_t i = 1; i < free_run.size(); ++i) {
    Point cur = p;
    Point q{p.x + sx * (free_run[i].x - free_run[i - 1].x), p.y + sy * (free_run[i].y - free_run[i - 1].y)};
    for (int guard = 0; guard < 64; ++guard) {
      const double dx = q.x - cur.x, dy = q.y - cur.y;
      const double inf = std::numeric_limits<double>::infinity();
      const double tx = q.x > wp.w ? (wp.w - cur.x) / dx : (q.x < 0.0 ? -cur.x / dx : inf);
      const double ty = q.y > wp.h ? (wp.h - cur.y) / dy : (q.y < 0.0 ? -cur.y / dy : inf);
      if (tx == inf && ty == inf) break;
      const double t = std::min(tx, ty);
      Point hit{cur.x + t * dx, cur.y + t * dy};
      if (tx <= ty) hit.x = q.x > wp.w ? wp.w : 0.0;
      if (ty <= tx) hit.y = q.y > wp.h ? wp.h : 0.0;
      hit = {clamp(hit.x, 0.0, wp.w), clamp(hit.y, 0.0, wp.h)};
      if (tx <= ty) {
        q.x = q.x > wp.w ? 2.0 * wp.w - q.x : -q.x;
        if (mode == MirrorMode::fold) sx = -sx;
        ++out.reflections;
      }
      if (ty <= tx) {
        q.y = q.y > wp.h ? 2.0 * wp.h - q.y : -q.y;
        if (mode == MirrorMode::fold) sy = -sy;
        ++out.reflections;
      }
      out.crossings.push_back(hit);
      if (segments) g.mark_segment(cur.x, cur.y, hit.x, hit.y);
      cur = hit;
    }
    q = {clamp(q.x, 0.0, wp.w), clamp(q.y, 0.0, wp.h)};  // only if a step outran the guard
    if (segments) g.mark_segment(cur.x, cur.y, q.x, q.y);
    else g.mark_point(q.x, q.y);
    out.path.push_back(q);
    p = q;
  }
  out.coverage = g.coverage();
  return out;
}

std::vector<Candidate> ic_grid_candidates(const ContractionRobot& robot, double step, const Workplace& wp,
                                          const CandidateParams& p) {
  std::vector<Candidate> out;
  const int k = int(std::lround(10.0 / step));
  for (int i = 0; i <= k; ++i)
    for (int j = 0; j <= k; ++j) {
      ContractionRobot r = robot;
      r.ic = {i * step, j * step, 0.0};
      const CandidateSweep s = candidate_sweep(r, {i * step, j * step}, wp, p);
      if (s.kept) out.insert(out.end(), s.samples.begin(), s.samples.end());
    }
  return out;
}

}  // namespace chaosweep::contraction_paper

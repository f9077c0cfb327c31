#include "kernels/core/rect_decomposition.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace chaosweep {

namespace {

bool inside_any(const std::vector<Rect>& obstacles, double x, double y) {
  for (const Rect& o : obstacles)
    if (x > o.x0 && x < o.x1 && y > o.y0 && y < o.y1) return true;
  return false;
}

void add_cut(std::vector<double>& cuts, double v, double lo, double hi) {
  if (v > lo && v < hi) cuts.push_back(v);
}

void unique_sorted(std::vector<double>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

}  // namespace

int RectDecomposition::region_at(double x, double y) const {
  for (std::size_t r = 0; r < regions.size(); ++r)
    if (regions[r].box.contains_closed(x, y)) return int(r);
  return -1;
}

int RectDecomposition::transition_between(int a, int b) const {
  for (std::size_t t = 0; t < transitions.size(); ++t)
    if ((transitions[t].a == a && transitions[t].b == b) || (transitions[t].a == b && transitions[t].b == a))
      return int(t);
  return -1;
}

std::vector<int> RectDecomposition::neighbours(int r) const {
  std::vector<int> out;
  for (const Transition& t : transitions) {
    if (t.a == r) out.push_back(t.b);
    if (t.b == r) out.push_back(t.a);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::string small_name(const RectDecomposition& d, int s) {
  std::string name = "c";
  name += std::to_string(d.small[std::size_t(s)].i);
  name += 'r';
  name += std::to_string(d.small[std::size_t(s)].j);
  return name;
}

namespace {

// The cut grid: d.xs x d.ys, and the small rectangle of each grid cell (i, j)
// (-1: inside a grown obstacle).
struct CutGrid {
  int nx, ny;
  std::vector<int> id;
  int at(int i, int j) const { return id[std::size_t(j * nx + i)]; }
};

// Step 1: cut lines along every (grown) obstacle edge, across the whole
// workplace (a line may cross other obstacles, as the paper allows); the
// free grid cells become d.small.
CutGrid cut_into_small_rectangles(const Environment& env, const std::vector<Rect>& grown, const Rect& free,
                                  RectDecomposition& d) {
  d.xs = {free.x0, free.x1};
  d.ys = {free.y0, free.y1};
  for (const Rect& o : grown) {
    add_cut(d.xs, o.x0, free.x0, free.x1), add_cut(d.xs, o.x1, free.x0, free.x1);
    add_cut(d.ys, o.y0, free.y0, free.y1), add_cut(d.ys, o.y1, free.y0, free.y1);
  }
  unique_sorted(d.xs);
  unique_sorted(d.ys);
  const int nx = int(d.xs.size()) - 1, ny = int(d.ys.size()) - 1;
  if (double(nx) * double(ny) > max_decomposition_cells)
    throw std::invalid_argument("the edges of the " + std::to_string(env.obstacles.size()) +
                                " obstacles cut the workplace into " + std::to_string(nx) + " x " + std::to_string(ny) +
                                " cells, more than the Chebyshev decomposition's " +
                                std::to_string(int(max_decomposition_cells)) +
                                " (its merging grows faster than their square): use fewer obstacles");
  CutGrid g{nx, ny, std::vector<int>(std::size_t(nx * ny), -1)};
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Rect b{d.xs[std::size_t(i)], d.ys[std::size_t(j)], d.xs[std::size_t(i + 1)], d.ys[std::size_t(j + 1)]};
      if (inside_any(grown, 0.5 * (b.x0 + b.x1), 0.5 * (b.y0 + b.y1))) continue;
      g.id[std::size_t(j * nx + i)] = int(d.small.size());
      d.small.push_back({b, i, j, -1});
    }
  if (d.small.empty()) throw std::invalid_argument("the obstacles (grown by the robot radius) leave no free space");
  return g;
}

// A candidate coverage rectangle: an inclusive range of grid cells.
struct Cand {
  int i0, j0, i1, j1;
  double area, width;
};

// The largest candidate first, ties by width, then bottom-most, then left-most.
bool better(const Cand& a, const Cand& b) {
  if (a.area != b.area) return a.area > b.area;
  if (a.width != b.width) return a.width > b.width;
  if (a.j0 != b.j0) return a.j0 < b.j0;
  return a.i0 < b.i0;
}

// Every rectangle of free cells containing (ci, cj) (small grids, so try
// all), offered to `best`.
template <class FreeAt>
void best_rectangle_containing(const RectDecomposition& d, const CutGrid& g, int ci, int cj, FreeAt free_at,
                               Cand& best) {
  for (int i0 = ci; i0 >= 0 && free_at(i0, cj); --i0)
    for (int i1 = ci; i1 < g.nx && free_at(i1, cj); ++i1)
      for (int j0 = cj; j0 >= 0; --j0) {
        bool row_ok = true;
        for (int i = i0; i <= i1 && row_ok; ++i) row_ok = free_at(i, j0);
        if (!row_ok) break;
        for (int j1 = cj; j1 < g.ny; ++j1) {
          bool ok = true;
          for (int j = std::max(j0, cj); j <= j1 && ok; ++j)
            for (int i = i0; i <= i1 && ok; ++i) ok = free_at(i, j);
          if (!ok) break;
          const double w = d.xs[std::size_t(i1 + 1)] - d.xs[std::size_t(i0)];
          const double h = d.ys[std::size_t(j1 + 1)] - d.ys[std::size_t(j0)];
          const Cand c{i0, j0, i1, j1, w * h, w};
          if (better(c, best)) best = c;
        }
      }
}

// The next coverage rectangle among the small rectangles `left`: grown from
// the corner rectangles (Definition 1), those extreme in both x and y first.
Cand next_coverage_rectangle(const RectDecomposition& d, const CutGrid& g, const std::vector<bool>& left) {
  auto free_at = [&](int i, int j) {
    const int s = g.at(i, j);
    return s >= 0 && left[std::size_t(s)];
  };
  double min_x = 1e300, max_x = -1e300, min_y = 1e300, max_y = -1e300;
  for (std::size_t s = 0; s < d.small.size(); ++s) {
    if (!left[s]) continue;
    min_x = std::min(min_x, d.small[s].box.x0), max_x = std::max(max_x, d.small[s].box.x0);
    min_y = std::min(min_y, d.small[s].box.y0), max_y = std::max(max_y, d.small[s].box.y0);
  }
  auto x_extreme = [&](const Rect& b) { return b.x0 == min_x || b.x0 == max_x; };
  auto y_extreme = [&](const Rect& b) { return b.y0 == min_y || b.y0 == max_y; };
  bool any_double = false;
  for (std::size_t s = 0; s < d.small.size(); ++s)
    any_double = any_double || (left[s] && x_extreme(d.small[s].box) && y_extreme(d.small[s].box));
  Cand best{0, 0, -1, -1, -1, -1};
  for (std::size_t s = 0; s < d.small.size(); ++s) {
    if (!left[s]) continue;
    const Rect& b = d.small[s].box;
    if (any_double ? !(x_extreme(b) && y_extreme(b)) : !(x_extreme(b) || y_extreme(b))) continue;
    best_rectangle_containing(d, g, d.small[s].i, d.small[s].j, free_at, best);
  }
  return best;
}

// Step 2: merge. Corner rectangles are those with an extreme lower-left x
// or y among the rectangles left (Definition 1); each is grown to the
// largest rectangle of free, unmerged cells containing it, which becomes a
// coverage rectangle, and the rest is searched again. The paper picks at
// random among equals; we take corners extreme in both x and y first (the
// free space's own corners), then the largest candidate, ties by width,
// then bottom-most, then left-most. This reproduces both decompositions the
// paper lists (Section 5.4) and is reproducible.
void merge_into_regions(const CutGrid& g, RectDecomposition& d) {
  std::vector<bool> left(d.small.size(), true);
  std::size_t remaining = d.small.size();
  while (remaining > 0) {
    const Cand best = next_coverage_rectangle(d, g, left);
    RectDecomposition::Region reg{{d.xs[std::size_t(best.i0)], d.ys[std::size_t(best.j0)],
                                   d.xs[std::size_t(best.i1 + 1)], d.ys[std::size_t(best.j1 + 1)]},
                                  {}};
    for (int j = best.j0; j <= best.j1; ++j)
      for (int i = best.i0; i <= best.i1; ++i) {
        const int s = g.at(i, j);
        left[std::size_t(s)] = false;
        d.small[std::size_t(s)].region = int(d.regions.size());
        reg.small.push_back(s);
        --remaining;
      }
    d.regions.push_back(std::move(reg));
  }
}

// Two small rectangles of different regions facing each other across a cut line.
struct Pair {
  int a, b;  // regions (a < b)
  int s, t;  // the two small rectangles
  bool vertical_line;
  double line;  // the cut coordinate
  Rect box;
};

// Every facing pair: each small rectangle with its right and upper neighbours.
std::vector<Pair> facing_pairs(const CutGrid& g, const RectDecomposition& d) {
  std::vector<Pair> pairs;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const int s = g.at(i, j);
      if (s < 0) continue;
      const int rs = d.small[std::size_t(s)].region;
      const Rect& bs = d.small[std::size_t(s)].box;
      if (i + 1 < g.nx) {  // right neighbour
        const int t = g.at(i + 1, j);
        if (t >= 0 && d.small[std::size_t(t)].region != rs) {
          const int rt = d.small[std::size_t(t)].region;
          pairs.push_back({std::min(rs, rt),
                           std::max(rs, rt),
                           s,
                           t,
                           true,
                           bs.x1,
                           {bs.x0, bs.y0, d.small[std::size_t(t)].box.x1, bs.y1}});
        }
      }
      if (j + 1 < g.ny) {  // upper neighbour
        const int t = g.at(i, j + 1);
        if (t >= 0 && d.small[std::size_t(t)].region != rs) {
          const int rt = d.small[std::size_t(t)].region;
          pairs.push_back({std::min(rs, rt),
                           std::max(rs, rt),
                           s,
                           t,
                           false,
                           bs.y1,
                           {bs.x0, bs.y0, bs.x1, d.small[std::size_t(t)].box.y1}});
        }
      }
    }
  return pairs;
}

// Step 3: transitions. Two regions meeting along a cut line are linked by
// the small rectangles facing each other across it: each facing pair is a
// rectangle (same extent along the line); consecutive pairs along one line
// merge while their union stays a rectangle.
void link_transitions(const CutGrid& g, RectDecomposition& d) {
  for (const Pair& p : facing_pairs(g, d)) {
    bool merged = false;
    for (RectDecomposition::Transition& tr : d.transitions) {
      if (tr.a != p.a || tr.b != p.b) continue;
      // Same line, adjacent along it, same extent across it: still a rectangle.
      const Rect& q = tr.box;
      const bool joins = p.vertical_line
                             ? (q.x0 == p.box.x0 && q.x1 == p.box.x1 && (q.y1 == p.box.y0 || q.y0 == p.box.y1))
                             : (q.y0 == p.box.y0 && q.y1 == p.box.y1 && (q.x1 == p.box.x0 || q.x0 == p.box.x1));
      if (!joins) continue;
      tr.box = {std::min(q.x0, p.box.x0), std::min(q.y0, p.box.y0), std::max(q.x1, p.box.x1), std::max(q.y1, p.box.y1)};
      tr.small.push_back(p.s), tr.small.push_back(p.t);
      merged = true;
      break;
    }
    if (!merged) d.transitions.push_back({p.box, p.a, p.b, {p.s, p.t}});
  }
}

}  // namespace

RectDecomposition decompose_free_space(const Environment& env, double radius) {
  const Rect free{radius, radius, env.lx - radius, env.ly - radius};
  if (!(free.x1 > free.x0 && free.y1 > free.y0))
    throw std::invalid_argument("the robot radius leaves no free space in the workplace");
  // Edge expansion: obstacles grown by the radius, clipped to the workplace.
  std::vector<Rect> grown;
  for (const Rect& o : env.obstacles)
    grown.push_back({std::max(free.x0, o.x0 - radius), std::max(free.y0, o.y0 - radius),
                     std::min(free.x1, o.x1 + radius), std::min(free.y1, o.y1 + radius)});
  RectDecomposition d;
  const CutGrid g = cut_into_small_rectangles(env, grown, free, d);
  merge_into_regions(g, d);
  link_transitions(g, d);
  return d;
}

}  // namespace chaosweep

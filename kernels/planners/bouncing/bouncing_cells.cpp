#include "kernels/planners/bouncing/bouncing_cells.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace chaosweep::bouncing_paper {

namespace {
constexpr double kPi = 3.14159265358979323846;
double rad(double deg) { return deg * kPi / 180.0; }
}  // namespace

CellGrid make_grid(const Environment& env, double cell, int bins) {
  CellGrid g;
  g.env = env;
  g.cell = cell;
  g.bins = bins;
  // Small tolerance so that lx = 15, cell = 1 gives 15 cells, not 16.
  g.nx = static_cast<int>(std::floor(env.lx / cell + 1e-9));
  g.ny = static_cast<int>(std::floor(env.ly / cell + 1e-9));
  g.free_index.assign(static_cast<std::size_t>(g.nx) * g.ny, -1);
  for (int iy = 0; iy < g.ny; ++iy)
    for (int ix = 0; ix < g.nx; ++ix)
      if (env.obstacle_at((ix + 0.5) * cell, (iy + 0.5) * cell) < 0) {
        g.free_index[ix + g.nx * iy] = static_cast<int>(g.free_cells.size());
        g.free_cells.push_back(ix + g.nx * iy);
      }
  return g;
}

int CellGrid::free_at(double x, double y) const {
  if (!(x >= 0.0 && y >= 0.0 && x < nx * cell && y < ny * cell)) return -1;
  if (env.obstacle_at(x, y) >= 0) return -1;
  const int ix = std::min(nx - 1, static_cast<int>(x / cell));
  const int iy = std::min(ny - 1, static_cast<int>(y / cell));
  return free_index[ix + nx * iy];
}

std::pair<double, double> CellGrid::centre(int free) const {
  const int c = free_cells[free];
  return {(c % nx + 0.5) * cell, (c / nx + 0.5) * cell};
}

std::optional<Contact> drive_to_contact(const CellGrid& grid, double x, double y, double heading_deg) {
  const double dx = std::cos(rad(heading_deg)), dy = std::sin(rad(heading_deg));
  double best = std::numeric_limits<double>::infinity(), nx = 0.0, ny = 0.0;
  const double W = grid.nx * grid.cell, H = grid.ny * grid.cell;
  // Map boundary, from inside.
  if (dx > 1e-12 && (W - x) / dx < best) best = (W - x) / dx, nx = -1.0, ny = 0.0;
  if (dx < -1e-12 && (0.0 - x) / dx < best) best = (0.0 - x) / dx, nx = 1.0, ny = 0.0;
  if (dy > 1e-12 && (H - y) / dy < best) best = (H - y) / dy, nx = 0.0, ny = -1.0;
  if (dy < -1e-12 && (0.0 - y) / dy < best) best = (0.0 - y) / dy, nx = 0.0, ny = 1.0;
  // Obstacles, from outside (slab method; the entry face gives the normal).
  for (const Rect& o : grid.env.obstacles) {
    double t0 = 0.0, t1 = std::numeric_limits<double>::infinity(), fx = 0.0, fy = 0.0;
    bool miss = false;
    auto slab = [&](double p, double d, double lo, double hi, double ax, double ay) {
      if (std::abs(d) < 1e-12) {
        if (p <= lo || p >= hi) miss = true;
        return;
      }
      double ta = (lo - p) / d, tb = (hi - p) / d;
      double sx = -ax, sy = -ay;  // entering through the low face: normal points to -axis
      if (ta > tb) std::swap(ta, tb), sx = ax, sy = ay;
      if (ta > t0) t0 = ta, fx = sx, fy = sy;
      t1 = std::min(t1, tb);
    };
    slab(x, dx, o.x0, o.x1, 1.0, 0.0);
    slab(y, dy, o.y0, o.y1, 0.0, 1.0);
    if (!miss && t0 < t1 && t0 > 0.0 && t0 < best) best = t0, nx = fx, ny = fy;
  }
  if (!std::isfinite(best)) return std::nullopt;
  Contact c{x + best * dx, y + best * dy, best, -1, nx, ny};
  // The contact point lies on a cell edge: take the free cell just before it.
  const double back = 1e-9 * grid.cell;
  c.free = grid.free_at(c.x - back * dx, c.y - back * dy);
  return c;
}

std::vector<std::pair<int, double>> rotation_offsets(int bins, double phi_deg, double eps_deg, double r) {
  const double w = 360.0 / bins;
  std::map<int, double> acc;
  auto wrap = [bins](long k) { return static_cast<int>(((k % bins) + bins) % bins); };
  const double reliable = (eps_deg > 0.0) ? r : 1.0;
  acc[wrap(std::lround(phi_deg / w))] += reliable;
  if (eps_deg > 0.0 && r < 1.0) {
    // Bin k (relative) covers [(k-1/2)w, (k+1/2)w); overlap with [phi-eps, phi+eps].
    const double lo = phi_deg - eps_deg, hi = phi_deg + eps_deg;
    const long k0 = static_cast<long>(std::floor(lo / w + 0.5)), k1 = static_cast<long>(std::floor(hi / w + 0.5));
    for (long k = k0; k <= k1; ++k) {
      const double a = std::max(lo, (k - 0.5) * w), b = std::min(hi, (k + 0.5) * w);
      if (b > a) acc[wrap(k)] += (1.0 - r) * (b - a) / (hi - lo);
    }
  }
  return {acc.begin(), acc.end()};
}

CellMap build_cell_map(const CellGrid& grid, double phi_deg, double eps_deg, double r, const GcmOptions& opts) {
  const double step = opts.step > 0.0 ? opts.step : grid.cell;
  const int s = std::max(1, opts.samples);
  const auto rot = rotation_offsets(grid.bins, phi_deg, eps_deg, r);
  // Precompute the step vector per bin (heading at the bin centre).
  std::vector<double> sx(grid.bins), sy(grid.bins);
  for (int k = 0; k < grid.bins; ++k) {
    sx[k] = step * std::cos(rad(k * grid.bin_width_deg()));
    sy[k] = step * std::sin(rad(k * grid.bin_width_deg()));
  }
  CellMap m;
  m.n = grid.num_configs();
  m.row_start.reserve(m.n + 1);
  m.row_start.push_back(0);
  const double wsample = 1.0 / (s * s);
  std::vector<std::pair<int, double>> row;
  for (int f = 0; f < grid.num_free(); ++f) {
    const int c = grid.free_cells[f];
    const double x0 = (c % grid.nx) * grid.cell, y0 = (c / grid.nx) * grid.cell;
    for (int k = 0; k < grid.bins; ++k) {
      row.clear();
      double bump_weight = 0.0;
      for (int a = 0; a < s; ++a)
        for (int b = 0; b < s; ++b) {
          // Sample points at (i + 1/2)/s of the cell: s = 1 is the centroid,
          // s = 2 the quarter points (which never land on a cell edge for
          // 5-degree multiples with step = cell, unlike the centroid at 30/60).
          const double px = x0 + (a + 0.5) / s * grid.cell, py = y0 + (b + 0.5) / s * grid.cell;
          const int nf = grid.free_at(px + sx[k], py + sy[k]);
          if (nf >= 0) row.emplace_back(grid.config(nf, k), wsample);
          else bump_weight += wsample;
        }
      // Forward targets first (negative marker distinguishes bumps while merging).
      std::sort(row.begin(), row.end());
      const int first = static_cast<int>(m.to.size());
      for (const auto& [to, p] : row) {
        if (static_cast<int>(m.to.size()) > first && m.to.back() == to && !m.bump.back()) m.prob.back() += p;
        else m.to.push_back(to), m.prob.push_back(p), m.bump.push_back(0);
      }
      if (bump_weight > 0.0)
        for (const auto& [off, p] : rot)
          m.to.push_back(grid.config(f, (k + off) % grid.bins)), m.prob.push_back(bump_weight * p), m.bump.push_back(1);
      m.row_start.push_back(static_cast<int>(m.to.size()));
    }
  }
  return m;
}

}  // namespace chaosweep::bouncing_paper

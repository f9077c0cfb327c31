#include "kernels/core/environment.hpp"

#include <algorithm>
#include <cmath>

#include "kernels/core/obstacle_index.hpp"

namespace chaosweep {

double Environment::obstacle_area() const {
  // Exact union area by a sweep over x: at each obstacle edge the covered
  // length along y changes; a segment tree over the obstacles' y edges keeps
  // that length, so n obstacles take O(n log n) (9,000 small ones: a few ms;
  // testing every cell of the coordinate grid took O(n^3), hours).
  struct Event {
    double x, y0, y1;
    int delta;
  };
  std::vector<Event> events;
  std::vector<double> ys;
  for (const Rect& r : obstacles) {
    const double x0 = std::clamp(r.x0, 0.0, lx), x1 = std::clamp(r.x1, 0.0, lx);
    const double y0 = std::clamp(r.y0, 0.0, ly), y1 = std::clamp(r.y1, 0.0, ly);
    if (!(x1 > x0 && y1 > y0)) continue;
    events.push_back({x0, y0, y1, +1});
    events.push_back({x1, y0, y1, -1});
    ys.insert(ys.end(), {y0, y1});
  }
  if (events.empty()) return 0.0;
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
  std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.x < b.x; });
  // Node k covers the y intervals [lo, hi) of ys; cover[k]: obstacles
  // spanning all of it; length[k]: its covered length.
  const std::size_t m = ys.size() - 1;
  std::vector<int> cover(4 * m, 0);
  std::vector<double> length(4 * m, 0.0);
  const auto update = [&](auto&& self, std::size_t k, std::size_t lo, std::size_t hi, std::size_t a, std::size_t b,
                          int delta) -> void {
    if (b <= lo || hi <= a) return;
    if (a <= lo && hi <= b) {
      cover[k] += delta;
    } else {
      const std::size_t mid = (lo + hi) / 2;
      self(self, 2 * k + 1, lo, mid, a, b, delta);
      self(self, 2 * k + 2, mid, hi, a, b, delta);
    }
    length[k] = cover[k] > 0 ? ys[hi] - ys[lo] : hi - lo == 1 ? 0.0 : length[2 * k + 1] + length[2 * k + 2];
  };
  const auto index = [&](double y) { return std::size_t(std::lower_bound(ys.begin(), ys.end(), y) - ys.begin()); };
  double area = 0.0;
  for (std::size_t e = 0; e < events.size(); ++e) {
    if (e > 0) area += length[0] * (events[e].x - events[e - 1].x);
    update(update, 0, 0, m, index(events[e].y0), index(events[e].y1), events[e].delta);
  }
  return area;
}

namespace {

// Below this many obstacles a scan is as fast as the index.
constexpr std::size_t index_from = 32;

// Widens a query box past the rounding of `x - fo` and `r.x0 - fo`, so that
// the box meets every obstacle the exact tests can accept.
double slack(double x, double y, double fo) { return 1e-9 * (std::fabs(x) + std::fabs(y) + fo + 1.0); }

Rect grown_by(const Rect& r, double fo) { return {r.x0 - fo, r.y0 - fo, r.x1 + fo, r.y1 + fo}; }

// Moves the point to the face of least penetration of `grown` (Eq. 8 as
// printed) or, with `mirror`, reflects it about that face (Eq. 7 applied at
// the obstacle), counting the face's axis in `hit`.
void move_to_face(const Rect& grown, bool mirror, double& x, double& y, ObstacleHit& hit) {
  const double to_left = x - grown.x0, to_right = grown.x1 - x;
  const double to_bottom = y - grown.y0, to_top = grown.y1 - y;
  const double m = std::min({to_left, to_right, to_bottom, to_top});
  auto place = [mirror](double& u, double face) { u = mirror ? (face + face) - u : face; };
  if (m == to_left) place(x, grown.x0), ++hit.x_faces;
  else if (m == to_right) place(x, grown.x1), ++hit.x_faces;
  else if (m == to_bottom) place(y, grown.y0), ++hit.y_faces;
  else place(y, grown.y1), ++hit.y_faces;
  hit.moved = true;
}

}  // namespace

void Environment::index_obstacles() {
  index = obstacles.size() >= index_from ? std::make_shared<const ObstacleIndex>(obstacles, 0.0) : nullptr;
}

const ObstacleIndex* Environment::usable_index() const {
  return index && index->size() == obstacles.size() ? index.get() : nullptr;
}

int Environment::obstacle_at(double x, double y) const {
  if (const ObstacleIndex* ix = usable_index()) {
    int hit = -1;
    ix->find(x, y, x, y, [&](std::size_t k) { return obstacles[k].contains(x, y) && (hit = int(k), true); });
    return hit;
  }
  for (std::size_t i = 0; i < obstacles.size(); ++i)
    if (obstacles[i].contains(x, y)) return static_cast<int>(i);
  return -1;
}

bool Environment::near_obstacle(double x, double y, double fo) const {
  const auto near = [&](std::size_t k) { return grown_by(obstacles[k], fo).contains(x, y); };
  if (const ObstacleIndex* ix = usable_index()) {
    const double s = fo + slack(x, y, fo);
    return ix->find(x - s, y - s, x + s, y + s, near);
  }
  for (std::size_t k = 0; k < obstacles.size(); ++k)
    if (near(k)) return true;
  return false;
}

bool push_out_of_obstacles(const Environment& env, double fo, double& x, double& y) {
  return keep_out_of_obstacles(env, fo, false, x, y).moved;
}

ObstacleHit keep_out_of_obstacles(const Environment& env, double fo, bool mirror, double& x, double& y) {
  ObstacleHit hit;
  const ObstacleIndex* ix = env.usable_index();
  // A move can land in a neighbour's margin; a few rounds settle any layout
  // whose obstacles are not packed tighter than 2*fo.
  for (int round = 0; round < 8; ++round) {
    const int before = hit.x_faces + hit.y_faces;
    if (!ix) {
      for (const Rect& r : env.obstacles) {
        const Rect grown = grown_by(r, fo);
        if (grown.contains(x, y)) move_to_face(grown, mirror, x, y, hit);
      }
    } else {
      // The same pass in the same order: the next obstacle (by index) whose
      // grown rectangle holds the point as it now is, among those near it.
      for (std::size_t next = 0;;) {
        std::size_t found = env.obstacles.size();
        const double s = fo + slack(x, y, fo);
        ix->find(x - s, y - s, x + s, y + s, [&](std::size_t k) {
          return k >= next && grown_by(env.obstacles[k], fo).contains(x, y) && (found = k, true);
        });
        if (found == env.obstacles.size()) break;
        move_to_face(grown_by(env.obstacles[found], fo), mirror, x, y, hit);
        next = found + 1;
      }
    }
    if (hit.x_faces + hit.y_faces == before) break;
  }
  return hit;
}

std::vector<unsigned char> cells_clear_of_obstacles(const Environment& env, double fo, int nx, int ny, double cell) {
  std::vector<unsigned char> clear(std::size_t(nx) * std::size_t(ny), 1);
  const double margin = 1e-6 * cell + 1e-9 * std::max(env.lx, env.ly);
  // Each cell's extent, widened by the margin; both ends grow with the index,
  // so the cells an obstacle (grown by fo) meets are a range found by search.
  const auto n_x = static_cast<std::size_t>(nx), n_y = static_cast<std::size_t>(ny);
  std::vector<double> x0(n_x), x1(n_x), y0(n_y), y1(n_y);
  for (int i = 0; i < nx; ++i) {
    x0[std::size_t(i)] = i * cell - margin;
    x1[std::size_t(i)] = (i + 1 == nx ? std::max((i + 1) * cell, env.lx) : (i + 1) * cell) + margin;
  }
  for (int j = 0; j < ny; ++j) {
    y0[std::size_t(j)] = j * cell - margin;
    y1[std::size_t(j)] = (j + 1 == ny ? std::max((j + 1) * cell, env.ly) : (j + 1) * cell) + margin;
  }
  // The cells [lo, hi) with hi_end > a and lo_end < b.
  const auto range = [](const std::vector<double>& lo_end, const std::vector<double>& hi_end, double a, double b) {
    const auto lo = std::upper_bound(hi_end.begin(), hi_end.end(), a) - hi_end.begin();
    const auto hi = std::lower_bound(lo_end.begin(), lo_end.end(), b) - lo_end.begin();
    return std::pair{std::size_t(lo), std::size_t(std::max(hi, lo))};
  };
  for (const Rect& r : env.obstacles) {
    const auto [i0, i1] = range(x0, x1, r.x0 - fo, r.x1 + fo);
    const auto [j0, j1] = range(y0, y1, r.y0 - fo, r.y1 + fo);
    for (std::size_t j = j0; j < j1; ++j)
      std::fill(clear.begin() + std::ptrdiff_t(j * std::size_t(nx) + i0),
                clear.begin() + std::ptrdiff_t(j * std::size_t(nx) + i1), 0);
  }
  return clear;
}

}  // namespace chaosweep

#include "kernels/core/environment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

ObstacleBox obstacle_box(const Environment& env, double fo, double x, double y, const Rect& band, double reach,
                         bool with_near) {
  ObstacleBox out;
  const ObstacleIndex* ix = env.usable_index();
  // A query the index answers from its buckets, not by a scan of every obstacle.
  const double s = fo + slack(std::fabs(x) + reach, std::fabs(y) + reach, fo);
  if (ix) reach = std::max(0.0, std::min(reach, 0.5 * ix->bucket_query_side() - s));
  Rect c{std::max(band.x0, x - reach), std::max(band.y0, y - reach), std::min(band.x1, x + reach),
         std::min(band.y1, y + reach)};
  if (!(c.x0 <= x && x <= c.x1 && c.y0 <= y && y <= c.y1)) return out;  // outside the band, or NaN
  // The closed box c meets the open rectangle g.
  const auto meets = [&c](const Rect& g) { return c.x1 > g.x0 && c.x0 < g.x1 && c.y1 > g.y0 && c.y0 < g.y1; };
  // Every obstacle whose grown rectangle may meet c (as it is now: c only shrinks), in index order.
  const auto each = [&](auto&& f) {
    if (ix) ix->find(c.x0 - s, c.y0 - s, c.x1 + s, c.y1 + s, [&](std::size_t k) { return f(k), false; });
    else
      for (std::size_t k = 0; k < env.obstacles.size(); ++k) f(k);
  };
  std::size_t near = env.obstacles.size();
  if (with_near) {
    double best = std::numeric_limits<double>::infinity();
    each([&](std::size_t k) {
      const Rect g = grown_by(env.obstacles[k], fo);
      if (!meets(g)) return;
      const double dx = std::max({g.x0 - x, 0.0, x - g.x1}), dy = std::max({g.y0 - y, 0.0, y - g.y1});
      if (dx * dx + dy * dy < best) best = dx * dx + dy * dy, near = k;
    });
  }
  bool ok = true;
  each([&](std::size_t k) {
    if (k == near || !ok) return;
    const Rect g = grown_by(env.obstacles[k], fo);
    if (!meets(g)) return;
    // The four ways to cut g off (each leaves c disjoint from g) that keep (x, y).
    const Rect cuts[] = {
        {c.x0, c.y0, g.x0, c.y1}, {g.x1, c.y0, c.x1, c.y1}, {c.x0, c.y0, c.x1, g.y0}, {c.x0, g.y1, c.x1, c.y1}};
    // The cut whose new edge lies farthest from (x, y): a lane leaves its
    // box when a step ends beyond an edge, and the band's own edges never
    // make it leave (a step reflects back into the band).
    const double gap[] = {g.x0 - x, x - g.x1, g.y0 - y, y - g.y1};
    double most = -1;
    Rect best = c;
    for (int q = 0; q < 4; ++q) {
      const Rect& r = cuts[q];
      if (r.x0 <= x && x <= r.x1 && r.y0 <= y && y <= r.y1 && gap[q] > most) most = gap[q], best = r;
    }
    c = best;
    ok = most >= 0;
  });
  if (!ok) return out;
  out.box = c;
  if (near < env.obstacles.size()) out.near = grown_by(env.obstacles[near], fo);
  return out;
}

}  // namespace chaosweep

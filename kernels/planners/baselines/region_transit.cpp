#include "kernels/planners/baselines/region_transit.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "kernels/math/inline_hypot.hpp"

namespace chaosweep {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

double dist(Point a, Point b) { return inline_hypot(b.x - a.x, b.y - a.y); }

}  // namespace

RegionTransit::RegionTransit(const RectDecomposition& d) : d_(d), portals_of_(d.regions.size()) {
  for (std::size_t a = 0; a < d.regions.size(); ++a)
    for (int b : d.neighbours(int(a))) {
      if (b < int(a)) continue;
      // Two rectangles linked by a transition share a piece of edge (their
      // interiors are disjoint, so the boxes meet in a segment).
      const Rect& p = d.regions[a].box;
      const Rect& q = d.regions[std::size_t(b)].box;
      const Point mid{0.5 * (std::max(p.x0, q.x0) + std::min(p.x1, q.x1)),
                      0.5 * (std::max(p.y0, q.y0) + std::min(p.y1, q.y1))};
      portals_of_[a].push_back(int(portals_.size()));
      portals_of_[std::size_t(b)].push_back(int(portals_.size()));
      portals_.push_back({mid, int(a), b});
    }
}

void RegionTransit::search_from(Point p) {
  from_ = p;
  from_regions_.clear();
  for (std::size_t r = 0; r < d_.regions.size(); ++r)
    if (d_.regions[r].box.contains_closed(p.x, p.y)) from_regions_.push_back(int(r));
  dist_.assign(portals_.size(), inf);
  prev_.assign(portals_.size(), -1);
  using Item = std::pair<double, int>;  // ties pop the lower portal first: deterministic
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (int r : from_regions_)
    for (int k : portals_of_[std::size_t(r)]) {
      const double l = dist(p, portals_[std::size_t(k)].at);
      if (l < dist_[std::size_t(k)]) dist_[std::size_t(k)] = l, queue.push({l, k});
    }
  while (!queue.empty()) {
    const auto [l, k] = queue.top();
    queue.pop();
    if (l > dist_[std::size_t(k)]) continue;
    const Portal& u = portals_[std::size_t(k)];
    for (int r : {u.a, u.b})
      for (int m : portals_of_[std::size_t(r)]) {
        const double lm = l + dist(u.at, portals_[std::size_t(m)].at);
        if (lm < dist_[std::size_t(m)]) dist_[std::size_t(m)] = lm, prev_[std::size_t(m)] = k, queue.push({lm, m});
      }
  }
}

std::pair<int, double> RegionTransit::last_portal(Point q, int region) const {
  if (std::find(from_regions_.begin(), from_regions_.end(), region) != from_regions_.end()) return {-1, dist(from_, q)};
  int best = -1;
  double length = inf;
  for (int k : portals_of_[std::size_t(region)]) {
    const double l = dist_[std::size_t(k)] + dist(portals_[std::size_t(k)].at, q);
    if (l < length) best = k, length = l;
  }
  return {best, length};
}

double RegionTransit::distance_to(Point q, int region) const { return last_portal(q, region).second; }

std::vector<Point> RegionTransit::path_to(Point q, int region) const {
  const auto [k, length] = last_portal(q, region);
  if (length == inf) return {};
  std::vector<Point> path{q};
  for (int m = k; m >= 0; m = prev_[std::size_t(m)]) path.push_back(portals_[std::size_t(m)].at);
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace chaosweep

#pragma once
// The lawnmower's transits between free rectangles: straight legs, each
// inside one rectangle of the decomposition (convex, so free), joined at
// portals, the midpoints of the edges two rectangles share. Shortest over
// that graph (Dijkstra), deterministic.
#include <vector>

#include "kernels/core/geometry.hpp"
#include "kernels/core/rect_decomposition.hpp"

namespace chaosweep {

class RegionTransit {
 public:
  explicit RegionTransit(const RectDecomposition& d);

  // Shortest distances from p, a point of the free space, to every portal.
  void search_from(Point p);
  // The length of the transit from the last search's p to q (a point of
  // the free space), or infinity when no chain of rectangles links them.
  double distance_to(Point q) const;
  // Its points after p, ending with q (empty when unreachable).
  std::vector<Point> path_to(Point q) const;

 private:
  struct Portal {
    Point at;
    int a, b;  // the two rectangles it joins
  };
  // The rectangles whose closed box holds q.
  std::vector<int> regions_at(Point q) const;
  // The portal that ends the shortest chain to q, with its length (-1: q
  // shares a rectangle with p, or none reaches it).
  std::pair<int, double> last_portal(Point q) const;

  const RectDecomposition& d_;
  std::vector<Portal> portals_;
  std::vector<std::vector<int>> portals_of_;  // each rectangle's portals
  Point from_{0, 0};
  std::vector<int> from_regions_;
  std::vector<double> dist_;  // from p to each portal
  std::vector<int> prev_;     // the portal before each on its shortest chain (-1: p)
};

}  // namespace chaosweep

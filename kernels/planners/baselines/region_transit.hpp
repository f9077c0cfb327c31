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
  // The length of the transit from the last search's p to q, a point of
  // rectangle `region`, entering it last (q may lie on other rectangles'
  // edges too; going by the one given keeps this O(its portals)), or
  // infinity when no chain of rectangles links them.
  double distance_to(Point q, int region) const;
  // Its points after p, ending with q (empty when unreachable).
  std::vector<Point> path_to(Point q, int region) const;

 private:
  struct Portal {
    Point at;
    int a, b;  // the two rectangles it joins
  };
  // The portal of `region` that ends the shortest chain to q, with its
  // length (-1: p is in that rectangle too, or no chain reaches it).
  std::pair<int, double> last_portal(Point q, int region) const;

  const RectDecomposition& d_;
  std::vector<Portal> portals_;
  std::vector<std::vector<int>> portals_of_;  // each rectangle's portals
  Point from_{0, 0};
  std::vector<int> from_regions_;
  std::vector<double> dist_;  // from p to each portal
  std::vector<int> prev_;     // the portal before each on its shortest chain (-1: p)
};

}  // namespace chaosweep

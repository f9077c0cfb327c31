#include "kernels/planners/baselines/lawnmower.hpp"

#include <limits>
#include <stdexcept>

#include "kernels/core/param_table.hpp"
#include "kernels/core/rect_decomposition.hpp"
#include "kernels/planners/baselines/baseline_robot.hpp"
#include "kernels/planners/baselines/lawnmower_lanes.hpp"
#include "kernels/planners/baselines/region_transit.hpp"

namespace chaosweep {

namespace {

class LawnmowerRun {
 public:
  LawnmowerRun(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r, TraceSink* trace)
      : grid_(grid),
        r_(r),
        robot_(p, grid, r, trace),
        d_(decompose_free_space(env, 0.0)),
        transit_(d_),
        centres_(env, grid) {}

  void run() {
    std::vector<bool> done(d_.regions.size(), false);
    while (!robot_.ended()) {
      // Greedy: the rectangle whose lanes start nearest (by transit) next.
      transit_.search_from({robot_.x(), robot_.y()});
      int region = -1;
      std::vector<Point> path;
      double nearest = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < d_.regions.size(); ++k) {
        if (done[k]) continue;
        const Rect& box = d_.regions[k].box;
        // Lanes along the longer side: fewer of them, fewer turns.
        const std::vector<Lane> lanes = box_lanes(grid_, centres_, box, box.x1 - box.x0 >= box.y1 - box.y0);
        if (lanes.empty()) {
          done[k] = true;  // its cells are covered already
          continue;
        }
        for (int corner = 0; corner < corners; ++corner) {
          std::vector<Point> way = boustrophedon(lanes, corner);
          const double l = transit_.distance_to(way.front(), int(k));
          if (l < nearest) nearest = l, region = int(k), path = std::move(way);
        }
      }
      if (region < 0) return robot_.end(Status::stuck, "every lane the lawnmower can reach is driven, short of dc");
      for (const Point& q : transit_.path_to(path.front(), region)) robot_.walk_to(q.x, q.y, SegmentKind::transit);
      for (const Point& q : path) robot_.walk_to(q.x, q.y, SegmentKind::move);
      done[std::size_t(region)] = true;
      if (!robot_.ended()) ++r_.segments;
    }
  }

 private:
  CoverageGrid& grid_;
  RunResult& r_;
  BaselineRobot robot_;
  RectDecomposition d_;
  RegionTransit transit_;
  CellCentres centres_;
};

}  // namespace

std::string validate_lawnmower(const RunParams& p, const Environment& env) {
  RectDecomposition d;
  try {
    d = decompose_free_space(env, 0.0);
  } catch (const std::invalid_argument& e) {
    return std::string("planner = lawnmower (the Chebyshev planner's decomposition, radius 0) on environment '") +
           env.name + "': " + e.what();
  }
  if (d.region_at(p.start_x, p.start_y) < 0)
    return "start (" + format_number(p.start_x) + ", " + format_number(p.start_y) +
           ") lies in no free rectangle of environment '" + env.name + "' (planner = lawnmower)";
  return {};
}

void run_lawnmower(const RunParams& p, const Environment& env, CoverageGrid& grid, RunResult& r, TraceSink* trace) {
  LawnmowerRun(p, env, grid, r, trace).run();
}

}  // namespace chaosweep

#include "clutter.hpp"

#include "splitmix.hpp"

namespace chaosweep {

std::vector<Rect> generate_clutter(double lx, double ly, const ClutterSpec& spec, double start_x,
                                   double start_y) {
  std::vector<Rect> out;
  std::uint64_t state = spec.seed;
  const double target = spec.occupancy * lx * ly;
  const double g = spec.gap;
  double area = 0.0;
  for (int attempt = 0; attempt < 100000 && area < target; ++attempt) {
    const double side = spec.min_side + (spec.max_side - spec.min_side) * uniform01(state);
    const double x = g + (lx - side - 2 * g) * uniform01(state);
    const double y = g + (ly - side - 2 * g) * uniform01(state);
    if (x < g || y < g || x + side > lx - g || y + side > ly - g) continue;  // map too small for this side
    const Rect r{x, y, x + side, y + side};
    const Rect grown{r.x0 - g, r.y0 - g, r.x1 + g, r.y1 + g};
    bool clear = !grown.contains(start_x, start_y);
    for (const Rect& o : out)
      clear = clear && !(grown.x0 < o.x1 && o.x0 < grown.x1 && grown.y0 < o.y1 && o.y0 < grown.y1);
    if (!clear) continue;
    out.push_back(r);
    area += side * side;
  }
  return out;
}

}  // namespace chaosweep

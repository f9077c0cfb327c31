#include "kernels/core/clutter.hpp"

#include <algorithm>
#include <cmath>

#include "kernels/math/splitmix.hpp"

namespace chaosweep {

std::vector<Rect> generate_clutter(double lx, double ly, const ClutterSpec& spec, double start_x, double start_y) {
  std::vector<Rect> out;
  std::uint64_t state = spec.seed;
  const double target = spec.occupancy * lx * ly;
  const double g = spec.gap;
  // Squares placed so far, by bucket: a candidate (grown by the gap) can
  // only overlap squares listed in the buckets it meets, so each attempt
  // costs a few buckets, not a pass over every square (which made many
  // small squares quadratic). Buckets are at least a grown square wide.
  const double side_max = std::max({spec.max_side + 2 * g, lx / 256, ly / 256});
  const int nbx = std::clamp(int(std::ceil(lx / side_max)), 1, 256),
            nby = std::clamp(int(std::ceil(ly / side_max)), 1, 256);
  const double inv_x = nbx / lx, inv_y = nby / ly;
  // Non-decreasing in v: squares that overlap share a bucket.
  const auto bucket = [](double v, double inv, int n) {
    const double t = v * inv;
    return t < 1 ? 0 : t >= double(n - 1) ? n - 1 : int(t);
  };
  std::vector<std::vector<std::uint32_t>> buckets(std::size_t(nbx) * std::size_t(nby));
  double area = 0.0;
  for (int attempt = 0; attempt < max_clutter_attempts && area < target; ++attempt) {
    const double side = spec.min_side + (spec.max_side - spec.min_side) * uniform01(state);
    const double x = g + (lx - side - 2 * g) * uniform01(state);
    const double y = g + (ly - side - 2 * g) * uniform01(state);
    if (x < g || y < g || x + side > lx - g || y + side > ly - g) continue;  // map too small for this side
    const Rect r{x, y, x + side, y + side};
    const Rect grown{r.x0 - g, r.y0 - g, r.x1 + g, r.y1 + g};
    bool clear = !grown.contains(start_x, start_y);
    for (int j = bucket(grown.y0, inv_y, nby); clear && j <= bucket(grown.y1, inv_y, nby); ++j)
      for (int i = bucket(grown.x0, inv_x, nbx); clear && i <= bucket(grown.x1, inv_x, nbx); ++i)
        for (std::uint32_t k : buckets[std::size_t(j) * std::size_t(nbx) + std::size_t(i)]) {
          const Rect& o = out[k];
          clear = clear && !(grown.x0 < o.x1 && o.x0 < grown.x1 && grown.y0 < o.y1 && o.y0 < grown.y1);
        }
    if (!clear) continue;
    for (int j = bucket(r.y0, inv_y, nby); j <= bucket(r.y1, inv_y, nby); ++j)
      for (int i = bucket(r.x0, inv_x, nbx); i <= bucket(r.x1, inv_x, nbx); ++i)
        buckets[std::size_t(j) * std::size_t(nbx) + std::size_t(i)].push_back(std::uint32_t(out.size()));
    out.push_back(r);
    area += side * side;
  }
  return out;
}

}  // namespace chaosweep

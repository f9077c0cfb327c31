#include "kernels/core/obstacle_index.hpp"

#include <cmath>

namespace chaosweep {

ObstacleIndex::ObstacleIndex(const std::vector<Rect>& obstacles, double reach)
    : count_(std::uint32_t(obstacles.size())) {
  if (obstacles.empty()) return;
  x0_ = y0_ = INFINITY;
  x1_ = y1_ = -INFINITY;
  for (const Rect& r : obstacles) {
    x0_ = std::min(x0_, r.x0), y0_ = std::min(y0_, r.y0);
    x1_ = std::max(x1_, r.x1), y1_ = std::max(y1_, r.y1);
  }
  const double w = x1_ - x0_, h = y1_ - y0_;
  // About one obstacle per bucket, no bucket smaller than `reach`, at most
  // 1024 x 1024 buckets.
  double side = std::max({reach, std::sqrt(w * h / double(obstacles.size())), std::max(w, h) / 1024, 1e-300});
  for (;;) {
    nx_ = std::clamp(int(std::ceil(w / side)), 1, 1024);
    ny_ = std::clamp(int(std::ceil(h / side)), 1, 1024);
    inv_w_ = double(nx_) / std::max(w, 1e-300);
    inv_h_ = double(ny_) / std::max(h, 1e-300);
    // Count the entries; large obstacles listed in many buckets coarsen the
    // grid until the lists hold a few entries per obstacle.
    double entries = 0;
    for (const Rect& r : obstacles)
      entries += double(bucket(r.x1, x0_, inv_w_, nx_) - bucket(r.x0, x0_, inv_w_, nx_) + 1) *
                 double(bucket(r.y1, y0_, inv_h_, ny_) - bucket(r.y0, y0_, inv_h_, ny_) + 1);
    if (entries <= 16.0 * double(obstacles.size()) || (nx_ == 1 && ny_ == 1)) break;
    side *= 2;
  }
  start_.assign(std::size_t(nx_) * std::size_t(ny_) + 1, 0);
  const auto each_bucket = [&](const Rect& r, auto&& f) {
    for (int j = bucket(r.y0, y0_, inv_h_, ny_); j <= bucket(r.y1, y0_, inv_h_, ny_); ++j)
      for (int i = bucket(r.x0, x0_, inv_w_, nx_); i <= bucket(r.x1, x0_, inv_w_, nx_); ++i)
        f(std::size_t(j) * std::size_t(nx_) + std::size_t(i));
  };
  for (const Rect& r : obstacles) each_bucket(r, [&](std::size_t b) { ++start_[b + 1]; });
  for (std::size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
  items_.resize(start_.back());
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::uint32_t k = 0; k < count_; ++k) each_bucket(obstacles[k], [&](std::size_t b) { items_[fill[b]++] = k; });
}

}  // namespace chaosweep

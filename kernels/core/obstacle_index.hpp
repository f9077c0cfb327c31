#pragma once
// A uniform grid of buckets over the obstacles' bounding box, each listing
// (in increasing index) the obstacles whose closed rectangle meets it, so
// that "which obstacles near (x, y)" costs a few buckets instead of a pass
// over every obstacle (a map of 9,000 obstacles made each step and each cell
// of a run's setup scan all 9,000). Queries return a superset of the
// obstacles meeting the query box, in increasing index, each once; callers
// apply their own exact test, so results equal those of a full scan.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "kernels/core/environment.hpp"

namespace chaosweep {

class ObstacleIndex {
 public:
  // `reach`: the side of the query boxes callers make, if known (0: buckets
  // of about one obstacle each). A query spanning more than 4 buckets along
  // x or y scans every obstacle, still correctly.
  ObstacleIndex(const std::vector<Rect>& obstacles, double reach);

  std::size_t size() const { return count_; }  // obstacles indexed
  // The widest side of a query box that find() answers from its buckets
  // (a box spanning more buckets scans every obstacle).
  double bucket_query_side() const { return double(max_span - 1) * 0.95 / std::max(inv_w_, inv_h_); }

  // Calls f(k) for the obstacles k that may meet [x0, x1] x [y0, y1], in
  // increasing k, until f returns true; returns whether it did.
  template <class F>
  bool find(double x0, double y0, double x1, double y1, F&& f) const {
    // Outside the bounding box (or NaN): no obstacle meets the box.
    if (!(x1 >= x0_ && x0 <= x1_ && y1 >= y0_ && y0 <= y1_)) return false;
    const int i0 = bucket(x0, x0_, inv_w_, nx_), i1 = bucket(x1, x0_, inv_w_, nx_);
    const int j0 = bucket(y0, y0_, inv_h_, ny_), j1 = bucket(y1, y0_, inv_h_, ny_);
    if (i1 - i0 >= max_span || j1 - j0 >= max_span) {  // a box wider than the buckets: every obstacle
      for (std::uint32_t k = 0; k < count_; ++k)
        if (f(std::size_t(k))) return true;
      return false;
    }
    // Merge the (up to max_span^2) sorted bucket lists, dropping repeats.
    const std::uint32_t* at[max_span * max_span];
    const std::uint32_t* end[max_span * max_span];
    int lists = 0;
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const std::size_t b = std::size_t(j) * std::size_t(nx_) + std::size_t(i);
        at[lists] = items_.data() + start_[b];
        end[lists] = items_.data() + start_[b + 1];
        ++lists;
      }
    for (;;) {
      std::uint32_t next = UINT32_MAX;
      for (int l = 0; l < lists; ++l)
        if (at[l] != end[l] && *at[l] < next) next = *at[l];
      if (next == UINT32_MAX) return false;
      for (int l = 0; l < lists; ++l)
        if (at[l] != end[l] && *at[l] == next) ++at[l];
      if (f(std::size_t(next))) return true;
    }
  }

 private:
  static constexpr int max_span = 4;  // buckets a query box may span along x or y
  // Non-decreasing in v (correctly rounded subtraction and product, floor,
  // clamp): a point common to a rectangle and a query box falls in a bucket
  // of both, so every obstacle meeting the box is listed.
  static int bucket(double v, double origin, double inv, int n) {
    const double t = (v - origin) * inv;
    return t < 1 ? 0 : t >= double(n - 1) ? n - 1 : int(t);
  }

  std::uint32_t count_ = 0;
  int nx_ = 1, ny_ = 1;
  double x0_ = 0, y0_ = 0, x1_ = -1, y1_ = -1;  // bounding box (empty: x1_ < x0_)
  double inv_w_ = 0, inv_h_ = 0;
  std::vector<std::uint32_t> start_;  // bucket b lists items_[start_[b], start_[b + 1])
  std::vector<std::uint32_t> items_;
};

}  // namespace chaosweep

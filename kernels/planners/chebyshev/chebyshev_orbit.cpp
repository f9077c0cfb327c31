#include "kernels/planners/chebyshev/chebyshev_orbit.hpp"

#include <algorithm>
#include <vector>

#include "kernels/core/setup_cache.hpp"
#include "kernels/systems/chebyshev_map.hpp"

namespace chaosweep {

struct OrbitBlock {
  std::vector<ChebyshevOrbit::Value> values;
};

namespace {

ChebyshevOrbit::Value drawn(double x, ChebTransform t) {
  const double lo = cheb_lo(t), span = cheb_hi(t) - lo;
  return {x, (cheb_transform(x, t) - lo) / span};
}

// Block j holds the 64 * 2^j iterates (at most 2^16) after block j - 1's,
// the first those after the run's own: a run that stops early computes
// little it does not use, one that runs long looks the cache up seldom.
std::size_t block_size(int j) { return std::size_t(64) << std::min(j, 10); }

std::shared_ptr<const OrbitBlock> make_block(int k, ChebTransform t, double x, int j) {
  auto b = std::make_shared<OrbitBlock>();
  b->values.resize(block_size(j));
  for (ChebyshevOrbit::Value& v : b->values) v = drawn(x = chebyshev_step(x, k), t);
  return b;
}

}  // namespace

ChebyshevOrbit::ChebyshevOrbit(int k, double x0, ChebTransform transform)
    : k_(k), x0_(x0), transform_(transform), x_(x0) {}

ChebyshevOrbit::~ChebyshevOrbit() = default;

ChebyshevOrbit::Value ChebyshevOrbit::advance() {
  if (drawn_ < own_iterates) {
    ++drawn_;
    return drawn(x_ = chebyshev_step(x_, k_), transform_);
  }
  // Bounded by values held (16 bytes each): 2^18 of them, 4 MiB, several
  // thousand iterates of each orbit of a sweep like seed001's (128 orbits);
  // more only made a sweep whose orbits never repeat fault in more memory.
  static SetupCache<OrbitBlock> cache(std::size_t(1) << 18);
  const int j = index_ + 1;
  // The iterate before the block's first: the run's last own, or the last
  // of the block held.
  const double from = j == 0 ? x_ : block_->values.back().x;
  SetupKey key;
  key.add(k_).add(x0_).add(int(transform_)).add(j);
  block_ = cache.get(key, block_size(j), [&] { return make_block(k_, transform_, from, j); });
  index_ = j;
  at_ = block_->values.data();
  end_ = at_ + block_->values.size();
  return *at_++;
}

}  // namespace chaosweep

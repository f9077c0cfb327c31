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

// Block j holds the 64 * 2^j iterates (at most 2^16) after the span before
// it (the run's own 32, then blocks 0 .. j - 1): a run that stops early
// computes little it does not use, one that runs long looks the cache up
// seldom.
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
  if (block_) {  // a block read to its end: go on from its last iterate
    x_ = block_->values.back().x;
    block_.reset();
  }
  if (drawn_ < own_end_) {
    ++drawn_;
    return drawn(x_ = chebyshev_step(x_, k_), transform_);
  }
  // Bounded by values held (16 bytes each; a mark counts one): 2^18 of them,
  // 4 MiB, several thousand iterates of each orbit of a sweep like seed001's
  // (128 orbits); more only made a sweep whose orbits never repeat fault in
  // more memory.
  static SetupCache<OrbitBlock> cache(std::size_t(1) << 18);
  static const auto mark = std::make_shared<const OrbitBlock>();
  const int j = ++index_;
  const long n = long(block_size(j));
  SetupKey key;
  key.add(k_).add(x0_).add(int(transform_)).add(j);
  bool first = false;
  std::shared_ptr<const OrbitBlock> b = cache.get(key, 1, [&] {
    first = true;
    return mark;
  });
  if (first) {  // no run has drawn this far: draw on, leaving the mark
    own_end_ = drawn_ + n;
    ++drawn_;
    return drawn(x_ = chebyshev_step(x_, k_), transform_);
  }
  if (b->values.empty()) {  // a second run: the orbit is shared, build
    b = make_block(k_, transform_, x_, j);
    cache.replace(key, std::size_t(n), b);
  }
  block_ = std::move(b);
  drawn_ += n;
  own_end_ = drawn_;
  at_ = block_->values.data();
  end_ = at_ + block_->values.size();
  return *at_++;
}

}  // namespace chaosweep

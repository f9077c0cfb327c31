#include "kernels/planners/chebyshev/chebyshev_orbit.hpp"

#include "kernels/systems/chebyshev_map.hpp"

namespace chaosweep {

namespace {

SharedOrbit<ChebyshevOrbit::Value>::Cache& chebyshev_orbit_cache() {
  // Bounded by values held (16 bytes each; a mark counts one): 2^18 of them,
  // 4 MiB, several thousand iterates of each orbit of a sweep like seed001's
  // (128 orbits); more only made a sweep whose orbits never repeat fault in
  // more memory.
  static SharedOrbit<ChebyshevOrbit::Value>::Cache cache(std::size_t(1) << 18);
  return cache;
}

SetupKey chebyshev_orbit_key(int k, double x0, ChebTransform t) {
  SetupKey key;
  key.add(k).add(x0).add(int(t));
  return key;
}

}  // namespace

ChebyshevOrbit::ChebyshevOrbit(int k, double x0, ChebTransform transform)
    : k_(k), transform_(transform), orbit_(chebyshev_orbit_key(k, x0, transform), x0, chebyshev_orbit_cache()) {}

ChebyshevOrbit::Value ChebyshevOrbit::draw(double& x) const {
  x = chebyshev_step(x, k_);
  const double lo = cheb_lo(transform_), span = cheb_hi(transform_) - lo;
  return {x, (cheb_transform(x, transform_) - lo) / span};
}

}  // namespace chaosweep

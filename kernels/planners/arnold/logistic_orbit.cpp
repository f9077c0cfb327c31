#include "kernels/planners/arnold/logistic_orbit.hpp"

#include <cmath>

#include "kernels/systems/logistic_map.hpp"

namespace chaosweep {

namespace {

SharedOrbit<LogisticOrbit::Value>::Cache& logistic_orbit_cache() {
  // Bounded by values held (48 bytes each; a mark counts one): 2^20 of them,
  // 48 MiB: Table 1's transit orbit (one x0, no jitter) is drawn 50 k
  // values deep by the median run, 200 k by one in ten, 830 k at most; a
  // smaller bound evicts its first blocks before the next run needs them.
  static SharedOrbit<LogisticOrbit::Value>::Cache cache(std::size_t(1) << 20);
  return cache;
}

SetupKey logistic_orbit_key(double r, double x0) {
  SetupKey key;
  key.add(r).add(x0);
  return key;
}

}  // namespace

LogisticOrbit::LogisticOrbit(double r, double x0)
    : r_(r),
      fixed_(LogisticMap::fixed_point(r)),
      x_(x0),
      orbit_(logistic_orbit_key(r, x0), x0, logistic_orbit_cache()) {}

LogisticOrbit::Heading LogisticOrbit::draw(double& x, bool rightwards) const {
  Heading h;
  x = h.x = LogisticMap::iterate(x, r_);
  h.ok = LogisticMap::usable(x, fixed_);
  const double th = LogisticMap::angle(x, LogisticMap::branch(rightwards));
  h.cos = std::cos(th);
  h.sin = std::sin(th);
  return h;
}

LogisticOrbit::Value LogisticOrbit::both(double& x) const {
  Value v;
  x = v.x = LogisticMap::iterate(x, r_);
  v.ok = LogisticMap::usable(x, fixed_);
  const double right = LogisticMap::angle(x, LogisticMap::rightwards);
  const double left = LogisticMap::angle(x, LogisticMap::leftwards);
  v.cos_right = std::cos(right);
  v.sin_right = std::sin(right);
  v.cos_left = std::cos(left);
  v.sin_left = std::sin(left);
  return v;
}

}  // namespace chaosweep

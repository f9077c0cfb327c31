#include "kernels/core/chaotic_spread.hpp"

#include "kernels/math/splitmix.hpp"

namespace chaosweep {

double uniform_pm1(std::uint64_t& state) { return 2.0 * uniform01(state) - 1.0; }

Vec3<double> jittered_ic(const RunParams& p) {
  Vec3<double> u = system_ic(p);
  if (p.ic_jitter > 0) {
    std::uint64_t s = std::uint64_t(p.seed);
    u.x += p.ic_jitter * uniform_pm1(s);
    u.y += p.ic_jitter * uniform_pm1(s);
    u.z += p.ic_jitter * uniform_pm1(s);
  }
  return u;
}

}  // namespace chaosweep

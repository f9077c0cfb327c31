#pragma once
// splitmix64: the small, well-mixed generator every seeded draw of a run uses,
// so that a run's randomness is a pure function of its seed.
#include <cstdint>

namespace chaosweep {

inline std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Uniform in [0, 1) from 53 random bits.
inline double uniform01(std::uint64_t& state) { return double(splitmix64(state) >> 11) * 0x1p-53; }

}  // namespace chaosweep

#pragma once
// The decisions Algorithm 1 (seed 000) takes after each Arnold segment.

namespace chaosweep {

// Eq. 5: keep exploring the current zone while c_n / c_nn >= c * c_u / c_T,
// with c_n new and c_nn distinct cells of the segment, c_u unvisited cells
// before it and c_T free cells. Evaluated without division (c_nn >= 1).
inline bool eq5_keep_exploring(long c_n, long c_nn, long c_u, long c_t, double c) {
  return double(c_n) * double(c_t) >= c * double(c_u) * double(c_nn);
}

// Orientation control: DSindex <- DSindex mod 3 + 1 (mod 2 + 1 for a
// system of two coordinates).
inline int next_ds_index(int ds, int dimension = 3) { return ds % dimension + 1; }

}  // namespace chaosweep

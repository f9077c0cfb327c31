#pragma once
// Seed 001's numbers about the Chebyshev map itself (Section 2: Lyapunov
// exponents, Table 1's v(xy)), computed here beside the paper's. Runs no
// sweep: every value comes from kernels/chebyshev_analysis.
#include "analysis/text_table.hpp"

namespace chaosweep {

// Rows: the Lyapunov exponent at k = 6 of the raw map, of the arcsine-
// transformed (conjugate) map, of the paper's Eq. 7 as printed (along the
// raw orbit and along its Eq. 9 orbit); v(xy) for the original map and both
// transforms at n = 2000 and 10000 (x1 = 0.1, y1 = 0.2). Columns: quantity,
// n, ours, paper, note. Deterministic; about 0.5 s.
TextTable seed001_table();

}  // namespace chaosweep

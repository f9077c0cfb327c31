#pragma once
// Analysis of the Chebyshev map itself (seed 001, Sections 2.1-2.3): Lyapunov
// exponents, the variable difference v(xy) of Eq. 6, orbit histograms and
// their chi-square statistics. Numbers for docs/spec.md §3's "say which is right".
//
// Orbits: x_0 = x0, x_{i+1} = chebyshev_step(x_i, k), iterated on x; a
// transform is applied to each sample only (docs/spec.md §3), never fed back.
//
// Floating point: a double orbit of cos(k acos x) can land exactly on +-1
// (cos rounds to 1 whenever k acos x is within ~1e-8 of a multiple of pi,
// roughly 7e-9 per step at k = 6), after which it sits on the fixed point
// x = 1 forever. Every function here throws std::domain_error naming the step
// when its orbit collapses onto a fixed point (x_{i+1} == x_i); the Lyapunov
// functions also throw when a sample is exactly +-1 (f' is 0/0 there). Pick
// another x0 then. Bad arguments (k < 2, n < 1, x0 outside [-1, 1] or not
// finite, bins < 1) throw std::invalid_argument.
#include <vector>

#include "kernels/systems/chebyshev_map.hpp"

namespace chaosweep {

// Largest Lyapunov exponent of the raw map: the mean of ln|f'(x_i)| over
// i = burn_in .. burn_in + n - 1, f'(x) = k sin(k acos x) / sqrt(1 - x^2).
// Exactly ln k in the limit (with x = cos t the sum telescopes:
// ln|f'(x_i)| = ln k + ln sin t_{i+1} - ln sin t_i), so the error is O(1/n).
double lyapunov_exponent(int k, double x0, long n, long burn_in = 1000);

// The same for the arcsine-transformed map g = T o f o T^-1, T(x) = (2/pi)
// asin x, measured on u_i = T(x_i) with g'(u) by the chain rule,
// T'(f(x)) f'(x) (dx/du). T is a conjugacy, so this is ln k again (indeed
// |g'| = k everywhere: g is a zigzag of slope +-k).
double lyapunov_exponent_arcsine(int k, double x0, long n, long burn_in = 1000);

// The paper's Eq. 7 evaluated as printed, 2k sin(k acos x) / (pi sqrt(1 -
// cos^2(k acos x)) sqrt(1 - x^2)), its ln|.| averaged along the raw orbit.
// Eq. 7 is d(T o f)/dx, not the conjugate map's derivative: it lacks the
// factor dx/du = (pi/2) sqrt(1 - x^2). With x = cos t, t uniform on [0, pi]
// under the invariant measure, |Eq. 7| = (2k/pi) / sin t, so the mean is
// ln(2k/pi) + E[-ln sin t] = ln(2k/pi) + ln 2 = ln(4k/pi) (2.0333 at k = 6),
// not the paper's 3.2147.
double lyapunov_paper_eq7(int k, double x0, long n, long burn_in = 1000);

// Eq. 7 averaged along the orbit of the paper's Eq. 9 read as a map on its
// own, x_{i+1} = h(x_i) = (2/pi) asin(cos(k acos x_i)), whose derivative Eq. 7
// is: the other reading of "substituting it into Eq. (2)". About 1.64 at
// k = 6 (measured; no closed form here), again not 3.2147.
double lyapunov_paper_eq7_on_eq9(int k, double x0, long n, long burn_in = 1000);

// v(xy) of Eq. 6: the mean over i = 1..n of |T(x_i) - T(y_i)| for two orbits
// with x_1 = x1, y_1 = y1. The initial values count as the first samples
// (the paper: "the initial values are x1 = 0.1, y1 = 0.2" for {x1..xn}). For
// independent samples the limit is 8/pi^2 (arcsine density, t = none) and 2/3
// (uniform, arcsine or arccosine: the two differ by the constant 1, so their
// v(xy) agree to rounding).
double variable_difference(int k, double x1, double y1, long n, ChebTransform t);

// Counts of T(x_i), i = 0..n-1 (x_0 = x0 included), in `bins` equal bins over
// [cheb_lo(t), cheb_hi(t)]; the top edge falls in the last bin.
std::vector<long> orbit_histogram(int k, double x0, long n, int bins, ChebTransform t);

// Pearson's statistic sum (O - E)^2 / E against equal expected counts.
double chi_square_uniform(const std::vector<long>& counts);

// The same against the arcsine density 1 / (pi sqrt(1 - x^2)): the bins are
// equal ones over [-1, 1] (a raw-orbit histogram, t = none) and E_j is the
// total times the density's mass in bin j, by its CDF 1/2 + asin(x)/pi.
double chi_square_arcsine(const std::vector<long>& counts);

}  // namespace chaosweep

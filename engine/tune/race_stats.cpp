#include "engine/tune/race_stats.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>

#include "kernels/math/splitmix.hpp"

namespace chaosweep {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double eps = std::numeric_limits<double>::epsilon();
// Lentz's floor for a vanishing denominator.
constexpr double tiny = 1e-300;
constexpr int max_iterations = 1'000'000;

// A total order (NaN after +inf, NaNs tied) so that sorting never sees an
// invalid comparator, whatever the input.
// One term of a continued fraction b + a / (...) by the modified Lentz
// method (c, d its running state): the factor the value is multiplied by.
double lentz_step(double a, double b, double& c, double& d) {
  d = b + a * d;
  if (std::abs(d) < tiny) d = tiny;
  c = b + a / c;
  if (std::abs(c) < tiny) c = tiny;
  d = 1 / d;
  return d * c;
}

bool before(double a, double b) { return !std::isnan(a) && (std::isnan(b) || a < b); }
bool tied(double a, double b) { return !before(a, b) && !before(b, a); }

// ---- special functions ----

// lgamma(x) - ((x - 1/2) ln x - x + ln sqrt(2 pi)) for x >= 10 (Stirling's
// series): lets log-gamma differences at large arguments be formed without
// cancelling two huge numbers.
double lgamma_correction(double x) {
  const double r = 1 / x, r2 = r * r;
  return r * (1.0 / 12 +
              r2 * (-1.0 / 360 +
                    r2 * (1.0 / 1260 + r2 * (-1.0 / 1680 + r2 * (1.0 / 1188 + r2 * (-691.0 / 360360 + r2 / 156))))));
}

constexpr double ln_sqrt_2pi = 0.918938533204672741780329736406;  // ln sqrt(2 pi)

// ln B(a, b), accurate when a or b is large (the formulas of R's lbeta).
double log_beta(double a, double b) {
  const double p = std::min(a, b), q = std::max(a, b);
  if (p >= 10) {
    const double corr = lgamma_correction(p) + lgamma_correction(q) - lgamma_correction(p + q);
    return -0.5 * std::log(q) + ln_sqrt_2pi + corr + (p - 0.5) * std::log(p / (p + q)) + q * std::log1p(-p / (p + q));
  }
  if (q >= 10) {
    const double corr = lgamma_correction(q) - lgamma_correction(p + q);
    return std::lgamma(p) + corr + p - p * std::log(p + q) + (q - 0.5) * std::log1p(-p / (p + q));
  }
  return std::lgamma(p) + std::lgamma(q) - std::lgamma(p + q);
}

// ln(x^a e^-x / Gamma(a)), the prefactor of the incomplete gamma function.
double log_gamma_prefactor(double a, double x) {
  if (a < 10) return a * std::log(x) - x - std::lgamma(a);
  // a ln(x/a) + a - x = a (log1p(d) - d): small when x is near a, where the
  // plain formula would subtract numbers of size a ln a.
  const double d = (x - a) / a;
  return a * (std::log1p(d) - d) + 0.5 * std::log(a) - ln_sqrt_2pi - lgamma_correction(a);
}

struct Tails {
  double lower, upper;
};

// Regularized incomplete gamma P(a, x) and Q(a, x) = 1 - P, each computed
// directly where it is the smaller (series below a + 1, continued fraction above).
Tails incomplete_gamma(double a, double x) {
  if (!(x > 0)) return {0, 1};
  if (std::isinf(x)) return {1, 0};
  const double prefactor = std::exp(log_gamma_prefactor(a, x));
  if (x < a + 1) {
    double term = 1 / a, sum = term;
    for (int n = 1; n < max_iterations; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * eps) break;
    }
    const double p = std::min(1.0, sum * prefactor);
    return {p, 1 - p};
  }
  double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
  for (int i = 1; i < max_iterations; ++i) {
    const double an = -i * (i - a);
    b += 2;
    const double delta = lentz_step(an, b, c, d);
    h *= delta;
    if (std::abs(delta - 1) < eps) break;
  }
  const double q = std::min(1.0, h * prefactor);
  return {1 - q, q};
}

// The continued fraction of the incomplete beta function (modified Lentz).
double beta_continued_fraction(double a, double b, double x) {
  const double qab = a + b, qap = a + 1, qam = a - 1;
  double c = 1, d = 1 - qab * x / qap;
  if (std::abs(d) < tiny) d = tiny;
  d = 1 / d;
  double h = d;
  for (int m = 1; m < max_iterations; ++m) {
    const int m2 = 2 * m;
    h *= lentz_step(m * (b - m) * x / ((qam + m2) * (a + m2)), 1, c, d);
    const double delta = lentz_step(-(a + m) * (qab + m) * x / ((a + m2) * (qap + m2)), 1, c, d);
    h *= delta;
    if (std::abs(delta - 1) < eps) break;
  }
  return h;
}

// Regularized incomplete beta I_x(a, b) given x and y = 1 - x, both passed
// because the caller can form the small one without cancellation.
double incomplete_beta(double a, double b, double x, double y) {
  if (!(x > 0)) return 0;
  if (!(y > 0)) return 1;
  const double log_x = x > 0.5 ? std::log1p(-y) : std::log(x);
  const double log_y = y > 0.5 ? std::log1p(-x) : std::log(y);
  const double prefactor = std::exp(a * log_x + b * log_y - log_beta(a, b));
  if (x < (a + 1) / (a + b + 2)) return prefactor * beta_continued_fraction(a, b, x) / a;
  return 1 - prefactor * beta_continued_fraction(b, a, y) / b;
}

// ln(Gamma(a) / Gamma(a + b)) for a >= 10, from Stirling's series without
// subtracting the two large log-gammas.
double log_gamma_ratio(double a, double b) {
  return -(a - 0.5) * std::log1p(b / a) - b * std::log(a + b) + b + lgamma_correction(a) - lgamma_correction(a + b);
}

// e^(s^2) erfc(s) for s >= 0, finite where erfc itself underflows (Laplace's
// continued fraction for large s).
double scaled_erfc(double s) {
  if (s < 5) return std::exp(s * s) * std::erfc(s);
  // erfc(s) e^(s^2) sqrt(pi) = 1 / (s + (1/2) / (s + (2/2) / (s + (3/2) / ...)))
  double c = s, d = 0, h = s;
  for (int n = 1; n < 1000; ++n) {
    const double delta = lentz_step(0.5 * n, s, c, d);
    h *= delta;
    if (std::abs(delta - 1) < eps) break;
  }
  return 1 / (h * std::sqrt(std::numbers::pi));
}

// I_x(a, 1/2) for large a from ln x, by the asymptotic expansion in
// incomplete gamma functions of DiDonato & Morris (1992, section 9; BGRAT in
// TOMS 708), here with b = 1/2 so that Q(b, z) = erfc(sqrt z). Student's t at
// large df needs it: x is then close to 1, where the continued fraction loses
// digits in proportion to a.
double incomplete_beta_large_a_half_b(double a, double log_x) {
  constexpr double b = 0.5;
  constexpr int terms = 30;
  const double nu = a + (b - 1) / 2, z = -nu * log_x;
  if (!(z > 0)) return 1;
  const double sqrt_z = std::sqrt(z);
  // I = u * sum_n d_n J_n, J_n scaled by 1/r with r = e^-z z^b / Gamma(b).
  const double log_r = -z + b * std::log(z) - 0.5 * std::log(std::numbers::pi);
  const double u = std::exp(log_r - log_gamma_ratio(a, b) - b * std::log(nu));
  if (u == 0) return 0;
  double j = scaled_erfc(sqrt_z) * std::sqrt(std::numbers::pi) / sqrt_z;  // Q(b, z) / r
  double sum = j, t = 1, cn = 1, n2 = 0;
  const double v = 0.25 / (nu * nu), t2 = 0.25 * log_x * log_x;
  double c[terms], d[terms];
  for (int n = 1; n <= terms; ++n) {
    const double bp2n = b + n2;
    j = (bp2n * (bp2n + 1) * j + (z + bp2n + 1) * t) * v;
    n2 += 2;
    t *= t2;
    cn /= n2 * (n2 + 1);
    c[n - 1] = cn;
    double s = 0, coef = b - n;
    for (int i = 1; i < n; ++i, coef += b) s += coef * c[i - 1] * d[n - 1 - i];
    d[n - 1] = (b - 1) * cn + s / n;
    const double dj = d[n - 1] * j;
    sum += dj;
    if (std::abs(dj) <= eps * sum) break;
  }
  return u * sum;
}

double chi2_upper(double x, double df) { return incomplete_gamma(df / 2, x / 2).upper; }

// Half-degrees of freedom from which Student's t uses the asymptotic expansion
// (where the continued fraction had lost ~1e-14 near x = 1).
constexpr double large_half_df = 50;

// P(T > t) for t >= 0: I_x(df/2, 1/2) / 2 with x = df / (df + t^2), formed
// from u = t / sqrt(df) so that neither x nor 1 - x overflows or cancels.
double student_t_upper(double t, double df) {
  if (std::isinf(t)) return 0;
  if (t == 0) return 0.5;
  const double u = t / std::sqrt(df);
  double x, y, log_x;
  if (u <= 1) {
    x = 1 / (1 + u * u);
    y = u * u / (1 + u * u);
    log_x = -std::log1p(u * u);
  } else {
    const double w = 1 / u;
    x = w * w / (1 + w * w);
    y = 1 / (1 + w * w);
    log_x = 2 * std::log(w) - std::log1p(w * w);
  }
  // The expansion is in powers of ln x, so it wants x near 1 as much as the
  // continued fraction does not.
  if (df / 2 >= large_half_df && y <= 0.5) return 0.5 * incomplete_beta_large_a_half_b(df / 2, log_x);
  return 0.5 * incomplete_beta(df / 2, 0.5, x, y);
}

// The x >= 0 where a monotone condition flips: too_small(x) holds below the
// root and fails above it. A doubling bracket from `start`, then bisection to
// the last representable digit (robust where Newton steps on a flat or steep
// tail would not be).
template <class TooSmall>
double solve_increasing(TooSmall too_small, double start) {
  double lo = 0, hi = start;
  while (too_small(hi)) {
    lo = hi;
    hi *= 2;
    if (std::isinf(hi)) return inf;
  }
  for (int i = 0; i < 5000; ++i) {
    const double mid = lo == 0 ? hi / 2 : lo + (hi - lo) / 2;
    if (mid <= lo || mid >= hi || hi - lo <= 1e-15 * hi) break;
    (too_small(mid) ? lo : hi) = mid;
  }
  return lo + (hi - lo) / 2;
}

// ---- Friedman ----

struct FriedmanParts {
  FriedmanResult result;
  double sum_squared_ranks = 0;  // A1
};

FriedmanParts friedman_parts(std::span<const double> values, std::size_t blocks, std::size_t k) {
  if (values.size() != blocks * k) throw std::invalid_argument("friedman: values.size() != blocks * k");
  FriedmanParts parts;
  FriedmanResult& r = parts.result;
  r.rank_sums.assign(k, 0.0);
  for (std::size_t i = 0; i < blocks; ++i) {
    const std::vector<double> ranks = ranks_with_ties(values.subspan(i * k, k));
    for (std::size_t j = 0; j < k; ++j) {
      r.rank_sums[j] += ranks[j];
      parts.sum_squared_ranks += ranks[j] * ranks[j];
    }
  }
  const double b = double(blocks), kk = double(k);
  // Ranks are multiples of 1/2, so A1 and C1 are exact and the comparison is too.
  const double denominator = parts.sum_squared_ranks - b * kk * (kk + 1) * (kk + 1) / 4;
  if (k < 2 || !(denominator > 0)) return parts;
  double spread = 0;
  for (double rj : r.rank_sums) spread += (rj - b * (kk + 1) / 2) * (rj - b * (kk + 1) / 2);
  r.statistic = (kk - 1) * spread / denominator;
  r.p_value = chi2_upper(r.statistic, kk - 1);
  return parts;
}

// ---- Wilcoxon ----

// P(V <= v) and P(V >= v) for V the sum of the positive ranks among n
// untied ranks 1..n (each rank's sign a fair coin), by counting subsets.
Tails signed_rank_tails(std::size_t n, std::size_t v) {
  const std::size_t max_sum = n * (n + 1) / 2;
  // Counts stay below 2^n <= 2^50, exact in a double.
  std::vector<double> count(max_sum + 1, 0.0);
  count[0] = 1;
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t s = max_sum; s >= i; --s) count[s] += count[s - i];
  const double total = std::ldexp(1.0, int(n));
  double lower = 0, upper = 0;
  for (std::size_t s = 0; s <= max_sum; ++s) {
    if (s <= v) lower += count[s];
    if (s >= v) upper += count[s];
  }
  return {lower / total, upper / total};
}

// ---- medians ----

// The floor(n/2)-th order statistic (0-based) of w (reordered in place), with the
// one before it for an even count.
double median_in_place(std::vector<double>& w) {
  if (w.empty()) return nan;
  const std::size_t m = w.size() / 2;
  std::nth_element(w.begin(), w.begin() + std::ptrdiff_t(m), w.end(), before);
  const double upper = w[m];
  if (w.size() % 2 == 1) return upper;
  const double lower = *std::max_element(w.begin(), w.begin() + std::ptrdiff_t(m), before);
  if (upper == inf) return inf;
  return std::midpoint(lower, upper);
}

// The high 64 bits of a * b: an unbiased-enough index draw (multiply-shift)
// without relying on a 128-bit integer type.
std::uint64_t mul_high(std::uint64_t a, std::uint64_t b) {
  const std::uint64_t a_lo = a & 0xffffffffULL, a_hi = a >> 32, b_lo = b & 0xffffffffULL, b_hi = b >> 32;
  const std::uint64_t lo_lo = a_lo * b_lo, hi_lo = a_hi * b_lo, lo_hi = a_lo * b_hi, hi_hi = a_hi * b_hi;
  const std::uint64_t cross = (lo_lo >> 32) + (hi_lo & 0xffffffffULL) + lo_hi;
  return hi_hi + (hi_lo >> 32) + (cross >> 32);
}

}  // namespace

std::vector<double> ranks_with_ties(std::span<const double> v) {
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return before(v[i], v[j]); });
  std::vector<double> ranks(v.size());
  for (std::size_t first = 0; first < order.size();) {
    std::size_t last = first + 1;
    while (last < order.size() && tied(v[order[first]], v[order[last]])) ++last;
    // Positions first..last-1 hold ranks first+1..last; each gets their mean.
    const double mean_rank = (double(first) + 1 + double(last)) / 2;
    for (std::size_t i = first; i < last; ++i) ranks[order[i]] = mean_rank;
    first = last;
  }
  return ranks;
}

FriedmanResult friedman(std::span<const double> values, std::size_t blocks, std::size_t k) {
  return friedman_parts(values, blocks, k).result;
}

std::vector<bool> friedman_survivors(std::span<const double> values, std::size_t blocks, std::size_t k,
                                     double confidence) {
  std::vector<bool> keep(k, true);
  const FriedmanParts parts = friedman_parts(values, blocks, k);
  if (k < 2 || blocks < 2) return keep;
  const FriedmanResult& r = parts.result;
  const double alpha = 1 - confidence;
  if (!(r.p_value < alpha)) return keep;
  const double b = double(blocks), df = (b - 1) * (double(k) - 1);
  double sum_squared_sums = 0;
  for (double rj : r.rank_sums) sum_squared_sums += rj * rj;
  // 2 b (A1 - sum R^2 / b) written as 2 (b A1 - sum R^2), exact in doubles.
  const double spread = std::max(0.0, 2 * (b * parts.sum_squared_ranks - sum_squared_sums) / df);
  const double bound = student_t_quantile(1 - alpha / 2, df) * std::sqrt(spread);
  const double best = *std::min_element(r.rank_sums.begin(), r.rank_sums.end());
  for (std::size_t j = 0; j < k; ++j) keep[j] = std::abs(r.rank_sums[j] - best) <= bound;
  return keep;
}

double wilcoxon_signed_rank_p(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size()) throw std::invalid_argument("wilcoxon_signed_rank_p: a and b differ in size");
  std::vector<double> d;
  for (std::size_t i = 0; i < a.size(); ++i) {
    // a == b first: inf - inf would be NaN, and two missed targets are a tie.
    if (a[i] == b[i]) continue;
    d.push_back(a[i] - b[i]);
  }
  const std::size_t n = d.size();
  if (n == 0) return 1;
  std::vector<double> magnitude(n);
  for (std::size_t i = 0; i < n; ++i) magnitude[i] = std::abs(d[i]);
  const std::vector<double> ranks = ranks_with_ties(magnitude);
  double v = 0;  // the sum of the positive differences' ranks
  for (std::size_t i = 0; i < n; ++i)
    if (d[i] > 0) v += ranks[i];

  std::sort(magnitude.begin(), magnitude.end(), before);
  double tie_term = 0;  // sum over groups of tied |d| of t^3 - t
  for (std::size_t first = 0; first < n;) {
    std::size_t last = first + 1;
    while (last < n && tied(magnitude[first], magnitude[last])) ++last;
    const double t = double(last - first);
    tie_term += t * t * t - t;
    first = last;
  }

  if (n <= 50 && tie_term == 0) {
    // Untied ranks are the integers 1..n, so v is an integer.
    const Tails tails = signed_rank_tails(n, std::size_t(std::llround(v)));
    return std::min(1.0, 2 * std::min(tails.lower, tails.upper));
  }
  const double nn = double(n);
  const double sigma = std::sqrt(nn * (nn + 1) * (2 * nn + 1) / 24 - tie_term / 48);
  double z = v - nn * (nn + 1) / 4;
  z = (z - (z > 0 ? 0.5 : z < 0 ? -0.5 : 0.0)) / sigma;
  return std::min(1.0, std::erfc(std::abs(z) / std::numbers::sqrt2));
}

double chi2_cdf(double x, double df) {
  if (std::isnan(x) || !(df > 0)) return nan;
  return incomplete_gamma(df / 2, x / 2).lower;
}

double chi2_quantile(double p, double df) {
  if (std::isnan(p) || !(df > 0)) return nan;
  if (p <= 0) return 0;
  if (p >= 1) return inf;
  // Each side solved on its own tail, where the small probability is exact.
  const double start = std::max(df, 1.0);
  if (p <= 0.5) return solve_increasing([&](double x) { return chi2_cdf(x, df) < p; }, start);
  const double q = 1 - p;
  return solve_increasing([&](double x) { return chi2_upper(x, df) > q; }, start);
}

double student_t_cdf(double x, double df) {
  if (std::isnan(x) || !(df > 0)) return nan;
  return x >= 0 ? 1 - student_t_upper(x, df) : student_t_upper(-x, df);
}

double student_t_quantile(double p, double df) {
  if (std::isnan(p) || !(df > 0)) return nan;
  if (p <= 0) return -inf;
  if (p >= 1) return inf;
  if (p == 0.5) return 0;
  // Symmetric: solve on the upper tail, where the small probability is exact.
  const double q = p < 0.5 ? p : 1 - p;
  const double x = solve_increasing([&](double t) { return student_t_upper(t, df) > q; }, 1.0);
  return p < 0.5 ? -x : x;
}

double median(std::span<const double> v) {
  std::vector<double> w(v.begin(), v.end());
  return median_in_place(w);
}

Interval bootstrap_median_interval(std::span<const double> v, double level, int resamples, std::uint64_t seed) {
  if (v.empty()) return {nan, nan};
  const std::size_t count = std::size_t(std::max(resamples, 1));
  std::uint64_t state = seed;
  std::vector<double> sample(v.size()), medians(count);
  for (double& m : medians) {
    for (double& x : sample) x = v[mul_high(splitmix64(state), v.size())];
    m = median_in_place(sample);
  }
  std::sort(medians.begin(), medians.end(), before);
  const double alpha = std::clamp(1 - level, 0.0, 1.0), r = double(count);
  // The slack keeps a product that is an integer on paper (1000 * 0.025) from
  // moving to the next order statistic by a rounding error.
  const std::size_t lo = std::min(count - 1, std::size_t(std::floor(r * alpha / 2 + 1e-9)));
  const std::size_t hi = std::clamp(std::size_t(std::ceil(r * (1 - alpha / 2) - 1e-9)), std::size_t(1), count) - 1;
  return {medians[std::min(lo, hi)], medians[hi]};
}

}  // namespace chaosweep

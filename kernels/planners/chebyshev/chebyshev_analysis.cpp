#include "kernels/planners/chebyshev/chebyshev_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "kernels/core/param_table.hpp"

namespace chaosweep {

namespace {

constexpr double pi = std::numbers::pi;

std::string num(double v) { return format_number(v); }

void check_args(const char* who, int k, double x0, long n) {
  if (k < 2) throw std::invalid_argument(std::string(who) + ": k must be >= 2, got " + std::to_string(k));
  if (n < 1) throw std::invalid_argument(std::string(who) + ": n must be >= 1, got " + std::to_string(n));
  if (!(x0 >= -1.0 && x0 <= 1.0))
    throw std::invalid_argument(std::string(who) + ": the initial value must be in [-1, 1], got " + num(x0));
}

// sqrt(1 - x^2) as sqrt((1 - x)(1 + x)): 1 - x is exact near x = 1, so the
// derivatives keep their relative accuracy where the orbit is densest.
double root_one_minus_sq(double x) { return std::sqrt((1.0 - x) * (1.0 + x)); }

// The next sample of `step`'s orbit; throws when it equals the current one,
// i.e. the double orbit sits on a fixed point and would repeat it forever.
template <class Step>
double advance(const char* who, Step step, double x, long i) {
  const double next = step(x);
  if (next == x)
    throw std::domain_error(std::string(who) + ": the orbit collapsed onto the fixed point x = " + num(x) +
                            " at step " + std::to_string(i) + " (floating point); try another initial value");
  return next;
}

// Mean of log_abs_deriv(x_i) over i = burn_in .. burn_in + n - 1 of the orbit
// x_{i+1} = step(x_i), with the guards the header describes.
template <class Step, class LogAbsDeriv>
double mean_log_derivative(const char* who, int k, double x0, long n, long burn_in, Step step,
                           LogAbsDeriv log_abs_deriv) {
  check_args(who, k, x0, n);
  if (burn_in < 0) throw std::invalid_argument(std::string(who) + ": burn_in must be >= 0");
  double x = x0, sum = 0.0;
  const long total = burn_in + n;
  for (long i = 0; i < total; ++i) {
    if (std::abs(x) == 1.0)
      throw std::domain_error(
          std::string(who) + ": the orbit hit x = " + num(x) + " at step " + std::to_string(i) +
          ", where f' is 0/0 and x = 1 is a fixed point (floating point); try another initial value");
    if (i >= burn_in) {
      const double l = log_abs_deriv(x);
      if (!std::isfinite(l))
        throw std::domain_error(std::string(who) + ": ln|derivative| is not finite at x = " + num(x) + ", step " +
                                std::to_string(i));
      sum += l;
    }
    if (i + 1 < total) x = advance(who, step, x, i);
  }
  return sum / static_cast<double>(n);
}

}  // namespace

double lyapunov_exponent(int k, double x0, long n, long burn_in) {
  auto step = [k](double x) { return chebyshev_step(x, k); };
  auto log_fprime = [k](double x) { return std::log(std::abs(k * std::sin(k * std::acos(x)) / root_one_minus_sq(x))); };
  return mean_log_derivative("lyapunov_exponent", k, x0, n, burn_in, step, log_fprime);
}

double lyapunov_exponent_arcsine(int k, double x0, long n, long burn_in) {
  auto step = [k](double x) { return chebyshev_step(x, k); };
  // g'(u) = T'(f(x)) f'(x) dx/du at x = T^-1(u) = sin(pi u / 2), each factor
  // from its own argument rather than simplified to k.
  auto log_gprime = [k](double x) {
    const double u = cheb_transform(x, ChebTransform::arcsine);
    const double xr = std::sin(pi / 2 * u);
    const double y = chebyshev_step(xr, k);
    const double dT_dy = 2.0 / pi / root_one_minus_sq(y);
    const double df_dx = k * std::sin(k * std::acos(xr)) / root_one_minus_sq(xr);
    const double dx_du = pi / 2 * std::cos(pi / 2 * u);
    return std::log(std::abs(dT_dy * df_dx * dx_du));
  };
  return mean_log_derivative("lyapunov_exponent_arcsine", k, x0, n, burn_in, step, log_gprime);
}

namespace {

// |Eq. 7| as printed: 2k sin(k acos x) / (pi sqrt(1 - cos^2(k acos x)) sqrt(1 - x^2)).
double log_abs_eq7(int k, double x) {
  const double a = k * std::acos(x);
  return std::log(std::abs(2.0 * k * std::sin(a) / (pi * root_one_minus_sq(std::cos(a)) * root_one_minus_sq(x))));
}

}  // namespace

double lyapunov_paper_eq7(int k, double x0, long n, long burn_in) {
  auto step = [k](double x) { return chebyshev_step(x, k); };
  return mean_log_derivative("lyapunov_paper_eq7", k, x0, n, burn_in, step,
                             [k](double x) { return log_abs_eq7(k, x); });
}

double lyapunov_paper_eq7_on_eq9(int k, double x0, long n, long burn_in) {
  auto step = [k](double x) { return cheb_transform(chebyshev_step(x, k), ChebTransform::arcsine); };
  return mean_log_derivative("lyapunov_paper_eq7_on_eq9", k, x0, n, burn_in, step,
                             [k](double x) { return log_abs_eq7(k, x); });
}

double variable_difference(int k, double x1, double y1, long n, ChebTransform t) {
  const char* who = "variable_difference";
  check_args(who, k, x1, n);
  check_args(who, k, y1, n);
  auto step = [k](double x) { return chebyshev_step(x, k); };
  double x = x1, y = y1, sum = 0.0;
  for (long i = 0; i < n; ++i) {
    sum += std::abs(cheb_transform(x, t) - cheb_transform(y, t));
    if (i + 1 < n) {
      x = advance(who, step, x, i);
      y = advance(who, step, y, i);
    }
  }
  return sum / static_cast<double>(n);
}

std::vector<long> orbit_histogram(int k, double x0, long n, int bins, ChebTransform t) {
  const char* who = "orbit_histogram";
  check_args(who, k, x0, n);
  if (bins < 1) throw std::invalid_argument("orbit_histogram: bins must be >= 1");
  auto step = [k](double x) { return chebyshev_step(x, k); };
  const double lo = cheb_lo(t), width = cheb_hi(t) - lo;
  std::vector<long> counts(static_cast<std::size_t>(bins), 0);
  double x = x0;
  for (long i = 0; i < n; ++i) {
    const double b = std::floor((cheb_transform(x, t) - lo) / width * bins);
    const long j = std::clamp(static_cast<long>(b), 0L, static_cast<long>(bins - 1));
    ++counts[static_cast<std::size_t>(j)];
    if (i + 1 < n) x = advance(who, step, x, i);
  }
  return counts;
}

namespace {

double total_of(const char* who, const std::vector<long>& counts) {
  double total = 0.0;
  for (long c : counts) total += static_cast<double>(c);
  if (counts.empty() || total <= 0.0) throw std::invalid_argument(std::string(who) + ": no counts");
  return total;
}

}  // namespace

double chi_square_uniform(const std::vector<long>& counts) {
  const double e = total_of("chi_square_uniform", counts) / static_cast<double>(counts.size());
  double s = 0.0;
  for (long c : counts) s += (c - e) * (c - e) / e;
  return s;
}

double chi_square_arcsine(const std::vector<long>& counts) {
  const double total = total_of("chi_square_arcsine", counts);
  const double bins = static_cast<double>(counts.size());
  auto cdf = [](double x) { return 0.5 + std::asin(std::clamp(x, -1.0, 1.0)) / pi; };
  double s = 0.0;
  for (std::size_t j = 0; j < counts.size(); ++j) {
    const double e = total * (cdf(-1.0 + 2.0 * (j + 1) / bins) - cdf(-1.0 + 2.0 * j / bins));
    s += (counts[j] - e) * (counts[j] - e) / e;
  }
  return s;
}

}  // namespace chaosweep

#include "analysis/papers/chebyshev_paper.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "kernels/planners/chebyshev/chebyshev_analysis.hpp"

namespace chaosweep {

TextTable seed001_table() {
  constexpr int k = 6;
  constexpr double x0 = 0.1, y0 = 0.2;
  constexpr long n_lyap = 1'000'000;
  constexpr double pi = std::numbers::pi;

  TextTable t;
  t.title = "Seed 001: the Chebyshev map (k = 6), paper vs ours";
  t.header = {"quantity", "n", "ours", "paper", "note"};
  const std::string nl = std::to_string(n_lyap);
  t.add_row({"Lyapunov exponent, raw map", nl, fixed_cell(lyapunov_exponent(k, x0, n_lyap), 4), "1.7918",
             "ln 6 = " + fmt_fixed(std::log(6.0), 4)});
  t.add_row({"Lyapunov exponent, after arcsine transform", nl, fixed_cell(lyapunov_exponent_arcsine(k, x0, n_lyap), 4),
             "3.2147", "conjugate map g = T f T^-1: |g'| = 6, so ln 6"});
  t.add_row({"Eq. 7 as printed, along the raw orbit", nl, fixed_cell(lyapunov_paper_eq7(k, x0, n_lyap), 4), "3.2147",
             "-> ln(4k/pi) = " + fmt_fixed(std::log(4 * k / pi), 4)});
  t.add_row({"Eq. 7 as printed, along the Eq. 9 orbit", nl, fixed_cell(lyapunov_paper_eq7_on_eq9(k, x0, n_lyap), 4),
             "3.2147", "Eq. 9 iterated as a map; Eq. 7 is its derivative"});

  struct Method {
    const char* name;
    ChebTransform t;
    const char* paper[2];
    const char* note;
  };
  const Method methods[] = {
      {"v(xy), original map", ChebTransform::none, {"0.8309", "0.8209"}, "limit 8/pi^2 = 0.8106"},
      {"v(xy), arcsine transform", ChebTransform::arcsine, {"0.6830", "0.6758"}, "limit 2/3 = 0.6667"},
      {"v(xy), arccosine transform",
       ChebTransform::arccosine,
       {"0.6830", "0.6758"},
       "= arcsine: (2/pi) acos x = 1 - (2/pi) asin x"},
  };
  const long ns[] = {2000, 10000};
  for (const Method& m : methods)
    for (int i = 0; i < 2; ++i)
      t.add_row({m.name, std::to_string(ns[i]), fixed_cell(variable_difference(k, x0, y0, ns[i], m.t), 4), m.paper[i],
                 m.note});

  t.notes.push_back(
      "Lyapunov exponents: x0 = 0.1, 1000 steps of burn-in. 1.7918 = ln 6 is right for both the raw map and the "
      "arcsine-transformed one: T(x) = (2/pi) asin x is a smooth conjugacy on (-1, 1), and a conjugacy leaves the "
      "exponent unchanged (the transformed map is a zigzag of slope +-6 exactly). The paper's 3.2147 is not "
      "reproduced by any reading of its Eq. 7 we tried: that formula is d(T o f)/dx, which lacks the factor dx/du = "
      "(pi/2) sqrt(1 - x^2); averaged along the raw orbit it tends to ln(2k/pi) + ln 2 = ln(4k/pi) = 2.0333, along "
      "the orbit of Eq. 9 iterated as a map it gives about 1.64. (Dropping the pi gives ln 24 = 3.178, still not "
      "3.2147.)");
  t.notes.push_back(
      "v(xy) = mean of |x_i - y_i|, i = 1..n, x1 = 0.1 and y1 = 0.2 counted as the first samples. Rounding makes "
      "any two implementations' orbits unrelated after about 20 steps (6^20 ~ 4e15), so finite-n values agree "
      "only statistically: one standard error is 0.013 / 0.006 (original, n = 2000 / 10000) and 0.011 / 0.005 "
      "(transformed), and the paper's values lie 1.6-2 of them above the limits 8/pi^2 and 2/3 for independent "
      "samples, ours within 1.7. The transforms lower v(xy) because a uniform law has a smaller mean gap than the "
      "arcsine law (2/3 < 8/pi^2), not because the orbit is more random; the decrease from n = 2000 to 10000 is "
      "sampling noise about the limit.");
  return t;
}

}  // namespace chaosweep

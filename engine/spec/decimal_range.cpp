#include "engine/spec/decimal_range.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace chaosweep {

namespace {

using i128 = decimal_int;

// Bounds that keep every product below 2^127 (about 1.7e38): scaled values
// of a step range under 1e36 (so stop - start fits), of a count range under
// 1e28 (times num - 1 < 1e8). Past 1e-40 the long division below would need
// more than its 100 digits to be sure of its rounding.
constexpr double step_limit = 1e36, count_limit = 1e28;
constexpr int finest_exponent = -40;

// v = mantissa * 10^exponent, with the shortest digits that round-trip v.
struct Decimal {
  std::int64_t mantissa;
  int exponent;
};

Decimal shortest_decimal(double v) {  // v finite
  char buf[40];
  const auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific);
  const std::string s(buf, res.ptr);  // "-3.0000000000000004e-01", "5e-02"
  const std::size_t e = s.find('e');
  std::int64_t m = 0;
  int decimals = 0;
  bool after_point = false;
  for (std::size_t i = 0; i < e; ++i) {
    if (s[i] == '.') after_point = true;
    else if (s[i] >= '0' && s[i] <= '9') {
      m = m * 10 + (s[i] - '0');
      decimals += after_point;
    }
  }
  return {s[0] == '-' ? -m : m, std::stoi(s.substr(e + 1)) - decimals};
}

// m * 10^shift, or nothing when its magnitude reaches `limit`.
std::optional<i128> scaled(std::int64_t m, int shift, double limit) {
  i128 v = m;
  for (int i = 0; i < shift; ++i) {
    v *= 10;
    if (double(v < 0 ? -v : v) >= limit) return std::nullopt;
  }
  if (double(v < 0 ? -v : v) >= limit) return std::nullopt;
  return v;
}

std::string digits_of(i128 v) {  // v >= 0
  std::string s;
  do {
    s += char('0' + int(v % 10));
    v /= 10;
  } while (v > 0);
  std::reverse(s.begin(), s.end());
  return s;
}

// The double nearest the text "[-]DIGITSeEXP" (std::from_chars rounds
// correctly, however many digits).
double parse_decimal(bool negative, const std::string& digits, int exponent) {
  const std::string text = (negative ? "-" : "") + digits + "e" + std::to_string(exponent);
  double v = 0;
  const auto res = std::from_chars(text.data(), text.data() + text.size(), v);
  if (res.ec != std::errc() || res.ptr != text.data() + text.size())
    throw std::logic_error("decimal range: cannot read back " + text);
  return v;
}

// The double nearest n / d * 10^exponent (d > 0). When the quotient does not
// terminate, 100 significant digits and a sticky final 1 (the digits go on)
// decide the rounding exactly: a halfway point between two doubles is
// M / 2^J with M < 2^54, so it differs from n / (d 10^-exponent) by at least
// 1 / (d 10^-exponent 2^J), which within the bounds above (d < 1e8,
// exponent >= -40) is more than 1e-65 of the value; the digits cut at 1e-99.
double nearest_quotient(i128 n, i128 d, int exponent) {
  const bool negative = n < 0;
  if (negative) n = -n;
  const i128 whole = n / d;
  i128 rest = n % d;
  std::string digits = whole > 0 ? digits_of(whole) : "";
  int significant = int(digits.size()), fraction = 0;
  while (rest != 0 && significant < 100) {
    rest *= 10;
    const int digit = int(rest / d);
    rest %= d;
    if (significant > 0 || digit != 0) {
      digits += char('0' + digit);
      ++significant;
    }
    ++fraction;
  }
  if (rest != 0) {
    digits += '1';
    ++fraction;
  }
  if (digits.empty()) digits.push_back('0');
  return parse_decimal(negative, digits, exponent - fraction);
}

}  // namespace

DecimalRange DecimalRange::by_step(double start, double stop, double step) {
  DecimalRange r;
  r.start_ = start, r.stop_ = stop, r.step_ = step;
  // The fallback's count: stop is included when it lies on the grid to 1e-9
  // of a step. (NaN or inf: the caller reports the values or the count.)
  r.count_ = std::floor((stop - start) / step + 1e-9) + 1;
  if (!(std::isfinite(start) && std::isfinite(stop) && std::isfinite(step))) return r;
  const Decimal a = shortest_decimal(start), b = shortest_decimal(stop), c = shortest_decimal(step);
  r.exponent_ = std::min({a.exponent, b.exponent, c.exponent});
  const auto s = scaled(a.mantissa, a.exponent - r.exponent_, step_limit);
  const auto t = scaled(b.mantissa, b.exponent - r.exponent_, step_limit);
  const auto p = scaled(c.mantissa, c.exponent - r.exponent_, step_limit);
  r.exact_ = s && t && p && *p != 0 && r.exponent_ >= finest_exponent;
  if (r.exact_) {
    r.s_ = *s, r.t_ = *t, r.p_ = *p;
    // (t - s) / p >= 0 (the caller checked the direction); integer division
    // truncates, which is the floor here.
    r.count_ = double((r.t_ - r.s_) / r.p_) + 1;
  }
  return r;
}

DecimalRange DecimalRange::by_count(double start, double stop, std::int64_t num) {
  DecimalRange r;
  r.by_count_ = true;
  r.start_ = start, r.stop_ = stop, r.count_ = double(num);
  if (!(std::isfinite(start) && std::isfinite(stop))) return r;  // the values carry the NaN or inf
  const Decimal a = shortest_decimal(start), b = shortest_decimal(stop);
  r.exponent_ = std::min(a.exponent, b.exponent);
  const auto s = scaled(a.mantissa, a.exponent - r.exponent_, count_limit);
  const auto t = scaled(b.mantissa, b.exponent - r.exponent_, count_limit);
  r.exact_ = s && t && r.exponent_ >= finest_exponent;
  if (r.exact_) r.s_ = *s, r.t_ = *t;
  return r;
}

double DecimalRange::at(std::int64_t k) const {
  if (by_count_) {
    const auto n = std::int64_t(count_);
    if (k == 0) return start_;  // the ends as written, even -0.0
    if (k == n - 1) return stop_;
    if (!exact_) return start_ + (stop_ - start_) * double(k) / double(n - 1);
    const i128 d = n - 1;
    return nearest_quotient(s_ * d + (t_ - s_) * k, d, exponent_);
  }
  if (k == 0) return start_;
  if (!exact_) return start_ + double(k) * step_;
  const i128 v = s_ + p_ * k;
  return parse_decimal(v < 0, digits_of(v < 0 ? -v : v), exponent_);
}

std::vector<double> DecimalRange::values() const {
  std::vector<double> out;
  out.reserve(std::size_t(count_));
  for (std::int64_t k = 0; k < std::int64_t(count_); ++k) out.push_back(at(k));
  return out;
}

}  // namespace chaosweep

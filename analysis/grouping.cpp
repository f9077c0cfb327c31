#include "analysis/grouping.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace chaosweep {

std::vector<Group> group_rows(const ResultSet& rs, const std::vector<std::string>& keys,
                              const std::vector<std::size_t>& rows) {
  for (const std::string& k : keys)
    if (!rs.has(k)) (void)rs.num(k);  // throws, naming the column
  // Ordering key: per column, a number or a string (in natural order).
  using Part = std::pair<double, std::string>;
  auto less = [](const std::vector<Part>& a, const std::vector<Part>& b) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].first != b[i].first) return a[i].first < b[i].first;
      if (natural_less(a[i].second, b[i].second)) return true;
      if (natural_less(b[i].second, a[i].second)) return false;
    }
    return false;
  };
  std::map<std::vector<Part>, Group, decltype(less)> by(less);
  for (std::size_t r : rows) {
    std::vector<Part> order;
    for (const std::string& k : keys) {
      if (rs.is_numeric(k)) order.emplace_back(rs.num(k)[r], "");
      else order.emplace_back(0.0, rs.text(k)[r]);
    }
    auto [it, fresh] = by.try_emplace(std::move(order));
    Group& g = it->second;
    if (fresh) {
      for (const std::string& k : keys) {
        g.key.push_back(rs.cell(k, r));
        g.key_num.push_back(rs.is_numeric(k) ? rs.num(k)[r] : std::numeric_limits<double>::quiet_NaN());
      }
    }
    g.rows.push_back(r);
  }
  std::vector<Group> out;
  for (auto& [k, g] : by) out.push_back(std::move(g));
  return out;
}

bool natural_less(const std::string& a, const std::string& b) {
  auto digit = [](char c) { return c >= '0' && c <= '9'; };
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (digit(a[i]) && digit(b[j])) {
      // Compare the digit runs as numbers: without leading zeros, the
      // shorter is smaller, then digit by digit.
      std::size_t ie = i, je = j;
      while (ie < a.size() && digit(a[ie])) ++ie;
      while (je < b.size() && digit(b[je])) ++je;
      std::size_t i0 = i, j0 = j;
      while (i0 + 1 < ie && a[i0] == '0') ++i0;
      while (j0 + 1 < je && b[j0] == '0') ++j0;
      if (ie - i0 != je - j0) return ie - i0 < je - j0;
      const int c = a.compare(i0, ie - i0, b, j0, je - j0);
      if (c != 0) return c < 0;
      i = ie, j = je;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i, ++j;
    }
  }
  if ((a.size() - i) != (b.size() - j)) return a.size() - i < b.size() - j;
  return a < b;  // equal but for leading zeros: a fixed order
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const double pos = q * double(v.size() - 1);
  const auto lo = std::size_t(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - double(lo)) * (v[hi] - v[lo]);
}

const std::vector<std::string>& statistic_names() {
  static const std::vector<std::string> names{"min", "q1", "median", "mean", "q3", "max", "ok_rate", "runs"};
  return names;
}

double group_statistic(const ResultSet& rs, const std::vector<std::size_t>& rows, const std::string& stat,
                       const std::string& column) {
  if (stat == "runs") return double(rows.size());
  const std::vector<std::size_t> ok = ok_rows(rs, rows);
  if (stat == "ok_rate")
    return rows.empty() ? std::numeric_limits<double>::quiet_NaN() : double(ok.size()) / double(rows.size());
  std::vector<double> v;
  for (std::size_t r : ok) v.push_back(rs.num(column)[r]);
  try {
    return value_statistic(std::move(v), stat);
  } catch (const AnalysisError&) {
    std::string list;
    for (const std::string& n : statistic_names()) list += (list.empty() ? "" : ", ") + n;
    throw AnalysisError("unknown statistic '" + stat + "' (allowed: " + list + ")");
  }
}

double value_statistic(std::vector<double> v, const std::string& stat) {
  if (stat == "min") return quantile(std::move(v), 0.0);
  if (stat == "q1") return quantile(std::move(v), 0.25);
  if (stat == "median") return quantile(std::move(v), 0.5);
  if (stat == "q3") return quantile(std::move(v), 0.75);
  if (stat == "max") return quantile(std::move(v), 1.0);
  if (stat == "mean") {
    if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
    double s = 0;
    for (double x : v) s += x;
    return s / double(v.size());
  }
  throw AnalysisError("unknown statistic '" + stat + "' (allowed: min, q1, median, mean, q3, max)");
}

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::size_t b = 0;
  while (b <= s.size()) {
    const std::size_t e = std::min(s.find(',', b), s.size());
    std::string item = s.substr(b, e - b);
    while (!item.empty() && item.front() == ' ') item.erase(item.begin());
    while (!item.empty() && item.back() == ' ') item.pop_back();
    if (!item.empty()) out.push_back(item);
    b = e + 1;
  }
  return out;
}

}  // namespace chaosweep

#include "analysis/grouping.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string_view>
#include <unordered_map>

namespace chaosweep {

namespace {

// Per row of `rows`, the rank of its value of `key` among the values it
// takes (numbers by value, text in natural order; NaN after every number).
std::vector<std::uint32_t> ranks(const ResultSet& rs, const std::string& key, const std::vector<std::size_t>& rows,
                                 std::uint32_t& distinct) {
  std::vector<std::uint32_t> out(rows.size());
  if (rs.is_numeric(key)) {
    const auto& col = rs.num(key);
    std::vector<double> values;
    values.reserve(rows.size());
    bool nan = false;
    for (std::size_t r : rows) {
      if (std::isnan(col[r])) nan = true;
      else values.push_back(col[r]);
    }
    std::sort(values.begin(), values.end());
    values.erase(std::unique(values.begin(), values.end()), values.end());  // -0 and 0 are one value
    distinct = std::uint32_t(values.size() + nan);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const double v = col[rows[k]];
      out[k] = std::isnan(v) ? std::uint32_t(values.size())
                             : std::uint32_t(std::lower_bound(values.begin(), values.end(), v) - values.begin());
    }
    return out;
  }
  const auto& col = rs.text(key);
  std::unordered_map<std::string_view, std::uint32_t> code;
  for (std::size_t r : rows) code.try_emplace(col[r], 0);
  std::vector<std::string_view> values;
  for (const auto& [v, c] : code) values.push_back(v);
  std::sort(values.begin(), values.end(), natural_less);  // "a2" before "a12"
  for (std::size_t k = 0; k < values.size(); ++k) code[values[k]] = std::uint32_t(k);
  distinct = std::uint32_t(values.size());
  for (std::size_t k = 0; k < rows.size(); ++k) out[k] = code[col[rows[k]]];
  return out;
}

}  // namespace

std::vector<std::size_t> RowSpans::rows_of(std::size_t g, const std::vector<std::size_t>& rows) const {
  std::vector<std::size_t> out;
  for (std::size_t k = start[g]; k < start[g + 1]; ++k) out.push_back(rows[order[k]]);
  return out;
}

RowSpans group_spans(const ResultSet& rs, const std::vector<std::string>& keys, const std::vector<std::size_t>& rows) {
  for (const std::string& k : keys)
    if (!rs.has(k)) (void)rs.num(k);  // throws, naming the column
  // Sorted by the keys' ranks, rows of one key in their order (stable).
  std::vector<std::vector<std::uint32_t>> rank;
  for (const std::string& k : keys) {
    std::uint32_t distinct = 0;
    rank.push_back(ranks(rs, k, rows, distinct));
  }
  RowSpans s;
  s.order.resize(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) s.order[k] = k;
  auto less = [&](std::size_t x, std::size_t y) {
    for (const auto& r : rank)
      if (r[x] != r[y]) return r[x] < r[y];
    return false;
  };
  std::stable_sort(s.order.begin(), s.order.end(), less);
  for (std::size_t k = 0; k < s.order.size(); ++k)
    if (k == 0 || less(s.order[k - 1], s.order[k])) s.start.push_back(k);
  s.start.push_back(s.order.size());
  if (rows.empty()) s.start = {0};
  return s;
}

std::vector<Group> group_rows(const ResultSet& rs, const std::vector<std::string>& keys,
                              const std::vector<std::size_t>& rows) {
  const RowSpans s = group_spans(rs, keys, rows);
  std::vector<Group> out(s.groups());
  for (std::size_t g = 0; g < s.groups(); ++g) {
    Group& grp = out[g];
    grp.rows = s.rows_of(g, rows);
    const std::size_t r = grp.rows[0];  // the key as its first row has it
    for (const std::string& k : keys) {
      grp.key.push_back(rs.cell(k, r));
      grp.key_num.push_back(rs.is_numeric(k) ? rs.num(k)[r] : std::numeric_limits<double>::quiet_NaN());
    }
  }
  return out;
}

bool natural_less(std::string_view a, std::string_view b) {
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

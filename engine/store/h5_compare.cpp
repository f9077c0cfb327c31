#include "engine/store/h5_compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <stdexcept>

#include "engine/rows/result_columns.hpp"
#include "engine/store/h5_store.hpp"
#include "kernels/core/param_table.hpp"

namespace chaosweep {

namespace {

// One file's columns, read once.
struct Table {
  std::vector<std::int64_t> run_id, param_hash;
  std::map<std::string, std::vector<double>> f64;
  std::map<std::string, std::vector<std::int64_t>> i64;
  std::map<std::string, std::vector<std::string>> text;

  std::set<std::string> names;

  explicit Table(const std::string& path) {
    check_result_columns(path);                    // run_id and param_hash integers, among others
    TypedColumns file = read_typed_columns(path);  // one pass over the file
    for (const std::string& n : column_names(path)) names.insert(n);
    run_id = file.i64.at("run_id");
    param_hash = file.i64.at("param_hash");
    // Each of this engine's deterministic columns, as this engine types it.
    for (const Column& c : result_columns()) {
      if (!c.deterministic || !names.count(c.name)) continue;
      auto ints = file.i64.find(c.name);
      auto reals = file.f64.find(c.name);
      if (c.type == Column::Type::f64 && reals != file.f64.end()) {
        f64[c.name] = std::move(reals->second);
      } else if (c.type == Column::Type::f64 && ints != file.i64.end()) {
        f64[c.name].assign(ints->second.begin(), ints->second.end());
      } else if (c.type == Column::Type::i64 && ints != file.i64.end()) {
        i64[c.name] = std::move(ints->second);
      } else if (c.type == Column::Type::i64 && reals != file.f64.end()) {
        for (double v : reals->second) i64[c.name].push_back(std::int64_t(v));
      } else if (c.type == Column::Type::text && file.text.count(c.name)) {
        text[c.name] = std::move(file.text[c.name]);
      } else {
        throw std::runtime_error(path + ": column '" + c.name + "' is of another kind than this engine's");
      }
    }
  }
  std::string group_key(std::size_t i) const {
    return text.at("variant")[i] + " " + text.at("env")[i] + " " + format_number(f64.at("size_x")[i]) + "x" +
           format_number(f64.at("size_y")[i]) + " m sr " + format_number(f64.at("sr")[i]);
  }
};

std::string num(double v) { return format_number(v); }

void refuse_repeated_run_ids(std::vector<std::int64_t> ids, const std::string& path) {
  std::sort(ids.begin(), ids.end());
  const auto twice = std::adjacent_find(ids.begin(), ids.end());
  if (twice != ids.end())
    throw std::runtime_error(path + " holds run_id " + std::to_string(*twice) +
                             " more than once: a result file holds each run once (the file is damaged or hand-made)");
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

}  // namespace

double mann_whitney_p(const std::vector<double>& x, const std::vector<double>& y) {
  const double n1 = double(x.size()), n2 = double(y.size());
  if (x.empty() || y.empty()) return NAN;
  std::vector<std::pair<double, int>> all;
  for (double v : x) all.push_back({v, 0});
  for (double v : y) all.push_back({v, 1});
  std::sort(all.begin(), all.end());
  double rank_sum_x = 0, tie_term = 0;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i;
    while (j < all.size() && all[j].first == all[i].first) ++j;
    const double avg_rank = 0.5 * double(i + 1 + j);  // ranks i+1 .. j
    const double t = double(j - i);
    tie_term += t * t * t - t;
    for (std::size_t k = i; k < j; ++k)
      if (all[k].second == 0) rank_sum_x += avg_rank;
    i = j;
  }
  const double u = rank_sum_x - n1 * (n1 + 1) / 2;
  const double n = n1 + n2;
  const double var = n1 * n2 / 12.0 * ((n + 1) - tie_term / (n * (n - 1)));
  if (var <= 0) return 1.0;
  const double z = (std::fabs(u - n1 * n2 / 2) - 0.5) / std::sqrt(var);  // continuity correction
  return std::min(1.0, std::erfc(std::max(z, 0.0) / std::sqrt(2.0)));
}

CompareReport compare_results(const std::string& a_path, const std::string& b_path, const CompareOptions& opt) {
  CompareReport rep;
  const Table a(a_path), b(b_path);
  rep.by_run_id = read_attribute(a_path, "spec_hash") == read_attribute(b_path, "spec_hash");
  for (const std::string& n : a.names)
    if (!b.names.count(n)) rep.schema.push_back("column '" + n + "' only in A");
  for (const std::string& n : b.names)
    if (!a.names.count(n)) rep.schema.push_back("column '" + n + "' only in B");
  const auto& ka = rep.by_run_id ? a.run_id : a.param_hash;
  const auto& kb = rep.by_run_id ? b.run_id : b.param_hash;
  // A run_id names one run of a spec: a file holding one twice is damaged.
  // Equal parameters may recur in a spec: the k-th such run of A meets the
  // k-th of B, so every row is counted once either way round.
  if (rep.by_run_id) {
    refuse_repeated_run_ids(a.run_id, a_path);
    refuse_repeated_run_ids(b.run_id, b_path);
  }
  std::map<std::int64_t, std::vector<std::size_t>> index_b;
  for (std::size_t j = 0; j < kb.size(); ++j) index_b[kb[j]].push_back(j);
  std::map<std::int64_t, std::size_t> taken;  // rows of B already aligned, per key
  std::vector<bool> used_b(kb.size(), false);
  auto note = [&](const std::string& s) {
    if (int(rep.details.size()) < opt.show) rep.details.push_back(s);
  };
  for (std::size_t i = 0; i < ka.size(); ++i) {
    const auto it = index_b.find(ka[i]);
    std::size_t& next = taken[ka[i]];
    if (it == index_b.end() || next == it->second.size()) {
      ++rep.missing;
      note("run_id " + std::to_string(a.run_id[i]) + ": only in A");
      continue;
    }
    const std::size_t j = it->second[next++];
    used_b[j] = true;
    ++rep.aligned;
    bool same = true;
    const std::string who =
        "run_id " + std::to_string(a.run_id[i]) + (rep.by_run_id ? "" : " (B: " + std::to_string(b.run_id[j]) + ")");
    for (const auto& [name, va] : a.f64) {
      const auto bi = b.f64.find(name);
      if (bi == b.f64.end()) continue;
      const double x = va[i], y = bi->second[j];
      const bool equal = (std::isnan(x) && std::isnan(y)) || std::fabs(x - y) <= opt.atol + opt.rtol * std::fabs(y);
      if (!equal) {
        same = false;
        note(who + ": " + name + " " + num(x) + " -> " + num(y));
      }
    }
    for (const auto& [name, va] : a.i64) {
      const auto bi = b.i64.find(name);
      if (bi == b.i64.end() || name == "run_id" || name == "param_hash") continue;
      if (va[i] != bi->second[j]) {
        same = false;
        note(who + ": " + name + " " + std::to_string(va[i]) + " -> " + std::to_string(bi->second[j]));
      }
    }
    for (const auto& [name, va] : a.text) {
      const auto bi = b.text.find(name);
      if (bi == b.text.end()) continue;
      if (va[i] != bi->second[j]) {
        same = false;
        note(who + ": " + name + " '" + va[i] + "' -> '" + bi->second[j] + "'");
      }
    }
    same ? ++rep.identical : ++rep.changed;
  }
  for (std::size_t j = 0; j < kb.size(); ++j)
    if (!used_b[j]) {
      ++rep.extra;
      note("run_id " + std::to_string(b.run_id[j]) + ": only in B");
    }
  // Distributions per group: chaotic runs of different specs or engine
  // versions agree in distribution, not run for run.
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> groups;
  for (std::size_t i = 0; i < a.run_id.size(); ++i)
    if (a.text.at("status")[i] == "ok") groups[a.group_key(i)].first.push_back(a.f64.at("coverage_time")[i]);
  for (std::size_t j = 0; j < b.run_id.size(); ++j)
    if (b.text.at("status")[j] == "ok") groups[b.group_key(j)].second.push_back(b.f64.at("coverage_time")[j]);
  for (const auto& [key, v] : groups)
    rep.groups.push_back({key, std::int64_t(v.first.size()), std::int64_t(v.second.size()), median(v.first),
                          median(v.second), mann_whitney_p(v.first, v.second)});
  return rep;
}

std::string CompareReport::text() const {
  std::string s = std::string("aligned on ") + (by_run_id ? "run_id (same spec)" : "parameters (param_hash)") + ": " +
                  std::to_string(aligned) + " runs, " + std::to_string(identical) + " identical, " +
                  std::to_string(changed) + " changed; " + std::to_string(missing) + " only in A, " +
                  std::to_string(extra) + " only in B\n";
  for (const std::string& d : schema) s += "  " + d + "\n";
  for (const std::string& d : details) s += "  " + d + "\n";
  s += "coverage time of ok runs per group (Mann-Whitney U):\n";
  for (const Group& g : groups) {
    char buf[160];  // the numbers; the key (of any length) goes in whole
    std::snprintf(buf, sizeof buf, " ok %lld / %lld, median %.6g / %.6g s, p = %.3g\n", (long long)g.ok_a,
                  (long long)g.ok_b, g.median_a, g.median_b, g.p_value);
    s += "  " + g.key + std::string(g.key.size() < 48 ? 48 - g.key.size() : 0, ' ') + buf;
  }
  return s;
}

}  // namespace chaosweep

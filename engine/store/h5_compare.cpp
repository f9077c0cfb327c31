#include "engine/store/h5_compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <tuple>
#include <unordered_set>

#include "engine/rows/result_columns.hpp"
#include "engine/store/column_blocks.hpp"
#include "engine/store/h5_store.hpp"
#include "kernels/core/param_table.hpp"

namespace chaosweep {

namespace {

std::string num(double v) { return format_number(v); }

std::string refused_twice(const std::string& path, std::int64_t id) {
  return path + " holds run_id " + std::to_string(id) +
         " more than once: a result file holds each run once (the file is damaged or hand-made)";
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// The columns compared: this engine's deterministic ones both files have,
// by this engine's kind, each kind in name order.
struct Compared {
  std::vector<std::string> f64, i64, text;
};

// Rows in columns (a block as read, or rows of B held for a pass), each
// column of this engine's kind.
struct Rows {
  std::vector<std::int64_t> run_id, param_hash;
  std::vector<std::vector<double>> f64;
  std::vector<std::vector<std::int64_t>> i64;
  std::vector<std::vector<std::string>> text;
  // For the groups: status, coverage_time and the group key's columns.
  std::vector<std::string> status, variant, env;
  std::vector<double> coverage_time, size_x, size_y, sr;
  std::size_t size() const { return run_id.size(); }
  void resize_like(const Compared& c) {
    f64.resize(c.f64.size());
    i64.resize(c.i64.size());
    text.resize(c.text.size());
  }
  void reserve(std::size_t n) {  // rows held for a pass: no doubling of every column
    run_id.reserve(n);
    param_hash.reserve(n);
    for (auto& v : f64) v.reserve(n);
    for (auto& v : i64) v.reserve(n);
    for (auto& v : text) v.reserve(n);
  }
  void clear() {
    for (auto* v : {&run_id, &param_hash}) v->clear();
    for (auto& v : f64) v.clear();
    for (auto& v : i64) v.clear();
    for (auto& v : text) v.clear();
    for (auto* v : {&status, &variant, &env}) v->clear();
    for (auto* v : {&coverage_time, &size_x, &size_y, &sr}) v->clear();
  }
  // Appends row r of `o` (the key columns and the compared ones).
  void push(const Rows& o, std::size_t r) {
    run_id.push_back(o.run_id[r]);
    param_hash.push_back(o.param_hash[r]);
    for (std::size_t k = 0; k < f64.size(); ++k) f64[k].push_back(o.f64[k][r]);
    for (std::size_t k = 0; k < i64.size(); ++k) i64[k].push_back(o.i64[k][r]);
    for (std::size_t k = 0; k < text.size(); ++k) text[k].push_back(o.text[k][r]);
  }
};

// Every column of `path` that compare reads must be of this engine's kind
// (integers where it has floats are taken as floats, and back).
void check_kinds(const std::string& path) {
  check_result_columns(path);  // run_id and param_hash integers, among others
  for (const auto& [name, type] : column_types(path)) {
    const Column* c = find_column(name);
    if (!c || !c->deterministic) continue;
    const bool numbers = c->type != Column::Type::text && type != Column::Type::text;
    if (!numbers && c->type != type)
      throw std::runtime_error(path + ": column '" + c->name + "' is of another kind than this engine's");
  }
}

// One file read block by block: its columns converted to this engine's kinds.
class Side {
 public:
  Side(const std::string& path, const Compared& compared, std::size_t block_rows)
      : path_(path), i64_names_(compared.i64), reader_(path, names(compared), block_rows) {
    block_.resize_like(compared);
    nf_ = compared.f64.size();
    ni_ = compared.i64.size();
    nt_ = compared.text.size();
  }
  std::size_t rows() const { return reader_.rows(); }
  // The next block into block(); false at the end.
  bool next() {
    block_.clear();
    if (!reader_.next()) return false;
    std::size_t c = 0;
    block_.run_id = reader_.i64(c++);
    block_.param_hash = reader_.i64(c++);
    for (std::size_t k = 0; k < nf_; ++k, ++c) block_.f64[k] = reader_.number(c);
    for (std::size_t k = 0; k < ni_; ++k, ++c) {
      if (reader_.type(c) == Column::Type::i64) {
        block_.i64[k] = reader_.i64(c);
      } else {
        // An integer column an older engine stored as numbers: a value no
        // int64 holds (NaN, inf, beyond 2^63) would make the cast undefined.
        for (double v : reader_.f64(c)) {
          if (!(std::fabs(v) < 9.2e18))
            throw std::runtime_error(path_ + ": column '" + i64_names_[k] + "' holds a value that is not an integer (" +
                                     std::to_string(v) + ")");
          block_.i64[k].push_back(std::int64_t(v));
        }
      }
    }
    for (std::size_t k = 0; k < nt_; ++k, ++c) block_.text[k] = reader_.text(c);
    block_.status = reader_.text(c++);
    block_.variant = reader_.text(c++);
    block_.env = reader_.text(c++);
    block_.coverage_time = reader_.number(c++);
    block_.size_x = reader_.number(c++);
    block_.size_y = reader_.number(c++);
    block_.sr = reader_.number(c++);
    return true;
  }
  std::size_t first() const { return reader_.first(); }
  const Rows& block() const { return block_; }

 private:
  static std::vector<std::string> names(const Compared& c) {
    std::vector<std::string> n{"run_id", "param_hash"};
    for (const auto* list : {&c.f64, &c.i64, &c.text}) n.insert(n.end(), list->begin(), list->end());
    for (const char* g : {"status", "variant", "env", "coverage_time", "size_x", "size_y", "sr"}) n.emplace_back(g);
    return n;
  }
  std::string path_;
  std::vector<std::string> i64_names_;
  ColumnBlockReader reader_;
  Rows block_;
  std::size_t nf_ = 0, ni_ = 0, nt_ = 0;
};

// The coverage times of ok runs per group, A's and B's. Consecutive rows
// mostly share a group, so its key is made once per run of equal rows.
class Groups {
 public:
  void add(const Rows& b, std::size_t r, int side) {
    if (b.status[r] != "ok") return;
    if (!last_ || b.variant[r] != variant_ || b.env[r] != env_ || !same(b.size_x[r], sx_) || !same(b.size_y[r], sy_) ||
        !same(b.sr[r], sr_)) {
      variant_ = b.variant[r];
      env_ = b.env[r];
      sx_ = b.size_x[r];
      sy_ = b.size_y[r];
      sr_ = b.sr[r];
      last_ = &groups_[variant_ + " " + env_ + " " + format_number(sx_) + "x" + format_number(sy_) + " m sr " +
                       format_number(sr_)];
    }
    (side == 0 ? last_->first : last_->second).push_back(b.coverage_time[r]);
  }
  void clear() {
    groups_.clear();
    last_ = nullptr;
  }
  void report(CompareReport& rep) const {
    for (const auto& [key, v] : groups_)
      rep.groups.push_back({key, std::int64_t(v.first.size()), std::int64_t(v.second.size()), median(v.first),
                            median(v.second), mann_whitney_p(v.first, v.second)});
  }

 private:
  static bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> groups_;
  std::pair<std::vector<double>, std::vector<double>>* last_ = nullptr;
  std::string variant_, env_;
  double sx_ = 0, sy_ = 0, sr_ = 0;
};

// The first `show` differences in the order a whole-file comparison meets
// them: A's rows in order (each row's columns in order), then B's extras.
class Notes {
 public:
  using Pos = std::tuple<int, std::size_t, std::size_t>;  // (0: A / 1: B, row, note of the row)
  explicit Notes(int show) : show_(std::size_t(std::max(show, 0))) {}
  bool wants(const Pos& p) const { return show_ > 0 && (kept_.size() < show_ || p < kept_.rbegin()->first); }
  void add(const Pos& p, std::string s) {
    if (!wants(p)) return;
    kept_.emplace(p, std::move(s));
    if (kept_.size() > show_) kept_.erase(std::prev(kept_.end()));
  }
  void clear() { kept_.clear(); }
  std::vector<std::string> list() const {
    std::vector<std::string> out;
    for (const auto& [p, s] : kept_) out.push_back(s);
    return out;
  }

 private:
  std::size_t show_;
  std::map<Pos, std::string> kept_;
};

// Compares row i of A (the i_row-th of the file) with row j of B.
class PairCompare {
 public:
  PairCompare(const Compared& c, const CompareOptions& opt, bool by_run_id, Notes& notes)
      : c_(c), opt_(opt), by_run_id_(by_run_id), notes_(notes) {}
  bool operator()(const Rows& a, std::size_t i, std::size_t i_row, const Rows& b, std::size_t j) const {
    bool same = true;
    std::size_t seq = 0;
    auto note = [&](auto&& text) {
      const Notes::Pos p{0, i_row, seq++};
      if (notes_.wants(p)) notes_.add(p, who(a, i, b, j) + text());
    };
    for (std::size_t k = 0; k < c_.f64.size(); ++k) {
      const double x = a.f64[k][i], y = b.f64[k][j];
      const bool equal = (std::isnan(x) && std::isnan(y)) || std::fabs(x - y) <= opt_.atol + opt_.rtol * std::fabs(y);
      if (!equal) {
        same = false;
        note([&] { return ": " + c_.f64[k] + " " + num(x) + " -> " + num(y); });
      }
    }
    for (std::size_t k = 0; k < c_.i64.size(); ++k) {
      const std::int64_t x = a.i64[k][i], y = b.i64[k][j];
      if (x != y) {
        same = false;
        note([&] { return ": " + c_.i64[k] + " " + std::to_string(x) + " -> " + std::to_string(y); });
      }
    }
    for (std::size_t k = 0; k < c_.text.size(); ++k) {
      const std::string &x = a.text[k][i], &y = b.text[k][j];
      if (x != y) {
        same = false;
        note([&] { return ": " + c_.text[k] + " '" + x + "' -> '" + y + "'"; });
      }
    }
    return same;
  }

 private:
  std::string who(const Rows& a, std::size_t i, const Rows& b, std::size_t j) const {
    return "run_id " + std::to_string(a.run_id[i]) + (by_run_id_ ? "" : " (B: " + std::to_string(b.run_id[j]) + ")");
  }
  const Compared& c_;
  const CompareOptions& opt_;
  bool by_run_id_;
  Notes& notes_;
};

struct Inputs {
  const std::string &a, &b;
  const Compared& compared;
  const CompareOptions& opt;
};

// Both files in run_id order (the sweep's and merge's): merged as they
// stream, block by block. False (the counts then meaningless) as soon as a
// file turns out not to be in order.
bool align_streaming(const Inputs& in, CompareReport& rep, Notes& notes, Groups& groups) {
  Side a(in.a, in.compared, in.opt.block_rows), b(in.b, in.compared, in.opt.block_rows);
  const PairCompare same(in.compared, in.opt, true, notes);
  rep.passes = 1;
  std::size_t i = 0, j = 0;  // within the blocks
  bool more_a = a.next(), more_b = b.next();
  bool any_a = false, any_b = false;
  std::int64_t last_a = 0, last_b = 0;
  auto at_a = [&]() -> bool {  // row i of A available and in order
    if (i == a.block().size()) {
      more_a = a.next();
      i = 0;
    }
    return more_a;
  };
  auto at_b = [&]() -> bool {
    if (j == b.block().size()) {
      more_b = b.next();
      j = 0;
    }
    return more_b;
  };
  while (true) {
    const bool has_a = at_a(), has_b = at_b();
    if (!has_a && !has_b) break;
    // Each row is checked for order once, when it is taken.
    const std::int64_t ida = has_a ? a.block().run_id[i] : 0, idb = has_b ? b.block().run_id[j] : 0;
    if (has_a && (!has_b || ida < idb)) {  // only in A
      if (any_a && ida <= last_a) return false;
      any_a = true;
      last_a = ida;
      groups.add(a.block(), i, 0);
      ++rep.missing;
      notes.add({0, a.first() + i, 0}, "run_id " + std::to_string(ida) + ": only in A");
      ++i;
    } else if (!has_a || idb < ida) {  // only in B
      if (any_b && idb <= last_b) return false;
      any_b = true;
      last_b = idb;
      groups.add(b.block(), j, 1);
      ++rep.extra;
      notes.add({1, b.first() + j, 0}, "run_id " + std::to_string(idb) + ": only in B");
      ++j;
    } else {
      if ((any_a && ida <= last_a) || (any_b && idb <= last_b)) return false;
      any_a = any_b = true;
      last_a = ida;
      last_b = idb;
      groups.add(a.block(), i, 0);
      groups.add(b.block(), j, 1);
      ++rep.aligned;
      same(a.block(), i, a.first() + i, b.block(), j) ? ++rep.identical : ++rep.changed;
      ++i;
      ++j;
    }
  }
  return true;
}

std::uint64_t mix(std::uint64_t x) {  // splitmix64's finaliser: keys spread evenly over the parts
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Any order: the keys split by their hash into parts, each aligned in one
// pass over both files holding only that part of B. Equal keys (parameters
// recurring) fall in one part, where the k-th of A meets the k-th of B as
// in a whole-file alignment.
void align_in_passes(const Inputs& in, CompareReport& rep, Notes& notes, Groups& groups, bool groups_done) {
  const std::size_t most = std::max(count_rows(in.a), count_rows(in.b));
  const std::size_t part = std::max<std::size_t>(in.opt.part_rows, 1);
  const std::size_t parts = std::max<std::size_t>(1, (most + part - 1) / part);
  const bool by_id = rep.by_run_id;
  const PairCompare same(in.compared, in.opt, by_id, notes);
  std::optional<std::int64_t> twice_a, twice_b;  // the least run_id held twice, by file
  auto least = [](std::optional<std::int64_t>& t, std::int64_t id) {
    if (!t || id < *t) t = id;
  };
  for (std::size_t p = 0; p < parts; ++p) {
    ++rep.passes;
    Rows held;  // B's rows of this part, in file order
    held.resize_like(in.compared);
    const std::size_t rows_b = std::size_t(count_rows(in.b));
    held.reserve(rows_b / parts + rows_b / parts / 8 + 1024);  // a part's share, with room for an uneven spread
    std::vector<std::size_t> held_row;                         // their rows in B
    Side b(in.b, in.compared, in.opt.block_rows);
    while (b.next()) {
      const Rows& blk = b.block();
      for (std::size_t r = 0; r < blk.size(); ++r) {
        if (!groups_done) groups.add(blk, r, 1);
        const std::int64_t key = by_id ? blk.run_id[r] : blk.param_hash[r];
        if (mix(std::uint64_t(key)) % parts != p) continue;
        held.push(blk, r);
        held_row.push_back(b.first() + r);
      }
    }
    rep.rows_held = std::max(rep.rows_held, std::int64_t(held.size()));
    // Held rows by (key, row): the rows of one key are consecutive, in file order.
    const auto& keys = by_id ? held.run_id : held.param_hash;
    std::vector<std::pair<std::int64_t, std::size_t>> order(held.size());
    for (std::size_t h = 0; h < held.size(); ++h) order[h] = {keys[h], h};
    std::sort(order.begin(), order.end());
    std::vector<std::uint32_t> taken(order.size(), 0);  // per key, at its first entry
    std::vector<bool> used(held.size(), false);
    if (by_id)
      for (std::size_t k = 1; k < order.size(); ++k)
        if (order[k].first == order[k - 1].first) least(twice_b, order[k].first);
    std::unordered_set<std::int64_t> seen_a;  // this part's run_ids of A (a run_id held twice is refused)
    Side a(in.a, in.compared, in.opt.block_rows);
    while (a.next()) {
      const Rows& blk = a.block();
      for (std::size_t r = 0; r < blk.size(); ++r) {
        if (!groups_done) groups.add(blk, r, 0);
        const std::int64_t key = by_id ? blk.run_id[r] : blk.param_hash[r];
        if (mix(std::uint64_t(key)) % parts != p) continue;
        if (by_id && !seen_a.insert(key).second) least(twice_a, key);
        const std::size_t row = a.first() + r;
        const auto it = std::lower_bound(order.begin(), order.end(), std::make_pair(key, std::size_t(0)));
        const std::size_t f = std::size_t(it - order.begin());
        const std::size_t k = f + (it != order.end() && it->first == key ? taken[f] : 0);
        if (it == order.end() || it->first != key || k >= order.size() || order[k].first != key) {
          ++rep.missing;
          notes.add({0, row, 0}, "run_id " + std::to_string(blk.run_id[r]) + ": only in A");
          continue;
        }
        ++taken[f];
        const std::size_t h = order[k].second;
        used[h] = true;
        ++rep.aligned;
        same(blk, r, row, held, h) ? ++rep.identical : ++rep.changed;
      }
    }
    groups_done = true;
    for (std::size_t h = 0; h < held.size(); ++h)
      if (!used[h]) {
        ++rep.extra;
        notes.add({1, held_row[h], 0}, "run_id " + std::to_string(held.run_id[h]) + ": only in B");
      }
  }
  // A run_id names one run of a spec: a file holding one twice is damaged.
  if (twice_a) throw std::runtime_error(refused_twice(in.a, *twice_a));
  if (twice_b) throw std::runtime_error(refused_twice(in.b, *twice_b));
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
  check_kinds(a_path);
  check_kinds(b_path);
  rep.by_run_id = read_attribute(a_path, "spec_hash") == read_attribute(b_path, "spec_hash");
  std::set<std::string> names_a, names_b;
  for (const std::string& n : column_names(a_path)) names_a.insert(n);
  for (const std::string& n : column_names(b_path)) names_b.insert(n);
  Compared compared;
  for (const std::string& n : names_a) {  // in name order
    const Column* c = find_column(n);
    if (!c || !c->deterministic || !names_b.count(n) || n == "run_id" || n == "param_hash") continue;
    (c->type == Column::Type::f64   ? compared.f64
     : c->type == Column::Type::i64 ? compared.i64
                                    : compared.text)
        .push_back(n);
  }
  const Inputs in{a_path, b_path, compared, opt};
  Notes notes(opt.show);
  Groups groups;
  // Equal parameters may recur in a spec, and files of other specs are in
  // no param_hash order: those are aligned in passes.
  bool streamed = false;
  if (rep.by_run_id && !opt.force_passes) {
    streamed = align_streaming(in, rep, notes, groups);
    if (!streamed) {  // a file out of run_id order: start over in passes (rep.passes counts the streaming one)
      const std::int64_t passes = rep.passes;
      rep = CompareReport{};
      rep.by_run_id = true;
      rep.passes = passes;
      notes.clear();
      groups.clear();
    }
  }
  if (!streamed) align_in_passes(in, rep, notes, groups, false);
  // Columns only one file has (other engine versions).
  for (const std::string& n : names_a)
    if (!names_b.count(n)) rep.schema.push_back("column '" + n + "' only in A");
  for (const std::string& n : names_b)
    if (!names_a.count(n)) rep.schema.push_back("column '" + n + "' only in B");
  rep.details = notes.list();
  // Distributions per group: chaotic runs of different specs or engine
  // versions agree in distribution, not run for run.
  groups.report(rep);
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

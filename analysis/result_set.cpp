#include "analysis/result_set.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>
#include <tuple>

#include "engine/store/column_blocks.hpp"
#include "engine/store/h5_store.hpp"
#include "kernels/core/param_table.hpp"

namespace chaosweep {

namespace {

// A run of a spec (spec_hash, run_id) in two files, or twice in one, would
// be counted twice by every table and figure.
void refuse_runs_held_twice(const std::vector<StoredColumns>& files, const std::vector<std::string>& spec_hashes,
                            const std::vector<std::string>& paths) {
  struct Held {
    std::size_t spec;  // files of one spec_hash share it
    double run_id;
    std::size_t file;
    bool operator<(const Held& o) const { return std::tie(spec, run_id, file) < std::tie(o.spec, o.run_id, o.file); }
  };
  std::vector<Held> held;
  for (std::size_t f = 0; f < files.size(); ++f) {
    const std::size_t spec =
        std::size_t(std::find(spec_hashes.begin(), spec_hashes.end(), spec_hashes[f]) - spec_hashes.begin());
    for (const auto& [name, v] : files[f].numeric)
      if (name == "run_id")
        for (double id : v) held.push_back({spec, id, f});
  }
  std::sort(held.begin(), held.end());
  for (std::size_t k = 1; k < held.size(); ++k) {
    const Held &a = held[k - 1], &b = held[k];
    if (a.spec != b.spec || a.run_id != b.run_id) continue;
    const std::string id = format_number(a.run_id);
    if (a.file == b.file)
      throw AnalysisError(paths[a.file] + " holds run_id " + id + " more than once (the file is damaged or hand-made)");
    throw AnalysisError(paths[a.file] + " and " + paths[b.file] + " both hold run_id " + id +
                        " of the same spec: its runs would be counted twice (give each shard once, or the "
                        "merged file alone)");
  }
}

// A column read only if it varies, while it has not: its first value.
struct Constant {
  bool any = false;  // a row was seen
  double number = 0;
  std::string text;
  bool same_as(const Constant& o) const {
    return !any || !o.any || (std::memcmp(&number, &o.number, sizeof number) == 0 && text == o.text);
  }
};

// `path`'s columns `want` (file order) as read_all_columns gives them; each
// marked varying_only is kept only once it takes a second value (its rows
// before then filled in), else left out with its value in `constants`.
StoredColumns read_columns(const std::string& path, const std::vector<std::pair<std::string, Column::Type>>& want,
                           const std::vector<bool>& varying_only, std::map<std::string, Constant>& constants) {
  std::vector<std::string> names;
  for (const auto& [name, type] : want) names.push_back(name);
  ColumnBlockReader reader(path, names);
  const std::size_t n = want.size();
  std::vector<std::vector<double>> nums(n);
  std::vector<std::vector<std::string>> texts(n);
  std::vector<bool> keep(n);
  std::vector<Constant> first(n);
  for (std::size_t c = 0; c < n; ++c) keep[c] = !varying_only[c];
  std::size_t done = 0;  // rows before this block
  while (reader.next()) {
    for (std::size_t c = 0; c < n; ++c) {
      const bool text = want[c].second == Column::Type::text;
      const std::size_t size = reader.size();
      std::size_t from = 0;  // rows of the block to take
      if (!keep[c]) {
        Constant& k = first[c];
        if (!k.any && size > 0) {
          k.any = true;
          if (text) k.text = reader.text(c)[0];
          else k.number = reader.number(c)[0];
        }
        while (from < size && (text ? reader.text(c)[from] == k.text
                                    : std::memcmp(&reader.number(c)[from], &k.number, sizeof(double)) == 0))
          ++from;
        if (from == size) continue;  // constant so far
        keep[c] = true;              // varies: its rows so far all held the first value
        if (text) texts[c].assign(done + from, k.text);
        else nums[c].assign(done + from, k.number);
      }
      if (text) texts[c].insert(texts[c].end(), reader.text(c).begin() + long(from), reader.text(c).end());
      else nums[c].insert(nums[c].end(), reader.number(c).begin() + long(from), reader.number(c).end());
    }
    done += reader.size();
  }
  StoredColumns out;
  out.rows = reader.rows();
  for (std::size_t c = 0; c < n; ++c) {
    if (!keep[c]) {
      constants[want[c].first] = first[c];
      continue;
    }
    if (want[c].second == Column::Type::text) out.text.emplace_back(want[c].first, std::move(texts[c]));
    else out.numeric.emplace_back(want[c].first, std::move(nums[c]));
  }
  return out;
}

}  // namespace

ResultSet ResultSet::load(const std::vector<std::string>& paths) { return load_some(paths, nullptr, {}); }

ResultSet ResultSet::load(const std::vector<std::string>& paths, const std::vector<std::string>& columns,
                          const std::vector<std::string>& if_varying) {
  return load_some(paths, &columns, if_varying);
}

ResultSet ResultSet::load_some(const std::vector<std::string>& paths, const std::vector<std::string>* columns,
                               const std::vector<std::string>& if_varying) {
  if (paths.empty()) throw AnalysisError("no result file given");
  ResultSet rs;
  std::vector<StoredColumns> files;
  std::vector<std::string> spec_hashes;
  std::vector<std::map<std::string, Constant>> constants(paths.size());
  std::vector<std::vector<std::pair<std::string, Column::Type>>> kinds;  // every file's columns
  auto listed = [](const std::vector<std::string>& v, const std::string& n) {
    return std::find(v.begin(), v.end(), n) != v.end();
  };
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const std::string& path = paths[i];
    for (std::size_t j = 0; j < i; ++j) {
      std::error_code ec;
      if (std::filesystem::equivalent(path, paths[j], ec))
        throw AnalysisError(path + " is given twice (also as " + paths[j] + "): its runs would be counted twice");
    }
    try {
      kinds.push_back(column_types(path));
      if (!columns) {
        files.push_back(read_all_columns(path));
      } else {
        std::vector<std::pair<std::string, Column::Type>> want;
        std::vector<bool> varying_only;
        for (const auto& [name, type] : kinds.back()) {
          const bool needed = name == "run_id" || name == "status" || listed(*columns, name);
          if (needed || listed(if_varying, name)) {
            want.emplace_back(name, type);
            varying_only.push_back(!needed);
          }
        }
        files.push_back(read_columns(path, want, varying_only, constants[i]));
      }
      for (const auto& [name, type] : kinds.back())
        if (name == "run_id" && type != Column::Type::i64)
          throw AnalysisError(path + ": column 'run_id' is " + (type == Column::Type::f64 ? "floating-point" : "text") +
                              ", not integers (not a chaosweep result file)");
      spec_hashes.push_back(has_attribute(path, "spec_hash") ? read_attribute(path, "spec_hash") : "");
    } catch (const AnalysisError&) {
      throw;
    } catch (const std::exception& e) {
      // The store's messages name the file and what is wrong with it.
      const std::string what = e.what();
      throw AnalysisError(
          what.find(path) != std::string::npos ? what : path + ": not a readable chaosweep result file (" + what + ")");
    }
    // A foreign /runs (another program's table) lacks the columns every run has.
    const StoredColumns& f = files.back();
    auto has_numeric = [&](const char* name) {
      return std::any_of(f.numeric.begin(), f.numeric.end(), [&](const auto& c) { return c.first == name; });
    };
    auto has_text = [&](const char* name) {
      return std::any_of(f.text.begin(), f.text.end(), [&](const auto& c) { return c.first == name; });
    };
    if (!has_numeric("run_id") || !has_text("status"))
      throw AnalysisError(path + ": /runs has no " + (has_numeric("run_id") ? "'status'" : "'run_id'") +
                          " column (not a chaosweep result file)");
  }
  refuse_runs_held_twice(files, spec_hashes, paths);
  // A column left out as constant in a file is needed after all when it
  // varies in another, or holds another constant there.
  for (const std::string& name : if_varying) {
    bool needed = false;
    const Constant* seen = nullptr;
    for (std::size_t i = 0; i < files.size(); ++i) {
      const auto k = constants[i].find(name);
      if (k == constants[i].end()) {
        const bool has = std::any_of(kinds[i].begin(), kinds[i].end(), [&](const auto& t) { return t.first == name; });
        needed = needed || has;  // held in full: it varies there
        continue;
      }
      if (seen && !seen->same_as(k->second)) needed = true;
      if (k->second.any) seen = &k->second;
    }
    if (!needed) continue;
    for (std::size_t i = 0; i < files.size(); ++i) {
      const auto k = constants[i].find(name);
      if (k == constants[i].end()) continue;
      const bool text = std::any_of(kinds[i].begin(), kinds[i].end(),
                                    [&](const auto& t) { return t.first == name && t.second == Column::Type::text; });
      if (text) files[i].text.emplace_back(name, std::vector<std::string>(files[i].rows, k->second.text));
      else files[i].numeric.emplace_back(name, std::vector<double>(files[i].rows, k->second.number));
    }
  }
  // The columns every file has, loaded or not (with the first file's kinds).
  for (const auto& kind : kinds[0]) {
    // Not a structured binding: clang 14 (the fuzz build) cannot capture one.
    const std::string& name = kind.first;
    const bool text = kind.second == Column::Type::text;
    bool everywhere = true;
    for (const auto& k : kinds)
      everywhere = everywhere && std::any_of(k.begin(), k.end(), [&](const auto& t) {
                     return t.first == name && (t.second == Column::Type::text) == text;
                   });
    if (everywhere) rs.file_columns_.push_back(name);
  }
  std::sort(rs.file_columns_.begin(), rs.file_columns_.end());
  // Columns every file has (a merged or older file may carry fewer), with
  // the first file's kinds.
  auto in_all = [&](const std::string& name, bool numeric) {
    for (const StoredColumns& f : files) {
      bool found = false;
      if (numeric) {
        for (const auto& [n, v] : f.numeric) found = found || n == name;
      } else {
        for (const auto& [n, v] : f.text) found = found || n == name;
      }
      if (!found) return false;
    }
    return true;
  };
  for (const auto& [name, v] : files[0].numeric)
    if (in_all(name, true)) rs.num_[name];
  for (const auto& [name, v] : files[0].text)
    if (in_all(name, false)) rs.text_[name];
  for (std::size_t i = 0; i < files.size(); ++i) {
    StoredColumns& f = files[i];
    for (auto& [name, v] : f.numeric)
      if (auto it = rs.num_.find(name); it != rs.num_.end()) {
        if (it->second.empty()) it->second = std::move(v);  // the first file's: no copy
        else it->second.insert(it->second.end(), v.begin(), v.end());
      }
    for (auto& [name, v] : f.text)
      if (auto it = rs.text_.find(name); it != rs.text_.end()) {
        if (it->second.empty()) it->second = std::move(v);
        else it->second.insert(it->second.end(), std::make_move_iterator(v.begin()), std::make_move_iterator(v.end()));
      }
    rs.rows_ += f.rows;
    rs.sources_.push_back(paths[i]);
  }
  return rs;
}

ResultSet ResultSet::from_columns(std::map<std::string, std::vector<double>> numeric,
                                  std::map<std::string, std::vector<std::string>> text) {
  ResultSet rs;
  std::size_t n = numeric.empty() ? (text.empty() ? 0 : text.begin()->second.size()) : numeric.begin()->second.size();
  for (const auto& [k, v] : numeric)
    if (v.size() != n)
      throw AnalysisError("column '" + k + "' has " + std::to_string(v.size()) + " rows, not " + std::to_string(n));
  for (const auto& [k, v] : text)
    if (v.size() != n)
      throw AnalysisError("column '" + k + "' has " + std::to_string(v.size()) + " rows, not " + std::to_string(n));
  rs.rows_ = n;
  rs.num_ = std::move(numeric);
  rs.text_ = std::move(text);
  return rs;
}

std::vector<std::string> ResultSet::names() const {
  std::vector<std::string> out;
  for (const auto& [k, v] : num_) out.push_back(k);
  for (const auto& [k, v] : text_) out.push_back(k);
  std::sort(out.begin(), out.end());
  return out;
}

void ResultSet::missing(const std::string& name, const char* kind) const {
  std::string list;  // the files' columns, not only those loaded
  for (const std::string& n : file_columns_.empty() ? names() : file_columns_) list += (list.empty() ? "" : ", ") + n;
  if (has(name)) throw AnalysisError("column '" + name + "' is not " + kind);
  throw AnalysisError("no column '" + name + "' in the results (columns: " + list + ")");
}

const std::vector<double>& ResultSet::num(const std::string& name) const {
  const auto it = num_.find(name);
  if (it == num_.end()) missing(name, "numeric");
  return it->second;
}

const std::vector<std::string>& ResultSet::text(const std::string& name) const {
  const auto it = text_.find(name);
  if (it == text_.end()) missing(name, "text");
  return it->second;
}

std::string ResultSet::cell(const std::string& name, std::size_t row) const {
  if (const auto it = text_.find(name); it != text_.end()) return it->second[row];
  return format_number(num(name)[row]);
}

namespace {

// "0.2, 0.25, 0.3" (at most 12, then "..."): the values a column takes.
template <class T, class Text>
std::string some_values(const std::vector<T>& v, Text text) {
  std::set<T> distinct(v.begin(), v.end());
  std::string s;
  std::size_t n = 0;
  for (const T& x : distinct) {
    if (++n > 12) return s + ", ... (" + std::to_string(distinct.size()) + " values)";
    s += (s.empty() ? "" : ", ") + text(x);
  }
  return s;
}

}  // namespace

ResultSet ResultSet::where(const std::vector<std::string>& conditions) const {
  std::vector<bool> keep(rows_, true);
  for (const std::string& c : conditions) {
    const auto eq = c.find('=');
    if (eq == std::string::npos || eq == 0) throw AnalysisError("--where " + c + ": expected COLUMN=VALUE");
    const std::string col = c.substr(0, eq), val = c.substr(eq + 1);
    std::vector<bool> match(rows_);
    std::string values;  // what the column holds, for when nothing matches
    if (is_numeric(col)) {
      double v;
      try {
        std::size_t used = 0;
        v = std::stod(val, &used);
        if (used != val.size()) throw std::invalid_argument(val);
      } catch (const std::exception&) {
        throw AnalysisError("--where " + c + ": '" + col + "' is numeric, '" + val + "' is not a number");
      }
      const auto& x = num(col);
      for (std::size_t r = 0; r < rows_; ++r) match[r] = std::fabs(x[r] - v) <= 1e-9 * std::max(1.0, std::fabs(v));
      values = some_values(x, [](double d) { return format_number(d); });
    } else {
      const auto& x = text(col);  // throws naming a missing column
      for (std::size_t r = 0; r < rows_; ++r) match[r] = x[r] == val;
      values = some_values(x, [](const std::string& t) { return "'" + t + "'"; });
    }
    if (rows_ > 0 && std::find(match.begin(), match.end(), true) == match.end())
      throw AnalysisError("--where " + c + " matches none of the " + std::to_string(rows_) + " runs: " + col +
                          " takes " + values);
    for (std::size_t r = 0; r < rows_; ++r) keep[r] = keep[r] && match[r];
  }
  if (rows_ > 0 && std::find(keep.begin(), keep.end(), true) == keep.end()) {
    std::string all;
    for (const std::string& c : conditions) all.append(all.empty() ? "" : " ").append("--where ").append(c);
    throw AnalysisError(all + ": no run matches them all (each alone matches some of the " + std::to_string(rows_) +
                        " runs)");
  }
  ResultSet out;
  out.sources_ = sources_;
  out.file_columns_ = file_columns_;
  for (const auto& [k, v] : num_) {
    auto& dst = out.num_[k];
    for (std::size_t r = 0; r < rows_; ++r)
      if (keep[r]) dst.push_back(v[r]);
  }
  for (const auto& [k, v] : text_) {
    auto& dst = out.text_[k];
    for (std::size_t r = 0; r < rows_; ++r)
      if (keep[r]) dst.push_back(v[r]);
  }
  for (bool k : keep) out.rows_ += k;
  return out;
}

std::vector<std::size_t> all_rows(const ResultSet& rs) {
  std::vector<std::size_t> r(rs.rows());
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = i;
  return r;
}

std::vector<std::size_t> ok_rows(const ResultSet& rs, const std::vector<std::size_t>& rows) {
  const auto& status = rs.text("status");
  std::vector<std::size_t> out;
  for (std::size_t r : rows)
    if (status[r] == "ok") out.push_back(r);
  return out;
}

}  // namespace chaosweep

#include "result_set.hpp"

#include <algorithm>
#include <set>

#include "h5_store.hpp"
#include "param_table.hpp"

namespace chaosweep {

ResultSet ResultSet::load(const std::vector<std::string>& paths) {
  if (paths.empty()) throw AnalysisError("no result file given");
  ResultSet rs;
  // Columns every file has, with the first file's types.
  std::vector<std::pair<std::string, Column::Type>> common;
  for (std::size_t f = 0; f < paths.size(); ++f) {
    std::vector<std::pair<std::string, Column::Type>> types;
    try {
      types = column_types(paths[f]);
    } catch (const std::exception& e) {
      throw AnalysisError(paths[f] + ": not a chaosweep result file (" + e.what() + ")");
    }
    if (f == 0) {
      common = types;
      continue;
    }
    std::set<std::string> here;
    for (const auto& [n, t] : types) here.insert(n);
    std::erase_if(common, [&](const auto& c) { return !here.count(c.first); });
  }
  for (const std::string& path : paths) {
    try {
      const auto n = std::size_t(count_rows(path));
      for (const auto& [name, type] : common) {
        if (type == Column::Type::text) {
          auto col = read_text_column(path, name);
          auto& dst = rs.text_[name];
          dst.insert(dst.end(), col.begin(), col.end());
        } else if (type == Column::Type::i64) {
          const auto col = read_i64_column(path, name);
          auto& dst = rs.num_[name];
          for (std::int64_t v : col) dst.push_back(double(v));
        } else {
          const auto col = read_f64_column(path, name);
          auto& dst = rs.num_[name];
          dst.insert(dst.end(), col.begin(), col.end());
        }
      }
      rs.rows_ += n;
    } catch (const std::exception& e) {
      throw AnalysisError(path + ": " + e.what());
    }
    rs.sources_.push_back(path);
  }
  return rs;
}

ResultSet ResultSet::from_columns(std::map<std::string, std::vector<double>> numeric,
                                  std::map<std::string, std::vector<std::string>> text) {
  ResultSet rs;
  std::size_t n = numeric.empty() ? (text.empty() ? 0 : text.begin()->second.size()) : numeric.begin()->second.size();
  for (const auto& [k, v] : numeric)
    if (v.size() != n) throw AnalysisError("column '" + k + "' has " + std::to_string(v.size()) + " rows, not " + std::to_string(n));
  for (const auto& [k, v] : text)
    if (v.size() != n) throw AnalysisError("column '" + k + "' has " + std::to_string(v.size()) + " rows, not " + std::to_string(n));
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
  std::string list;
  for (const std::string& n : names()) list += (list.empty() ? "" : ", ") + n;
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

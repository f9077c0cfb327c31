#include "engine/store/stored_run.hpp"

#include <algorithm>
#include <bit>
#include <cstdio>

#include "engine/rows/result_columns.hpp"
#include "kernels/core/param_table.hpp"

namespace chaosweep {

StoredRow stored_row(const StoredColumns& cols, std::size_t r) {
  StoredRow row;
  for (const auto& [name, v] : cols.numeric) row.numeric[name] = v.at(r);
  for (const auto& [name, v] : cols.text) row.text[name] = v.at(r);
  return row;
}

std::size_t row_of_run_id(const std::vector<double>& ids, std::int64_t id, const std::string& where) {
  std::size_t found = ids.size();
  for (std::size_t r = 0; r < ids.size(); ++r) {
    if (ids[r] != double(id)) continue;
    if (found != ids.size())
      throw SpecError(where + ": run_id " + std::to_string(id) + " is in rows " + std::to_string(found) + " and " +
                      std::to_string(r) + " (give one result file; a sweep's file holds each run once)");
    found = r;
  }
  if (found == ids.size()) {
    const auto [lo, hi] = std::minmax_element(ids.begin(), ids.end());
    throw SpecError(where + ": no run with run_id " + std::to_string(id) +
                    (ids.empty() ? " (the file holds no runs)"
                                 : " (its " + std::to_string(ids.size()) + " runs have run_ids " + format_number(*lo) +
                                       " to " + format_number(*hi) + ")"));
  }
  return found;
}

RunSpec run_spec_of(const StoredRow& row) {
  auto missing = [](const std::string& name) {
    return SpecError("cannot rebuild the run: the results have no column '" + name + "'");
  };
  RunSpec s;
  for (const ParamInfo& p : param_table()) {
    const std::string name(p.name);
    double v;
    if (p.kind == ParamInfo::Kind::choice) {
      const auto it = row.text.find(name);
      if (it == row.text.end()) throw missing(name);
      const auto idx = p.choice_index(it->second);
      if (!idx) throw SpecError("cannot rebuild the run: '" + it->second + "' is not a value of " + name);
      v = *idx;
    } else {
      const auto exact = row.integers.find(name);
      const auto it = row.numeric.find(name);
      if (exact != row.integers.end()) v = double(exact->second);
      else if (it != row.numeric.end()) v = it->second;
      else throw missing(name);
    }
    // A foreign or damaged file may hold any value: the spec's ranges apply.
    if (const std::string e = p.check(v); !e.empty()) throw SpecError("cannot rebuild the run: column " + e);
    p.set(s.params, v);
  }
  const auto env = row.text.find("env");
  if (env == row.text.end()) throw missing("env");
  s.env = env->second;
  if (const auto label = row.text.find("label"); label != row.text.end()) s.label = label->second;
  return s;
}

StoredRun load_stored_run(const std::string& path, std::int64_t run_id) {
  const StoredColumns cols = read_all_columns(path);
  const std::vector<double>* ids = nullptr;
  for (const auto& [name, v] : cols.numeric)
    if (name == "run_id") ids = &v;
  if (!ids) throw SpecError(path + ": /runs has no 'run_id' column (not a chaosweep result file)");
  const std::size_t r = row_of_run_id(*ids, run_id, path);
  StoredRun out;
  out.row = stored_row(cols, r);
  // A 64-bit hash does not survive the trip through a double: read it exactly.
  if (out.row.numeric.count("param_hash")) out.row.integers["param_hash"] = read_i64_column(path, "param_hash").at(r);
  try {
    EnvironmentCache cache;
    out.tuple = resolve_run(run_id, run_spec_of(out.row), cache);
    // A tune's row says which race and configuration it ran for (files of
    // older engines have neither: a sweep's -1).
    const auto from_row = [&](const char* name, std::int64_t& field) {
      if (const auto it = out.row.numeric.find(name); it != out.row.numeric.end()) field = std::int64_t(it->second);
    };
    from_row("race_round", out.tuple.race_round);
    from_row("config_id", out.tuple.config_id);
  } catch (const std::exception& e) {  // a missing column, an environment gone since
    throw SpecError(path + ": run_id " + std::to_string(run_id) + ": " + e.what());
  }
  return out;
}

RowComparison compare_row(const StoredRow& stored, const RunRow& rerun) {
  RowComparison out;
  for (const Column& c : result_columns()) {
    if (!c.deterministic) continue;
    const CellValue v = c.get(rerun);
    std::string was, now;
    bool same;
    if (c.type == Column::Type::text) {
      const auto it = stored.text.find(c.name);
      if (it == stored.text.end()) continue;
      was = it->second, now = std::get<std::string>(v);
      same = was == now;
    } else if (c.type == Column::Type::i64) {
      const std::int64_t x = std::get<std::int64_t>(v);
      now = std::to_string(x);
      if (const auto exact = stored.integers.find(c.name); exact != stored.integers.end()) {
        same = exact->second == x;
        was = std::to_string(exact->second);
      } else if (const auto it = stored.numeric.find(c.name); it != stored.numeric.end()) {
        same = it->second == double(x);
        was = format_number(it->second);
      } else {
        continue;
      }
    } else {
      const auto it = stored.numeric.find(c.name);
      if (it == stored.numeric.end()) continue;
      const double x = std::get<double>(v);
      const auto a = std::bit_cast<std::uint64_t>(it->second), b = std::bit_cast<std::uint64_t>(x);
      same = a == b;
      was = format_number(it->second), now = format_number(x);
      if (!same && was == now) {  // two NaNs, or 0 and -0 after all: show the bits
        char buf[64];
        std::snprintf(buf, sizeof buf, " (bits %016llx)", (unsigned long long)a);
        was += buf;
        std::snprintf(buf, sizeof buf, " (bits %016llx)", (unsigned long long)b);
        now += buf;
      }
    }
    out.compared.push_back(c.name);
    if (!same) out.differences.push_back({c.name, was, now});
  }
  return out;
}

}  // namespace chaosweep

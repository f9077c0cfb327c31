#include "analysis/ct_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "analysis/grouping.hpp"
#include "analysis/plot.hpp"
#include "analysis/text_table.hpp"
#include "kernels/core/param_table.hpp"

namespace chaosweep {

namespace fs = std::filesystem;

std::vector<std::string> file_labels(const std::vector<std::string>& paths) {
  auto distinct = [](const std::vector<std::string>& v) {
    std::map<std::string, int> n;
    for (const std::string& s : v) ++n[s];
    return std::all_of(n.begin(), n.end(), [](const auto& e) { return e.second == 1; });
  };
  std::vector<std::string> stems, parents;
  for (const std::string& p : paths) {
    const fs::path f(p);
    stems.push_back(f.stem().string());
    const std::string dir = f.parent_path().filename().string();
    parents.push_back(dir.empty() ? f.stem().string() : dir + "/" + f.stem().string());
  }
  if (distinct(stems)) return stems;
  if (distinct(parents)) return parents;
  return paths;
}

namespace {

struct Curve {
  std::size_t file, group;
  std::vector<std::string> key;
  std::vector<double> key_num;  // NaN for text keys
  std::string name;
  std::size_t runs = 0;
  std::vector<double> ct;  // of the ok runs, sorted
};

}  // namespace

LineSeries ecdf_steps(const std::vector<double>& sorted, std::size_t runs, double x0, double x_end) {
  LineSeries s;
  s.x = {x0};
  s.y = {0.0};
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    s.x.push_back(sorted[i]), s.y.push_back(s.y.back());
    s.x.push_back(sorted[i]), s.y.push_back(100.0 * double(i + 1) / double(runs));
  }
  s.x.push_back(x_end), s.y.push_back(s.y.back());
  return s;
}

FigureOutput ct_distribution(const std::vector<LabelledResults>& sets, const FigureOptions& opt,
                             const std::string& path) {
  if (sets.empty()) throw AnalysisError("ct_distribution: give one or more result files (.h5)");
  const std::vector<std::string> by = split_list(opt.by);
  // The groups of every file, in one order (natural, as group_rows gives them).
  std::vector<std::pair<std::vector<double>, std::vector<std::string>>> keys;
  std::vector<Curve> curves;
  for (std::size_t f = 0; f < sets.size(); ++f) {
    const ResultSet& rs = sets[f].rs;
    (void)rs.num("coverage_time");
    for (const Group& g : group_rows(rs, by, all_rows(rs))) {
      Curve c{f, 0, g.key, g.key_num, sets[f].label, g.rows.size(), {}};
      for (std::size_t r : ok_rows(rs, g.rows)) c.ct.push_back(rs.num("coverage_time")[r]);
      std::sort(c.ct.begin(), c.ct.end());
      for (std::size_t k = 0; k < by.size(); ++k) c.name += (k ? ", " : ": ") + by[k] + " " + g.key[k];
      curves.push_back(std::move(c));
      if (std::find_if(keys.begin(), keys.end(), [&](const auto& k) { return k.second == g.key; }) == keys.end())
        keys.emplace_back(g.key_num, g.key);
    }
  }
  if (curves.size() > ct_distribution_max_curves) {
    throw AnalysisError("ct_distribution: " + std::to_string(curves.size()) + " curves (" +
                        std::to_string(sets.size()) + " file(s) x the groups of --by " + (by.empty() ? "-" : opt.by) +
                        "); at most " + std::to_string(ct_distribution_max_curves) +
                        " fit one figure: narrow the rows with --where or group by fewer columns");
  }
  std::size_t ok_total = 0;
  for (const Curve& c : curves) ok_total += c.ct.size();
  if (ok_total == 0) {
    std::string names;
    for (const LabelledResults& s : sets) names += (names.empty() ? "" : ", ") + s.label;
    throw AnalysisError("ct_distribution: no run in " + names +
                        " reached the target (status ok): there are no coverage times to draw");
  }
  // Groups in key order across files (numbers by value, text in natural
  // order, as group_rows); curves by group, then file.
  std::sort(keys.begin(), keys.end(), [](const auto& a, const auto& b) {
    for (std::size_t i = 0; i < a.second.size(); ++i) {
      const double x = a.first[i], y = b.first[i];
      if (!std::isnan(x) && !std::isnan(y) && x != y) return x < y;
      if (natural_less(a.second[i], b.second[i])) return true;
      if (natural_less(b.second[i], a.second[i])) return false;
    }
    return false;
  });
  for (Curve& c : curves)
    c.group = std::size_t(std::find_if(keys.begin(), keys.end(), [&](const auto& k) { return k.second == c.key; }) -
                          keys.begin());
  std::stable_sort(curves.begin(), curves.end(), [](const Curve& a, const Curve& b) {
    return std::pair(a.group, a.file) < std::pair(b.group, b.file);
  });
  double tmax = 0;
  for (const Curve& c : curves)
    if (!c.ct.empty()) tmax = std::max(tmax, c.ct.back());

  TextTable csv;
  csv.header = by;
  for (const char* h : {"label", "runs", "ok", "not_ok_share", "coverage_time", "cumulative_share"})
    csv.header.push_back(h);
  LinePlot p;
  p.title = "Coverage-time distributions (ECDF)";
  p.xlabel = "coverage time (s)";
  p.ylabel = "runs that reached the target (%)";
  p.y_range = {0.0, 100.0};
  FigureOutput out{path, csv_beside(path), {}};
  const bool colour_by_group = sets.size() > 1 && keys.size() > 1;
  for (std::size_t k = 0; k < curves.size(); ++k) {
    const Curve& c = curves[k];
    const double n = double(c.runs), ok = double(c.ct.size());
    auto row = [&](const std::string& ct, double share) {
      std::vector<Cell> r(c.key.begin(), c.key.end());
      for (Cell v : std::vector<Cell>{sets[c.file].label, std::to_string(c.runs), std::to_string(c.ct.size()),
                                      sig_cell((n - ok) / n, 6), ct, sig_cell(share, 6)})
        r.push_back(std::move(v));
      csv.add_row(std::move(r));
    };
    LineSeries s = ecdf_steps(c.ct, c.runs, 0.0, tmax);
    s.name = c.name + " (" + std::to_string(c.ct.size()) + "/" + std::to_string(c.runs) + " ok)";
    if (colour_by_group)  // a colour per group, a dash per file: A and B of a group side by side
      s.colour = int(c.group % line_colour_count), s.dash = int(c.file + sets.size() * (c.group / line_colour_count));
    if (c.ct.empty()) row("-", 0.0);
    for (std::size_t i = 0; i < c.ct.size(); ++i) row(format_number(c.ct[i]), double(i + 1) / n);
    std::string line = s.name + ": " + fmt_fixed(100.0 * ok / n, 1) + "% reached the target";
    if (!c.ct.empty()) line += ", median CT " + fmt_sig(quantile(c.ct, 0.5), 6) + " s";
    out.lines.push_back(std::move(line));
    p.series.push_back(std::move(s));
  }
  csv.write_file(out.csv, TableFormat::csv);
  render(p, path, opt.size);
  return out;
}

}  // namespace chaosweep

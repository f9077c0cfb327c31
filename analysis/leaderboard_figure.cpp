#include "analysis/leaderboard_figure.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/ct_distribution.hpp"
#include "analysis/grouping.hpp"
#include "analysis/leaderboard.hpp"
#include "analysis/plot.hpp"
#include "analysis/text_table.hpp"
#include "kernels/core/param_table.hpp"

namespace chaosweep {

FigureOutput leaderboard_figure(const ResultSet& rs, const FigureOptions& opt, const std::string& path) {
  const Leaderboard lb = rank_planners(rs, split_list(opt.by));
  const std::vector<double>& pr = rs.num("pr");
  LinePlot p;
  p.title = "Leaderboard: runs within a PR, over " + std::to_string(lb.maps.size()) + " map(s)";
  p.xlabel = "PR = coverage time / T_opt (log)";
  p.ylabel = "runs that reached the target (%)";
  p.y_range = {0.0, 100.0};
  p.x_log = true;
  TextTable csv;
  csv.header = {"planner", "mean_rank", "runs", "ok", "pr", "cumulative_share"};
  FigureOutput out{path, csv_beside(path), {}};
  double lo = INFINITY, hi = 0;
  std::vector<std::vector<double>> prs;
  for (const Leaderboard::Standing& s : lb.overall) {
    std::vector<double> v;
    for (std::size_t r : ok_rows(rs, s.rows))
      if (pr[r] > 0 && std::isfinite(pr[r])) v.push_back(pr[r]);
    std::sort(v.begin(), v.end());
    if (!v.empty()) lo = std::min(lo, v.front()), hi = std::max(hi, v.back());
    prs.push_back(std::move(v));
  }
  if (!(hi > 0)) throw AnalysisError("leaderboard: no run reached the target (status ok): there is no PR to draw");
  for (std::size_t k = 0; k < lb.overall.size(); ++k) {
    const Leaderboard::Standing& s = lb.overall[k];
    const std::vector<double>& v = prs[k];
    const double n = double(s.rows.size());
    const std::string rank = fmt_sig(s.mean_rank, 3);
    LineSeries line = ecdf_steps(v, s.rows.size(), lo, hi);
    line.name = s.name + " (mean rank " + rank + ")";
    if (v.empty()) csv.add_row({s.name, rank, std::to_string(s.rows.size()), "0", "-", "0"});
    for (std::size_t i = 0; i < v.size(); ++i)
      csv.add_row({s.name, rank, std::to_string(s.rows.size()), std::to_string(v.size()), format_number(v[i]),
                   sig_cell(double(i + 1) / n, 6)});
    std::string said = s.name + ": mean rank " + rank + " over " + std::to_string(s.maps) + " map(s), " +
                       fmt_fixed(100.0 * double(v.size()) / n, 1) + "% of " + std::to_string(s.rows.size()) +
                       " runs reached the target";
    if (!v.empty()) said += ", median PR of those " + fmt_sig(quantile(v, 0.5), 3);
    out.lines.push_back(std::move(said));
    p.series.push_back(std::move(line));
  }
  csv.write_file(out.csv, TableFormat::csv);
  render(p, path, opt.size);
  return out;
}

}  // namespace chaosweep

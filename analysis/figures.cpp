#include "analysis/figures.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "analysis/column_labels.hpp"
#include "analysis/ct_distribution.hpp"
#include "analysis/grouping.hpp"
#include "analysis/leaderboard_figure.hpp"
#include "analysis/named_list.hpp"
#include "analysis/papers/bouncing_paper.hpp"
#include "analysis/replay.hpp"
#include "analysis/tables.hpp"
#include "analysis/text_table.hpp"
#include "kernels/core/param_table.hpp"
#include "kernels/core/rect_decomposition.hpp"
#include "kernels/planners/arnold/zones.hpp"
#include "kernels/planners/chebyshev/chebyshev_analysis.hpp"
#include "kernels/systems/chebyshev_map.hpp"

namespace chaosweep {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

std::vector<double> distinct_sorted(const std::vector<double>& v, const std::vector<std::size_t>& rows) {
  std::set<double> s;
  for (std::size_t r : rows) s.insert(v[r]);
  return {s.begin(), s.end()};
}

std::size_t index_of(const std::vector<double>& axis, double v) {
  return std::size_t(std::lower_bound(axis.begin(), axis.end(), v) - axis.begin());
}

// The paper's tuple for Fig. 6 (seed 000): (A, B, C) = (0.5, 0.25, 0.25).
std::vector<double> mark_or_default(const std::vector<double>& m) {
  if (m.empty()) return {0.5, 0.25, 0.25};
  if (m.size() != 3) throw AnalysisError("--mark: expected A,B,C (three numbers)");
  return m;
}

std::string tuple_text(double a, double b, double c) {
  return "(" + format_number(a) + ", " + format_number(b) + ", " + format_number(c) + ")";
}

// ---------------------------------------------------------------- heatmaps

FigureOutput heatmap_figure(const ResultSet& rs, const std::string& xcol, const std::string& ycol,
                            const std::string& stat, const std::string& title, std::optional<PlotMark> mark,
                            const FigureOptions& opt, const std::string& path) {
  const auto& xv = rs.num(xcol);
  const auto& yv = rs.num(ycol);
  const auto rows = all_rows(rs);
  (void)group_statistic(rs, {}, stat);  // an unknown statistic fails before any work
  HeatmapPlot p;
  p.title = title;
  p.xlabel = axis_label(xcol);
  p.ylabel = axis_label(ycol);
  const bool of_ct = stat != "ok_rate" && stat != "runs";
  p.zlabel = stat == "ok_rate" ? "ok rate" : stat == "runs" ? "runs" : stat + " CT (s)";
  p.empty_label = of_ct ? "grey: no run there reached the target (or none ran)" : "grey: no runs there";
  p.xs = distinct_sorted(xv, rows);
  p.ys = distinct_sorted(yv, rows);
  p.z.assign(p.xs.size() * p.ys.size(), nan);
  TextTable csv;
  csv.header = {xcol, ycol, stat == "ok_rate" || stat == "runs" ? stat : stat + "_ct", "runs", "ok"};
  for (const Group& g : group_rows(rs, {xcol, ycol}, rows)) {
    const double z = group_statistic(rs, g.rows, stat);
    p.z[index_of(p.ys, g.key_num[1]) * p.xs.size() + index_of(p.xs, g.key_num[0])] = z;
    csv.add_row({g.key[0], g.key[1], sig_cell(z, 6), std::to_string(g.rows.size()),
                 std::to_string(ok_rows(rs, g.rows).size())});
  }
  p.mark = std::move(mark);
  FigureOutput out{path, csv_beside(path), {}};
  csv.write_file(out.csv, TableFormat::csv);
  render(p, path, opt.size);
  return out;
}

FigureOutput fig6a(const ResultSet& rs, const FigureOptions& opt, const std::string& path) {
  for (const char* c : {"A", "B", "C"}) (void)rs.num(c);
  const auto m = mark_or_default(opt.mark);
  return heatmap_figure(
      rs, "A", "C", "min", "Fig. 6a: minimum coverage time over B",
      PlotMark{m[0], m[2], "(A, C) = (" + format_number(m[0]) + ", " + format_number(m[2]) + ")", opt.mark_label}, opt,
      path);
}

// ------------------------------------------------------------------ fig6b

FigureOutput fig6b(const ResultSet& rs, const FigureOptions& opt, const std::string& path) {
  const auto m = mark_or_default(opt.mark);
  for (const char* c : {"A", "B", "C"}) (void)rs.num(c);
  double bound = opt.bound;
  if (bound <= 0 && rs.has("max_time"))
    for (double t : rs.num("max_time")) bound = std::max(bound, t);
  if (!(bound > 0)) throw AnalysisError("--bound: give the time bound (the runs carry no max_time)");
  // Each (A, B, C) tuple scored by its median CT (tables.hpp: tuple_score).
  struct Tuple {
    double a, b, c, ct;
  };
  std::vector<Tuple> tuples;
  for (const Group& g : group_rows(rs, {"A", "B", "C"}, all_rows(rs)))
    tuples.push_back({g.key_num[0], g.key_num[1], g.key_num[2], tuple_score(rs, g.rows)});
  std::stable_sort(tuples.begin(), tuples.end(), [](const Tuple& x, const Tuple& y) { return x.ct < y.ct; });
  const double n = double(tuples.size());
  // The marked tuple, or the nearest on the grid (relative to each axis' span).
  auto span = [&](auto get) {
    double lo = 1e300, hi = -1e300;
    for (const Tuple& t : tuples) lo = std::min(lo, get(t)), hi = std::max(hi, get(t));
    return hi > lo ? hi - lo : 1.0;
  };
  const double sa = span([](const Tuple&t) { return t.a; }), sb = span([](const Tuple&t) { return t.b; }),
               sc = span([](const Tuple&t) { return t.c; });
  std::size_t best = 0;
  double best_d = 1e300;
  for (std::size_t i = 0; i < tuples.size(); ++i) {
    const double d = std::hypot((tuples[i].a - m[0]) / sa, (tuples[i].b - m[1]) / sb, (tuples[i].c - m[2]) / sc);
    if (d < best_d) best_d = d, best = i;
  }
  const Tuple& mk = tuples[best];
  const bool exact = best_d < 1e-9;
  // Share of tuples at least as fast as the marked one.
  double within = 0;
  for (const Tuple& t : tuples) within += t.ct <= mk.ct;

  TextTable csv;
  csv.header = {"rank", "A", "B", "C", "median_ct", "percent_of_tuples_within"};
  LineSeries curve{"tuples", {0.0}, {0.0}};
  for (std::size_t i = 0; i < tuples.size(); ++i) {
    const Tuple& t = tuples[i];
    const bool reached = t.ct <= bound;
    const double pct = 100.0 * double(i + 1) / n;
    csv.add_row({std::to_string(i + 1), format_number(t.a), format_number(t.b), format_number(t.c),
                 std::isinf(t.ct) ? "-" : sig_cell(t.ct, 6), reached ? fixed_cell(pct, 3) : "-"});
    if (reached) {  // a step: the share jumps at each tuple's CT
      curve.x.push_back(t.ct);
      curve.y.push_back(curve.y.back());
      curve.x.push_back(t.ct);
      curve.y.push_back(pct);
    }
  }
  curve.x.push_back(bound);
  curve.y.push_back(curve.y.back());
  FigureOutput out{path, csv_beside(path), {}};
  const std::string who = (exact ? "tuple " : "nearest grid tuple to " + tuple_text(m[0], m[1], m[2]) + ": ") +
                          tuple_text(mk.a, mk.b, mk.c);
  if (std::isinf(mk.ct)) {
    out.lines.push_back(who + " did not reach the target within its runs' budget");
  } else {
    out.lines.push_back(who + ": median CT " + fmt_sig(mk.ct, 6) + " s; " + fmt_fixed(100.0 * within / n, 1) + "% of " +
                        std::to_string(tuples.size()) + " tuples are at least as fast (rank " +
                        std::to_string(best + 1) + ")");
  }
  LinePlot p;
  p.title = "Fig. 6b: tuples reaching the target within a time bound";
  p.xlabel = "time bound (s)";
  p.ylabel = "tuples (%)";
  p.series.push_back(std::move(curve));
  p.y_range = {0.0, 100.0};
  if (!std::isinf(mk.ct))
    p.mark = PlotMark{mk.ct, 100.0 * within / n,
                      tuple_text(mk.a, mk.b, mk.c) + ": " + fmt_fixed(100.0 * within / n, 1) + "%", opt.mark_label};
  csv.write_file(out.csv, TableFormat::csv);
  render(p, path, opt.size);
  return out;
}

// ------------------------------------------------------ trajectory, coverage

std::vector<std::int64_t> chosen_runs(const ResultSet& rs, const FigureOptions& opt, std::size_t max_default) {
  if (!opt.runs.empty()) return opt.runs;
  const auto& ids = rs.num("run_id");
  std::vector<std::int64_t> out;
  if (!opt.by.empty()) {
    // One run per group: the one whose CT is the group's median among ok runs.
    for (const Group& g : group_rows(rs, {opt.by}, all_rows(rs))) {
      std::vector<std::size_t> ok = ok_rows(rs, g.rows);
      if (ok.empty()) ok = g.rows;
      std::stable_sort(ok.begin(), ok.end(), [&](std::size_t a, std::size_t b) {
        return rs.num("coverage_time")[a] < rs.num("coverage_time")[b];
      });
      out.push_back(std::int64_t(ids[ok[(ok.size() - 1) / 2]]));
    }
    return out;
  }
  for (std::size_t r = 0; r < rs.rows() && out.size() < max_default; ++r) out.push_back(std::int64_t(ids[r]));
  return out;
}

std::string run_name(const ResultSet& rs, std::size_t r, const std::string& by) {
  std::string s = "run " + rs.cell("run_id", r);
  if (!by.empty()) return s + " (" + by + " " + rs.cell(by, r) + ")";
  if (rs.has("label") && !rs.text("label")[r].empty()) s += ", " + rs.text("label")[r];
  if (rs.has("variant")) s += ", " + rs.text("variant")[r];
  return s;
}

FigureOutput trajectory(const ResultSet& rs, const FigureOptions& opt, const std::string& path) {
  const auto ids = chosen_runs(rs, opt, 1);
  if (ids.size() != 1) throw AnalysisError("trajectory: give one run with --run ID");
  const std::size_t r = row_of_run(rs, ids[0]);
  const Replay rp = replay_row(rs, r);
  FigureOutput out{path, csv_beside(path), {}};
  if (!rp.mismatch.empty()) out.lines.push_back("warning: the replay differs from the stored run: " + rp.mismatch);
  const Environment& env = *rp.tuple.env;
  const RunParams& p = rp.tuple.params;
  MapPlot m;
  m.title = "Run " + rs.cell("run_id", r) + ": " + rs.text("variant")[r] + ", " + to_string(rp.result.status) +
            (std::isnan(rp.result.coverage_time) ? "" : ", CT " + fmt_sig(rp.result.coverage_time, 5) + " s") + ", " +
            fmt_fixed(100.0 * rp.grid.coverage(), 1) + "% covered";
  m.lx = env.lx, m.ly = env.ly;
  m.cell = rp.grid.cell_size();
  m.nx = rp.grid.nx(), m.ny = rp.grid.ny();
  for (int j = 0; j < m.ny; ++j)
    for (int i = 0; i < m.nx; ++i) m.covered.push_back(rp.grid.at(i, j) == CoverageGrid::visited);
  for (const Rect& o : env.obstacles) m.obstacles.push_back({o.x0, o.y0, o.x1, o.y1});
  if (p.map_zoning && p.planner == Planner::arnold) {
    const Zones zones(env, rp.grid, p.zones_x, p.zones_y, p.zone_goal == ZoneGoal::free_cell, p.fo);
    for (const ZoneInfo& z : zones.snapshot(rp.grid)) m.zone_midpoints.emplace_back(z.mid_x, z.mid_y);
  }
  if (p.planner == Planner::chebyshev) {
    const RectDecomposition d = decompose_free_space(env, p.radius);
    for (const auto& reg : d.regions) m.regions.push_back({reg.box.x0, reg.box.y0, reg.box.x1, reg.box.y1});
    for (const auto& t : d.transitions) m.transitions.push_back({t.box.x0, t.box.y0, t.box.x1, t.box.y1});
    for (const TracePoint& q : rp.points)
      if (q.kind == SegmentKind::subgoal) m.subgoals.emplace_back(q.x, q.y);
  }
  // Paths split where the kind changes; each piece keeps its first point's
  // predecessor so the pieces join up. Long runs are thinned for drawing
  // only (at most ~200k points); the CSV keeps every point.
  const std::size_t stride = std::max<std::size_t>(1, rp.points.size() / 200000);
  TextTable csv;
  csv.header = {"t", "x", "y", "kind", "ds_index", "visited_cells"};
  bool in_transit = false;  // the class of the current piece: transit or not
  for (std::size_t i = 0; i < rp.points.size(); ++i) {
    const TracePoint& q = rp.points[i];
    csv.add_row({format_number(q.t), format_number(q.x), format_number(q.y), to_string(q.kind),
                 std::to_string(q.ds_index), std::to_string(rp.visited[i])});
    if (q.kind == SegmentKind::start) continue;
    const bool transit = q.kind == SegmentKind::transit;
    auto& paths = transit ? m.transit_paths : m.arnold_paths;
    if (transit != in_transit || paths.empty()) {
      paths.emplace_back();
      if (i > 0) paths.back().emplace_back(rp.points[i - 1].x, rp.points[i - 1].y);
      in_transit = transit;
    }
    if (i % stride == 0 || i + 1 == rp.points.size() || q.kind == SegmentKind::transit)
      paths.back().emplace_back(q.x, q.y);
  }
  if (!rp.points.empty()) {
    m.start = {rp.points.front().x, rp.points.front().y};
    m.end = {rp.points.back().x, rp.points.back().y};
  }
  csv.write_file(out.csv, TableFormat::csv);
  render(m, path, opt.size);
  return out;
}

FigureOutput coverage(const ResultSet& rs, const FigureOptions& opt, const std::string& path) {
  const auto ids = chosen_runs(rs, opt, 5);
  if (ids.empty()) throw AnalysisError("coverage: no runs chosen");
  if (ids.size() > 12)
    throw AnalysisError("coverage: at most 12 runs in one figure (" + std::to_string(ids.size()) + " chosen)");
  FigureOutput out{path, csv_beside(path), {}};
  LinePlot p;
  p.title = "Coverage over time";
  p.xlabel = "t (s)";
  p.ylabel = "coverage (%)";
  p.y_range = {0.0, 100.0};
  TextTable csv;
  csv.header = {"run_id", "t", "coverage_percent"};
  for (std::int64_t id : ids) {
    const std::size_t r = row_of_run(rs, id);
    const Replay rp = replay_row(rs, r);
    if (!rp.mismatch.empty())
      out.lines.push_back("warning: run " + std::to_string(id) + " replays differently: " + rp.mismatch);
    LineSeries s{run_name(rs, r, opt.by), {}, {}};
    const double free = std::max(1, rp.grid.free_cells());
    int last = -1;
    // A step curve: one point where the visited count changes, and the end.
    for (std::size_t i = 0; i < rp.points.size(); ++i) {
      if (rp.visited[i] == last && i + 1 != rp.points.size()) continue;
      last = rp.visited[i];
      const double pct = 100.0 * double(rp.visited[i]) / free;
      s.x.push_back(rp.points[i].t);
      s.y.push_back(pct);
      csv.add_row({std::to_string(id), format_number(rp.points[i].t), fixed_cell(pct, 4)});
    }
    p.series.push_back(std::move(s));
  }
  csv.write_file(out.csv, TableFormat::csv);
  render(p, path, opt.size);
  return out;
}

// ------------------------------------------------------------- line plots

// A statistic of column y (median by default) per value of column x, one
// series per value of --by (e.g. seed 003's coverage vs n).
FigureOutput line_figure(const ResultSet& rs, const FigureOptions& opt, const std::string& path) {
  if (opt.x.empty() || opt.y.empty()) throw AnalysisError("line: give the axes with --x COLUMN --y COLUMN");
  (void)rs.num(opt.x), (void)rs.num(opt.y);
  const std::string stat = opt.stat == "min" && opt.stat_default ? "median" : opt.stat;
  LinePlot p;
  p.title = stat + " of " + opt.y + " over " + opt.x;
  p.xlabel = axis_label(opt.x);
  p.ylabel = stat + " " + axis_label(opt.y);
  TextTable csv;
  csv.header = {opt.by.empty() ? "series" : opt.by, opt.x, stat + "_" + opt.y, "runs"};
  std::vector<Group> series;
  if (opt.by.empty()) {
    Group all;
    all.key = {"all"};
    all.key_num = {0.0};
    all.rows = all_rows(rs);
    series.push_back(std::move(all));
  } else {
    series = group_rows(rs, {opt.by}, all_rows(rs));
  }
  for (const Group& s : series) {
    LineSeries line{opt.by.empty() ? "" : opt.by + " " + s.key[0], {}, {}};
    for (const Group& g : group_rows(rs, {opt.x}, s.rows)) {
      std::vector<double> v;
      for (std::size_t r : g.rows) v.push_back(rs.num(opt.y)[r]);
      const double y = value_statistic(std::move(v), stat);
      line.x.push_back(g.key_num[0]);
      line.y.push_back(y);
      csv.add_row({s.key[0], g.key[0], sig_cell(y, 6), std::to_string(g.rows.size())});
    }
    p.series.push_back(std::move(line));
  }
  FigureOutput out{path, csv_beside(path), {}};
  csv.write_file(out.csv, TableFormat::csv);
  render(p, path, opt.size);
  return out;
}

// ------------------------------------------------- the Chebyshev map itself

// Seed 001, Figs. 2-3: the orbit's histogram raw and after the arcsine
// transform (k = 6, x0 = 0.1, n = 2000 as in the paper, 20 bins), with the
// chi-square statistics against flat and arcsine densities printed.
FigureOutput cheb_histogram(const FigureOptions& opt, const std::string& path) {
  const int k = 6, bins = 20;
  const long n = 2000;
  const auto raw = orbit_histogram(k, 0.1, n, bins, ChebTransform::none);
  const auto flat = orbit_histogram(k, 0.1, n, bins, ChebTransform::arcsine);
  LinePlot p;
  p.title = "Chebyshev map k = 6: orbit histogram, raw and arcsine-transformed";
  p.xlabel = "value";
  p.ylabel = "share of the orbit (%)";
  TextTable csv;
  csv.header = {"bin_lo", "bin_hi", "raw_count", "arcsine_count"};
  LineSeries a{"raw x", {}, {}}, b{"(2/pi) asin x", {}, {}};
  for (int i = 0; i < bins; ++i) {
    const double lo = -1.0 + 2.0 * i / bins, hi = -1.0 + 2.0 * (i + 1) / bins;
    for (double x : {lo, hi}) {  // steps
      a.x.push_back(x), a.y.push_back(100.0 * double(raw[std::size_t(i)]) / double(n));
      b.x.push_back(x), b.y.push_back(100.0 * double(flat[std::size_t(i)]) / double(n));
    }
    csv.add_row({format_number(lo), format_number(hi), std::to_string(raw[std::size_t(i)]),
                 std::to_string(flat[std::size_t(i)])});
  }
  double top = 0;
  for (double y : a.y) top = std::max(top, y);
  p.y_range = {0.0, 1.1 * top};
  p.series = {std::move(a), std::move(b)};
  FigureOutput out{path, csv_beside(path), {}};
  out.lines.push_back("chi-square vs flat (19 dof, 99.9% critical 43.8): raw " + fmt_sig(chi_square_uniform(raw), 5) +
                      ", arcsine-transformed " + fmt_sig(chi_square_uniform(flat), 5) +
                      "; raw vs the arcsine density: " + fmt_sig(chi_square_arcsine(raw), 5));
  csv.write_file(out.csv, TableFormat::csv);
  render(p, path, opt.size);
  return out;
}

// Seed 001, Figs. 1b and 5: the largest Lyapunov exponent over k, of the raw
// map and of the arcsine-transformed one (a conjugate: both ln k), beside
// what the paper's Eq. 7 gives when averaged as printed.
FigureOutput cheb_lyapunov(const FigureOptions& opt, const std::string& path) {
  const long n = 200000;
  LinePlot p;
  p.title = "Chebyshev map: largest Lyapunov exponent over k";
  p.xlabel = "k";
  p.ylabel = "Lyapunov exponent";
  LineSeries raw{"raw map", {}, {}}, conj{"after arcsine transform", {}, {}}, eq7{"paper's Eq. 7, as printed", {}, {}};
  TextTable csv;
  csv.header = {"k", "raw", "arcsine", "eq7_as_printed", "ln_k"};
  for (int k = 2; k <= 10; ++k) {
    const double a = lyapunov_exponent(k, 0.1, n), b = lyapunov_exponent_arcsine(k, 0.1, n),
                 c = lyapunov_paper_eq7(k, 0.1, n);
    raw.x.push_back(k), raw.y.push_back(a);
    conj.x.push_back(k), conj.y.push_back(b);
    eq7.x.push_back(k), eq7.y.push_back(c);
    csv.add_row({std::to_string(k), fixed_cell(a, 5), fixed_cell(b, 5), fixed_cell(c, 5), fixed_cell(std::log(k), 5)});
  }
  conj.colour = 1, conj.dash = 2;  // dashed: the raw map's line (the same values) shows through
  p.series = {std::move(raw), std::move(conj), std::move(eq7)};
  p.mark = PlotMark{6, std::log(6.0), "ln 6 = 1.7918 (paper: 3.2147)"};
  FigureOutput out{path, csv_beside(path), {}};
  csv.write_file(out.csv, TableFormat::csv);
  render(p, path, opt.size);
  return out;
}

// Seed 002: the best mixture's (Eq. 5 fitted on the configurations) limiting
// distribution over the position cells as a heatmap (relative to uniform: 1 =
// the uniform share); the CSV holds every policy's column too.
FigureOutput seed002_limit(const FigureOptions& opt, const std::string& path) {
  BouncingPaperOptions so;
  so.bins = opt.bins;
  const BouncingPaperAnalysis a = analyse_seed002(so);
  const bouncing_paper::CellGrid& g = a.grid;
  if (opt.policy < 0 || opt.policy > int(a.Pi.cols()))
    throw AnalysisError("--policy must be 0 (the mixture) or 1.." + std::to_string(a.Pi.cols()));
  const Eigen::VectorXd mix =
      opt.policy == 0 ? Eigen::VectorXd(a.Pi * a.alpha) : Eigen::VectorXd(a.Pi.col(opt.policy - 1));
  HeatmapPlot p;
  p.title = opt.policy == 0 ? "Seed 002: limiting distribution of the best mixture (x uniform)"
                            : "Seed 002: limiting distribution of the " +
                                  format_number(so.angles[std::size_t(opt.policy - 1)]) + "-degree policy (x uniform)";
  p.xlabel = "x (m)";
  p.ylabel = "y (m)";
  p.zlabel = "pi / uniform";
  p.empty_label = "grey: obstacle cells";
  for (int i = 0; i < g.nx; ++i) p.xs.push_back((i + 0.5) * g.cell);
  for (int j = 0; j < g.ny; ++j) p.ys.push_back((j + 0.5) * g.cell);
  p.z.assign(std::size_t(g.nx * g.ny), nan);
  TextTable csv;
  csv.header = {"x", "y", opt.policy == 0 ? "mixture" : "shown_policy"};
  for (double phi : so.angles) csv.header.push_back("policy_" + format_number(phi));
  for (int f = 0; f < g.num_free(); ++f) {
    const int cell = g.free_cells[std::size_t(f)];
    const double rel = mix(f) * g.num_free();
    p.z[std::size_t(cell)] = rel;
    const auto [cx, cy] = g.centre(f);
    std::vector<Cell> row{format_number(cx), format_number(cy), sig_cell(mix(f), 6)};
    for (Eigen::Index k = 0; k < a.Pi.cols(); ++k) row.push_back(sig_cell(a.Pi(f, k), 6));
    csv.add_row(std::move(row));
  }
  FigureOutput out{path, csv_beside(path), {}};
  std::ostringstream alpha;
  for (Eigen::Index k = 0; k < a.alpha.size(); ++k) alpha << (k ? ", " : "") << fmt_fixed(a.alpha(k), 3);
  out.lines.push_back("alpha = (" + alpha.str() +
                      "), fitted on the configurations (Eq. 5), ||Pi alpha - b|| = " + fmt_sig(a.residual, 4));
  csv.write_file(out.csv, TableFormat::csv);
  render(p, path, opt.size);
  return out;
}

FigureOutput heatmap(const ResultSet& rs, const FigureOptions& opt, const std::string& path) {
  if (opt.x.empty() || opt.y.empty()) throw AnalysisError("heatmap: give the two axes with --x COLUMN --y COLUMN");
  return heatmap_figure(rs, opt.x, opt.y, opt.stat, opt.stat + " of coverage time over " + opt.x + " and " + opt.y,
                        std::nullopt, opt, path);
}

struct FigureKind {
  std::string name;
  bool needs_results;
  FigureOutput (*make)(const ResultSet&, const FigureOptions&, const std::string&);
  bool per_file = false;  // a curve per file: make_per_file_figure
};

// Every figure `chaosweep figure` knows: its dispatch, its list of names and
// `--help`'s list are all this one list.
const std::vector<FigureKind>& figure_kinds() {
  static const std::vector<FigureKind> kinds{
      {"fig6a", true, fig6a},
      {"fig6b", true, fig6b},
      {"heatmap", true, heatmap},
      {"line", true, line_figure},
      {"trajectory", true, trajectory},
      {"coverage", true, coverage},
      {"ct_distribution", true,
       [](const ResultSet& rs, const FigureOptions& o, const std::string& p) {
         return ct_distribution({LabelledResults{"results", rs}}, o, p);
       },
       true},
      {"leaderboard", true, leaderboard_figure},
      {"cheb_histogram", false,
       [](const ResultSet&, const FigureOptions& o, const std::string& p) { return cheb_histogram(o, p); }},
      {"cheb_lyapunov", false,
       [](const ResultSet&, const FigureOptions& o, const std::string& p) { return cheb_lyapunov(o, p); }},
      {"seed002_limit", false,
       [](const ResultSet&, const FigureOptions& o, const std::string& p) { return seed002_limit(o, p); }},
  };
  return kinds;
}

const FigureKind& figure_kind(const std::string& name) { return find_named(figure_kinds(), name, "figure"); }

}  // namespace

bool figure_needs_results(const std::string& name) { return figure_kind(name).needs_results; }

std::string csv_beside(const std::string& image_path) {
  return std::filesystem::path(image_path).replace_extension(".csv").string();
}

const std::vector<std::string>& figure_names() {
  static const std::vector<std::string> names = names_of(figure_kinds());
  return names;
}

bool figure_per_file(const std::string& name) { return figure_kind(name).per_file; }

FigureOutput make_per_file_figure(const std::string& name, const std::vector<std::string>& files,
                                  const std::vector<std::string>& where, const FigureOptions& opt,
                                  const std::string& image_path) {
  if (!figure_kind(name).per_file) throw AnalysisError("figure " + name + " reads the files' rows together");
  check_image_path(image_path);
  if (files.empty()) throw AnalysisError("give one or more result files (.h5)");
  const std::vector<std::string> labels = file_labels(files);
  std::vector<LabelledResults> sets;
  for (std::size_t i = 0; i < files.size(); ++i) {
    ResultSet rs = ResultSet::load({files[i]});
    if (rs.rows() == 0) throw AnalysisError(files[i] + " holds no runs");
    sets.push_back({labels[i], where.empty() ? std::move(rs) : rs.where(where)});
  }
  return ct_distribution(sets, opt, image_path);
}

FigureOutput make_figure(const std::string& name, const ResultSet& rs, const FigureOptions& opt,
                         const std::string& image_path) {
  const FigureKind& kind = figure_kind(name);
  check_image_path(image_path);
  if (kind.needs_results && rs.rows() == 0) throw AnalysisError("the result files hold no runs");
  return kind.make(rs, opt, image_path);
}

}  // namespace chaosweep

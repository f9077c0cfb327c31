#include "replay.hpp"

#include <cmath>

#include "param_table.hpp"
#include "planner.hpp"

namespace chaosweep {

namespace {

class CollectingSink final : public TraceSink {
 public:
  explicit CollectingSink(std::vector<TracePoint>& out) : out_(out) {}
  void point(const TracePoint& p) override { out_.push_back(p); }

 private:
  std::vector<TracePoint>& out_;
};

RunSpec spec_of_row(const ResultSet& rs, std::size_t r) {
  RunSpec s;
  for (const ParamInfo& p : param_table()) {
    const std::string name(p.name);
    if (!rs.has(name)) throw AnalysisError("cannot rebuild the run: the results have no column '" + name + "'");
    double v;
    if (p.kind == ParamInfo::Kind::choice) {
      const auto idx = p.choice_index(rs.text(name)[r]);
      if (!idx) throw AnalysisError("cannot rebuild the run: '" + rs.text(name)[r] + "' is not a value of " + name);
      v = *idx;
    } else {
      v = rs.num(name)[r];
    }
    p.set(s.params, v);
  }
  s.env = rs.text("env")[r];
  if (rs.has("label")) s.label = rs.text("label")[r];
  return s;
}

}  // namespace

std::size_t row_of_run(const ResultSet& rs, std::int64_t id) {
  const auto& ids = rs.num("run_id");
  std::size_t found = rs.rows();
  for (std::size_t r = 0; r < ids.size(); ++r) {
    if (ids[r] != double(id)) continue;
    if (found != rs.rows())
      throw AnalysisError("run_id " + std::to_string(id) + " occurs in more than one row; give one result file");
    found = r;
  }
  if (found == rs.rows()) throw AnalysisError("no run with run_id " + std::to_string(id) + " in the results");
  return found;
}

Replay replay_row(const ResultSet& rs, std::size_t r) {
  EnvironmentCache cache;
  RunTuple tuple;
  try {
    tuple = resolve_run(std::int64_t(rs.num("run_id")[r]), spec_of_row(rs, r), cache);
  } catch (const AnalysisError&) {
    throw;
  } catch (const std::exception& e) {
    throw AnalysisError("cannot rebuild run " + rs.cell("run_id", r) + ": " + e.what());
  }
  std::vector<TracePoint> points;
  CollectingSink sink(points);
  const RunRow row = evaluate(tuple, &sink);
  Replay out{tuple, row.result, std::move(points), {}, CoverageGrid(*tuple.env, tuple.params.sr), {}};
  // The covered cells, by the kernel's own marking rule between trace points.
  bool first = true;
  double px = 0, py = 0;
  for (const TracePoint& p : out.points) {
    if (first || tuple.params.sampling == Sampling::points) out.grid.mark_point(p.x, p.y);
    else out.grid.mark_segment(px, py, p.x, p.y);
    first = false;
    px = p.x, py = p.y;
    out.visited.push_back(out.grid.visited_cells());
  }
  const std::string status = to_string(row.result.status);
  if (status != rs.text("status")[r]) out.mismatch = "status " + status + " vs stored " + rs.text("status")[r];
  else if (rs.has("steps") && double(row.result.steps) != rs.num("steps")[r])
    out.mismatch = "steps " + std::to_string(row.result.steps) + " vs stored " + rs.cell("steps", r);
  else if (!(row.result.coverage_time == rs.num("coverage_time")[r]) &&
           !(std::isnan(row.result.coverage_time) && std::isnan(rs.num("coverage_time")[r])))
    out.mismatch = "coverage_time " + format_number(row.result.coverage_time) + " vs stored " + rs.cell("coverage_time", r);
  return out;
}

}  // namespace chaosweep

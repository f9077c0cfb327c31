#include "analysis/replay.hpp"

#include <cmath>

#include "engine/run/serial_batch_evaluator.hpp"
#include "engine/store/stored_run.hpp"
#include "kernels/core/param_table.hpp"
#include "kernels/planners/planner.hpp"

namespace chaosweep {

namespace {

class CollectingSink final : public TraceSink {
 public:
  explicit CollectingSink(std::vector<TracePoint>& out) : out_(out) {}
  void point(const TracePoint& p) override { out_.push_back(p); }

 private:
  std::vector<TracePoint>& out_;
};

// Row r's cells, for the engine to rebuild its run from.
StoredRow stored_row_of(const ResultSet& rs, std::size_t r) {
  StoredRow row;
  for (const std::string& name : rs.names()) {
    if (rs.is_numeric(name)) row.numeric[name] = rs.num(name)[r];
    else row.text[name] = rs.text(name)[r];
  }
  return row;
}

}  // namespace

std::size_t row_of_run(const ResultSet& rs, std::int64_t id) {
  try {
    return row_of_run_id(rs.num("run_id"), id, "the results");
  } catch (const SpecError& e) {
    throw AnalysisError(e.what());
  }
}

Replay replay_row(const ResultSet& rs, std::size_t r) {
  EnvironmentCache cache;
  const StoredRow stored = stored_row_of(rs, r);
  RunTuple tuple;
  try {
    tuple = resolve_run(std::int64_t(rs.num("run_id")[r]), run_spec_of(stored), cache);
  } catch (const SpecError& e) {
    throw AnalysisError(e.what());
  } catch (const std::exception& e) {
    throw AnalysisError("cannot rebuild run " + rs.cell("run_id", r) + ": " + e.what());
  }
  std::vector<TracePoint> points;
  CollectingSink sink(points);
  const RunRow row{tuple, SerialBatchEvaluator(&sink).evaluate(tuple)};
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
  for (const ColumnDifference& d : compare_row(stored, row).differences)
    out.mismatch += (out.mismatch.empty() ? "" : ", ") + d.column + " " + d.rerun + " vs stored " + d.stored;
  return out;
}

}  // namespace chaosweep

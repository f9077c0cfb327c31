#include "engine/rows/result_columns.hpp"

#include <algorithm>

#include "engine/rows/run_hash.hpp"
#include "kernels/core/param_table.hpp"

namespace chaosweep {

namespace {

using Type = Column::Type;

Column f64(std::string name, double (*g)(const RunRow&), bool det = true) {
  return {std::move(name), Type::f64, 0, [g](const RunRow& r) { return CellValue(g(r)); }, det};
}
Column i64(std::string name, std::int64_t (*g)(const RunRow&)) {
  return {std::move(name), Type::i64, 0, [g](const RunRow& r) { return CellValue(g(r)); }, true};
}
Column text(std::string name, std::size_t size, std::string (*g)(const RunRow&)) {
  return {std::move(name), Type::text, size, [g](const RunRow& r) { return CellValue(g(r)); }, true};
}

constexpr std::size_t variable = 0;

// Fixed storage for a word of `choices`: the longest, its NUL, and room.
std::size_t word_size(const std::vector<std::string_view>& choices) {
  std::size_t n = 0;
  for (std::string_view c : choices) n = std::max(n, c.size());
  return std::max<std::size_t>(16, n + 1);
}

std::vector<Column> make_columns() {
  std::vector<Column> c;
  c.push_back(i64("run_id", [](const RunRow& r) { return r.tuple.run_id; }));
  c.push_back(i64("param_hash", [](const RunRow& r) { return param_hash(r.tuple.params, r.tuple.env_spec); }));
  c.push_back(text("env", variable, [](const RunRow& r) { return r.tuple.env_spec; }));
  c.push_back(text("label", variable, [](const RunRow& r) { return r.tuple.label; }));
  c.push_back(text("variant", 48, [](const RunRow& r) { return variant_name(r.tuple.params); }));
  // Every run parameter, named as in the parameter table.
  for (const ParamInfo& p : param_table()) {
    const ParamInfo* info = &p;
    switch (p.kind) {
      case ParamInfo::Kind::real:
        c.push_back({std::string(p.name), Type::f64, 0,
                     [info](const RunRow& r) { return CellValue(info->get(r.tuple.params)); }, true});
        break;
      case ParamInfo::Kind::integer:
        c.push_back({std::string(p.name), Type::i64, 0,
                     [info](const RunRow& r) { return CellValue(std::int64_t(info->get(r.tuple.params))); }, true});
        break;
      case ParamInfo::Kind::choice:
        c.push_back(
            {std::string(p.name), Type::text, word_size(p.choices),
             [info](const RunRow& r) { return CellValue(std::string(info->choices[int(info->get(r.tuple.params))])); },
             true});
        break;
    }
  }
  c.push_back(text("status", 12, [](const RunRow& r) { return std::string(to_string(r.result.status)); }));
  c.push_back(f64("coverage_time", [](const RunRow& r) { return r.result.coverage_time; }));
  c.push_back(f64("final_coverage", [](const RunRow& r) { return r.result.final_coverage; }));
  c.push_back(i64("steps", [](const RunRow& r) { return r.result.steps; }));
  c.push_back(f64("t_end", [](const RunRow& r) { return r.result.t_end; }));
  c.push_back(f64("t_opt", [](const RunRow& r) { return r.result.t_opt; }));
  c.push_back(f64("pr", [](const RunRow& r) { return r.result.pr; }));
  c.push_back(i64("free_cells", [](const RunRow& r) { return r.result.free_cells; }));
  c.push_back(i64("visited_cells", [](const RunRow& r) { return r.result.visited_cells; }));
  c.push_back(i64("dt_halvings", [](const RunRow& r) { return r.result.dt_halvings; }));
  c.push_back(f64("final_x", [](const RunRow& r) { return r.result.final_x; }));
  c.push_back(f64("final_y", [](const RunRow& r) { return r.result.final_y; }));
  c.push_back(i64("segments", [](const RunRow& r) { return r.result.segments; }));
  c.push_back(i64("index_switches", [](const RunRow& r) { return r.result.index_switches; }));
  c.push_back(i64("zonings", [](const RunRow& r) { return r.result.zonings; }));
  c.push_back(i64("transits", [](const RunRow& r) { return r.result.transits; }));
  c.push_back(i64("zones_dropped", [](const RunRow& r) { return r.result.zones_dropped; }));
  c.push_back(i64("transit_points", [](const RunRow& r) { return r.result.transit_points; }));
  c.push_back(i64("transit_attempts", [](const RunRow& r) { return r.result.transit_attempts; }));
  c.push_back(i64("final_ds_index", [](const RunRow& r) { return std::int64_t(r.result.final_ds_index); }));
  c.push_back(i64("subgoals", [](const RunRow& r) { return r.result.subgoals; }));
  c.push_back(i64("reflections", [](const RunRow& r) { return r.result.reflections; }));
  c.push_back(f64("visit_evenness", [](const RunRow& r) { return r.result.visit_evenness; }));
  c.push_back(f64("turn_entropy", [](const RunRow& r) { return r.result.turn_entropy; }));
  c.push_back(f64("coverage_area", [](const RunRow& r) { return r.result.coverage_area; }));
  c.push_back(i64("race_round", [](const RunRow& r) { return r.tuple.race_round; }));
  c.push_back(i64("config_id", [](const RunRow& r) { return r.tuple.config_id; }));
  c.push_back(text("message", variable, [](const RunRow& r) { return r.result.message; }));
  c.push_back(f64(
      "wall_time", [](const RunRow& r) { return r.result.wall_time; }, false));
  return c;
}

}  // namespace

const std::vector<Column>& result_columns() {
  static const std::vector<Column> columns = make_columns();
  return columns;
}

const Column* find_column(const std::string& name) {
  for (const Column& c : result_columns())
    if (c.name == name) return &c;
  return nullptr;
}

}  // namespace chaosweep

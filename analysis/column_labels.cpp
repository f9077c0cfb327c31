#include "analysis/column_labels.hpp"

#include <map>

#include "kernels/core/param_table.hpp"

namespace chaosweep {

namespace {

// The measured columns (engine/rows/result_columns.cpp), as docs/parameters.md describes them.
const std::map<std::string, std::string>& measured() {
  static const std::map<std::string, std::string> m{
      {"run_id", "run id"},
      {"coverage_time", "coverage time (s)"},
      {"final_coverage", "final coverage (share of cells)"},
      {"steps", "integration steps"},
      {"t_end", "end time (s)"},
      {"t_opt", "T_opt (s)"},
      {"pr", "PR = CT / T_opt"},
      {"free_cells", "free cells"},
      {"visited_cells", "visited cells"},
      {"dt_halvings", "step halvings"},
      {"final_x", "final x (m)"},
      {"final_y", "final y (m)"},
      {"segments", "path segments"},
      {"index_switches", "ds_index switches"},
      {"zonings", "map zonings"},
      {"transits", "transits (count)"},
      {"zones_dropped", "zones dropped"},
      {"transit_points", "transit points"},
      {"transit_attempts", "transit attempts"},
      {"final_ds_index", "final ds_index"},
      {"subgoals", "sub-goals"},
      {"reflections", "reflections (count)"},
      {"visit_evenness", "evenness of cell visits (Pielou, 0-1)"},
      {"turn_entropy", "turn entropy between cell entries (bits)"},
      {"coverage_area", "coverage area (mean first-visit time / T_opt)"},
      {"race_round", "race round"},
      {"config_id", "configuration"},
      {"wall_time", "wall time (s)"},
  };
  return m;
}

// "contraction planner: RK2 steps of the trajectory (map, mirror)" -> "RK2
// steps of the trajectory"; "robot speed, m/s" -> meaning "robot speed",
// unit "m/s". Long descriptions give the name alone.
std::string from_help(const std::string& name, std::string help) {
  if (const auto colon = help.find(": "); colon != std::string::npos && colon < 30) help.erase(0, colon + 2);
  if (const auto paren = help.find(" ("); paren != std::string::npos) help.erase(paren);
  for (const char* cut : {"; ", " = "})
    if (const auto c = help.find(cut); c != std::string::npos) help.erase(c);
  std::string unit;
  if (const auto comma = help.rfind(", "); comma != std::string::npos) {
    const std::string tail = help.substr(comma + 2);
    if (tail == "m" || tail == "s" || tail == "m/s" || tail == "degrees") unit = tail, help.erase(comma);
  }
  if (help.size() > name.size() + 1 && help.compare(help.size() - name.size() - 1, std::string::npos, " " + name) == 0)
    help.erase(help.size() - name.size() - 1);  // "Arnold coefficient A" -> "Arnold coefficient"
  std::string label = name;
  if (!help.empty() && name.size() + help.size() <= 42 && help.find(',') == std::string::npos) label += ": " + help;
  if (!unit.empty()) label += " (" + unit + ")";
  return label;
}

}  // namespace

std::string axis_label(const std::string& column) {
  if (const auto it = measured().find(column); it != measured().end()) return it->second;
  if (const ParamInfo* p = find_param(column)) return from_help(column, std::string(p->help));
  return column;
}

}  // namespace chaosweep

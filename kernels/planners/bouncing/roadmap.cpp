#include "kernels/planners/bouncing/roadmap.hpp"

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>
#include <sstream>

namespace chaosweep::bouncing_paper {

Roadmap build_roadmap(const CellGrid& grid, const std::vector<double>& angles_deg, double w1, double w2,
                      const GcmOptions& opts) {
  Roadmap rm;
  rm.configs = grid.num_configs();
  rm.policies = static_cast<int>(angles_deg.size());
  rm.angles_deg = angles_deg;
  std::vector<CellMap> maps;
  for (double a : angles_deg) maps.push_back(build_cell_map(grid, a, 0.0, 1.0, opts));
  const int m = rm.policies;
  rm.start.reserve(static_cast<std::size_t>(rm.configs) * m + 1);
  rm.start.push_back(0);
  for (int z = 0; z < rm.configs; ++z)
    for (int i = 0; i < m; ++i) {
      // Forward moves do not depend on the policy: take them from map i.
      const CellMap& mi = maps[i];
      for (int e = mi.row_start[z]; e < mi.row_start[z + 1]; ++e)
        if (!mi.bump[e]) rm.to.push_back(mi.to[e] * m + i), rm.weight.push_back(w1), rm.step.push_back({i, false});
      for (int k = 0; k < m; ++k) {
        const CellMap& mk = maps[k];
        for (int e = mk.row_start[z]; e < mk.row_start[z + 1]; ++e)
          if (mk.bump[e])
            rm.to.push_back(mk.to[e] * m + k), rm.weight.push_back(k == i ? w1 : w2), rm.step.push_back({k, true});
      }
      rm.start.push_back(static_cast<int>(rm.to.size()));
    }
  return rm;
}

ShortestTree shortest_tree(const Roadmap& rm, int source_config) {
  const int nv = rm.configs * rm.policies;
  ShortestTree t;
  t.source = source_config;
  t.dist.assign(nv, std::numeric_limits<double>::infinity());
  t.pred.assign(nv, -1);
  using Item = std::pair<double, int>;  // (dist, vertex): ties pop the lower vertex first
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  for (int i = 0; i < rm.policies; ++i) {
    const int v = source_config * rm.policies + i;
    t.dist[v] = 0.0;
    heap.emplace(0.0, v);
  }
  while (!heap.empty()) {
    const auto [d, v] = heap.top();
    heap.pop();
    if (d > t.dist[v]) continue;
    for (int e = rm.start[v]; e < rm.start[v + 1]; ++e) {
      const int w = rm.to[e];
      // Strict improvement only: the first-found (lowest-vertex) path wins ties.
      if (d + rm.weight[e] < t.dist[w] && w / rm.policies != source_config) {
        t.dist[w] = d + rm.weight[e];
        t.pred[w] = e;
        heap.emplace(t.dist[w], w);
      }
    }
  }
  return t;
}

namespace {
// Roadmap vertex an edge starts from (binary search in the CSR offsets).
int edge_source(const Roadmap& rm, int e) {
  return static_cast<int>(std::upper_bound(rm.start.begin(), rm.start.end(), e) - rm.start.begin()) - 1;
}
}  // namespace

std::optional<Plan> plan_to(const Roadmap& rm, const ShortestTree& tree, int goal_config) {
  int best = -1;
  for (int i = 0; i < rm.policies; ++i) {
    const int v = goal_config * rm.policies + i;
    if (best < 0 ? tree.dist[v] < std::numeric_limits<double>::infinity() : tree.dist[v] < tree.dist[best]) best = v;
  }
  if (best < 0) return std::nullopt;
  Plan p;
  p.weight = tree.dist[best];
  if (goal_config == tree.source) {
    p.weight = 0.0;
    p.configs = {goal_config};
    return p;
  }
  for (int v = best; tree.pred[v] >= 0; v = edge_source(rm, tree.pred[v])) {
    p.steps.push_back(rm.step[tree.pred[v]]);
    p.configs.push_back(v / rm.policies);
  }
  p.configs.push_back(tree.source);
  std::reverse(p.steps.begin(), p.steps.end());
  std::reverse(p.configs.begin(), p.configs.end());
  return p;
}

std::optional<Plan> minimum_plan(const Roadmap& rm, int source_config, int goal_config) {
  return plan_to(rm, shortest_tree(rm, source_config), goal_config);
}

std::string observation_string(const Plan& plan, const std::vector<double>& angles_deg) {
  std::ostringstream s;
  for (const PlanStep& st : plan.steps) {
    if (st.bump) s << angles_deg[st.policy] << "\u00b0";
    else s << '0';
  }
  return s.str();
}

PlanRow all_plans_from(const Roadmap& rm, int source_config) {
  const ShortestTree t = shortest_tree(rm, source_config);
  PlanRow row;
  row.plans.resize(rm.configs);
  row.weights.assign(rm.configs, -1.0);
  for (int g = 0; g < rm.configs; ++g)
    if (auto p = plan_to(rm, t, g)) {
      row.plans[g] = observation_string(*p, rm.angles_deg);
      row.weights[g] = p->weight;
    }
  return row;
}

}  // namespace chaosweep::bouncing_paper

#pragma once
// Seed 002, Algorithms 1-2: the roadmap over configuration cells and the
// minimum navigation plan (an observation string) between two configurations.
//
// The paper's union of per-policy graphs G_i has vertices = cells only, so a
// rotation by phi_k is always available at w1 (from G_k) and w2 would never
// matter. To honour "minimum number of bouncing angle changes" the roadmap's
// vertices are (configuration, current policy): a forward step keeps the
// policy (weight w1, observation '0'); a bump under policy k moves to the
// rotated configuration with policy k, weight w1 if k is the current policy,
// else w2 (observation phi_k). The start policy is free (every (x_I, i) starts
// at 0); the goal is x_G under any policy. Rotations are reliable (eps = 0).
#include <optional>
#include <string>
#include <vector>

#include "kernels/planners/bouncing/bouncing_cells.hpp"

namespace chaosweep::bouncing_paper {

struct PlanStep {
  int policy;  // the policy in force after this step
  bool bump;   // true: bump + rotation by angle[policy] (observation phi); false: forward ('0')
  bool operator==(const PlanStep&) const = default;
};

struct Roadmap {
  int configs = 0, policies = 0;
  std::vector<double> angles_deg;
  // CSR over vertices v = config * policies + policy.
  std::vector<int> start;
  std::vector<int> to;
  std::vector<double> weight;
  std::vector<PlanStep> step;
};

Roadmap build_roadmap(const CellGrid& grid, const std::vector<double>& angles_deg, double w1, double w2,
                      const GcmOptions& opts = {});

// Dijkstra from one source configuration (all start policies), over the whole
// roadmap: one row of Algorithm 2. Independent per source, so callers may run
// sources in parallel.
struct ShortestTree {
  int source = -1;
  std::vector<double> dist;  // per roadmap vertex; +inf when unreachable
  std::vector<int> pred;     // per vertex: the edge index that reached it, -1 at the roots
};
ShortestTree shortest_tree(const Roadmap& rm, int source_config);

struct Plan {
  double weight = 0.0;
  std::vector<PlanStep> steps;  // empty when source == goal
  std::vector<int> configs;     // configurations visited, source first, goal last
};
// The minimum plan to goal_config (min over the final policy, lowest policy
// index on ties), or nullopt if the goal is unreachable.
std::optional<Plan> plan_to(const Roadmap& rm, const ShortestTree& tree, int goal_config);
std::optional<Plan> minimum_plan(const Roadmap& rm, int source_config, int goal_config);

// The paper's observation string: '0' per forward step, the bouncing angle in
// degrees followed by "°" per bump, e.g. "00000090°00090°".
std::string observation_string(const Plan& plan, const std::vector<double>& angles_deg);

// Algorithm 2, one source: M[source][*] and L[source][*]. L is -1 where no
// plan exists and 0 with an empty M on the diagonal.
struct PlanRow {
  std::vector<std::string> plans;
  std::vector<double> weights;
};
PlanRow all_plans_from(const Roadmap& rm, int source_config);

}  // namespace chaosweep::bouncing_paper

#pragma once
// Seed 002: strongly connected components (Tarjan, iterative: the GCM graphs
// have ~1e5 nodes and long chains, too deep for recursion) and persistent
// groups (SCCs with no edge leaving them: closed communicating classes).
#include <cstdint>
#include <vector>

namespace chaosweep::bouncing_paper {

// Directed graph in CSR form: the successors of v are adj[start[v] .. start[v+1]).
struct Digraph {
  std::vector<int> start;  // n + 1
  std::vector<int> adj;
  int size() const { return static_cast<int>(start.size()) - 1; }
};

struct Scc {
  std::vector<int> component;  // node -> component id
  int count = 0;
  // Component ids follow Tarjan's completion order: a component's successors
  // get smaller ids (sinks first, reverse topological order).
  std::vector<std::uint8_t> closed;  // per component: no edge leaves it (persistent group)
};

Scc tarjan_scc(const Digraph& g);

// Per node: index of its persistent group (0.., numbered by increasing
// component id) or -1 for a transient node; `groups` receives the count.
std::vector<int> persistent_groups(const Scc& scc, int* groups = nullptr);

}  // namespace chaosweep::bouncing_paper

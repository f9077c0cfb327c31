#include "kernels/planners/bouncing/scc.hpp"

#include <algorithm>

namespace chaosweep::bouncing_paper {

Scc tarjan_scc(const Digraph& g) {
  const int n = g.size();
  Scc out;
  out.component.assign(n, -1);
  std::vector<int> index(n, -1), low(n, 0), next_edge(n, 0);
  std::vector<int> stack, call;  // Tarjan's node stack and the explicit DFS stack
  std::vector<std::uint8_t> on_stack(n, 0);
  int counter = 0;
  for (int root = 0; root < n; ++root) {
    if (index[root] >= 0) continue;
    call.push_back(root);
    index[root] = low[root] = counter++;
    next_edge[root] = g.start[root];
    stack.push_back(root), on_stack[root] = 1;
    while (!call.empty()) {
      const int v = call.back();
      if (next_edge[v] < g.start[v + 1]) {
        const int w = g.adj[next_edge[v]++];
        if (index[w] < 0) {
          index[w] = low[w] = counter++;
          next_edge[w] = g.start[w];
          stack.push_back(w), on_stack[w] = 1;
          call.push_back(w);
        } else if (on_stack[w]) {
          low[v] = std::min(low[v], index[w]);
        }
        continue;
      }
      // v is finished: pop its component if it is a root, then return to the parent.
      if (low[v] == index[v]) {
        int w;
        do {
          w = stack.back();
          stack.pop_back();
          on_stack[w] = 0;
          out.component[w] = out.count;
        } while (w != v);
        ++out.count;
      }
      call.pop_back();
      if (!call.empty()) low[call.back()] = std::min(low[call.back()], low[v]);
    }
  }
  out.closed.assign(out.count, 1);
  for (int v = 0; v < n; ++v)
    for (int e = g.start[v]; e < g.start[v + 1]; ++e)
      if (out.component[g.adj[e]] != out.component[v]) out.closed[out.component[v]] = 0;
  return out;
}

std::vector<int> persistent_groups(const Scc& scc, int* groups) {
  std::vector<int> group_of_comp(scc.count, -1);
  int k = 0;
  for (int c = 0; c < scc.count; ++c)
    if (scc.closed[c]) group_of_comp[c] = k++;
  if (groups) *groups = k;
  std::vector<int> out(scc.component.size());
  for (std::size_t v = 0; v < out.size(); ++v) out[v] = group_of_comp[scc.component[v]];
  return out;
}

}  // namespace chaosweep::bouncing_paper

#include "kernels/planners/bouncing/markov_chain.hpp"

#include <Eigen/SparseLU>
#include <stdexcept>

namespace chaosweep::bouncing_paper {

SparseMatrix transition_matrix(const CellMap& m) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(m.to.size());
  for (int i = 0; i < m.n; ++i)
    for (int e = m.row_start[i]; e < m.row_start[i + 1]; ++e) t.emplace_back(i, m.to[e], m.prob[e]);
  SparseMatrix P(m.n, m.n);
  P.setFromTriplets(t.begin(), t.end());  // sums duplicates (a forward and a bump to one cell)
  return P;
}

Digraph support_graph(const SparseMatrix& P) {
  const int n = static_cast<int>(P.rows());
  Digraph g;
  g.start.assign(n + 1, 0);
  for (int k = 0; k < P.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(P, k); it; ++it)
      if (it.value() > 0.0) ++g.start[it.row() + 1];
  for (int i = 0; i < n; ++i) g.start[i + 1] += g.start[i];
  g.adj.resize(g.start[n]);
  std::vector<int> fill(g.start.begin(), g.start.end() - 1);
  for (int k = 0; k < P.outerSize(); ++k)  // column-major: targets come in increasing order
    for (SparseMatrix::InnerIterator it(P, k); it; ++it)
      if (it.value() > 0.0) g.adj[fill[it.row()]++] = static_cast<int>(it.col());
  return g;
}

namespace {

void solve_check(Eigen::ComputationInfo info) {
  if (info != Eigen::Success) throw std::runtime_error("seed002: sparse LU failed");
}

// Stationary distribution of one irreducible group: pi (I - P_gg) = 0 with
// sum pi = 1, solved as (I - P_gg)^T pi = 0 whose last equation is replaced
// by the normalisation (the rank deficiency of an irreducible chain is one).
Eigen::VectorXd group_stationary(const SparseMatrix& P, const std::vector<int>& members,
                                 const std::vector<int>& local) {
  const int k = static_cast<int>(members.size());
  if (k == 1) return Eigen::VectorXd::Ones(1);
  std::vector<Eigen::Triplet<double>> t;
  for (int a = 0; a < k - 1; ++a) t.emplace_back(a, a, 1.0);
  for (int b = 0; b < k; ++b) t.emplace_back(k - 1, b, 1.0);
  // Row lj of A = (I - P_gg)^T holds -P(i, j) for members i; only the
  // members' columns of P are read (a group is closed: all its mass stays).
  for (int lj = 0; lj < k - 1; ++lj)
    for (SparseMatrix::InnerIterator it(P, members[lj]); it; ++it) {
      const int li = local[it.row()];
      if (li >= 0) t.emplace_back(lj, li, -it.value());
    }
  SparseMatrix A(k, k);
  A.setFromTriplets(t.begin(), t.end());
  Eigen::SparseLU<SparseMatrix> lu;
  lu.compute(A);
  solve_check(lu.info());
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(k);
  rhs(k - 1) = 1.0;
  Eigen::VectorXd pi = lu.solve(rhs);
  solve_check(lu.info());
  return pi;
}

}  // namespace

Limit limiting_distribution(const SparseMatrix& P) {
  return limiting_distribution(P, Eigen::VectorXd::Constant(P.rows(), 1.0 / P.rows()));
}

Limit limiting_distribution(const SparseMatrix& P, const Eigen::VectorXd& p0) {
  const int n = static_cast<int>(P.rows());
  Limit out;
  const Scc scc = tarjan_scc(support_graph(P));
  out.group = persistent_groups(scc, &out.groups);

  // Mass ending in each persistent state: its own p0 plus what the transient
  // states send: y^T R with (I - Q)^T y = p0_T (y = expected visits).
  std::vector<int> tlocal(n, -1), transients;
  for (int i = 0; i < n; ++i)
    if (out.group[i] < 0) tlocal[i] = static_cast<int>(transients.size()), transients.push_back(i);
  Eigen::VectorXd arrive = p0;
  if (!transients.empty()) {
    const int nt = static_cast<int>(transients.size());
    std::vector<Eigen::Triplet<double>> t;
    for (int a = 0; a < nt; ++a) t.emplace_back(a, a, 1.0);
    for (int kk = 0; kk < P.outerSize(); ++kk)
      for (SparseMatrix::InnerIterator it(P, kk); it; ++it) {
        const int li = tlocal[it.row()], lj = tlocal[it.col()];
        if (li >= 0 && lj >= 0) t.emplace_back(lj, li, -it.value());  // (I - Q)^T
      }
    SparseMatrix A(nt, nt);
    A.setFromTriplets(t.begin(), t.end());
    Eigen::SparseLU<SparseMatrix> lu;
    lu.compute(A);
    solve_check(lu.info());
    Eigen::VectorXd rhs(nt);
    for (int a = 0; a < nt; ++a) rhs(a) = p0(transients[a]);
    const Eigen::VectorXd y = lu.solve(rhs);
    solve_check(lu.info());
    for (int i : transients) arrive(i) = 0.0;
    for (int kk = 0; kk < P.outerSize(); ++kk)
      for (SparseMatrix::InnerIterator it(P, kk); it; ++it) {
        const int li = tlocal[it.row()];
        if (li >= 0 && out.group[it.col()] >= 0) arrive(it.col()) += y(li) * it.value();
      }
  }

  out.group_mass.assign(out.groups, 0.0);
  std::vector<std::vector<int>> members(out.groups);
  for (int i = 0; i < n; ++i)
    if (out.group[i] >= 0) out.group_mass[out.group[i]] += arrive(i), members[out.group[i]].push_back(i);
  out.pi = Eigen::VectorXd::Zero(n);
  std::vector<int> local(n, -1);
  for (int g = 0; g < out.groups; ++g) {
    if (out.group_mass[g] <= 0.0) continue;  // unreachable from p(0): no mass to place
    for (std::size_t a = 0; a < members[g].size(); ++a) local[members[g][a]] = static_cast<int>(a);
    const Eigen::VectorXd pg = group_stationary(P, members[g], local);
    for (std::size_t a = 0; a < members[g].size(); ++a) {
      out.pi(members[g][a]) = out.group_mass[g] * pg(a);
      local[members[g][a]] = -1;
    }
  }
  return out;
}

Eigen::VectorXd position_marginal(const CellGrid& grid, const Eigen::VectorXd& pi) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(grid.num_free());
  for (int c = 0; c < grid.num_configs(); ++c) out(grid.free_of(c)) += pi(c);
  return out;
}

Eigen::VectorXd policy_coverage(const CellGrid& grid, double phi_deg, double eps_deg, double r,
                                const GcmOptions& opts) {
  const SparseMatrix P = transition_matrix(build_cell_map(grid, phi_deg, eps_deg, r, opts));
  return position_marginal(grid, limiting_distribution(P).pi);
}

}  // namespace chaosweep::bouncing_paper

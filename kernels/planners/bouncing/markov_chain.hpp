#pragma once
// Seed 002, Algorithm 3 (per policy): the GCM Markov chain, its persistent
// groups and its limiting distribution.
//
// "Limiting distribution" with several persistent groups (or transients)
// depends on the start; we report the Cesaro limit lim (1/n) sum_k p(0) P^k
// from p(0) uniform over all configuration cells (transient and persistent),
// i.e. sum_g m_g pi_g with m_g the probability of ending in group g and pi_g
// the group's stationary distribution. It is zero on transient cells, sums to
// 1, and exists for periodic groups too (a deterministic bounce cycle is
// periodic, so plain p(n) need not converge).
//
// Both pi_g and m_g are sparse LU solves (Eigen::SparseLU), not power
// iteration: power iteration does not converge on periodic groups and mixes
// slowly on large ones; a direct solve is exact and deterministic.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "kernels/planners/bouncing/bouncing_cells.hpp"
#include "kernels/planners/bouncing/scc.hpp"

namespace chaosweep::bouncing_paper {

// P(i, j) = Pr(config i -> config j); rows sum to 1.
using SparseMatrix = Eigen::SparseMatrix<double>;

SparseMatrix transition_matrix(const CellMap& m);

// The edges i -> j with P(i, j) > 0.
Digraph support_graph(const SparseMatrix& P);

struct Limit {
  Eigen::VectorXd pi;      // per state, sums to 1, zero on transients
  std::vector<int> group;  // per state: persistent group or -1 (transient)
  int groups = 0;
  std::vector<double> group_mass;  // m_g: probability of ending in group g
};

Limit limiting_distribution(const SparseMatrix& P);  // p(0) uniform
Limit limiting_distribution(const SparseMatrix& P, const Eigen::VectorXd& p0);

// pi over configurations -> pi over free position cells (sum over bins).
Eigen::VectorXd position_marginal(const CellGrid& grid, const Eigen::VectorXd& pi);

// One column of Pi: build_cell_map -> transition_matrix -> limiting
// distribution -> position marginal.
Eigen::VectorXd policy_coverage(const CellGrid& grid, double phi_deg, double eps_deg, double r,
                                const GcmOptions& opts = {});

}  // namespace chaosweep::bouncing_paper

#pragma once
// Seed 002, Eq. 5: the policy mixture alpha >= 0, sum alpha = 1 minimising
// ||Pi alpha - b||_2 (Pi: one column per policy, its limiting distribution
// over free position cells; b: the target, e.g. uniform).
//
// Exact active-set enumeration: the problem is a convex QP on the simplex, so
// its optimum is the equality-constrained least-squares optimum of some face
// (support S) that is feasible (alpha_S >= 0). We solve the KKT system of
// every non-empty support (2^m - 1 of them) and keep the best feasible one.
// Exact and deterministic for the few policies the paper uses; refused above
// max_policies (a projected-gradient solver would be the tool there).
#include <Eigen/Core>

namespace chaosweep::bouncing_paper {

struct Mixture {
  Eigen::VectorXd alpha;
  double residual = 0.0;  // ||Pi alpha - b||_2
};

inline constexpr int kMaxMixturePolicies = 16;

Mixture best_mixture(const Eigen::MatrixXd& Pi, const Eigen::VectorXd& b);

double mixture_residual(const Eigen::MatrixXd& Pi, const Eigen::VectorXd& b, const Eigen::VectorXd& alpha);

}  // namespace chaosweep::bouncing_paper

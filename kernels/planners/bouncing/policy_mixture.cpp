#include "kernels/planners/bouncing/policy_mixture.hpp"

#include <Eigen/Dense>
#include <limits>
#include <stdexcept>
#include <vector>

namespace chaosweep::bouncing_paper {

double mixture_residual(const Eigen::MatrixXd& Pi, const Eigen::VectorXd& b, const Eigen::VectorXd& alpha) {
  return (Pi * alpha - b).norm();
}

Mixture best_mixture(const Eigen::MatrixXd& Pi, const Eigen::VectorXd& b) {
  const int m = static_cast<int>(Pi.cols());
  if (m < 1 || m > kMaxMixturePolicies) throw std::invalid_argument("seed002: best_mixture needs 1..16 policies");
  if (Pi.rows() != b.size()) throw std::invalid_argument("seed002: Pi and b disagree in size");
  const Eigen::MatrixXd G = Pi.transpose() * Pi;  // Gram matrix: m x m, all we need
  const Eigen::VectorXd c = Pi.transpose() * b;
  Mixture best;
  best.residual = std::numeric_limits<double>::infinity();
  constexpr double tol = 1e-12;
  for (unsigned mask = 1; mask < (1u << m); ++mask) {
    std::vector<int> s;
    for (int i = 0; i < m; ++i)
      if (mask & (1u << i)) s.push_back(i);
    const int k = static_cast<int>(s.size());
    // KKT of min a^T G_S a - 2 c_S^T a s.t. 1^T a = 1:  [G_S 1; 1^T 0][a; mu] = [c_S; 1].
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(k + 1, k + 1);
    Eigen::VectorXd rhs(k + 1);
    for (int a = 0; a < k; ++a) {
      for (int bb = 0; bb < k; ++bb) K(a, bb) = G(s[a], s[bb]);
      K(a, k) = K(k, a) = 1.0;
      rhs(a) = c(s[a]);
    }
    rhs(k) = 1.0;
    // Complete orthogonal decomposition: a least-norm answer when G_S is
    // singular (e.g. two identical columns); checked for feasibility below.
    const Eigen::VectorXd sol = K.completeOrthogonalDecomposition().solve(rhs);
    Eigen::VectorXd alpha = Eigen::VectorXd::Zero(m);
    bool feasible = true;
    for (int a = 0; a < k; ++a) {
      if (!(sol(a) >= -tol)) feasible = false;
      alpha(s[a]) = std::max(0.0, sol(a));
    }
    if (!feasible || std::abs(alpha.sum() - 1.0) > 1e-9) continue;
    alpha /= alpha.sum();
    const double res = mixture_residual(Pi, b, alpha);
    if (res < best.residual - 1e-15) best.alpha = alpha, best.residual = res;
  }
  return best;  // singletons are always feasible, so best is set
}

}  // namespace chaosweep::bouncing_paper

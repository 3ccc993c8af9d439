#include "solver/largest_eigenvalue.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

namespace fetic::solver {
namespace {

// The largest eigenvalue of the tridiagonal matrix (diagonal, off) and the last
// component of its unit eigenvector.
std::pair<double, double> largest_ritz(const std::vector<double>& diagonal,
                                       const std::vector<double>& off) {
  const auto m = static_cast<Eigen::Index>(diagonal.size());
  if (m == 1) return {diagonal[0], 1.0};
  const Eigen::VectorXd d = Eigen::Map<const Eigen::VectorXd>(diagonal.data(), m);
  const Eigen::VectorXd e = Eigen::Map<const Eigen::VectorXd>(off.data(), m - 1);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver;
  solver.computeFromTridiagonal(d, e, Eigen::ComputeEigenvectors);
  return {solver.eigenvalues()(m - 1), solver.eigenvectors()(m - 1, m - 1)};
}

}  // namespace

EigenvalueEstimate largest_eigenvalue(const LanczosOperator& op, Eigen::VectorXd start,
                                      const LanczosStop& stop) {
  EigenvalueEstimate estimate;
  const double size = std::sqrt(std::max(0.0, op.dot(start, start)));
  if (!(size > 0.0)) return estimate;
  Eigen::VectorXd v = start / size, previous = Eigen::VectorXd::Zero(v.size()), w;
  std::vector<double> diagonal, off;
  double beta = 0.0;
  while (estimate.products < stop.max_products) {
    op.before_product();
    op.apply(v, w);
    ++estimate.products;
    const double alpha = op.dot(w, v);
    w -= alpha * v + beta * previous;
    diagonal.push_back(alpha);
    beta = std::sqrt(std::max(0.0, op.dot(w, w)));
    const auto [ritz, last] = largest_ritz(diagonal, off);
    estimate.ritz = ritz;
    estimate.residual = beta * std::abs(last);
    // beta vanishing against the operator's scale: the Krylov space is invariant, the
    // Ritz values are eigenvalues (and a zero operator ends here with ritz 0).
    const bool invariant = !(beta > 1e-14 * std::max(ritz, std::abs(alpha)));
    estimate.converged = invariant || estimate.residual <= stop.tolerance * ritz;
    if (invariant || (estimate.converged && estimate.products >= stop.min_products)) break;
    off.push_back(beta);
    previous = std::move(v);
    v = w / beta;
  }
  return estimate;
}

}  // namespace fetic::solver

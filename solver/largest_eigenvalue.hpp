#pragma once
// The largest eigenvalue of a symmetric positive semidefinite operator known only by its
// products, by the Lanczos method (docs/METHODS.md, "MPRGP": the estimate of ||A||).
// MPRGP's expansion step needs alpha_bar in (0, 2/||A||]; the power method it replaces
// took 10 products to come within 3.5% below ||A||, Lanczos' largest Ritz value
// gets closer in fewer, because it uses the whole Krylov space, not only its last vector.
//
// Step k holds the tridiagonal T_k of the k Lanczos vectors. Its largest eigenvalue theta
// (the Ritz value) is a lower bound of lambda_max; its Ritz vector y has the residual
// r = ||A y - theta y|| = beta_k |s_k| (s the eigenvector of T_k, beta_k the next
// off-diagonal), and some eigenvalue of A lies within r of theta. Lanczos finds the
// largest eigenvalue first, so theta + r bounds lambda_max from above once that Ritz
// value has separated from the others. The stop: r <= tolerance * theta after at least
// min_products (a start close to another eigenvector has a small residual at once), an
// invariant Krylov space (beta_k = 0: theta exact), or max_products. The estimate can
// still fall short where the start holds almost nothing of the top eigenvector (the
// power method fell further there); the tests and docs/METHODS.md give how often.
//
// Plain three-term recurrence, three vectors: rounding's loss of orthogonality shows
// only after the largest Ritz value has converged (Paige), which is where it stops.

#include <functional>

#include <Eigen/Core>

namespace fetic::solver {

struct EigenvalueEstimate {
  double ritz = 0.0;       // the largest Ritz value: <= lambda_max
  double residual = 0.0;   // ||A y - ritz y||, y its unit Ritz vector
  int products = 0;        // applications of the operator
  bool converged = false;  // residual <= tolerance * ritz (or an invariant subspace)
  double upper() const { return ritz + residual; }
};

struct LanczosOperator {
  // out = A x; A symmetric positive semidefinite on the subspace `start` lies in.
  std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& out)> apply;
  // The scalar product A is symmetric in (collective under mpirun: DualSpace::dot).
  std::function<double(const Eigen::VectorXd& a, const Eigen::VectorXd& b)> dot;
  // Called before each product (interruption).
  std::function<void()> before_product = [] {};
};

// `start` need not be normalized; a zero start gives a zero estimate and no product.
struct LanczosStop {
  double tolerance = 0.05;  // residual <= tolerance * ritz
  int min_products = 3;     // not before (a start near another eigenvector looks converged)
  int max_products = 10;
};
EigenvalueEstimate largest_eigenvalue(const LanczosOperator& op, Eigen::VectorXd start,
                                      const LanczosStop& stop);

}  // namespace fetic::solver

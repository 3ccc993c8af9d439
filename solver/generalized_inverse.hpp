#pragma once
// K^+ of a symmetric positive semidefinite stiffness K whose kernel is known (rigid-body
// modes R of a floating strut or subdomain): the DOFs that best pin R are fixed, the
// rest of K is factorized once by CHOLMOD, and K^+ x = [K_rr^-1 x_r; 0]. This is a
// generalized inverse (K K^+ K = K) exactly when the fixed DOFs remove only ker K, so a
// breakdown of the factorization means a singularity the rigid-body modes do not explain.

#include <vector>

#include <Eigen/Core>

#include "solver/cholmod_factor.hpp"

namespace fetic::solver {

class GeneralizedInverse {
 public:
  // `kernel` spans ker K (zero columns for a regular K).
  CholmodFactor::Result factorize(const SparseMatrix& K, const Eigen::MatrixXd& kernel);

  int size() const { return size_; }
  const std::vector<int>& fixed_dofs() const { return fixed_; }
  // Original DOF where the factorization broke down, or -1.
  int failed_dof() const;
  double rcond() const { return factor_.rcond(); }
  std::size_t factor_nonzeros() const { return factor_.factor_nonzeros(); }
  std::size_t peak_memory() const { return factor_.peak_memory(); }

  // y = K^+ x for `columns` column-major right-hand sides. Not reentrant.
  void apply(const double* x, double* y, int columns = 1) const;
  Eigen::VectorXd apply(const Eigen::VectorXd& x) const;

 private:
  int size_ = 0;
  std::vector<int> fixed_;
  std::vector<int> kept_;  // factorized DOFs, in order
  CholmodFactor factor_;
  mutable Eigen::MatrixXd rhs_, solution_;
};

// DOFs (rows of `kernel`) whose rows form the best-conditioned square block of the
// kernel, chosen by QR with column pivoting of kernel'.
std::vector<int> choose_fixing_dofs(const Eigen::MatrixXd& kernel);

}  // namespace fetic::solver

#pragma once
// K^+ of a symmetric positive semidefinite stiffness K whose kernel is known (rigid-body
// modes R of a floating strut or subdomain): the DOFs that best pin R are fixed, the
// rest of K is factorized once by CHOLMOD, and K^+ x = [K_rr^-1 x_r; 0]. This is a
// generalized inverse (K K^+ K = K) exactly when the fixed DOFs remove only ker K, so a
// breakdown of the factorization means a singularity the rigid-body modes do not explain.

#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "solver/boundary_last.hpp"
#include "solver/cholmod_factor.hpp"

namespace fetic::solver {

class GeneralizedInverse {
 public:
  // `kernel` spans ker K (zero columns for a regular K).
  CholmodFactor::Result factorize(const SparseMatrix& K, const Eigen::MatrixXd& kernel);
  // The same for the Dirichlet preconditioner too, whose S_j is the Schur complement of K
  // onto `boundary` (sorted DOFs). By default one factor with the boundary last
  // (solver/boundary_last.hpp): the fixing DOFs chosen among the boundary's, K's kept
  // DOFs ordered interior first, then the boundary (CAMD); apply_boundary_schur()
  // applies S_j from the factor's trailing block. Where the boundary's rows pin the kernel
  // badly, or there is no interior (or with use_boundary_last(false)): a second factor, of
  // the interior block K_ii, for interior_solve(); each factor then has its own
  // fill-reducing ordering, and has_interior_solve() is false when there is no interior
  // or K_ii is singular.
  CholmodFactor::Result factorize(const SparseMatrix& K, const Eigen::MatrixXd& kernel,
                                  const std::vector<int>& boundary);
  void use_boundary_last(bool boundary_last) { boundary_last_ = boundary_last; }
  bool has_boundary_schur() const { return schur_ != nullptr; }
  // y = S_j x over the boundary DOFs given to factorize() (in their order).
  void apply_boundary_schur(const double* x, double* y) const {
    schur_->apply(*factor_.compact_factor(), x, y);
  }
  // The factor's first boundary row: F's solves are on its rows from there on
  // (CompactFactor::solve_trailing_in_place).
  int boundary_schur_first() const { return schur_->first(); }
  // Bytes one apply_boundary_schur() reads: the factor's trailing columns and T's map.
  std::size_t boundary_schur_bytes() const {
    return factor_.compact_factor()->trailing_bytes(schur_->first()) + schur_->bytes();
  }
  // Keep the factors' entries below the diagonal as floats (CompactFactor), for the
  // factorizations after this call.
  void use_single_precision(bool single) { single_ = single; }
  // The same for K_ii's factor alone (on by default). Only the Dirichlet preconditioner
  // solves with it, so its rounding changes the preconditioner M^-1 - still a fixed
  // symmetric positive definite operator - and not the problem solved: the iterations
  // converge to the same answer at the same tolerance (tests/solver/local_factor_test.cpp)
  // while K_ii's entries take 6 bytes instead of 10 (docs/BENCHMARKS.md, issue 25).
  void use_single_precision_interior(bool single) { single_interior_ = single; }
  // Factorize small factors simplicial (CholmodFactor::factorize's `to_compact`): FETI's
  // thousands of subdomains. Off by default, so that the primal methods' strut blocks
  // keep CHOLMOD's own choice and their answers' round-off.
  void use_simplicial_when_small(bool simplicial) { simplicial_ = simplicial; }
  bool has_interior_solve() const { return interior_factor_.size() > 0; }
  // y = K_ii^-1 x over the interior DOFs (those not in the boundary, in increasing order).
  void interior_solve(const double* x, double* y) const;

  int size() const { return size_; }
  const std::vector<int>& fixed_dofs() const { return fixed_; }
  // Original DOF where the factorization broke down, or -1.
  int failed_dof() const;
  double rcond() const { return factor_.rcond(); }
  std::size_t factor_nonzeros() const { return factor_.factor_nonzeros(); }
  std::size_t interior_nonzeros() const { return interior_factor_.factor_nonzeros(); }
  std::size_t peak_memory() const { return factor_.peak_memory() + interior_factor_.peak_memory(); }
  // Bytes held now by K's factor and by K_ii's.
  std::size_t factor_memory() const { return factor_.memory_in_use(); }
  std::size_t interior_memory() const { return interior_factor_.memory_in_use(); }
  std::size_t index_memory() const {
    return (fixed_.capacity() + kept_.capacity()) * sizeof(int) + (schur_ ? schur_->bytes() : 0);
  }

  // y = K^+ x for `columns` column-major right-hand sides. Not reentrant.
  void apply(const double* x, double* y, int columns = 1) const;
  // The lean copies of the factors (null where CHOLMOD keeps its own), for callers that
  // solve in place in the factor's order (CompactFactor::solve_in_place) and so skip
  // apply()'s gathers and scatters: K's, whose row k is DOF
  // kept_dofs()[permutation()[k]] (the fixed DOFs, whose rows of K^+ are zero, are not
  // among them), and K_ii's, whose row k is interior DOF permutation()[k] (interior DOFs
  // numbered in increasing order).
  const CompactFactor* compact_factor() const { return factor_.compact_factor(); }
  const std::vector<int>& kept_dofs() const { return kept_; }
  const CompactFactor* compact_interior_factor() const { return interior_factor_.compact_factor(); }
  // K's lean factor laid out for solves on `rows` (its order) alone
  // (CompactFactor::reach_first): F's fused pass. K_ii's is laid out so at factorize(),
  // for the interior DOFs K couples to the boundary: the Dirichlet preconditioner's.
  void reach_first(const std::vector<int>& rows) { factor_.compact_factor()->reach_first(rows); }
  Eigen::VectorXd apply(const Eigen::VectorXd& x) const;

 private:
  int size_ = 0;
  std::vector<int> fixed_;
  std::vector<int> kept_;  // factorized DOFs, in order
  CholmodFactor::Result factorize_kept(const SparseMatrix& K);
  std::vector<int> keep_unfixed();
  std::optional<CholmodFactor::Result> factorize_boundary_last(const SparseMatrix& K,
                                                               const Eigen::MatrixXd& kernel,
                                                               const std::vector<int>& boundary);
  CholmodFactor::Result compacted(CholmodFactor::Result result);
  static void reach_coupled_rows(const SparseMatrix& K, const std::vector<int>& position,
                                 CompactFactor& factor);
  CholmodFactor factor_;
  CholmodFactor interior_factor_;         // K_ii's (empty unless asked for)
  std::unique_ptr<BoundarySchur> schur_;  // the boundary-last path's S_j (else null)
  bool boundary_last_ = true;
  bool single_ = false;
  bool single_interior_ = true;
  bool simplicial_ = false;
};

// DOFs (rows of `kernel`) whose rows form the best-conditioned square block of the
// kernel, chosen by QR with column pivoting of kernel'.
std::vector<int> choose_fixing_dofs(const Eigen::MatrixXd& kernel);

}  // namespace fetic::solver

#pragma once
// One subdomain factor with the boundary last (issue 25; docs/BENCHMARKS.md, "One
// subdomain factor with the boundary last"). With K's kept DOFs ordered [interior...,
// boundary...] - boundary: the DOFs B touches, the DOFs fixing K's kernel chosen among
// them, so that the leading block is all of K_ii - the factor is
//   L = [L_11 0; L_21 L_22],  L_11 L_11' = K_ii,  L_22 L_22' = S_kk,
// S_kk the Schur complement of K onto its kept boundary DOFs. F's solves, whose right-hand
// sides and results are on the boundary alone, need only L_22 (CompactFactor::reach_first
// holds it), and so does the Dirichlet preconditioner's S_j = K_bb - K_bi K_ii^-1
// K_ib: S_j R_b = 0 (K R = 0), so S_j = T' S_kk T with T x = x_k - R_k R_f^-1 x_f (R_k,
// R_f: the kernel's rows at the kept and the fixed boundary DOFs), and T = I for a regular
// K. No K_ii factor, no K_ib and K_bb, one ordering and one symbolic pass per subdomain.

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "solver/compact_factor.hpp"
#include "solver/stiffness.hpp"

namespace fetic::solver {

// The DOFs (sorted) fixing `kernel` chosen among the rows `boundary` (sorted DOFs) as
// choose_fixing_dofs() chooses among all rows; none when those rows pin the kernel much
// worse than the best rows of all (the smallest singular value of the chosen rows, the
// kernel's columns normalized, under kWorseFixing times that of choose_fixing_dofs()'s).
inline constexpr double kWorseFixing = 0.1;
std::optional<std::vector<int>> choose_boundary_fixing_dofs(const Eigen::MatrixXd& kernel,
                                                            const std::vector<int>& boundary);

// Row k of P A P' is row order[k] of A: the rows with on_boundary[row] == 0 first, then the
// others, in CAMD's fill-reducing order under that constraint (A's lower triangle given).
std::vector<int> interior_first_order(const SparseMatrix& A, const std::vector<char>& on_boundary);

// S_j applied from the trailing block of K's factor in interior_first_order().
class BoundarySchur {
 public:
  // `first`: the factor's first boundary row; `factor_row`: per boundary DOF (in order)
  // its row in the factor, -1 for a fixed DOF; `kernel_rows`: the kernel's rows at the
  // boundary DOFs (zero columns for a regular K).
  BoundarySchur(int first, const std::vector<int>& factor_row, const Eigen::MatrixXd& kernel_rows);
  // y = S_j x over the boundary DOFs (both in the boundary's order).
  void apply(const CompactFactor& factor, const double* x, double* y) const;
  std::size_t bytes() const;
  int first() const { return first_; }

 private:
  int first_ = 0;
  std::vector<int> kept_at_;   // per trailing row, its place in the boundary
  std::vector<int> fixed_at_;  // per fixed DOF, its place in the boundary
  Eigen::MatrixXd map_;        // R_k R_f^-1, a row per trailing row
};

}  // namespace fetic::solver

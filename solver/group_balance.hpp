#pragma once
// MPRGP's balance constraints for the groups of struts the equality rows leave free and
// only contacts hold (docs/METHODS.md, "MPRGP"): for each such free direction z of the
// coarse space, c_z = G'z on the contact rows, C = [c_z ...], and
// Q_C x = C (C'C)^+ C'x, the orthogonal projector onto span C.
//
// Each c_z is nonzero only on the contact rows of its group, so C is kept by its nonzeros
// and C'C falls apart into blocks of groups linked by shared rows (a block is mostly the
// few free motions of one body); each block's pseudo-inverse is small and dense. The cost
// is linear in the number of groups: a dense Gram-Schmidt over all of them was cubic
// (300 copies of a beam held only by contacts took 113 s to set up, 1,000 did not finish).
// A block of more than kMaxBlock groups is refused (SolverError) rather than factorized
// densely for minutes.

#include <vector>

#include <Eigen/Core>
#include <Eigen/QR>

#include "solver/coarse_problem.hpp"
#include "solver/feti_system.hpp"

namespace fetic::solver {

class GroupBalance {
 public:
  // Groups that share rows through contacts, at most this many in one block.
  static constexpr int kMaxBlock = 1000;

  GroupBalance() = default;
  // The groups among `groups` that touch a contact row (the others are left to the
  // boundedness check). Collective. Polls for interrupts.
  GroupBalance(const FetiSystem& system, const std::vector<UnheldGroup>& groups);

  int size() const { return static_cast<int>(columns_.size()); }
  bool empty() const { return columns_.empty(); }
  // C'x: one exact scalar product per group, reduced at once (collective).
  Eigen::VectorXd transpose_times(const Eigen::VectorXd& x) const;
  // C a, over the local rows.
  Eigen::VectorXd times(const Eigen::VectorXd& a) const;
  // (C'C)^+ y: the least-norm least-squares solution, block by block.
  Eigen::VectorXd gram_solve(const Eigen::VectorXd& y) const;
  // Q_C x (collective).
  Eigen::VectorXd project(const Eigen::VectorXd& x) const {
    return times(gram_solve(transpose_times(x)));
  }
  // z'e for every group's direction z (e over the coarse space).
  Eigen::VectorXd direction_dots(const Eigen::VectorXd& e) const;
  // out += sum_i a_i z_i.
  void add_directions(const Eigen::VectorXd& a, Eigen::VectorXd& out) const;

 private:
  struct SparseColumn {
    std::vector<int> index;
    std::vector<double> value;
  };
  struct Block {
    std::vector<int> groups;
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> gram;
  };
  void keep_groups_with_contacts(const FetiSystem& system, const std::vector<UnheldGroup>& groups);
  void factorize_blocks();

  const DualSpace* space_ = nullptr;
  std::vector<SparseColumn> columns_;     // c_z over the local contact rows
  std::vector<SparseColumn> directions_;  // z over the modes
  std::vector<Block> blocks_;
};

}  // namespace fetic::solver

#pragma once
// The dual (multiplier) vectors the FETI methods iterate on, as this process holds them:
// one entry per row of B that touches one of its subdomains, in increasing global row
// order (so equality rows come first, then contact rows). Every scalar product, norm
// and decision that involves all rows goes through here, so a method never needs to
// know whether the other rows live in this process or in others (MPI). In one process
// every row is held and the reductions are plain loops.
//
// Rules for methods: take scalar products and norms of dual vectors only through
// dot()/norm()/max_abs(); combine per-row decisions over all processes with any()/sum();
// index rows only through kind()/is_contact() and first_contact().

#include <vector>

#include <Eigen/Core>

#include "solver/decomposition.hpp"

namespace fetic::solver {

class DualSpace {
 public:
  explicit DualSpace(const Decomposition& decomposition);

  int rows() const { return static_cast<int>(kind_.size()); }
  int first_contact() const { return first_contact_; }
  RowKind kind(int row) const { return kind_[row]; }
  bool is_contact(int row) const { return kind_[row] == RowKind::Contact; }

  double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;
  double norm(const Eigen::VectorXd& a) const;
  double max_abs(const Eigen::VectorXd& a) const;
  // Reductions of one number per process.
  double sum(double value) const { return value; }
  double max(double value) const { return value; }
  bool any(bool value) const { return value; }

 private:
  std::vector<RowKind> kind_;
  int first_contact_ = 0;
};

}  // namespace fetic::solver

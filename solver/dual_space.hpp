#pragma once
// The dual (multiplier) vectors the FETI methods iterate on, as this process holds them:
// one entry per row of B that touches one of its subdomains ("local rows"), in
// increasing global row order - so equality rows come first, then contact rows. A row
// that joins subdomains of two processes is held by both, with the same value: every
// operation keeps the copies equal (F and the preconditioner end with `complete_rows`,
// which adds the partial sums of the processes holding a row). Each row is owned by the
// process of its lowest subdomain; scalar products count owned rows only.
//
// Every scalar product, norm and decision that involves all rows goes through here, so
// a method never needs to know whether the other rows live in this process or in others.
// In one process every row is local and the reductions are plain loops.
//
// Rules for methods: take scalar products and norms of dual vectors only through
// dot()/norm()/max_abs(); combine per-row decisions over all processes with any()/sum();
// index rows only through kind()/is_contact() and first_contact().

#include <vector>

#include <Eigen/Core>

#include "solver/communicator.hpp"
#include "solver/decomposition.hpp"
#include "solver/partition.hpp"

namespace fetic::solver {

class DualSpace {
 public:
  // All rows in one process.
  explicit DualSpace(const Decomposition& decomposition);
  // The rows touching the subdomains `partition` gives to `communicator.rank()`.
  DualSpace(const Decomposition& decomposition, const Partition& partition,
            const Communicator& communicator);

  const Communicator& communicator() const { return *communicator_; }
  int rows() const { return static_cast<int>(kind_.size()); }
  int first_contact() const { return first_contact_; }
  RowKind kind(int row) const { return kind_[row]; }
  bool is_contact(int row) const { return kind_[row] == RowKind::Contact; }
  int global_row(int row) const { return global_[row]; }
  bool owned(int row) const { return owned_.empty() || owned_[row]; }
  // Local index of a global row, or -1 when this process does not hold it.
  int local_row(int global_row) const { return local_[global_row]; }
  int global_rows() const { return static_cast<int>(local_.size()); }
  // Local rows another process holds too.
  int shared_rows() const { return static_cast<int>(send_.size()); }

  // Summed exactly (exact_sum.hpp): the same bits for any number of processes.
  double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;
  double norm(const Eigen::VectorXd& a) const;
  double max_abs(const Eigen::VectorXd& a) const;
  // Reductions of one number per process.
  double sum(double value) const { return communicator_->sum(value); }
  double max(double value) const { return communicator_->max(value); }
  bool any(bool value) const { return communicator_->any(value); }

  // Rows shared with other processes hold this process' partial sum on entry and the
  // sum over all processes (in rank order) on return.
  void complete_rows(Eigen::VectorXd& partial) const;
  // The values the other process holds for the shared rows, without adding (set-up).
  // Returns, per local row, the other process' value (0 where no other process holds it).
  Eigen::VectorXd other_side(const Eigen::VectorXd& mine) const;

 private:
  // Sends this process' values of the shared rows to their peers, receives theirs (receive_).
  void exchange_shared_rows(const Eigen::VectorXd& values) const;
  struct Peer {
    int rank = 0;
    std::vector<int> rows;  // local rows shared with it, increasing
  };

  const Communicator* communicator_;
  std::vector<RowKind> kind_;
  std::vector<int> global_;
  std::vector<int> local_;
  std::vector<char> owned_;  // empty: all owned
  int first_contact_ = 0;
  std::vector<Peer> peers_;
  std::vector<ExchangePeer> exchange_peers_;
  mutable std::vector<double> send_, receive_;
};

}  // namespace fetic::solver

#pragma once
// A numeric supernodal Cholesky factorization P A P' = L L' of a small sparse SPD matrix (a
// FETI subdomain's K_j or K_ii, ~1,000 unknowns) computed straight into CompactFactor's
// layout (solver/compact_factor.hpp): per supernode the strict lower triangle packed by
// columns, then the dense m x nc block of its rows below, one row list per supernode.
// AMD (SuiteSparse, called directly) chooses the fill-reducing permutation; the rest is
// done here. For these sizes
// CHOLMOD's simplicial up-looking factorization (a sparse triangular solve per row) and
// the copy of its columns into supernodes were most of the FETI set-up, and its own
// supernodal factorization spends more time in BLAS call overheads than in arithmetic
// (docs/BENCHMARKS.md, "Subdomain factors computed in the compact layout").
//
// Symbolic (solver/elimination_tree.hpp): the elimination tree of P A P' and L's column
// counts (Gilbert, Ng and Peyton: the row subtrees' leaves), the fundamental supernodes (a
// column whose parent is the next column, its only child, with one entry fewer), merged
// greedily with the following ones while at most CompactFactor::kRelaxedZeros of the
// merged supernode's stored entries are zeros, as CompactFactor does with given columns. Numeric:
// left-looking by supernodes. Each supernode's columns are gathered from A into a dense (nc + m) x
// nc workspace, every earlier supernode whose rows reach into its columns subtracts its update
// there (dense loops over its block, scattered through a row map), then the dense trapezoid is
// factorized and packed. Entries that cancel to zero are kept (CHOLMOD's simplicial path
// dropped them: rare in stiffness matrices, docs/BENCHMARKS.md).

#include <cstddef>
#include <memory>
#include <vector>

#include "solver/compact_factor.hpp"
#include "solver/stiffness.hpp"

namespace fetic::solver {

class SupernodalFactorization {
 public:
  // P A P' = L L' for the symmetric A (its lower triangle is read) and `permutation`
  // (row k of P A P' is row permutation[k] of A). Returns -1, or the column of P A P'
  // whose pivot was not positive (CHOLMOD's `minor`): L is then incomplete.
  int factorize(const SparseMatrix& A, const int* permutation);
  // The same on AMD's ordering of A (as CHOLMOD's analysis calls it: default controls),
  // postordered by the elimination tree as CHOLMOD postorders it.
  int factorize(const SparseMatrix& A);
  const std::vector<int>& permutation() const { return permutation_; }

  int size() const { return size_; }
  // Stored entries of L: the diagonal and the supernodes' (their zeros included).
  std::size_t nonzeros() const { return stored_ + diagonal_.size(); }
  int supernodes() const { return static_cast<int>(first_.size()) - 1; }
  // Bytes held now (the factor before it is compacted).
  std::size_t bytes() const;
  // min(diag L)^2 / max(diag L)^2, as CHOLMOD estimates rcond of an LL' factor.
  double rcond() const;
  // The factor as a CompactFactor (its entries below the diagonal as floats: `single`).
  std::unique_ptr<CompactFactor> compact(bool single) const;

 private:
  struct Permuted;
  // `postordered`: C's columns are in a postorder of its elimination tree `parent`.
  void analyse(const Permuted& C, const std::vector<int>& parent, bool postordered);
  void find_fundamental(const std::vector<int>& parent, const std::vector<int>& count);
  void relax(const Permuted& C, const std::vector<int>& count);
  int numeric(const Permuted& C);
  int factorize_supernode(const Permuted& C, int s, std::vector<int>& head, std::vector<int>& next,
                          std::vector<int>& next_row);

  int size_ = 0;
  std::vector<int> permutation_;
  std::vector<int> first_;      // supernode s: columns first_[s] .. first_[s + 1] - 1
  std::vector<int> row_start_;  // its rows below them: rows_[row_start_[s] ..]
  std::vector<int> rows_;
  std::vector<std::size_t> offset_;  // where its entries start in values_
  // CompactFactor's layout, in double: stored_ entries (values_capacity_ allocated), all
  // written by the numeric pass, so allocated without zeroing them first.
  std::unique_ptr<double[]> values_;
  std::size_t stored_ = 0;
  std::size_t values_capacity_ = 0;
  std::vector<double> diagonal_;
};

}  // namespace fetic::solver

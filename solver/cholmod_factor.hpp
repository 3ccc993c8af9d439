#pragma once
// A sparse Cholesky factor through CHOLMOD (SuiteSparse), with its own cholmod_common so
// that different factors may be used from different threads at the same time. CHOLMOD
// prints nothing: problems come back as results for the caller to report.

#include <cstddef>
#include <memory>
#include <vector>

#include "solver/compact_factor.hpp"
#include "solver/stiffness.hpp"

namespace fetic::solver {

class SupernodalFactorization;

class CholmodFactor {
 public:
  enum class Result { Ok, NotPositiveDefinite, OutOfMemory, Failed };

  CholmodFactor();
  ~CholmodFactor();
  CholmodFactor(const CholmodFactor&) = delete;
  CholmodFactor& operator=(const CholmodFactor&) = delete;
  CholmodFactor(CholmodFactor&&) noexcept;
  CholmodFactor& operator=(CholmodFactor&&) noexcept;

  // Factorizes the symmetric matrix A (only its lower triangle is read). Throws
  // std::bad_alloc when CHOLMOD runs out of memory (OutOfMemory is never returned).
  // NotPositiveDefinite when A is not positive definite, from CHOLMOD's LDL' (its default
  // for a small A, which factorizes through negative pivots) as from its LL'.
  // `to_compact`: the factor is only going to be compact()ed, so a small one (at most
  // kSimplicialUpTo rows) is factorized by SupernodalFactorization straight into
  // CompactFactor's layout, on AMD's ordering as CHOLMOD's analysis would choose it;
  // CHOLMOD's analysis, numeric factorization and the copy of its columns took longer at
  // the ~1,100 rows of a FETI subdomain (docs/BENCHMARKS.md). Such a factor must be compact()ed
  // before solve(); refactorize() factorizes it anew, update() throws.
  Result factorize(const SparseMatrix& A, bool to_compact = false);
  // The same as factorize(A, true) on the given fill-reducing ordering (row k of P A P' is
  // row permutation[k] of A) instead of AMD's; A of at most kSimplicialUpTo rows.
  Result factorize(const SparseMatrix& A, const int* permutation);
  static constexpr int kSimplicialUpTo = 5000;
  // The same for a matrix with the nonzero pattern of the last factorize(): the fill-
  // reducing ordering and symbolic analysis are kept, only the numbers are factorized
  // again (a working-set change in FETI-C changes values of G G', not its pattern).
  Result refactorize(const SparseMatrix& A);
  // The factor of A + C C' (add) or A - C C' (remove) from that of A, for a C of few
  // columns (CHOLMOD's multiple-rank update/downdate, Davis & Hager 2001): the factor
  // becomes a simplicial LDL', whose pattern the update may not leave (C C' within the
  // analysed pattern). NotPositiveDefinite when a removal leaves A singular.
  Result update(const SparseMatrix& C, bool add);
  // Replaces CHOLMOD's factor by a lean copy for solving only (CompactFactor: its
  // nonzeros in supernodes of nested columns, one row list each, and faster solves for
  // small factors). Afterwards only
  // solve() and the queries work; refactorize() and update() throw.
  // Returns false (and keeps CHOLMOD's factor) when the order is too large for it.
  // `single`: L's entries below the diagonal kept as floats (CompactFactor).
  bool compact(bool single = false);
  bool compacted() const { return compact_ != nullptr; }
  // The lean copy after compact() (solve_in_place, its permutation), else null.
  const CompactFactor* compact_factor() const { return compact_.get(); }
  CompactFactor* compact_factor() { return compact_.get(); }  // to reach_first() it
  // Column where factorization broke down (valid after NotPositiveDefinite).
  int failed_column() const { return failed_column_; }
  // CHOLMOD's cheap estimate min(diag L) / max(diag L), squared for an LL' factor.
  double rcond() const;
  int size() const { return size_; }
  std::size_t factor_nonzeros() const;
  // Peak bytes CHOLMOD allocated for this factor.
  std::size_t peak_memory() const;
  // Bytes CHOLMOD holds now for this factor: the factor and the solve's workspaces.
  std::size_t memory_in_use() const;

  // x = A^-1 b for `columns` right-hand sides stored column-major (size() rows each).
  // Not reentrant: one call at a time per factor.
  void solve(const double* b, double* x, int columns = 1) const;

 private:
  struct Impl;
  Result numeric(const SparseMatrix& A);
  Result factorize_supernodal(const SparseMatrix& A, const int* permutation = nullptr);
  void restart(const SparseMatrix& A);
  std::unique_ptr<Impl> impl_;
  // factorize(A, true)'s factor until compact() (then null).
  std::unique_ptr<SupernodalFactorization> supernodal_;
  std::unique_ptr<CompactFactor> compact_;
  std::size_t compact_peak_ = 0;  // CHOLMOD's peak before compact() released it
  int size_ = 0;
  int failed_column_ = -1;
};

}  // namespace fetic::solver

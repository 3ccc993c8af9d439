#include "solver/cholmod_factor.hpp"

#include <algorithm>
#include <cstring>
#include <new>
#include <stdexcept>

#include <cholmod.h>

#include "solver/supernodal_factorization.hpp"

namespace fetic::solver {

struct CholmodFactor::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  // Workspaces reused by cholmod_solve2 so that a solve does not allocate.
  cholmod_dense* x = nullptr;
  cholmod_dense* y = nullptr;
  cholmod_dense* e = nullptr;

  Impl() {
    cholmod_start(&common);
    common.print = 0;
    common.error_handler = nullptr;
  }
  ~Impl() {
    cholmod_free_dense(&x, &common);
    cholmod_free_dense(&y, &common);
    cholmod_free_dense(&e, &common);
    cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
};

CholmodFactor::CholmodFactor() : impl_(std::make_unique<Impl>()) {}
CholmodFactor::~CholmodFactor() = default;
CholmodFactor::CholmodFactor(CholmodFactor&&) noexcept = default;
CholmodFactor& CholmodFactor::operator=(CholmodFactor&&) noexcept = default;

namespace {

// A view of an Eigen matrix: CHOLMOD reads it, never writes it.
cholmod_sparse view_of(const SparseMatrix& A) {
  cholmod_sparse view{};
  view.nrow = static_cast<size_t>(A.rows());
  view.ncol = static_cast<size_t>(A.cols());
  view.nzmax = static_cast<size_t>(A.nonZeros());
  view.p = const_cast<int*>(A.outerIndexPtr());
  view.i = const_cast<int*>(A.innerIndexPtr());
  view.x = const_cast<double*>(A.valuePtr());
  view.stype = -1;
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;
  return view;
}

}  // namespace

// Forgets the factor held for one of A (checked compressed).
void CholmodFactor::restart(const SparseMatrix& A) {
  if (!A.isCompressed()) throw std::logic_error("CholmodFactor: matrix must be compressed");
  if (!impl_) impl_ = std::make_unique<Impl>();
  cholmod_free_factor(&impl_->factor, &impl_->common);
  compact_.reset();
  supernodal_.reset();
  size_ = static_cast<int>(A.rows());
  failed_column_ = -1;
}

CholmodFactor::Result CholmodFactor::factorize(const SparseMatrix& A, bool to_compact) {
  restart(A);
  if (size_ == 0) return Result::Ok;
  if (to_compact && size_ <= kSimplicialUpTo) return factorize_supernodal(A);
  cholmod_sparse view = view_of(A);
  cholmod_common& c = impl_->common;
  impl_->factor = cholmod_analyze(&view, &c);
  // CHOLMOD running out of memory is std::bad_alloc like any other allocation: the
  // commands report it as such (status 7), not as a singular or failed factorization.
  if (!impl_->factor && c.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
  if (!impl_->factor) return Result::Failed;
  return numeric(A);
}

CholmodFactor::Result CholmodFactor::factorize(const SparseMatrix& A, const int* permutation) {
  if (A.rows() > kSimplicialUpTo)
    throw std::logic_error("CholmodFactor: too large for an ordering");
  restart(A);
  if (size_ == 0) return Result::Ok;
  return factorize_supernodal(A, permutation);
}

// P A P' = L L' by SupernodalFactorization into CompactFactor's layout, on AMD's ordering
// postordered (CHOLMOD's analysis of a small matrix chooses the same; its transposes,
// copies and counts took a third of the time of the factorization itself), or on the
// given one.

CholmodFactor::Result CholmodFactor::factorize_supernodal(const SparseMatrix& A,
                                                          const int* permutation) {
  auto factor = std::make_unique<SupernodalFactorization>();
  const int failed = permutation ? factor->factorize(A, permutation) : factor->factorize(A);
  compact_peak_ = factor->bytes();
  if (failed >= 0) {
    failed_column_ = failed;
    return Result::NotPositiveDefinite;
  }
  supernodal_ = std::move(factor);
  return Result::Ok;
}

CholmodFactor::Result CholmodFactor::refactorize(const SparseMatrix& A) {
  if (compact_) throw std::logic_error("CholmodFactor: refactorize after compact()");
  if (supernodal_) return factorize(A, true);
  if (!impl_->factor || static_cast<int>(A.rows()) != size_) return factorize(A);
  if (!A.isCompressed()) throw std::logic_error("CholmodFactor: matrix must be compressed");
  failed_column_ = -1;
  return numeric(A);
}

namespace {

// The first column of a simplicial LDL' factor whose pivot D(j, j) is not positive (or
// NaN), -1 when there is none or the factor is LL'. CHOLMOD factorizes a small matrix
// as LDL' by default and goes on through negative pivots (it stops only at a zero one),
// where its LL' stops at the first pivot that is not positive.
int first_nonpositive_pivot(const cholmod_factor* L) {
  if (L->is_super || L->is_ll) return -1;
  const int* p = static_cast<const int*>(L->p);
  const double* x = static_cast<const double*>(L->x);
  for (int j = 0; j < static_cast<int>(L->n); ++j)
    if (!(x[p[j]] > 0.0)) return j;  // D(j, j) is the column's first entry
  return -1;
}

}  // namespace

CholmodFactor::Result CholmodFactor::numeric(const SparseMatrix& A) {
  cholmod_sparse view = view_of(A);
  cholmod_common& c = impl_->common;
  cholmod_factorize(&view, impl_->factor, &c);
  if (c.status == CHOLMOD_NOT_POSDEF || impl_->factor->minor < impl_->factor->n) {
    failed_column_ = static_cast<int>(impl_->factor->minor);
    return Result::NotPositiveDefinite;
  }
  if (c.status >= CHOLMOD_OK) failed_column_ = first_nonpositive_pivot(impl_->factor);
  if (failed_column_ >= 0) return Result::NotPositiveDefinite;
  if (c.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
  if (c.status < CHOLMOD_OK) return Result::Failed;
  // The factorization's workspace (O(n) per factor, thousands of factors in a FETI
  // solve) is not needed by a solve; a later factorization or update allocates it again.
  cholmod_free_work(&c);
  return Result::Ok;
}

CholmodFactor::Result CholmodFactor::update(const SparseMatrix& C, bool add) {
  if (compact_) throw std::logic_error("CholmodFactor: update after compact()");
  if (supernodal_) throw std::logic_error("CholmodFactor: update of a factorize(A, true) factor");
  if (!impl_->factor || static_cast<int>(C.rows()) != size_) return Result::Failed;
  if (C.cols() == 0) return Result::Ok;
  if (!C.isCompressed()) throw std::logic_error("CholmodFactor: matrix must be compressed");
  failed_column_ = -1;
  cholmod_common& c = impl_->common;
  cholmod_sparse view = view_of(C);
  view.stype = 0;  // C itself, not a symmetric matrix
  // CHOLMOD updates P A P' = L D L': C must be given in the factor's permutation.
  cholmod_sparse* permuted =
      cholmod_submatrix(&view, static_cast<int*>(impl_->factor->Perm),
                        static_cast<SuiteSparse_long>(size_), nullptr, -1, 1, 1, &c);
  if (!permuted) {
    if (c.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
    return Result::Failed;
  }
  const int ok = cholmod_updown(add ? 1 : 0, permuted, impl_->factor, &c);
  cholmod_free_sparse(&permuted, &c);
  if (c.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
  if (!ok || c.status < CHOLMOD_OK) return Result::Failed;
  if (c.status == CHOLMOD_NOT_POSDEF || impl_->factor->minor < impl_->factor->n) {
    failed_column_ = static_cast<int>(impl_->factor->minor);
    return Result::NotPositiveDefinite;
  }
  return Result::Ok;
}

double CholmodFactor::rcond() const {
  if (compact_) return compact_->rcond();
  if (supernodal_) return supernodal_->rcond();
  if (!impl_->factor || size_ == 0) return 1.0;
  return cholmod_rcond(impl_->factor, &impl_->common);
}

std::size_t CholmodFactor::factor_nonzeros() const {
  if (compact_) return compact_->nonzeros();
  if (supernodal_) return supernodal_->nonzeros();
  if (!impl_->factor) return 0;
  const cholmod_factor* L = impl_->factor;
  if (L->is_super) return L->xsize;
  return L->nzmax;
}

std::size_t CholmodFactor::peak_memory() const {
  return compact_ || supernodal_ ? compact_peak_ : impl_->common.memory_usage;
}

std::size_t CholmodFactor::memory_in_use() const {
  if (compact_) return compact_->bytes();
  if (supernodal_) return supernodal_->bytes() + impl_->common.memory_inuse;
  return impl_->common.memory_inuse;
}

void CholmodFactor::solve(const double* b, double* x, int columns) const {
  if (size_ == 0) return;
  if (compact_) {
    compact_->solve(b, x, columns);
    return;
  }
  if (supernodal_) throw std::logic_error("CholmodFactor: solve before compact()");
  cholmod_dense rhs{};
  rhs.nrow = static_cast<size_t>(size_);
  rhs.ncol = static_cast<size_t>(columns);
  rhs.nzmax = rhs.nrow * rhs.ncol;
  rhs.d = rhs.nrow;
  rhs.x = const_cast<double*>(b);
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  if (!cholmod_solve2(CHOLMOD_A, impl_->factor, &rhs, nullptr, &impl_->x, nullptr, &impl_->y,
                      &impl_->e, &impl_->common)) {
    if (impl_->common.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
    throw std::runtime_error("CHOLMOD solve failed");
  }
  std::memcpy(x, impl_->x->x, sizeof(double) * rhs.nzmax);
}

namespace {

// Column j of a supernodal LL' factor into `out`: its nonzeros below the diagonal, in
// increasing row order (the padding of relaxed supernodes, exact zeros, is left out).
void add_supernodal_column(const cholmod_factor* L, int s, int j, CompactFactor& out) {
  const int* super = static_cast<const int*>(L->super);
  const int* pi = static_cast<const int*>(L->pi);
  const int* px = static_cast<const int*>(L->px);
  const int* ls = static_cast<const int*>(L->s);
  const double* lx = static_cast<const double*>(L->x);
  const int rows = pi[s + 1] - pi[s];
  const int jj = j - super[s];
  const double* column = lx + px[s] + static_cast<std::size_t>(jj) * rows;
  out.start_column(column[jj]);
  int previous = j;
  for (int r = jj + 1; r < rows; ++r) {
    const int row = ls[pi[s] + r];
    if (row <= previous) throw std::logic_error("CholmodFactor: unsorted supernode rows");
    previous = row;
    if (column[r] != 0.0) out.add(row, column[r]);
  }
}

// Nonzeros below the diagonal of a supernodal factor: the compact copy's exact size, so
// that it is allocated once (reserving the padded size and shrinking after copied every
// factor once more and left the larger blocks free between long-lived ones).
std::size_t supernodal_nonzeros(const cholmod_factor* L) {
  const int* super = static_cast<const int*>(L->super);
  const int* pi = static_cast<const int*>(L->pi);
  const int* px = static_cast<const int*>(L->px);
  const double* lx = static_cast<const double*>(L->x);
  std::size_t count = 0;
  for (int s = 0; s < static_cast<int>(L->nsuper); ++s) {
    const int rows = pi[s + 1] - pi[s];
    for (int jj = 0; jj < super[s + 1] - super[s]; ++jj) {
      const double* column = lx + px[s] + static_cast<std::size_t>(jj) * rows;
      for (int r = jj + 1; r < rows; ++r)
        count += column[r] != 0.0;
    }
  }
  return count;
}

// A packed simplicial LL' factor's explicit zeros dropped in place (its arrays are
// CHOLMOD's, freed right after the compact copy is made), and the rows checked: each
// column starts with its diagonal, then rows increasing below it. The compact copy then
// reads the columns where they are (CompactFactor::Columns) - no copy of them, no
// per-entry add(): page faults on fresh memory are most of the FETI set-up's copying
// here (docs/BENCHMARKS.md).
CompactFactor::Columns drop_zeros(cholmod_factor* L) {
  int* p = static_cast<int*>(L->p);
  int* i = static_cast<int*>(L->i);
  const int* nz = static_cast<const int*>(L->nz);
  double* x = static_cast<double*>(L->x);
  const int n = static_cast<int>(L->n);
  int next = 0;
  for (int j = 0; j < n; ++j) {
    const int begin = p[j], end = p[j] + nz[j];
    if (i[begin] != j) throw std::logic_error("CholmodFactor: column without its diagonal first");
    p[j] = next;
    i[next] = j;
    x[next++] = x[begin];
    int previous = j;
    for (int k = begin + 1; k < end; ++k) {
      if (i[k] <= previous || i[k] >= n)
        throw std::logic_error("CholmodFactor: unsorted column rows");
      previous = i[k];
      if (x[k] == 0.0) continue;
      i[next] = i[k];
      x[next++] = x[k];
    }
  }
  p[n] = next;
  return {p, i, x};
}

}  // namespace

bool CholmodFactor::compact(bool single) {
  if (compact_) return true;
  if (supernodal_) {
    compact_ = supernodal_->compact(single);
    supernodal_.reset();
    impl_.reset();
    return true;
  }
  if (!impl_) return false;
  cholmod_factor* L = impl_->factor;
  if (!L || size_ == 0 || size_ > CompactFactor::kMaxSize) return false;
  cholmod_common& c = impl_->common;
  if (!L->is_super &&
      !cholmod_change_factor(CHOLMOD_REAL, 1, 0, 1, 1, L, &c)) {  // simplicial LL', packed
    if (c.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
    return false;
  }
  std::unique_ptr<CompactFactor> out;
  if (L->is_super) {
    out = std::make_unique<CompactFactor>(size_, static_cast<const int*>(L->Perm),
                                          supernodal_nonzeros(L), single);
    const int* super = static_cast<const int*>(L->super);
    for (int s = 0; s < static_cast<int>(L->nsuper); ++s)
      for (int j = super[s]; j < super[s + 1]; ++j)
        add_supernodal_column(L, s, j, *out);
    out->finish();
  } else {
    out = std::make_unique<CompactFactor>(size_, static_cast<const int*>(L->Perm), drop_zeros(L),
                                          single);
  }
  compact_peak_ = c.memory_usage;
  compact_ = std::move(out);
  impl_.reset();  // CHOLMOD's factor, workspaces and common: none is needed any more
  return true;
}

}  // namespace fetic::solver

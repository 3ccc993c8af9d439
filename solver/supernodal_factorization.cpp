#include "solver/supernodal_factorization.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <new>
#include <stdexcept>

#include <amd.h>

#include <Eigen/Core>

#include "solver/elimination_tree.hpp"

namespace fetic::solver {

namespace {

// CompactFactor's layout of a supernode of nc columns and m rows below them.
std::size_t entries_of_supernode(std::size_t nc, std::size_t m) {
  return nc * (nc - 1) / 2 + nc * m;
}

}  // namespace

// P A P' as compressed columns: its lower triangle with values (column j: rows >= j, the
// diagonal among them) for the column counts and the numeric factorization, its strict upper
// triangle's pattern (column k: rows i < k) for the elimination tree.
struct SupernodalFactorization::Permuted {
  int n = 0;
  std::vector<int> lower_start, lower_rows;
  std::vector<double> lower_values;
  std::vector<int> upper_start, upper_rows;

  void assign(const SparseMatrix& A, const int* permutation);
  // `from`'s lower triangle with its rows and columns renumbered: k becomes inverse[k]
  // (old[k'] = k' 's old number), an order in which each entry stays on its side of the
  // diagonal. The upper pattern is left empty: the tree it gave is relabelled instead.
  void relabel(const Permuted& from, const std::vector<int>& old, const std::vector<int>& inverse);
};

namespace {

// One triangle's columns renumbered (Permuted::relabel).
void relabel_columns(const std::vector<int>& start, const std::vector<int>& rows,
                     const std::vector<int>& old, const std::vector<int>& inverse,
                     std::vector<int>& new_start, std::vector<int>& new_rows,
                     const double* values = nullptr, std::vector<double>* new_values = nullptr) {
  const std::size_t n = old.size();
  new_start.resize(n + 1);
  new_rows.resize(rows.size());
  if (new_values) new_values->resize(rows.size());
  int at = 0;
  for (std::size_t k = 0; k < n; ++k) {
    new_start[k] = at;
    const int j = old[k];
    for (int e = start[j]; e < start[j + 1]; ++e, ++at) {
      new_rows[at] = inverse[rows[e]];
      if (new_values) (*new_values)[at] = values[e];
    }
  }
  new_start[n] = at;
}

}  // namespace

void SupernodalFactorization::Permuted::relabel(const Permuted& from, const std::vector<int>& old,
                                                const std::vector<int>& inverse) {
  n = from.n;
  relabel_columns(from.lower_start, from.lower_rows, old, inverse, lower_start, lower_rows,
                  from.lower_values.data(), &lower_values);
  upper_start.clear();  // read by the elimination tree alone, which is relabelled instead
  upper_rows.clear();
}

void SupernodalFactorization::Permuted::assign(const SparseMatrix& A, const int* permutation) {
  n = static_cast<int>(A.rows());
  thread_local std::vector<int> position;
  position.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k)
    position[static_cast<std::size_t>(permutation[k])] = k;
  lower_start.assign(static_cast<std::size_t>(n) + 2, 0);
  upper_start.assign(static_cast<std::size_t>(n) + 2, 0);
  // Counted at index + 2, summed to index + 1: the fill below advances start[j + 1]
  // from column j's beginning to its end, leaving start[] as the columns' beginnings.
  const auto each = [&](auto&& visit) {
    for (int col = 0; col < n; ++col)
      for (SparseMatrix::InnerIterator it(A, col); it; ++it) {
        if (it.row() < col) continue;  // the lower triangle alone, as CHOLMOD reads it
        const int i = position[static_cast<std::size_t>(it.row())];
        const int j = position[static_cast<std::size_t>(col)];
        visit(std::min(i, j), std::max(i, j), it.value());
      }
  };
  each([&](int low, int high, double) {
    ++lower_start[static_cast<std::size_t>(low) + 2];
    if (high != low) ++upper_start[static_cast<std::size_t>(high) + 2];
  });
  for (int j = 0; j < n; ++j) {
    lower_start[static_cast<std::size_t>(j) + 2] += lower_start[static_cast<std::size_t>(j) + 1];
    upper_start[static_cast<std::size_t>(j) + 2] += upper_start[static_cast<std::size_t>(j) + 1];
  }
  lower_rows.resize(static_cast<std::size_t>(lower_start[static_cast<std::size_t>(n) + 1]));
  lower_values.resize(lower_rows.size());
  upper_rows.resize(static_cast<std::size_t>(upper_start[static_cast<std::size_t>(n) + 1]));
  each([&](int low, int high, double value) {
    const auto at = static_cast<std::size_t>(lower_start[static_cast<std::size_t>(low) + 1]++);
    lower_rows[at] = high;
    lower_values[at] = value;
    if (high != low)
      upper_rows[static_cast<std::size_t>(upper_start[static_cast<std::size_t>(high) + 1]++)] = low;
  });
  lower_start.pop_back();
  upper_start.pop_back();
}

int SupernodalFactorization::factorize(const SparseMatrix& A) {
  const int n = static_cast<int>(A.rows());
  thread_local std::vector<int> order, parent, post;
  order.resize(static_cast<std::size_t>(n));
  if (n > 0) {
    const int status =
        amd_order(n, A.outerIndexPtr(), A.innerIndexPtr(), order.data(), nullptr, nullptr);
    if (status == AMD_OUT_OF_MEMORY) throw std::bad_alloc();
    if (status != AMD_OK && status != AMD_OK_BUT_JUMBLED)
      throw std::logic_error("SupernodalFactorization: AMD refused the matrix");
  }
  thread_local Permuted ordered, C;
  ordered.assign(A, order.data());
  elimination_tree(ordered.upper_start, ordered.upper_rows, n, parent);
  postorder(parent, post);
  // The postorder relabels the matrix and its tree: no second pass over A, no second tree.
  size_ = n;
  permutation_.resize(static_cast<std::size_t>(n));
  thread_local std::vector<int> inverse, relabelled;
  inverse.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    permutation_[static_cast<std::size_t>(k)] = order[static_cast<std::size_t>(post[k])];
    inverse[static_cast<std::size_t>(post[k])] = k;
  }
  C.relabel(ordered, post, inverse);
  relabelled.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j)
    relabelled[inverse[j]] = parent[j] < 0 ? -1 : inverse[parent[j]];
  analyse(C, relabelled, /*postordered=*/true);
  return numeric(C);
}

int SupernodalFactorization::factorize(const SparseMatrix& A, const int* permutation) {
  size_ = static_cast<int>(A.rows());
  permutation_.assign(permutation, permutation + size_);
  thread_local Permuted C;
  thread_local std::vector<int> parent;
  C.assign(A, permutation);
  elimination_tree(C.upper_start, C.upper_rows, size_, parent);
  analyse(C, parent, /*postordered=*/false);
  return numeric(C);
}

void SupernodalFactorization::analyse(const Permuted& C, const std::vector<int>& parent,
                                      bool postordered) {
  thread_local std::vector<int> count;
  column_counts(C.lower_start, C.lower_rows, parent, count, postordered);
  find_fundamental(parent, count);
  relax(C, count);
  offset_.resize(first_.size());
  std::size_t stored = 0;
  for (int s = 0; s < supernodes(); ++s) {
    offset_[static_cast<std::size_t>(s)] = stored;
    stored += entries_of_supernode(static_cast<std::size_t>(first_[s + 1] - first_[s]),
                                   static_cast<std::size_t>(row_start_[s + 1] - row_start_[s]));
  }
  offset_.back() = stored;
  if (stored > values_capacity_) {
    values_ = std::make_unique_for_overwrite<double[]>(stored);
    values_capacity_ = stored;
  }
  stored_ = stored;
  diagonal_.resize(static_cast<std::size_t>(size_));
}

// Fundamental supernodes into first_: column j continues j - 1's when j is j - 1's parent,
// j - 1 its only child, and column j - 1 has one entry more (its rows below are then j and
// column j's).
void SupernodalFactorization::find_fundamental(const std::vector<int>& parent,
                                               const std::vector<int>& count) {
  thread_local std::vector<int> children;
  children.assign(static_cast<std::size_t>(size_), 0);
  for (int j = 0; j < size_; ++j)
    if (parent[j] >= 0) ++children[static_cast<std::size_t>(parent[j])];
  first_.assign(1, 0);
  for (int j = 1; j < size_; ++j)
    if (parent[j - 1] != j || children[j] != 1 || count[j - 1] != count[j] + 1) first_.push_back(j);
  first_.push_back(size_);
}

// The fundamental supernodes (first_) merged greedily in order into the final ones
// (first_, row_start_, rows_): the next fundamental one joins the open run when the run's
// stored entries then hold at most CompactFactor::kRelaxedZeros zeros. A supernode's rows
// below it are A's there and those below it of every closed supernode whose first row
// falls in it (its children in the supernodal tree): closed under the updates the numeric
// factorization makes, whatever was merged (a merged supernode's rows are a union, so its
// children may bring rows its columns do not have: stored zeros).
void SupernodalFactorization::relax(const Permuted& C, const std::vector<int>& count) {
  thread_local std::vector<int> fundamental, fundamental_of, head, next, mark, own, run, merged,
      added, gathered;
  fundamental.assign(first_.begin(), first_.end());
  const int F = static_cast<int>(fundamental.size()) - 1;
  fundamental_of.resize(static_cast<std::size_t>(size_));
  for (int f = 0; f < F; ++f)
    std::fill(fundamental_of.begin() + fundamental[f], fundamental_of.begin() + fundamental[f + 1],
              f);
  head.assign(static_cast<std::size_t>(F), -1);  // closed supernodes attached to f
  next.assign(static_cast<std::size_t>(F), -1);
  mark.assign(static_cast<std::size_t>(size_), -1);
  int stamp = 0, below = 0, taken = 0;
  gathered.resize(static_cast<std::size_t>(size_) + 1);
  // r into gathered[0 .. taken), once, when below the open fundamental: without branches
  // (which rows are new is not predictable).
  const auto take = [&](int r) {
    const bool fresh = r >= below && mark[r] != stamp;
    mark[r] = stamp;  // rows above the fundamental are never taken under this stamp
    gathered[static_cast<std::size_t>(taken)] = r;
    taken += fresh;
  };
  const auto rows_of = [&](int f) {  // rows below fundamental f, into own
    below = fundamental[f + 1];
    taken = 0;
    ++stamp;
    for (int j = fundamental[f]; j < below; ++j)
      for (int e = C.lower_start[j]; e < C.lower_start[j + 1]; ++e)
        take(C.lower_rows[e]);
    for (int K = head[f]; K != -1; K = next[K])
      for (int e = row_start_[K]; e < row_start_[K + 1]; ++e)
        take(rows_[e]);
    own.assign(gathered.begin(), gathered.begin() + taken);
    std::sort(own.begin(), own.end());
  };
  const auto add_child = [&](int K) {  // a supernode closed as f's child: its rows too
    taken = 0;
    for (int e = row_start_[K]; e < row_start_[K + 1]; ++e)
      take(rows_[e]);  // increasing, as own
    added.clear();
    std::merge(own.begin(), own.end(), gathered.begin(), gathered.begin() + taken,
               std::back_inserter(added));
    own.swap(added);
  };
  first_.assign(1, 0);
  row_start_.assign(1, 0);
  rows_.clear();
  run.clear();
  std::size_t given = 0;             // L's entries below the diagonal in the run's columns
  const auto close = [&](int end) {  // the run as the next supernode; true: attached to f
    const int s = static_cast<int>(first_.size()) - 1;
    first_.push_back(end);
    rows_.insert(rows_.end(), run.begin(), run.end());
    row_start_.push_back(static_cast<int>(rows_.size()));
    if (run.empty()) return -1;
    const int f = fundamental_of[run.front()];
    next[s] = head[f];
    head[f] = s;
    return f;
  };
  for (int f = 0; f < F; ++f) {
    const int begin = fundamental[f], end = fundamental[f + 1];
    std::size_t own_given = 0;
    for (int j = begin; j < end; ++j)
      own_given += static_cast<std::size_t>(count[j]);
    rows_of(f);
    if (f > 0) {
      merged.clear();
      std::set_union(std::lower_bound(run.begin(), run.end(), end), run.end(), own.begin(),
                     own.end(), std::back_inserter(merged));
      const auto stored = static_cast<double>(
          entries_of_supernode(static_cast<std::size_t>(end - first_.back()), merged.size()));
      if (stored - static_cast<double>(given + own_given) <=
          CompactFactor::kRelaxedZeros * stored) {
        run.swap(merged);
        given += own_given;
        continue;
      }
      if (close(begin) == f) add_child(static_cast<int>(first_.size()) - 2);
    }
    run.assign(own.begin(), own.end());
    given = own_given;
  }
  close(size_);
}

int SupernodalFactorization::numeric(const Permuted& C) {
  const int S = supernodes();
  thread_local std::vector<int> head, next, next_row;
  head.assign(static_cast<std::size_t>(S), -1);  // supernodes whose next rows fall in s
  next.assign(static_cast<std::size_t>(S), -1);
  next_row.assign(static_cast<std::size_t>(S), 0);
  for (int s = 0; s < S; ++s) {
    const int failed = factorize_supernode(C, s, head, next, next_row);
    if (failed >= 0) return failed;
  }
  return -1;
}

namespace {

// The update of a supernode of NC columns (a node's two DOFs in a plane model: most
// of them), its columns' products summed in registers and subtracted in one pass.
template <int NC>
void subtract_narrow_update(const double* block, int m, const int* target, int p, int q, double* w,
                            int ld) {
  for (int c = p; c < q; ++c) {
    double a[NC];
    for (int k = 0; k < NC; ++k)
      a[k] = block[static_cast<std::ptrdiff_t>(k) * m + c];
    double* out = w + static_cast<std::ptrdiff_t>(target[c]) * ld;
    for (int r = c; r < m; ++r) {
      double sum = 0.0;
      for (int k = 0; k < NC; ++k)
        sum += block[static_cast<std::ptrdiff_t>(k) * m + r] * a[k];
      out[target[r]] -= sum;
    }
  }
}

// One earlier supernode's update of the current one: L_K's rows from `p` on (those from
// p to q - 1 are the current columns) times L_K's rows p .. q - 1, transposed, subtracted
// from the dense workspace w (leading dimension ld) through `map` (row of L -> row of w,
// the current columns 0 .. nc - 1 first). A wide supernode's products are formed a column
// at a time as dense loops over its block's rows (they vectorize), then scattered.
void subtract_update(const double* block, int m, int nc, const int* rows, int p, int q,
                     const int* map, double* w, int ld) {
  thread_local std::vector<int> target;
  target.resize(static_cast<std::size_t>(m));
  for (int r = p; r < m; ++r)
    target[r] = map[rows[r]];
  switch (nc) {
    case 1:
      return subtract_narrow_update<1>(block, m, target.data(), p, q, w, ld);
    case 2:
      return subtract_narrow_update<2>(block, m, target.data(), p, q, w, ld);
    case 3:
      return subtract_narrow_update<3>(block, m, target.data(), p, q, w, ld);
    case 4:
      return subtract_narrow_update<4>(block, m, target.data(), p, q, w, ld);
    default:
      break;
  }
  // Wider: the rows' products by Eigen's register-blocked matrix product, then scattered.
  using Rows = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
  const Rows below(block + p, m - p, nc, Eigen::OuterStride<>(m));
  const Rows columns(block + p, q - p, nc, Eigen::OuterStride<>(m));
  thread_local Eigen::MatrixXd product;
  product.resize(m - p, q - p);
  product.noalias() = below * columns.transpose();
  for (int c = 0; c < q - p; ++c) {
    double* out = w + static_cast<std::ptrdiff_t>(target[p + c]) * ld;
    const double* from = product.data() + static_cast<std::ptrdiff_t>(c) * (m - p);
    for (int r = c; r < m - p; ++r)
      out[target[p + r]] -= from[r];
  }
}

// The dense Cholesky factor of the ld x nc trapezoid w (leading dimension ld): its top
// nc x nc block's L_11 column by column, then the rows below times L_11'^-1 (Eigen's
// blocked triangular solve). Returns -1, or the column whose pivot was not positive.
int factorize_dense(double* w, int ld, int nc) {
  for (int k = 0; k < nc; ++k) {
    double* column = w + static_cast<std::ptrdiff_t>(k) * ld;
    const double pivot = column[k];
    if (!(pivot > 0.0)) return k;  // NaN too
    const double diagonal = std::sqrt(pivot);
    column[k] = diagonal;
    for (int r = k + 1; r < nc; ++r)
      column[r] /= diagonal;
    for (int c = k + 1; c < nc; ++c) {
      double* later = w + static_cast<std::ptrdiff_t>(c) * ld;
      const double f = column[c];
      for (int r = c; r < nc; ++r)
        later[r] -= column[r] * f;
    }
  }
  if (ld == nc) return -1;
  Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>> W(w, ld, nc, Eigen::OuterStride<>(ld));
  W.topRows(nc).triangularView<Eigen::Lower>().transpose().solveInPlace<Eigen::OnTheRight>(
      W.bottomRows(ld - nc));
  return -1;
}

}  // namespace

int SupernodalFactorization::factorize_supernode(const Permuted& C, int s, std::vector<int>& head,
                                                 std::vector<int>& next,
                                                 std::vector<int>& next_row) {
  thread_local std::vector<int> map, supernode_of;
  thread_local std::vector<double> work;
  if (s == 0) {
    map.resize(static_cast<std::size_t>(size_));
    supernode_of.resize(static_cast<std::size_t>(size_));
    for (int t = 0; t < supernodes(); ++t)
      std::fill(supernode_of.begin() + first_[t], supernode_of.begin() + first_[t + 1], t);
  }
  const int j0 = first_[s], nc = first_[s + 1] - j0;
  const int m = row_start_[s + 1] - row_start_[s], ld = nc + m;
  const int* rows = rows_.data() + row_start_[s];
  for (int k = 0; k < nc; ++k)
    map[j0 + k] = k;
  for (int r = 0; r < m; ++r)
    map[rows[r]] = nc + r;
  work.assign(static_cast<std::size_t>(ld) * nc, 0.0);
  for (int k = 0; k < nc; ++k)
    for (int e = C.lower_start[j0 + k]; e < C.lower_start[j0 + k + 1]; ++e)
      work[static_cast<std::size_t>(k) * ld + map[C.lower_rows[e]]] += C.lower_values[e];
  const auto link = [&](int K) {  // K to the supernode of its next row
    const int t = supernode_of[rows_[row_start_[K] + next_row[K]]];
    next[K] = head[t];
    head[t] = K;
  };
  for (int K = head[s]; K != -1;) {
    const int after = next[K];
    const int ncK = first_[K + 1] - first_[K], mK = row_start_[K + 1] - row_start_[K];
    const int* rowsK = rows_.data() + row_start_[K];
    const int p = next_row[K];
    int q = p;
    while (q < mK && rowsK[q] < j0 + nc)
      ++q;
    const double* block = values_.get() + offset_[K] + entries_of_supernode(ncK, 0);
    subtract_update(block, mK, ncK, rowsK, p, q, map.data(), work.data(), ld);
    next_row[K] = q;
    if (q < mK) link(K);
    K = after;
  }
  const int failed = factorize_dense(work.data(), ld, nc);
  if (failed >= 0) return j0 + failed;
  double* out = values_.get() + offset_[s];
  for (int k = 0; k < nc; ++k) {
    const double* column = work.data() + static_cast<std::size_t>(k) * ld;
    diagonal_[j0 + k] = column[k];
    out = std::copy(column + k + 1, column + nc, out);
  }
  for (int k = 0; k < nc; ++k) {
    const double* column = work.data() + static_cast<std::size_t>(k) * ld;
    out = std::copy(column + nc, column + ld, out);
  }
  if (m > 0) link(s);
  return -1;
}

std::size_t SupernodalFactorization::bytes() const {
  return (values_capacity_ + diagonal_.capacity()) * sizeof(double) +
         offset_.capacity() * sizeof(std::size_t) +
         (permutation_.capacity() + first_.capacity() + row_start_.capacity() + rows_.capacity()) *
             sizeof(int);
}

double SupernodalFactorization::rcond() const {
  if (diagonal_.empty()) return 1.0;
  const auto [low, high] = std::minmax_element(diagonal_.begin(), diagonal_.end());
  const double ratio = *low / *high;
  return ratio * ratio;
}

std::unique_ptr<CompactFactor> SupernodalFactorization::compact(bool single) const {
  const CompactFactor::Supernodes supernodes{this->supernodes(), first_.data(), row_start_.data(),
                                             rows_.data(),       values_.get(), diagonal_.data()};
  return std::make_unique<CompactFactor>(size_, permutation_.data(), supernodes, single);
}

}  // namespace fetic::solver

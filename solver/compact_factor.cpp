#include "solver/compact_factor.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <stdexcept>

namespace fetic::solver {

namespace {

// The packed layout of a supernode of nc columns and m rows below them: its strict lower
// triangle by columns (column k holds nc - 1 - k entries), then the m x nc block,
// column-major. These three give the layout its one definition.
constexpr std::ptrdiff_t triangle_entries(std::ptrdiff_t nc) {
  return nc * (nc - 1) / 2;
}

constexpr std::ptrdiff_t supernode_entries(std::ptrdiff_t nc, std::ptrdiff_t m) {
  return triangle_entries(nc) + nc * m;
}

// Where column k starts within the triangle: after columns 0..k-1's entries.
constexpr std::ptrdiff_t triangle_column(std::ptrdiff_t nc, std::ptrdiff_t k) {
  return k * (nc - 1) - k * (k - 1) / 2;
}

}  // namespace

CompactFactor::CompactFactor(int size, const int* permutation, std::size_t nonzeros_hint,
                             bool single)
    : size_(size), single_(single), permutation_(permutation, permutation + size) {
  if (size > kMaxSize) throw std::logic_error("CompactFactor: order above 65536");
  column_start_.reserve(static_cast<std::size_t>(size) + 1);
  inverse_diagonal_.reserve(static_cast<std::size_t>(size));
  column_rows_.reserve(nonzeros_hint);
  column_values_.reserve(nonzeros_hint);
}

void CompactFactor::start_column(double diagonal) {
  column_start_.push_back(static_cast<int>(column_rows_.size()));
  inverse_diagonal_.push_back(1.0 / diagonal);
}

void CompactFactor::add(int row, double value) {
  // finish() places each entry by its row (triangle offset or the block's row list): a
  // row out of order would be written outside the supernode.
  if (column_start_.empty()) throw std::logic_error("CompactFactor: add() before start_column()");
  const int column = static_cast<int>(inverse_diagonal_.size()) - 1;
  const bool first = static_cast<int>(column_rows_.size()) == column_start_.back();
  if (row <= column || row >= size_ || (!first && row <= column_rows_.back()))
    throw std::logic_error("CompactFactor: rows must be below the diagonal, increasing");
  column_rows_.push_back(static_cast<std::uint16_t>(row));
  column_values_.push_back(value);
}

CompactFactor::CompactFactor(int size, const int* permutation, const Columns& columns, bool single)
    : size_(size), single_(single), permutation_(permutation, permutation + size) {
  if (size > kMaxSize) throw std::logic_error("CompactFactor: order above 65536");
  inverse_diagonal_.resize(static_cast<std::size_t>(size));
  for (int j = 0; j < size; ++j)
    inverse_diagonal_[static_cast<std::size_t>(j)] = 1.0 / columns.values[columns.start[j]];
  build_supernodes(ColumnView<int>{columns.start, columns.rows, columns.values, 1});
}

CompactFactor::CompactFactor(int size, const int* permutation, const Supernodes& supernodes,
                             bool single)
    : size_(size), single_(single), permutation_(permutation, permutation + size) {
  if (size > kMaxSize) throw std::logic_error("CompactFactor: order above 65536");
  const auto count = static_cast<std::size_t>(supernodes.count);
  if (supernodes.count < 0 || supernodes.first[0] != 0 || supernodes.first[count] != size)
    throw std::logic_error("CompactFactor: supernodes do not cover the columns");
  first_.assign(supernodes.first, supernodes.first + count + 1);
  row_start_.assign(supernodes.row_start, supernodes.row_start + count + 1);
  rows_.assign(supernodes.rows, supernodes.rows + supernodes.row_start[count]);
  const std::size_t stored = size_supernodes();
  if (single_)
    values32_.assign(supernodes.values, supernodes.values + stored);
  else
    values_.assign(supernodes.values, supernodes.values + stored);
  inverse_diagonal_.resize(static_cast<std::size_t>(size));
  for (int j = 0; j < size; ++j)
    inverse_diagonal_[static_cast<std::size_t>(j)] = 1.0 / supernodes.diagonal[j];
}

void CompactFactor::finish() {
  column_start_.push_back(static_cast<int>(column_rows_.size()));
  if (static_cast<int>(inverse_diagonal_.size()) != size_)
    throw std::logic_error("CompactFactor: not every column was given");
  build_supernodes(ColumnView<std::uint16_t>{column_start_.data(), column_rows_.data(),
                                             column_values_.data(), 0});
  // The columns as given are not needed by a solve: nothing of them is held.
  std::vector<int>().swap(column_start_);
  std::vector<std::uint16_t>().swap(column_rows_);
  std::vector<double>().swap(column_values_);
}

// Greedy over the columns: column j joins the run before it when the run's stored entries
// (its triangle and the union of its columns' rows below it, for every column) are then
// at most kRelaxedZeros explicit zeros. Nested patterns (fundamental supernodes) add none.
template <class Row>
void CompactFactor::find_supernodes(const ColumnView<Row>& columns) {
  // Found in arrays reused from one factor to the next, then copied at their final size:
  // the kept ones are in huge pages, where a grown array's old copies would stay.
  thread_local std::vector<int> first, row_start;
  thread_local std::vector<std::uint16_t> rows;
  first.assign(1, 0);
  row_start.assign(1, 0);
  rows.clear();
  std::vector<int> below, merged;  // the run's rows below its last column
  std::size_t given = 0;           // entries given in the run's columns
  const auto close = [&](int end) {
    first.push_back(end);
    rows.insert(rows.end(), below.begin(), below.end());
    row_start.push_back(static_cast<int>(rows.size()));
  };
  for (int j = 0; j < size_; ++j) {
    const Row* begin = columns.rows + columns.begin(j);
    const Row* end = columns.rows + columns.end(j);
    const auto count = static_cast<std::size_t>(end - begin);
    if (j > first.back()) {
      const std::ptrdiff_t nc = j - first.back() + 1;
      merged.clear();  // row j becomes a row of the diagonal block
      const auto rest = below.begin() + (!below.empty() && below.front() == j ? 1 : 0);
      std::set_union(rest, below.end(), begin, end, std::back_inserter(merged));
      const auto stored =
          static_cast<double>(supernode_entries(nc, static_cast<std::ptrdiff_t>(merged.size())));
      if (stored - static_cast<double>(given + count) <= kRelaxedZeros * stored) {
        below.swap(merged);
        given += count;
        continue;
      }
      close(j);
    }
    below.assign(begin, end);
    given = count;
  }
  close(size_);
  first_.assign(first.begin(), first.end());
  row_start_.assign(row_start.begin(), row_start.end());
  rows_.assign(rows.begin(), rows.end());
}

// The entries the supernodes store below the diagonal (stored_below_, reached_below_)
// and the largest m (max_rows_), from first_ and row_start_.
std::size_t CompactFactor::size_supernodes() {
  std::size_t stored = 0;
  for (int s = 0; s < supernodes(); ++s) {
    const int nc = first_[s + 1] - first_[s];
    const int m = row_start_[s + 1] - row_start_[s];
    stored += static_cast<std::size_t>(supernode_entries(nc, m));
    max_rows_ = std::max(max_rows_, m);
  }
  stored_below_ = stored;
  reached_below_ = stored;
  return stored;
}

template <class Row>
void CompactFactor::build_supernodes(const ColumnView<Row>& columns) {
  find_supernodes(columns);
  const std::size_t stored = size_supernodes();
  if (single_)
    values32_.assign(stored, 0.0f);
  else
    values_.assign(stored, 0.0);
  std::vector<int> where(static_cast<std::size_t>(size_));
  std::size_t offset = 0;
  for (int s = 0; s < supernodes(); ++s)
    offset = fill_supernode(columns, s, offset, where);
}

// Supernode s's entries, stored from `triangle` on, from the columns given; those not
// given stay zero. Returns where the next supernode's entries start.
template <class Row>
std::size_t CompactFactor::fill_supernode(const ColumnView<Row>& columns, int s,
                                          std::size_t triangle, std::vector<int>& where) {
  const int j0 = first_[s], nc = first_[s + 1] - j0;
  const int m = row_start_[s + 1] - row_start_[s];
  for (int r = 0; r < m; ++r)
    where[rows_[static_cast<std::size_t>(row_start_[s] + r)]] = r;
  const std::size_t block = triangle + static_cast<std::size_t>(triangle_entries(nc));
  for (int k = 0; k < nc; ++k) {
    const int j = j0 + k;
    // Column k of the triangle holds rows j + 1 .. j0 + nc - 1.
    const std::size_t column = triangle + static_cast<std::size_t>(triangle_column(nc, k));
    for (int e = columns.begin(j); e < columns.end(j); ++e) {
      const int row = columns.rows[e];
      const std::size_t at = row < j0 + nc ? column + static_cast<std::size_t>(row - j - 1)
                                           : block + static_cast<std::size_t>(k) * m + where[row];
      if (single_)
        values32_[at] = static_cast<float>(columns.values[e]);
      else
        values_[at] = columns.values[e];
    }
  }
  return triangle + static_cast<std::size_t>(supernode_entries(nc, m));
}

std::size_t CompactFactor::bytes() const {
  return values_.capacity() * sizeof(double) + values32_.capacity() * sizeof(float) +
         rows_.capacity() * sizeof(std::uint16_t) + inverse_diagonal_.capacity() * sizeof(double) +
         (permutation_.capacity() + first_.capacity() + row_start_.capacity()) * sizeof(int);
}

double CompactFactor::rcond() const {
  if (inverse_diagonal_.empty()) return 1.0;
  const auto [low, high] = std::minmax_element(inverse_diagonal_.begin(), inverse_diagonal_.end());
  // inverse diagonal: its largest is 1 / the smallest diagonal entry.
  const double ratio = *low / *high;
  return ratio * ratio;
}

namespace {

// x = L_11^-1 x for a supernode's diagonal block (strict lower triangle packed by columns,
// inverse diagonal apart).
template <class Value>
void triangle_forward(const Value* v, int nc, const double* inverse_diagonal, double* x) {
  for (int k = 0; k < nc; ++k) {
    const double xk = x[k] * inverse_diagonal[k];
    x[k] = xk;
    for (int i = k + 1; i < nc; ++i)
      x[i] -= static_cast<double>(*v++) * xk;
  }
}

// x = L_11'^-1 x, column k's dot product with the x below it summed in order.
template <class Value>
void triangle_backward_in_order(const Value* v, int nc, const double* inverse_diagonal, double* x) {
  for (int k = nc - 1; k >= 0; --k) {
    const Value* column = v + triangle_column(nc, k);
    double s = x[k];
    for (int i = k + 1; i < nc; ++i)
      s -= static_cast<double>(column[i - k - 1]) * x[i];
    x[k] = s * inverse_diagonal[k];
  }
}

// The same as four partial sums. In order, each subtraction waits on the one before: on
// the top supernodes of a plane model (dense triangles of 60-75 columns, 11-12% of the
// reached entries) that chain was the back solve's critical path and the largest part of
// M^-1's (docs/BENCHMARKS.md, "F and M^-1: prefetching the factors"). Only there: it
// rounds otherwise, and the small supernodes of the ill-conditioned frame scenes keep their bits
// (in partial sums on every supernode frame_scaffold took 91 MPRGP iterations, not 89).
constexpr int kPartialSumsFrom = 16;  // supernode columns

// The dot product of n entries of a column with x, in four partial sums (they vectorize).
template <class Value>
double column_dot(const Value* __restrict column, const double* __restrict x, int n) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  int i = 0;
  for (; i + 4 <= n; i += 4) {
    s0 += static_cast<double>(column[i]) * x[i];
    s1 += static_cast<double>(column[i + 1]) * x[i + 1];
    s2 += static_cast<double>(column[i + 2]) * x[i + 2];
    s3 += static_cast<double>(column[i + 3]) * x[i + 3];
  }
  for (; i < n; ++i)
    s0 += static_cast<double>(column[i]) * x[i];
  return (s0 + s1) + (s2 + s3);
}

template <class Value>
void triangle_backward(const Value* v, int nc, const double* inverse_diagonal, double* x) {
  if (nc < kPartialSumsFrom) {
    triangle_backward_in_order(v, nc, inverse_diagonal, x);
    return;
  }
  for (int k = nc - 1; k >= 0; --k) {
    const Value* column = v + triangle_column(nc, k);  // rows k + 1 .. nc - 1
    x[k] = (x[k] - column_dot(column, x + k + 1, nc - k - 1)) * inverse_diagonal[k];
  }
}

// t = V x for the m x nc column-major block V: columns taken four, two, one at a time so
// that t is read and written once per group and the loop over rows vectorizes.
template <class Value>
void block_times(const Value* __restrict v, int m, int nc, const double* __restrict x,
                 double* __restrict t) {
  std::fill(t, t + m, 0.0);
  int k = 0;
  for (; k + 4 <= nc; k += 4) {
    const Value* c = v + static_cast<std::ptrdiff_t>(k) * m;
    const double x0 = x[k], x1 = x[k + 1], x2 = x[k + 2], x3 = x[k + 3];
    for (int r = 0; r < m; ++r)
      t[r] += static_cast<double>(c[r]) * x0 + static_cast<double>(c[m + r]) * x1 +
              static_cast<double>(c[2 * m + r]) * x2 + static_cast<double>(c[3 * m + r]) * x3;
  }
  for (; k + 2 <= nc; k += 2) {
    const Value* c = v + static_cast<std::ptrdiff_t>(k) * m;
    const double x0 = x[k], x1 = x[k + 1];
    for (int r = 0; r < m; ++r)
      t[r] += static_cast<double>(c[r]) * x0 + static_cast<double>(c[m + r]) * x1;
  }
  for (; k < nc; ++k) {
    const Value* c = v + static_cast<std::ptrdiff_t>(k) * m;
    const double x0 = x[k];
    for (int r = 0; r < m; ++r)
      t[r] += static_cast<double>(c[r]) * x0;
  }
}

// x -= V' t: independent dot products, two columns at a time, each summed as two partial
// sums (even and odd rows). Written out rather than left to `omp simd reduction`, which
// lets the compiler choose the order of the sum: the -O1 sanitizer build then rounded
// otherwise than the -O3 release build, and golden images that print a residual at
// round-off differed between the two.
template <class Value>
void block_transposed_times(const Value* __restrict v, int m, int nc, const double* __restrict t,
                            double* __restrict x) {
  int k = 0;
  for (; k + 2 <= nc; k += 2) {
    const Value* c = v + static_cast<std::ptrdiff_t>(k) * m;
    double even0 = 0.0, odd0 = 0.0, even1 = 0.0, odd1 = 0.0;
    int r = 0;
    for (; r + 2 <= m; r += 2) {
      even0 += static_cast<double>(c[r]) * t[r];
      odd0 += static_cast<double>(c[r + 1]) * t[r + 1];
      even1 += static_cast<double>(c[m + r]) * t[r];
      odd1 += static_cast<double>(c[m + r + 1]) * t[r + 1];
    }
    if (r < m) {
      even0 += static_cast<double>(c[r]) * t[r];
      even1 += static_cast<double>(c[m + r]) * t[r];
    }
    x[k] -= even0 + odd0;
    x[k + 1] -= even1 + odd1;
  }
  if (k < nc) {
    const Value* c = v + static_cast<std::ptrdiff_t>(k) * m;
    double even0 = 0.0, odd0 = 0.0;
    int r = 0;
    for (; r + 2 <= m; r += 2) {
      even0 += static_cast<double>(c[r]) * t[r];
      odd0 += static_cast<double>(c[r + 1]) * t[r + 1];
    }
    if (r < m) even0 += static_cast<double>(c[r]) * t[r];
    x[k] -= even0 + odd0;
  }
}

// A supernode of one column: a scatter forward, one dot product (two chains) back.
template <class Value>
void column_forward(const Value* c, int m, const std::uint16_t* rows, double inverse_diagonal,
                    double* y, int j) {
  const double x = y[j] * inverse_diagonal;
  y[j] = x;
  for (int r = 0; r < m; ++r)
    y[rows[r]] -= static_cast<double>(c[r]) * x;
}

template <class Value>
void column_backward(const Value* c, int m, const std::uint16_t* rows, double inverse_diagonal,
                     double* y, int j) {
  double a = 0.0, b = 0.0;
  int r = 0;
  for (; r + 2 <= m; r += 2) {
    a += static_cast<double>(c[r]) * y[rows[r]];
    b += static_cast<double>(c[r + 1]) * y[rows[r + 1]];
  }
  if (r < m) a += static_cast<double>(c[r]) * y[rows[r]];
  y[j] = (y[j] - (a + b)) * inverse_diagonal;
}

// A supernode of two columns (a node's two DOFs in a plane model: most supernodes), its
// triangle the one entry L_10 and its block two columns of m rows, scattered and gathered
// directly: no workspace pass and no loop set-up of the general case.
template <class Value>
void pair_forward(const Value* v, int m, const std::uint16_t* rows, const double* inverse_diagonal,
                  double* y, int j0) {
  const double x0 = y[j0] * inverse_diagonal[0];
  const double x1 = (y[j0 + 1] - static_cast<double>(v[0]) * x0) * inverse_diagonal[1];
  y[j0] = x0;
  y[j0 + 1] = x1;
  const Value* c0 = v + 1;
  const Value* c1 = c0 + m;
  for (int r = 0; r < m; ++r)
    y[rows[r]] -= static_cast<double>(c0[r]) * x0 + static_cast<double>(c1[r]) * x1;
}

template <class Value>
void pair_backward(const Value* v, int m, const std::uint16_t* rows, const double* inverse_diagonal,
                   double* y, int j0) {
  const Value* c0 = v + 1;
  const Value* c1 = c0 + m;
  double a0 = 0.0, a1 = 0.0, b0 = 0.0, b1 = 0.0;  // even and odd rows: shorter chains
  int r = 0;
  for (; r + 2 <= m; r += 2) {
    const double t0 = y[rows[r]], t1 = y[rows[r + 1]];
    a0 += static_cast<double>(c0[r]) * t0;
    a1 += static_cast<double>(c1[r]) * t0;
    b0 += static_cast<double>(c0[r + 1]) * t1;
    b1 += static_cast<double>(c1[r + 1]) * t1;
  }
  if (r < m) {
    const double t0 = y[rows[r]];
    a0 += static_cast<double>(c0[r]) * t0;
    a1 += static_cast<double>(c1[r]) * t0;
  }
  const double x1 = (y[j0 + 1] - (a1 + b1)) * inverse_diagonal[1];
  y[j0 + 1] = x1;
  y[j0] = (y[j0] - (a0 + b0) - static_cast<double>(v[0]) * x1) * inverse_diagonal[0];
}

}  // namespace

namespace {

// How far ahead of the supernode being solved the forward pass asks for the factor's
// entries. Each entry is read from memory once per solve, in order, but a supernode's
// columns are short runs (a few hundred bytes) that the hardware prefetcher does not
// follow: the block products waited on their loads (docs/BENCHMARKS.md, "F and M^-1:
// prefetching the factors"). 2 KB: 1 KB gained about as much, 4 KB less.
constexpr std::ptrdiff_t kPrefetchBytes = 2048;

// The cache lines of one part of the entries asked for so far. Addresses as integers: the
// lines past the last supernode's entries are asked for too (a prefetch does not fault),
// and a pointer may not point there.
struct Prefetch {
  std::uintptr_t done;
  void upto(const void* end) {
    const std::uintptr_t stop = reinterpret_cast<std::uintptr_t>(end) + kPrefetchBytes;
    for (; done < stop; done += 64)
      __builtin_prefetch(reinterpret_cast<const void*>(done));
  }
};

}  // namespace

template <class Value>
void CompactFactor::forward(const Value* values, double* y, int columns, double* t,
                            bool reached_only) const {
  // The supernodes' entries follow each other in two parts: the reached, then the others.
  const Value* next[2] = {values + reached_below_, values};
  Prefetch ahead[2] = {{reinterpret_cast<std::uintptr_t>(next[0])},
                       {reinterpret_cast<std::uintptr_t>(next[1])}};
  for (int s = 0; s < supernodes(); ++s) {
    const int j0 = first_[s], nc = first_[s + 1] - j0;
    const int m = row_start_[s + 1] - row_start_[s];
    const bool reached = is_reached(s);
    if (reached_only && !reached) continue;
    const Value* triangle = next[reached];
    next[reached] += supernode_entries(nc, m);
    ahead[reached].upto(next[reached]);
    const Value* block = triangle + triangle_entries(nc);
    const std::uint16_t* rows = rows_.data() + row_start_[s];
    for (int c = 0; c < columns; ++c) {
      double* yc = y + static_cast<std::ptrdiff_t>(c) * size_;
      if (nc == 1) {  // a chain's columns (bars, beams)
        column_forward(triangle, m, rows, inverse_diagonal_[j0], yc, j0);
        continue;
      }
      if (nc == 2) {  // most supernodes of a plane model: a node's two DOFs
        pair_forward(triangle, m, rows, inverse_diagonal_.data() + j0, yc, j0);
        continue;
      }
      triangle_forward(triangle, nc, inverse_diagonal_.data() + j0, yc + j0);
      if (m == 0) continue;
      block_times(block, m, nc, yc + j0, t);
      for (int r = 0; r < m; ++r)
        yc[rows[r]] -= t[r];
    }
  }
}

template <class Value>
void CompactFactor::backward(const Value* values, double* y, int columns, double* t,
                             bool reached_only) const {
  // Past the last supernode's entries of each part (the others, the reached).
  const Value* end[2] = {values + stored_below_, values + reached_below_};
  for (int s = supernodes() - 1; s >= 0; --s) {
    const int j0 = first_[s], nc = first_[s + 1] - j0;
    const int m = row_start_[s + 1] - row_start_[s];
    const bool reached = is_reached(s);
    if (reached_only && !reached) continue;
    end[reached] -= supernode_entries(nc, m);
    const Value* triangle = end[reached];
    const Value* block = triangle + triangle_entries(nc);
    const std::uint16_t* rows = rows_.data() + row_start_[s];
    for (int c = 0; c < columns; ++c) {
      double* yc = y + static_cast<std::ptrdiff_t>(c) * size_;
      if (nc == 1) {
        column_backward(triangle, m, rows, inverse_diagonal_[j0], yc, j0);
        continue;
      }
      if (nc == 2) {
        pair_backward(triangle, m, rows, inverse_diagonal_.data() + j0, yc, j0);
        continue;
      }
      if (m > 0) {
        for (int r = 0; r < m; ++r)
          t[r] = yc[rows[r]];
        block_transposed_times(block, m, nc, t, yc + j0);
      }
      triangle_backward(triangle, nc, inverse_diagonal_.data() + j0, yc + j0);
    }
  }
}

template <class Value>
void CompactFactor::trailing_entries(const Value* values, int first,
                                     std::vector<const Value*>& at) const {
  const Value* end[2] = {values + stored_below_, values + reached_below_};
  at.clear();
  for (int s = supernodes() - 1; s >= 0 && first_[s + 1] > first; --s) {
    const bool reached = is_reached(s);
    end[reached] -= supernode_entries(first_[s + 1] - first_[s], row_start_[s + 1] - row_start_[s]);
    at.push_back(end[reached]);
  }
}

template <class Value>
void CompactFactor::multiply_trailing(const Value* values, int first, const double* t,
                                      double* v) const {
  std::fill(v, v + (size_ - first), 0.0);
  thread_local std::vector<const Value*> at;
  trailing_entries(values, first, at);
  for (std::size_t p = 0; p < at.size(); ++p) {
    const int s = supernodes() - 1 - static_cast<int>(p), j0 = first_[s], nc = first_[s + 1] - j0;
    const int m = row_start_[s + 1] - row_start_[s];
    const Value* triangle = at[p];
    const Value* block = triangle + triangle_entries(nc);
    const std::uint16_t* rows = rows_.data() + row_start_[s];
    for (int k = std::max(0, first - j0); k < nc; ++k) {
      const int j = j0 + k - first;  // the column's row in t and v
      const Value* below = triangle + triangle_column(nc, k);
      const Value* column = block + static_cast<std::ptrdiff_t>(k) * m;
      const double diagonal = 1.0 / inverse_diagonal_[j0 + k];
      double a = diagonal * t[j] + column_dot(below, t + j + 1, nc - k - 1);
      for (int r = 0; r < m; ++r)
        a += static_cast<double>(column[r]) * t[rows[r] - first];
      v[j] += diagonal * a;
      for (int i = 0; i < nc - k - 1; ++i)
        v[j + 1 + i] += static_cast<double>(below[i]) * a;
      for (int r = 0; r < m; ++r)
        v[rows[r] - first] += static_cast<double>(column[r]) * a;
    }
  }
}

template <class Value>
void CompactFactor::solve_trailing(const Value* values, int first, double* y) const {
  thread_local std::vector<const Value*> at;
  thread_local std::vector<double> t;
  trailing_entries(values, first, at);
  const int count = static_cast<int>(at.size()), last = supernodes() - 1;
  if (t.size() < static_cast<std::size_t>(max_rows_)) t.resize(static_cast<std::size_t>(max_rows_));
  for (int a = count - 1; a >= 0; --a) {  // forward: L_t y' = y
    const int s = last - a, j0 = first_[s], nc = first_[s + 1] - j0;
    const int m = row_start_[s + 1] - row_start_[s], k0 = std::max(0, first - j0);
    const Value* block = at[static_cast<std::size_t>(a)] + triangle_entries(nc);
    for (int k = k0; k < nc; ++k) {
      const double xk = y[j0 + k] * inverse_diagonal_[j0 + k];
      y[j0 + k] = xk;
      const Value* below = at[static_cast<std::size_t>(a)] + triangle_column(nc, k);
      for (int i = 0; i < nc - k - 1; ++i)
        y[j0 + k + 1 + i] -= static_cast<double>(below[i]) * xk;
    }
    if (m == 0) continue;
    std::fill(t.begin(), t.begin() + m, 0.0);
    for (int k = k0; k < nc; ++k) {
      const Value* column = block + static_cast<std::ptrdiff_t>(k) * m;
      const double xk = y[j0 + k];
      for (int r = 0; r < m; ++r)
        t[static_cast<std::size_t>(r)] += static_cast<double>(column[r]) * xk;
    }
    const std::uint16_t* rows = rows_.data() + row_start_[s];
    for (int r = 0; r < m; ++r)
      y[rows[r]] -= t[static_cast<std::size_t>(r)];
  }
  for (int a = 0; a < count; ++a) {  // back: L_t' y' = y
    const int s = last - a, j0 = first_[s], nc = first_[s + 1] - j0;
    const int m = row_start_[s + 1] - row_start_[s], k0 = std::max(0, first - j0);
    const Value* block = at[static_cast<std::size_t>(a)] + triangle_entries(nc);
    const std::uint16_t* rows = rows_.data() + row_start_[s];
    for (int r = 0; r < m; ++r)
      t[static_cast<std::size_t>(r)] = y[rows[r]];
    for (int k = nc - 1; k >= k0; --k) {
      const Value* below = at[static_cast<std::size_t>(a)] + triangle_column(nc, k);
      const double sum = column_dot(block + static_cast<std::ptrdiff_t>(k) * m, t.data(), m) +
                         column_dot(below, y + j0 + k + 1, nc - k - 1);
      y[j0 + k] = (y[j0 + k] - sum) * inverse_diagonal_[j0 + k];
    }
  }
}

void CompactFactor::solve_trailing_in_place(int first, double* y) const {
  if (single_)
    solve_trailing(values32_.data(), first, y);
  else
    solve_trailing(values_.data(), first, y);
}

void CompactFactor::multiply_trailing(int first, const double* t, double* v) const {
  if (single_)
    multiply_trailing(values32_.data(), first, t, v);
  else
    multiply_trailing(values_.data(), first, t, v);
}

std::size_t CompactFactor::trailing_bytes(int first) const {
  std::size_t bytes = 0;
  const std::size_t value = single_ ? sizeof(float) : sizeof(double);
  for (int s = supernodes() - 1; s >= 0 && first_[s + 1] > first; --s) {
    const int j0 = first_[s], nc = first_[s + 1] - j0;
    const int m = row_start_[s + 1] - row_start_[s];
    const int k0 = std::max(0, first - j0);
    // Columns k0 .. nc - 1: their triangle's entries and block rows, diagonal and rows.
    const auto columns = static_cast<std::size_t>(nc - k0);
    bytes += (columns * (columns - 1) / 2 + columns * static_cast<std::size_t>(m)) * value +
             columns * sizeof(double) + static_cast<std::size_t>(m) * sizeof(std::uint16_t) +
             2 * sizeof(int);
  }
  return bytes;
}

std::vector<int> CompactFactor::positions() const {
  std::vector<int> position(permutation_.size());
  for (int k = 0; k < size_; ++k)
    position[static_cast<std::size_t>(permutation_[static_cast<std::size_t>(k)])] = k;
  return position;
}

void CompactFactor::solve_parts(double* y, int columns, bool reached_only) const {
  thread_local std::vector<double> t;
  if (t.size() < static_cast<std::size_t>(max_rows_)) t.resize(static_cast<std::size_t>(max_rows_));
  if (single_) {
    forward(values32_.data(), y, columns, t.data(), reached_only);
    backward(values32_.data(), y, columns, t.data(), reached_only);
  } else {
    forward(values_.data(), y, columns, t.data(), reached_only);
    backward(values_.data(), y, columns, t.data(), reached_only);
  }
}

void CompactFactor::solve_in_place(double* y, int columns) const {
  solve_parts(y, columns, false);
}

void CompactFactor::solve_reached_in_place(double* y) const {
  solve_parts(y, 1, true);
}

// The entries from the one ordered sequence to the two parts reached_ defines.
template <class Value>
void CompactFactor::reorder_reached_first(huge_pages::Vector<Value>& values) const {
  // Rewritten in place from a copy on the ordinary heap (reused from one factor to the
  // next): a second array in huge pages would stay mapped beside the first until the
  // whole chunk is freed.
  thread_local std::vector<Value> copy;
  copy.assign(values.begin(), values.end());
  std::size_t to = 0;
  for (const bool part : {true, false}) {
    std::size_t from = 0;
    for (int s = 0; s < supernodes(); ++s) {
      const auto count = static_cast<std::size_t>(
          supernode_entries(first_[s + 1] - first_[s], row_start_[s + 1] - row_start_[s]));
      if ((reached_[static_cast<std::size_t>(s)] != 0) == part) {
        std::copy_n(copy.begin() + static_cast<std::ptrdiff_t>(from), count,
                    values.begin() + static_cast<std::ptrdiff_t>(to));
        to += count;
      }
      from += count;
    }
  }
}

void CompactFactor::reach_first(const std::vector<int>& rows) {
  if (!reached_.empty()) throw std::logic_error("CompactFactor: reach_first() twice");
  std::vector<int> supernode_of(static_cast<std::size_t>(size_));
  for (int s = 0; s < supernodes(); ++s)
    std::fill(supernode_of.begin() + first_[s], supernode_of.begin() + first_[s + 1], s);
  std::vector<char> reached(static_cast<std::size_t>(supernodes()), 0);
  for (int row : rows)
    reached[static_cast<std::size_t>(supernode_of[static_cast<std::size_t>(row)])] = 1;
  // A supernode updates the rows below it, all in later supernodes: one pass in order
  // marks every supernode a marked one updates. Every row, not only the first: a relaxed
  // supernode's rows need not lie on one path of the elimination tree.
  std::size_t entries = 0;
  for (int s = 0; s < supernodes(); ++s) {
    if (!reached[static_cast<std::size_t>(s)]) continue;
    entries += static_cast<std::size_t>(
        supernode_entries(first_[s + 1] - first_[s], row_start_[s + 1] - row_start_[s]));
    for (int k = row_start_[s]; k < row_start_[s + 1]; ++k)
      reached[static_cast<std::size_t>(supernode_of[rows_[static_cast<std::size_t>(k)]])] = 1;
  }
  reached_.swap(reached);
  reached_below_ = entries;
  if (single_)
    reorder_reached_first(values32_);
  else
    reorder_reached_first(values_);
}

std::size_t CompactFactor::reached_bytes() const {
  std::size_t bytes = reached_below_ * (single_ ? sizeof(float) : sizeof(double));
  for (int s = 0; s < supernodes(); ++s)
    if (is_reached(s))
      bytes += static_cast<std::size_t>(row_start_[s + 1] - row_start_[s]) * sizeof(std::uint16_t) +
               static_cast<std::size_t>(first_[s + 1] - first_[s]) * sizeof(double) +
               2 * sizeof(int);
  return bytes;
}

bool CompactFactor::reached(int row) const {
  if (reached_.empty()) return true;
  const auto after = std::upper_bound(first_.begin(), first_.end(), row);
  return reached_[static_cast<std::size_t>(after - first_.begin() - 1)] != 0;
}

void CompactFactor::solve(const double* b, double* x, int columns) const {
  thread_local std::vector<double> work;
  const auto n = static_cast<std::size_t>(size_);
  work.resize(n * static_cast<std::size_t>(columns));
  for (int c = 0; c < columns; ++c) {
    const std::size_t offset = static_cast<std::size_t>(c) * n;
    for (std::size_t k = 0; k < n; ++k)
      work[offset + k] = b[offset + static_cast<std::size_t>(permutation_[k])];
  }
  solve_in_place(work.data(), columns);
  for (int c = 0; c < columns; ++c) {
    const std::size_t offset = static_cast<std::size_t>(c) * n;
    for (std::size_t k = 0; k < n; ++k)
      x[offset + static_cast<std::size_t>(permutation_[k])] = work[offset + k];
  }
}

}  // namespace fetic::solver

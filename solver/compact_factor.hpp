#pragma once
// A lean, solve-only copy of a sparse Cholesky factor P A P' = L L' (docs/BENCHMARKS.md,
// bytes per unknown; "Supernodal compact factors"). CHOLMOD's own supernodal factor of a
// ~1,000-unknown subdomain pads its supernodes with zeros (relaxed amalgamation: 1.6
// stored entries per nonzero) and spends more time per supernode in its BLAS calls than
// in the arithmetic; its simplicial factor keeps a 4-byte row index per entry and solves
// one column at a time, each waiting for the one before.
//
// Here L is given column by column and stored as supernodes: runs of consecutive columns
// whose rows below the run nest (fundamental supernodes), merged further while at most
// kRelaxedZeros of the stored entries are explicit zeros. A supernode of nc columns
// keeps its diagonal block's strict lower triangle (packed by columns) and a dense m x nc
// column-major block of its rows below the run, with ONE list of those m rows (16-bit)
// for the whole supernode: about 8 bytes an entry (4 with `single`) instead of 10 (6).
// The forward solve is a small triangular solve, then t = block * x with the columns'
// updates summed in several independent accumulators, scattered into y once; the back
// solve gathers y's rows, forms block' * t as independent dot products, then the
// triangle. The loops are dense and vectorize instead of one dependent chain a column.
// With `single` the entries below the diagonal are floats; the diagonal and all
// arithmetic stay double: the factor is then that of A + E with |E| about 6e-8 |L||L'|
// (docs/BENCHMARKS.md, single precision factors).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/huge_pages.hpp"

namespace fetic::solver {

class CompactFactor {
 public:
  // Largest order whose row indices fit the 16-bit entries.
  static constexpr int kMaxSize = 65536;
  // Share of a relaxed supernode's stored entries that may be explicit zeros.
  static constexpr double kRelaxedZeros = 0.1;

  // Built column by column in order: start_column(L_jj) for column j, then add(i, L_ij)
  // for rows i > j in increasing order (checked: std::logic_error otherwise); finish()
  // after the last column.
  CompactFactor(int size, const int* permutation, std::size_t nonzeros_hint, bool single = false);
  void start_column(double diagonal);
  void add(int row, double value);
  void finish();

  // A whole factor given as compressed columns, read in place (CHOLMOD's simplicial LL'
  // after its explicit zeros were dropped): column j's entries are start[j] ..
  // start[j + 1] - 1, its diagonal first, then nonzeros at increasing rows below it (the
  // caller checks this). The supernodes are built straight from these arrays: no column
  // copy, no per-entry add() (they were a fifth of the FETI set-up, docs/BENCHMARKS.md).
  struct Columns {
    const int* start;
    const int* rows;
    const double* values;
  };
  CompactFactor(int size, const int* permutation, const Columns& columns, bool single = false);
  // A factor computed in this layout already (solver/supernodal_factorization.hpp): `count`
  // supernodes, s holding columns first[s] .. first[s + 1] - 1 and rows rows[row_start[s]
  // .. row_start[s + 1] - 1] below them (increasing), its entries in `values` (all
  // supernodes' one after the other: the strict lower triangle packed by columns, then the
  // m x nc block column-major), L's diagonal apart. Copied once at their size; no
  // supernodes are looked for (the caller chose them).
  struct Supernodes {
    int count;
    const int* first;
    const int* row_start;
    const int* rows;
    const double* values;
    const double* diagonal;
  };
  CompactFactor(int size, const int* permutation, const Supernodes& supernodes,
                bool single = false);

  int size() const { return size_; }
  bool single() const { return single_; }
  // Stored entries of L (its diagonal and the relaxed supernodes' zeros included).
  std::size_t nonzeros() const { return stored_below_ + inverse_diagonal_.size(); }
  int supernodes() const { return static_cast<int>(first_.size()) - 1; }
  std::size_t bytes() const;
  // min(diag L)^2 / max(diag L)^2, as CHOLMOD estimates rcond of an LL' factor.
  double rcond() const;

  // x = A^-1 b for `columns` column-major right-hand sides, each supernode applied to all
  // of them while it is in the cache. Thread-safe (the workspaces are per thread).
  void solve(const double* b, double* x, int columns = 1) const;
  // The same on a vector already in the factor's order: y = (P A P')^-1 y, where y's row
  // k is row permutation()[k] of A's. A caller that gathers its right-hand side straight
  // into this order (FETI's F and the Dirichlet preconditioner) saves solve()'s two
  // permuting passes and its copy.
  void solve_in_place(double* y, int columns = 1) const;
  // Solves whose right-hand side is zero outside the rows `rows` (in the factor's order)
  // and which read only those rows of the solution - F's on a subdomain's boundary, the
  // Dirichlet preconditioner's on K_ii's rows next to it - need only the supernodes
  // holding those rows and every supernode a visited one updates (those holding its rows
  // below its columns: its ancestors). Every other supernode's columns stay zero forward
  // and are read by no visited one backward, so skipping them gives those rows the same
  // bits. reach_first(rows) marks these supernodes and stores their entries first, in
  // order, the others after: solve_reached_in_place() then streams one contiguous part
  // (skipping scattered supernodes in place saved nothing - the hardware prefetcher read
  // the gaps anyway). solve() and solve_in_place() still solve with all of them.
  void reach_first(const std::vector<int>& rows);
  // Whether row (factor order) is in a supernode reach_first() marked (all are without).
  bool reached(int row) const;
  // solve_in_place(y) on the marked supernodes: y's rows outside reach_first()'s `rows`
  // come out unspecified.
  void solve_reached_in_place(double* y) const;
  std::size_t reached_nonzeros() const { return reached_below_ + inverse_diagonal_.size(); }
  // Bytes of the factor that solve_reached_in_place() reads (each pass once): the marked
  // supernodes' entries, row lists, inverse diagonals and bounds.
  std::size_t reached_bytes() const;
  // v = L_t L_t' t, L_t the factor's columns from `first` on and their rows (all from
  // `first` on): for an ordering with the leading block's rows first, the Schur
  // complement of A onto its trailing rows (solver/boundary_last.hpp). t and v hold rows
  // first .. size() - 1 (factor order); each column is read once (v gains column j times
  // its product with t while the column is in the cache).
  void multiply_trailing(int first, const double* t, double* v) const;
  // y = (L_t L_t')^-1 y on rows first .. size() - 1 (factor order; the others neither read
  // nor written): for such an ordering, the solve of a right-hand side that is zero on the
  // leading rows, read on the trailing rows alone - F's on a subdomain's boundary. Only
  // the trailing columns are read, not the leading ones a relaxed supernode shares them with.
  void solve_trailing_in_place(int first, double* y) const;
  // Bytes multiply_trailing(first) reads of the factor (solve_trailing_in_place(): twice).
  std::size_t trailing_bytes(int first) const;
  const std::vector<int>& permutation() const { return permutation_; }
  // Per row of A, its row in the factor's order: the inverse of permutation().
  std::vector<int> positions() const;

 private:
  // The columns below the diagonal, as given to add() (Row = uint16) or as compressed
  // columns with the diagonal first (Row = int, skip = 1).
  template <class Row>
  struct ColumnView {
    const int* start;
    const Row* rows;
    const double* values;
    int skip;
    int begin(int j) const { return start[j] + skip; }
    int end(int j) const { return start[j + 1]; }
  };
  template <class Row>
  void build_supernodes(const ColumnView<Row>& columns);  // the columns into supernodes
  std::size_t size_supernodes();
  template <class Row>
  void find_supernodes(const ColumnView<Row>& columns);
  template <class Row>
  std::size_t fill_supernode(const ColumnView<Row>& columns, int s, std::size_t triangle,
                             std::vector<int>& where);
  // L y' = y and L' y' = y; `reached_only`: on the supernodes reach_first() marked.
  template <class Value>
  void forward(const Value* values, double* y, int columns, double* t, bool reached_only) const;
  template <class Value>
  void backward(const Value* values, double* y, int columns, double* t, bool reached_only) const;
  void solve_parts(double* y, int columns, bool reached_only) const;
  template <class Value>
  void multiply_trailing(const Value* values, int first, const double* t, double* v) const;
  template <class Value>
  void solve_trailing(const Value* values, int first, double* y) const;
  // The entries of the supernodes holding columns from `first` on, the last first.
  template <class Value>
  void trailing_entries(const Value* values, int first, std::vector<const Value*>& at) const;
  bool is_reached(int s) const { return reached_.empty() || reached_[static_cast<std::size_t>(s)]; }
  template <class Value>
  void reorder_reached_first(huge_pages::Vector<Value>& values) const;

  int size_ = 0;
  bool single_ = false;
  std::vector<int> permutation_;  // P: row k of P A P' is row permutation_[k] of A
  // Kept for the whole solve, allocated once at their size: in huge pages as values_.
  huge_pages::Vector<double> inverse_diagonal_;
  // The columns as given, until finish().
  std::vector<int> column_start_;
  std::vector<std::uint16_t> column_rows_;
  std::vector<double> column_values_;
  // The supernodes: s holds columns first_[s] .. first_[s + 1] - 1, its rows below them
  // rows_[row_start_[s] ..], its entries (triangle, then block) after those of s - 1.
  huge_pages::Vector<int> first_;
  huge_pages::Vector<int> row_start_;
  huge_pages::Vector<std::uint16_t> rows_;
  std::size_t stored_below_ = 0;
  // Per supernode, whether reach_first() marked it (empty: all); the marked supernodes'
  // entries come first (reached_below_ of them), then the others', each part in order.
  std::vector<char> reached_;
  std::size_t reached_below_ = 0;
  int max_rows_ = 0;  // the largest m: the solves' workspace
  // L's entries below the diagonal (double), or as floats (single): most of a FETI
  // solve's resident bytes, allocated once at their size, in huge pages (huge_pages.hpp).
  huge_pages::Vector<double> values_;
  huge_pages::Vector<float> values32_;
};

}  // namespace fetic::solver

#pragma once
// A lean, solve-only copy of a sparse Cholesky factor P A P' = L L' (docs/BENCHMARKS.md,
// bytes per unknown). CHOLMOD's supernodal factor of a ~1,000-unknown subdomain stores
// its supernodes as dense blocks padded with zeros (relaxed amalgamation: 1.6 stored
// entries per nonzero) and spends more time per supernode in its BLAS calls than in the
// arithmetic. Here L keeps only its nonzeros, column by column, with 16-bit row indices
// (10 bytes an entry): about a quarter fewer bytes than the supernodal factor, and the
// triangular solves are plain loops over them. With `single` the off-diagonal entries
// are kept as floats (6 bytes an entry), the diagonal and all arithmetic in double: the
// factor is then that of A + E with |E| about 6e-8 |L||L'| (docs/BENCHMARKS.md, single
// precision factors).

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fetic::solver {

class CompactFactor {
 public:
  // Largest order whose row indices fit the 16-bit entries.
  static constexpr int kMaxSize = 65536;

  // Built column by column in order: start_column(j, L_jj), then add(i, L_ij) for rows
  // i > j in increasing order; finish() after the last column.
  CompactFactor(int size, const int* permutation, std::size_t nonzeros_hint, bool single = false);
  void start_column(double diagonal);
  void add(int row, double value);
  void finish();

  int size() const { return size_; }
  bool single() const { return single_; }
  // Stored entries of L (its diagonal included).
  std::size_t nonzeros() const { return rows_.size() + inverse_diagonal_.size(); }
  std::size_t bytes() const;
  // min(diag L)^2 / max(diag L)^2, as CHOLMOD estimates rcond of an LL' factor.
  double rcond() const;

  // x = A^-1 b for `columns` column-major right-hand sides. Thread-safe (the workspace
  // is per thread).
  void solve(const double* b, double* x, int columns = 1) const;

 private:
  template <class Value>
  void forward(const Value* values, double* y) const;  // L y' = y
  template <class Value>
  void backward(const Value* values, double* y) const;  // L' y' = y

  int size_ = 0;
  bool single_ = false;
  std::vector<int> permutation_;   // P: row k of P A P' is row permutation_[k] of A
  std::vector<int> column_start_;  // into rows_/values_, size + 1
  std::vector<double> inverse_diagonal_;
  std::vector<std::uint16_t> rows_;
  std::vector<double> values_;   // L's entries below the diagonal (double)
  std::vector<float> values32_;  // or as floats (single)
};

}  // namespace fetic::solver

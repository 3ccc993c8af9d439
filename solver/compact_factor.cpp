#include "solver/compact_factor.hpp"

#include <algorithm>
#include <stdexcept>

namespace fetic::solver {

CompactFactor::CompactFactor(int size, const int* permutation, int leading,
                             std::size_t nonzeros_hint)
    : size_(size), leading_(leading), permutation_(permutation, permutation + size) {
  if (size > kMaxSize) throw std::logic_error("CompactFactor: order above 65536");
  column_start_.reserve(static_cast<std::size_t>(size) + 1);
  leading_end_.reserve(static_cast<std::size_t>(leading));
  inverse_diagonal_.reserve(static_cast<std::size_t>(size));
  rows_.reserve(nonzeros_hint);
  values_.reserve(nonzeros_hint);
}

void CompactFactor::start_column(double diagonal) {
  const int j = static_cast<int>(column_start_.size());
  // The previous column's rows all lay inside the leading block.
  if (j > 0 && j - 1 < leading_ && static_cast<int>(leading_end_.size()) == j - 1)
    leading_end_.push_back(static_cast<int>(values_.size()));
  column_start_.push_back(static_cast<int>(values_.size()));
  inverse_diagonal_.push_back(1.0 / diagonal);
}

void CompactFactor::add(int row, double value) {
  const int j = static_cast<int>(column_start_.size()) - 1;
  // Rows below the leading block follow those inside it (rows come in increasing order):
  // the first row past it closes the column's leading part.
  if (j < leading_ && row >= leading_ && static_cast<int>(leading_end_.size()) == j)
    leading_end_.push_back(static_cast<int>(values_.size()));
  rows_.push_back(static_cast<std::uint16_t>(row));
  values_.push_back(value);
}

void CompactFactor::finish() {
  const int last = static_cast<int>(column_start_.size()) - 1;
  if (last >= 0 && last < leading_ && static_cast<int>(leading_end_.size()) == last)
    leading_end_.push_back(static_cast<int>(values_.size()));
  column_start_.push_back(static_cast<int>(values_.size()));
  if (static_cast<int>(inverse_diagonal_.size()) != size_)
    throw std::logic_error("CompactFactor: not every column was given");
  // Exactly the entries given: no spare capacity held for the whole solve.
  rows_.shrink_to_fit();
  values_.shrink_to_fit();
}

std::size_t CompactFactor::bytes() const {
  return values_.capacity() * sizeof(double) + rows_.capacity() * sizeof(std::uint16_t) +
         inverse_diagonal_.capacity() * sizeof(double) +
         (permutation_.capacity() + column_start_.capacity() + leading_end_.capacity()) *
             sizeof(int);
}

double CompactFactor::rcond() const {
  if (inverse_diagonal_.empty()) return 1.0;
  const auto [low, high] = std::minmax_element(inverse_diagonal_.begin(), inverse_diagonal_.end());
  // inverse diagonal: its largest is 1 / the smallest diagonal entry.
  const double ratio = *low / *high;
  return ratio * ratio;
}

void CompactFactor::forward(double* y, int end, bool leading_only) const {
  for (int j = 0; j < end; ++j) {
    const double yj = y[j] * inverse_diagonal_[j];
    y[j] = yj;
    const int stop = leading_only ? leading_end_[j] : column_start_[j + 1];
    for (int k = column_start_[j]; k < stop; ++k)
      y[rows_[k]] -= values_[k] * yj;
  }
}

void CompactFactor::backward(double* y, int end, bool leading_only) const {
  for (int j = end - 1; j >= 0; --j) {
    double s = y[j];
    const int stop = leading_only ? leading_end_[j] : column_start_[j + 1];
    for (int k = column_start_[j]; k < stop; ++k)
      s -= values_[k] * y[rows_[k]];
    y[j] = s * inverse_diagonal_[j];
  }
}

void CompactFactor::solve(const double* b, double* x, int columns) const {
  thread_local std::vector<double> work;
  work.resize(static_cast<std::size_t>(size_));
  for (int c = 0; c < columns; ++c) {
    const double* bc = b + static_cast<std::size_t>(c) * size_;
    double* xc = x + static_cast<std::size_t>(c) * size_;
    for (int k = 0; k < size_; ++k)
      work[k] = bc[permutation_[k]];
    forward(work.data(), size_, false);
    backward(work.data(), size_, false);
    for (int k = 0; k < size_; ++k)
      xc[permutation_[k]] = work[k];
  }
}

void CompactFactor::solve_leading(const double* b, double* x) const {
  if (leading_ == 0) throw std::logic_error("CompactFactor: no leading block");
  thread_local std::vector<double> work;
  work.resize(static_cast<std::size_t>(leading_));
  for (int k = 0; k < leading_; ++k)
    work[k] = b[permutation_[k]];
  forward(work.data(), leading_, true);
  backward(work.data(), leading_, true);
  for (int k = 0; k < size_; ++k)
    x[permutation_[k]] = k < leading_ ? work[k] : 0.0;
}

}  // namespace fetic::solver

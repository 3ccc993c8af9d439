#include "solver/compact_factor.hpp"

#include <algorithm>
#include <stdexcept>

namespace fetic::solver {

CompactFactor::CompactFactor(int size, const int* permutation, std::size_t nonzeros_hint,
                             bool single)
    : size_(size), single_(single), permutation_(permutation, permutation + size) {
  if (size > kMaxSize) throw std::logic_error("CompactFactor: order above 65536");
  column_start_.reserve(static_cast<std::size_t>(size) + 1);
  inverse_diagonal_.reserve(static_cast<std::size_t>(size));
  rows_.reserve(nonzeros_hint);
  if (single_)
    values32_.reserve(nonzeros_hint);
  else
    values_.reserve(nonzeros_hint);
}

void CompactFactor::start_column(double diagonal) {
  column_start_.push_back(static_cast<int>(rows_.size()));
  inverse_diagonal_.push_back(1.0 / diagonal);
}

void CompactFactor::add(int row, double value) {
  rows_.push_back(static_cast<std::uint16_t>(row));
  if (single_)
    values32_.push_back(static_cast<float>(value));
  else
    values_.push_back(value);
}

void CompactFactor::finish() {
  column_start_.push_back(static_cast<int>(rows_.size()));
  if (static_cast<int>(inverse_diagonal_.size()) != size_)
    throw std::logic_error("CompactFactor: not every column was given");
  // Exactly the entries given: no spare capacity held for the whole solve.
  rows_.shrink_to_fit();
  values_.shrink_to_fit();
  values32_.shrink_to_fit();
}

std::size_t CompactFactor::bytes() const {
  return values_.capacity() * sizeof(double) + values32_.capacity() * sizeof(float) +
         rows_.capacity() * sizeof(std::uint16_t) + inverse_diagonal_.capacity() * sizeof(double) +
         (permutation_.capacity() + column_start_.capacity()) * sizeof(int);
}

double CompactFactor::rcond() const {
  if (inverse_diagonal_.empty()) return 1.0;
  const auto [low, high] = std::minmax_element(inverse_diagonal_.begin(), inverse_diagonal_.end());
  // inverse diagonal: its largest is 1 / the smallest diagonal entry.
  const double ratio = *low / *high;
  return ratio * ratio;
}

template <class Value>
void CompactFactor::forward(const Value* values, double* y) const {
  for (int j = 0; j < size_; ++j) {
    const double yj = y[j] * inverse_diagonal_[j];
    y[j] = yj;
    for (int k = column_start_[j]; k < column_start_[j + 1]; ++k)
      y[rows_[k]] -= static_cast<double>(values[k]) * yj;
  }
}

template <class Value>
void CompactFactor::backward(const Value* values, double* y) const {
  for (int j = size_ - 1; j >= 0; --j) {
    double s = y[j];
    for (int k = column_start_[j]; k < column_start_[j + 1]; ++k)
      s -= static_cast<double>(values[k]) * y[rows_[k]];
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
    if (single_) {
      forward(values32_.data(), work.data());
      backward(values32_.data(), work.data());
    } else {
      forward(values_.data(), work.data());
      backward(values_.data(), work.data());
    }
    for (int k = 0; k < size_; ++k)
      xc[permutation_[k]] = work[k];
  }
}

}  // namespace fetic::solver

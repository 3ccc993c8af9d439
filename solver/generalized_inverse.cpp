#include "solver/generalized_inverse.hpp"

#include <algorithm>

#include <Eigen/QR>

namespace fetic::solver {

std::vector<int> choose_fixing_dofs(const Eigen::MatrixXd& kernel) {
  const int m = static_cast<int>(kernel.cols());
  if (m == 0) return {};
  Eigen::MatrixXd scaled = kernel;
  for (int j = 0; j < m; ++j)
    scaled.col(j).normalize();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled.transpose());
  std::vector<int> fixed;
  for (int j = 0; j < m; ++j)
    fixed.push_back(qr.colsPermutation().indices()(j));
  std::sort(fixed.begin(), fixed.end());
  return fixed;
}

CholmodFactor::Result GeneralizedInverse::factorize(const SparseMatrix& K,
                                                    const Eigen::MatrixXd& kernel) {
  size_ = static_cast<int>(K.rows());
  fixed_ = choose_fixing_dofs(kernel);
  kept_.clear();
  std::vector<int> position(size_, -1);
  for (int dof = 0, f = 0; dof < size_; ++dof) {
    if (f < static_cast<int>(fixed_.size()) && fixed_[f] == dof) {
      ++f;
      continue;
    }
    position[dof] = static_cast<int>(kept_.size());
    kept_.push_back(dof);
  }
  if (fixed_.empty()) return factor_.factorize(K);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(K.nonZeros()));
  for (int col = 0; col < K.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(K, col); it; ++it)
      if (position[it.row()] >= 0 && position[col] >= 0)
        entries.emplace_back(position[it.row()], position[col], it.value());
  const int n = static_cast<int>(kept_.size());
  SparseMatrix reduced(n, n);
  reduced.setFromTriplets(entries.begin(), entries.end());
  return factor_.factorize(reduced);
}

int GeneralizedInverse::failed_dof() const {
  const int column = factor_.failed_column();
  if (column < 0 || column >= static_cast<int>(kept_.size())) return -1;
  return kept_[column];
}

void GeneralizedInverse::apply(const double* x, double* y, int columns) const {
  if (fixed_.empty()) {
    factor_.solve(x, y, columns);
    return;
  }
  const int n = static_cast<int>(kept_.size());
  rhs_.resize(n, columns);
  solution_.resize(n, columns);
  for (int c = 0; c < columns; ++c)
    for (int r = 0; r < n; ++r)
      rhs_(r, c) = x[static_cast<size_t>(c) * size_ + kept_[r]];
  factor_.solve(rhs_.data(), solution_.data(), columns);
  for (int c = 0; c < columns; ++c) {
    double* column = y + static_cast<size_t>(c) * size_;
    for (int dof : fixed_)
      column[dof] = 0.0;
    for (int r = 0; r < n; ++r)
      column[kept_[r]] = solution_(r, c);
  }
}

Eigen::VectorXd GeneralizedInverse::apply(const Eigen::VectorXd& x) const {
  Eigen::VectorXd y(size_);
  apply(x.data(), y.data());
  return y;
}

}  // namespace fetic::solver

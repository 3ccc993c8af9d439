#include "solver/generalized_inverse.hpp"

#include <algorithm>

#include <Eigen/QR>
#include <Eigen/SVD>

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

double pinning_quality(const Eigen::MatrixXd& kernel, const std::vector<int>& fixed) {
  const int m = static_cast<int>(kernel.cols());
  if (m == 0) return 1.0;
  Eigen::MatrixXd block(static_cast<int>(fixed.size()), m);
  for (int j = 0; j < m; ++j) {
    const double norm = kernel.col(j).norm();
    for (size_t k = 0; k < fixed.size(); ++k)
      block(static_cast<int>(k), j) = norm > 0.0 ? kernel(fixed[k], j) / norm : 0.0;
  }
  const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(block).singularValues();
  return s.size() == 0 || s(0) == 0.0 ? 0.0 : s(s.size() - 1) / s(0);
}

CholmodFactor::Result GeneralizedInverse::factorize(const SparseMatrix& K,
                                                    const Eigen::MatrixXd& kernel) {
  size_ = static_cast<int>(K.rows());
  fixed_ = choose_fixing_dofs(kernel);
  interior_.clear();
  return factorize_kept(K, nullptr);
}

CholmodFactor::Result GeneralizedInverse::factorize(const SparseMatrix& K,
                                                    const Eigen::MatrixXd& kernel,
                                                    const std::vector<int>& boundary) {
  size_ = static_cast<int>(K.rows());
  interior_.clear();
  fixed_ = choose_fixing_dofs(kernel);
  // Fixed DOFs on the boundary keep the interior whole; taken when they pin the modes
  // nearly as well as the best DOFs of all (a tenth of the quality; boundaries span the
  // subdomain, so they usually pin it better).
  if (kernel.cols() > 0 && static_cast<int>(boundary.size()) >= kernel.cols()) {
    Eigen::MatrixXd on_boundary(static_cast<int>(boundary.size()), kernel.cols());
    for (size_t k = 0; k < boundary.size(); ++k)
      on_boundary.row(static_cast<int>(k)) = kernel.row(boundary[k]);
    std::vector<int> chosen;
    for (int k : choose_fixing_dofs(on_boundary))
      chosen.push_back(boundary[k]);
    std::sort(chosen.begin(), chosen.end());
    if (pinning_quality(kernel, chosen) >= 0.1 * pinning_quality(kernel, fixed_)) fixed_ = chosen;
  }
  std::vector<char> is_boundary(size_, 0);
  for (int dof : boundary)
    is_boundary[dof] = 1;
  bool interior_whole = true;
  for (int dof : fixed_)
    interior_whole = interior_whole && is_boundary[dof];
  if (!interior_whole || static_cast<int>(boundary.size()) >= size_)
    return factorize_kept(K, nullptr);
  const CholmodFactor::Result result = factorize_kept(K, &is_boundary);
  for (size_t r = 0; r < kept_.size(); ++r)
    if (!is_boundary[kept_[r]]) interior_.push_back(static_cast<int>(r));
  return result;
}

CholmodFactor::Result GeneralizedInverse::factorize_kept(const SparseMatrix& K,
                                                         const std::vector<char>* boundary) {
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
  std::vector<char> leading;
  if (boundary) {
    for (int dof : kept_)
      leading.push_back((*boundary)[dof] ? 0 : 1);
  }
  if (fixed_.empty()) return compacted(boundary ? factor_.factorize(K, leading) : factor_.factorize(K));
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(K.nonZeros()));
  for (int col = 0; col < K.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(K, col); it; ++it)
      if (position[it.row()] >= 0 && position[col] >= 0)
        entries.emplace_back(position[it.row()], position[col], it.value());
  const int n = static_cast<int>(kept_.size());
  SparseMatrix reduced(n, n);
  reduced.setFromTriplets(entries.begin(), entries.end());
  return compacted(boundary ? factor_.factorize(reduced, leading) : factor_.factorize(reduced));
}

CholmodFactor::Result GeneralizedInverse::compacted(CholmodFactor::Result result) {
  // K^+ is only ever solved with: the lean copy holds the factor from here on.
  if (result == CholmodFactor::Result::Ok) factor_.compact();
  return result;
}

void GeneralizedInverse::interior_solve(const double* x, double* y) const {
  thread_local std::vector<double> in, out;
  const int n = static_cast<int>(kept_.size());
  in.assign(n, 0.0);
  out.resize(n);
  for (size_t k = 0; k < interior_.size(); ++k)
    in[interior_[k]] = x[k];
  factor_.solve_leading(in.data(), out.data());
  for (size_t k = 0; k < interior_.size(); ++k)
    y[k] = out[interior_[k]];
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
  // Per thread, not per subdomain: thousands of subdomains share a thread's workspace.
  thread_local Eigen::MatrixXd rhs, solution;
  const int n = static_cast<int>(kept_.size());
  rhs.resize(n, columns);
  solution.resize(n, columns);
  for (int c = 0; c < columns; ++c)
    for (int r = 0; r < n; ++r)
      rhs(r, c) = x[static_cast<size_t>(c) * size_ + kept_[r]];
  factor_.solve(rhs.data(), solution.data(), columns);
  for (int c = 0; c < columns; ++c) {
    double* column = y + static_cast<size_t>(c) * size_;
    for (int dof : fixed_)
      column[dof] = 0.0;
    for (int r = 0; r < n; ++r)
      column[kept_[r]] = solution(r, c);
  }
}

Eigen::VectorXd GeneralizedInverse::apply(const Eigen::VectorXd& x) const {
  Eigen::VectorXd y(size_);
  apply(x.data(), y.data());
  return y;
}

}  // namespace fetic::solver

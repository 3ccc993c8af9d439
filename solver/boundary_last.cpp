#include "solver/boundary_last.hpp"

#include <camd.h>

#include <new>
#include <stdexcept>

#include <Eigen/LU>
#include <Eigen/SVD>

#include "solver/generalized_inverse.hpp"

namespace fetic::solver {
namespace {

// The smallest singular value of the rows `rows` of `kernel` with its columns normalized:
// how well fixing those DOFs pins the kernel.
double pinning(const Eigen::MatrixXd& kernel, const std::vector<int>& rows) {
  Eigen::MatrixXd block(static_cast<Eigen::Index>(rows.size()), kernel.cols());
  for (Eigen::Index c = 0; c < kernel.cols(); ++c) {
    const double norm = kernel.col(c).norm();
    for (std::size_t k = 0; k < rows.size(); ++k)
      block(static_cast<Eigen::Index>(k), c) = norm > 0.0 ? kernel(rows[k], c) / norm : 0.0;
  }
  return Eigen::JacobiSVD<Eigen::MatrixXd>(block).singularValues().minCoeff();
}

}  // namespace

std::optional<std::vector<int>> choose_boundary_fixing_dofs(const Eigen::MatrixXd& kernel,
                                                            const std::vector<int>& boundary) {
  if (kernel.cols() == 0) return std::vector<int>{};
  if (boundary.size() < static_cast<std::size_t>(kernel.cols())) return std::nullopt;
  Eigen::MatrixXd rows(static_cast<Eigen::Index>(boundary.size()), kernel.cols());
  for (std::size_t k = 0; k < boundary.size(); ++k)
    rows.row(static_cast<Eigen::Index>(k)) = kernel.row(boundary[k]);
  std::vector<int> fixed = choose_fixing_dofs(rows);
  for (int& f : fixed)
    f = boundary[static_cast<std::size_t>(f)];
  const double best = pinning(kernel, choose_fixing_dofs(kernel));
  if (!(pinning(kernel, fixed) >= kWorseFixing * best)) return std::nullopt;
  return fixed;
}

std::vector<int> interior_first_order(const SparseMatrix& A, const std::vector<char>& on_boundary) {
  // CAMD with the interior rows in its first set, the boundary's in the second: it orders
  // the interior knowing which of its rows the boundary joins (on a 20x24-element plane
  // subdomain 5% fewer entries than AMD on K_ii alone with the boundary appended).
  const int n = static_cast<int>(A.rows());
  std::vector<int> order(static_cast<std::size_t>(n)), set(on_boundary.begin(), on_boundary.end());
  if (n == 0) return order;
  const int status = camd_order(n, A.outerIndexPtr(), A.innerIndexPtr(), order.data(), nullptr,
                                nullptr, set.data());
  if (status == CAMD_OUT_OF_MEMORY) throw std::bad_alloc();
  if (status != CAMD_OK && status != CAMD_OK_BUT_JUMBLED)
    throw std::logic_error("interior_first_order: CAMD refused the matrix");
  return order;
}

BoundarySchur::BoundarySchur(int first, const std::vector<int>& factor_row,
                             const Eigen::MatrixXd& kernel_rows)
    : first_(first) {
  const int nb = static_cast<int>(factor_row.size());
  int kept = 0;
  for (int p = 0; p < nb; ++p)
    kept += factor_row[static_cast<std::size_t>(p)] >= 0;
  kept_at_.assign(static_cast<std::size_t>(kept), -1);
  for (int p = 0; p < nb; ++p) {
    const int row = factor_row[static_cast<std::size_t>(p)];
    if (row < 0)
      fixed_at_.push_back(p);
    else
      kept_at_.at(static_cast<std::size_t>(row - first)) = p;
  }
  if (fixed_at_.empty()) return;
  const auto m = static_cast<Eigen::Index>(fixed_at_.size());
  Eigen::MatrixXd R_f(m, kernel_rows.cols()), R_k(kept, kernel_rows.cols());
  for (Eigen::Index c = 0; c < m; ++c)
    R_f.row(c) = kernel_rows.row(fixed_at_[static_cast<std::size_t>(c)]);
  for (int r = 0; r < kept; ++r)
    R_k.row(r) = kernel_rows.row(kept_at_[static_cast<std::size_t>(r)]);
  // R_k R_f^-1 as (R_f'^-1 R_k')'.
  map_ = R_f.transpose().fullPivLu().solve(R_k.transpose()).transpose();
}

void BoundarySchur::apply(const CompactFactor& factor, const double* x, double* y) const {
  const auto kept = static_cast<Eigen::Index>(kept_at_.size());
  thread_local Eigen::VectorXd t, v, fixed;  // per thread: no allocation per application
  t.resize(kept);
  v.resize(kept);
  for (Eigen::Index r = 0; r < kept; ++r)
    t(r) = x[kept_at_[static_cast<std::size_t>(r)]];
  if (!fixed_at_.empty()) {
    fixed.resize(static_cast<Eigen::Index>(fixed_at_.size()));
    for (std::size_t c = 0; c < fixed_at_.size(); ++c)
      fixed(static_cast<Eigen::Index>(c)) = x[fixed_at_[c]];
    t.noalias() -= map_ * fixed;
  }
  factor.multiply_trailing(first_, t.data(), v.data());
  for (Eigen::Index r = 0; r < kept; ++r)
    y[kept_at_[static_cast<std::size_t>(r)]] = v(r);
  if (!fixed_at_.empty()) {
    fixed.noalias() = -(map_.transpose() * v);
    for (std::size_t c = 0; c < fixed_at_.size(); ++c)
      y[fixed_at_[c]] = fixed(static_cast<Eigen::Index>(c));
  }
}

std::size_t BoundarySchur::bytes() const {
  return (kept_at_.capacity() + fixed_at_.capacity()) * sizeof(int) +
         static_cast<std::size_t>(map_.size()) * sizeof(double);
}

}  // namespace fetic::solver

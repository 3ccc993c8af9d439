#include "scenes/sparse_null_space.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/SPQRSupport>

namespace fetic::scenes {

Eigen::MatrixXd sparse_null_space(const Eigen::SparseMatrix<double>& C, int limit) {
  const auto columns = static_cast<int>(C.cols());
  if (C.rows() == 0 || C.nonZeros() == 0) {
    const int count = limit < 0 ? columns : std::min(limit, columns);
    return Eigen::MatrixXd::Identity(columns, count);
  }
  // The largest row norm, in one pass over the nonzeros (C is stored by columns).
  Eigen::VectorXd squares = Eigen::VectorXd::Zero(C.rows());
  for (int c = 0; c < C.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(C, c); it; ++it)
      squares(it.row()) += it.value() * it.value();
  const double largest = std::max(1.0, std::sqrt(squares.maxCoeff()));
  Eigen::SparseMatrix<double> transposed = C.transpose();
  transposed.makeCompressed();
  Eigen::SPQR<Eigen::SparseMatrix<double>> qr;
  qr.setPivotThreshold(1e-9 * largest);
  qr.compute(transposed);
  const int rank = static_cast<int>(qr.rank());
  const int nullity = columns - rank;
  const int count = limit < 0 ? nullity : std::min(limit, nullity);
  if (count <= 0) return Eigen::MatrixXd(columns, 0);
  Eigen::MatrixXd pick = Eigen::MatrixXd::Zero(columns, count);
  for (int j = 0; j < count; ++j)
    pick(rank + j, j) = 1.0;
  return qr.matrixQ() * pick;
}

}  // namespace fetic::scenes

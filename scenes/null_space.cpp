#include "scenes/null_space.hpp"

#include <algorithm>

#include <Eigen/SVD>

namespace fetic::scenes {

Eigen::MatrixXd null_space(const Eigen::MatrixXd& C, int columns) {
  if (C.rows() == 0) return Eigen::MatrixXd::Identity(columns, columns);
  constexpr double kRankTolerance = 1e-9;
  Eigen::BDCSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeFullV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  const double threshold = kRankTolerance * std::max(1.0, sigma.size() ? sigma(0) : 0.0);
  int rank = 0;
  while (rank < sigma.size() && sigma(rank) > threshold)
    ++rank;
  return svd.matrixV().rightCols(columns - rank);
}

Eigen::MatrixXd null_space_relative(const Eigen::MatrixXd& C, double relative) {
  return split_right_singular_vectors(C, relative).null_space;
}

RightSingularSplit split_right_singular_vectors(const Eigen::MatrixXd& C, double relative) {
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeFullV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  const double tolerance = relative * (sigma.size() > 0 ? sigma(0) : 1.0);
  int rank = 0;
  while (rank < sigma.size() && sigma(rank) > tolerance)
    ++rank;
  return {svd.matrixV().leftCols(rank), svd.matrixV().rightCols(C.cols() - rank)};
}

}  // namespace fetic::scenes

#include "solver/condition_estimate.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace fetic::solver {

void ConditionRecord::clear() {
  steps_.clear();
  run_start_ = longest_start_ = longest_size_ = 0;
}

void ConditionRecord::add(double a, double beta) {
  if (steps_.size() == run_start_) beta = 0.0;
  steps_.push_back({a, beta});
  if (steps_.size() - run_start_ >= longest_size_) {
    longest_start_ = run_start_;
    longest_size_ = steps_.size() - run_start_;
  }
}

ConditionEstimate ConditionRecord::estimate() const {
  const int m = static_cast<int>(longest_size_);
  if (m == 0) return {};
  const Step* run = steps_.data() + longest_start_;
  Eigen::VectorXd diagonal(m), off(std::max(m - 1, 1));
  for (int k = 0; k < m; ++k) {
    diagonal(k) = 1.0 / run[k].a + (k > 0 ? run[k].beta / run[k - 1].a : 0.0);
    // Rounding can leave beta a hair below zero where it vanishes in exact arithmetic.
    if (k + 1 < m) off(k) = std::sqrt(std::max(run[k + 1].beta, 0.0)) / run[k].a;
  }
  if (m == 1) return {1, diagonal(0), diagonal(0)};
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver;
  solver.computeFromTridiagonal(diagonal, off.head(m - 1), Eigen::EigenvaluesOnly);
  return {m, solver.eigenvalues()(0), solver.eigenvalues()(m - 1)};
}

}  // namespace fetic::solver

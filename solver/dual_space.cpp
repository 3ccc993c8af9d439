#include "solver/dual_space.hpp"

#include <cmath>

namespace fetic::solver {

DualSpace::DualSpace(const Decomposition& decomposition)
    : first_contact_(decomposition.equality_rows) {
  kind_.reserve(decomposition.rows.size());
  for (const Row& row : decomposition.rows)
    kind_.push_back(row.kind);
}

double DualSpace::dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  return sum(a.dot(b));
}

double DualSpace::norm(const Eigen::VectorXd& a) const {
  return std::sqrt(dot(a, a));
}

double DualSpace::max_abs(const Eigen::VectorXd& a) const {
  return max(a.size() > 0 ? a.lpNorm<Eigen::Infinity>() : 0.0);
}

}  // namespace fetic::solver

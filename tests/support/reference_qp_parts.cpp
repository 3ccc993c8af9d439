#include "tests/support/reference_qp_parts.hpp"

#include <CGAL/Gmpzf.h>
#include <CGAL/QP_functions.h>

namespace fetic::testing {

std::vector<std::vector<int>> groups_of(scenes::UnionFind& sets, int count) {
  std::vector<std::vector<int>> groups;
  for (int group = 0; group < count; ++group) {
    if (sets.root(group) != group) continue;
    groups.emplace_back();
    for (int s = 0; s < count; ++s)
      if (sets.root(s) == group) groups.back().push_back(s);
  }
  return groups;
}

namespace {

Eigen::MatrixXd rows_and_columns(const Eigen::MatrixXd& K, const std::vector<int>& r,
                                 const std::vector<int>& c) {
  Eigen::MatrixXd M(r.size(), c.size());
  for (size_t x = 0; x < r.size(); ++x)
    for (size_t y = 0; y < c.size(); ++y)
      M(x, y) = K(r[x], c[y]);
  return M;
}

Eigen::VectorXd entries(const Eigen::VectorXd& v, const std::vector<int>& r) {
  Eigen::VectorXd p(r.size());
  for (size_t x = 0; x < r.size(); ++x)
    p(x) = v(r[x]);
  return p;
}

}  // namespace

Condensation::Condensation(const Eigen::MatrixXd& K, const Eigen::VectorXd& f,
                           const std::vector<int>& kept, const std::vector<int>& interior)
    : Kii_(rows_and_columns(K, interior, interior)),
      Kic_(rows_and_columns(K, interior, kept)),
      fi_(entries(f, interior)) {
  S_ = rows_and_columns(K, kept, kept) - Kic_.transpose() * Kii_.solve(Kic_);
  S_ = 0.5 * (S_ + S_.transpose()).eval();
  g_ = entries(f, kept) - Kic_.transpose() * Kii_.solve(fi_);
}

Eigen::VectorXd Condensation::interior(const Eigen::VectorXd& kept_values) const {
  return Kii_.solve(fi_ - Kic_ * kept_values);
}

ExactSolution solve_exact(const CGAL::Quadratic_program<double>& qp, int variables, int rows) {
  CGAL::Quadratic_program_options options;
  options.set_pricing_strategy(CGAL::QP_DANTZIG);
  const auto result = CGAL::solve_quadratic_program(qp, CGAL::Gmpzf(), options);
  ExactSolution solution;
  solution.optimal = result.is_optimal();
  if (!solution.optimal) return solution;
  solution.x = Eigen::VectorXd::Zero(variables);
  int x = 0;
  for (auto it = result.variable_values_begin();
       it != result.variable_values_end() && x < variables; ++it, ++x)
    solution.x(x) = CGAL::to_double(*it);
  for (auto it = result.optimality_certificate_begin();
       it != result.optimality_certificate_end() &&
       static_cast<int>(solution.multipliers.size()) < rows;
       ++it)
    solution.multipliers.push_back(CGAL::to_double(*it));
  solution.multipliers.resize(static_cast<size_t>(rows), 0.0);
  return solution;
}

}  // namespace fetic::testing

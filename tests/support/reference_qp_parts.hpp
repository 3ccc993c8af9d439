#pragma once
// What the three reference QPs (bar, plane, frame: reference_qp*.cpp) share: the groups
// of struts that contacts (and joints) connect, static condensation onto the unknowns
// the contacts touch, and CGAL's exact solve.

#include <CGAL/QP_models.h>

#include <Eigen/Dense>
#include <utility>
#include <vector>

#include "scenes/union_find.hpp"

namespace fetic::testing {

// The members of each set of `sets` over 0..count-1, in increasing order, the sets in
// the order of their representatives.
std::vector<std::vector<int>> groups_of(scenes::UnionFind& sets, int count);

// One constraint a'u <= gap over the unknowns of a group; `index` is its contact (or
// contact node pair) in scene order.
struct ContactRow {
  int index;
  std::vector<std::pair<int, double>> entries;
  double gap;
};

// K u = f split into the kept unknowns c and the interior ones i, the interior eliminated
// by a dense Cholesky factor: S = K_cc - K_ci K_ii^-1 K_ic (symmetrized) and
// g = f_c - K_ci K_ii^-1 f_i; interior(u_c) = K_ii^-1 (f_i - K_ic u_c).
class Condensation {
 public:
  Condensation(const Eigen::MatrixXd& K, const Eigen::VectorXd& f, const std::vector<int>& kept,
               const std::vector<int>& interior);
  const Eigen::MatrixXd& S() const { return S_; }
  const Eigen::VectorXd& g() const { return g_; }
  Eigen::VectorXd interior(const Eigen::VectorXd& kept_values) const;

 private:
  Eigen::LLT<Eigen::MatrixXd> Kii_;
  Eigen::MatrixXd Kic_, S_;
  Eigen::VectorXd fi_, g_;
};

struct ExactSolution {
  bool optimal = false;
  Eigen::VectorXd x;                // `variables` entries, zero where CGAL has none
  std::vector<double> multipliers;  // one per row, in row order
};

// The QP solved exactly (Gmpzf arithmetic, Dantzig pricing: partial pricing trips a CGAL
// assertion).
ExactSolution solve_exact(const CGAL::Quadratic_program<double>& qp, int variables, int rows);

}  // namespace fetic::testing

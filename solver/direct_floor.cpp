#include "solver/direct_floor.hpp"

#include <chrono>
#include <cmath>

#include "solver/cholmod_factor.hpp"
#include "solver/primal_problem.hpp"
#include "solver/stopwatch.hpp"

namespace fetic::solver {

FloorSolution solve_with_working_set(const Model& model, double load_factor,
                                     const std::vector<char>& in_working_set) {
  FloorSolution result;
  auto start = std::chrono::steady_clock::now();
  const PrimalProblem problem(model, /*factorize_blocks=*/false);
  const RowSparseMatrix& A = problem.contact_rows();
  const int n = problem.size();

  // Eliminate, per active row, its DOF with the largest coefficient on the b side (the
  // last entries of the row belong to b; any entry would do).
  std::vector<int> eliminated_by(n, -1);
  for (int k = 0; k < A.rows(); ++k) {
    if (k >= static_cast<int>(in_working_set.size()) || !in_working_set[k]) continue;
    int best = -1;
    double best_value = 0.0;
    for (RowSparseMatrix::InnerIterator it(A, k); it; ++it)
      if (std::abs(it.value()) >= best_value) {
        best_value = std::abs(it.value());
        best = it.col();
      }
    if (best >= 0 && best_value > 0.0) eliminated_by[best] = k;
  }
  std::vector<int> kept(n, -1);
  int reduced = 0;
  for (int j = 0; j < n; ++j)
    if (eliminated_by[j] < 0) kept[j] = reduced++;
  std::vector<Eigen::Triplet<double>> z_entries;
  Eigen::VectorXd z0 = Eigen::VectorXd::Zero(n);
  for (int j = 0; j < n; ++j) {
    if (kept[j] >= 0) {
      z_entries.emplace_back(j, kept[j], 1.0);
      continue;
    }
    const int k = eliminated_by[j];
    const double pivot = A.coeff(k, j);
    z0(j) = problem.gaps()(k) / pivot;
    for (RowSparseMatrix::InnerIterator it(A, k); it; ++it)
      if (it.col() != j) z_entries.emplace_back(j, kept[it.col()], -it.value() / pivot);
  }
  SparseMatrix Z(n, reduced);
  Z.setFromTriplets(z_entries.begin(), z_entries.end());
  const SparseMatrix& K = problem.stiffness();
  SparseMatrix Kr = SparseMatrix(Z.transpose()) * K * Z;
  Kr.makeCompressed();
  const Eigen::VectorXd rhs = Z.transpose() * (load_factor * problem.load() - K * z0);
  result.assemble_seconds = seconds_since(start);

  start = std::chrono::steady_clock::now();
  CholmodFactor factor;
  const CholmodFactor::Result status = factor.factorize(Kr);
  result.factorize_seconds = seconds_since(start);
  if (status != CholmodFactor::Result::Ok)
    throw SolverError(
        "direct solve with the working set imposed: the constrained stiffness is "
        "singular (a strut the working set does not hold?)");
  start = std::chrono::steady_clock::now();
  Eigen::VectorXd v(reduced);
  factor.solve(rhs.data(), v.data());
  const Eigen::VectorXd u = Z * v + z0;
  result.solve_seconds = seconds_since(start);
  result.pieces = problem.pieces(u);
  result.unknowns = static_cast<std::size_t>(reduced);
  result.factor_nonzeros = factor.factor_nonzeros();
  result.factor_memory = factor.peak_memory();
  return result;
}

}  // namespace fetic::solver

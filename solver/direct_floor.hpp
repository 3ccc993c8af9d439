#pragma once
// The floor a contact solver is measured against: one sparse direct solve of the same
// assembled problem with a known working set imposed as equalities. Each active pair
// (u_a - u_b) . n = gap is used to eliminate one DOF of its b node (u = Z v + z0; each
// node is in at most one pair, so the eliminations are independent), and Z'K Z v =
// Z'(t f - K z0) is factorized and solved once by CHOLMOD.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "solver/method.hpp"

namespace fetic::solver {

struct FloorSolution {
  std::vector<Piece> pieces;
  double assemble_seconds = 0.0;  // K, A and Z'K Z
  double factorize_seconds = 0.0;
  double solve_seconds = 0.0;
  std::size_t unknowns = 0;
  std::size_t factor_nonzeros = 0;
  std::size_t factor_memory = 0;  // CHOLMOD's peak, bytes

  double total_seconds() const { return assemble_seconds + factorize_seconds + solve_seconds; }
};

// Throws SolverError when the constrained stiffness is singular (e.g. a floating strut
// the working set does not hold).
FloorSolution solve_with_working_set(const Model& model, double load_factor,
                                     const std::vector<char>& in_working_set);

}  // namespace fetic::solver

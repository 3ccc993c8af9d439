#pragma once
// Bytes a process holds for its subdomains, by kind: what `fetic solve --profile` and
// `fetic-bench-scale --only bytes` report per unknown (docs/BENCHMARKS.md). Counted from
// the containers' sizes and CHOLMOD's own accounting (memory in use, not its peak).

#include <cstddef>

#include "solver/stiffness.hpp"

namespace fetic::solver {

struct LocalMemory {
  double stiffness = 0.0;              // K_j, sparse (released after set-up when it is)
  double factor = 0.0;                 // CHOLMOD factors of K_j and their solve workspaces
  double preconditioner_factor = 0.0;  // the Dirichlet preconditioner's own K_ii factors
  double preconditioner_blocks = 0.0;  // K_bb, K_ib (sparse)
  double incidence = 0.0;              // B's entries: per subdomain, per row, scaled copies
  double rigid_modes = 0.0;            // R_j (dense) and G, |G| (sparse)
  double index = 0.0;                  // index arrays: kept/fixed DOFs, boundaries, offsets
  double workspaces = 0.0;             // vectors over the subdomains' DOFs and boundaries
  double loads = 0.0;                  // the subdomains' load vectors f_j

  double total() const {
    return stiffness + factor + preconditioner_factor + preconditioner_blocks + incidence +
           rigid_modes + index + workspaces + loads;
  }
};

// Bytes of a compressed sparse matrix's arrays, as allocated (an Eigen matrix assigned a
// smaller one keeps its storage).
inline double sparse_bytes(const SparseMatrix& A) {
  return static_cast<double>(A.data().allocatedSize()) * (sizeof(double) + sizeof(int)) +
         (static_cast<double>(A.outerSize()) + 1.0) * sizeof(int);
}

}  // namespace fetic::solver

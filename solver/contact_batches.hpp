#pragma once
// Which columns of the contact faces' coarse space (contact_coarse.hpp) can share one
// application of A at set-up, and which of them E = U'A U couples.
//
// Where A u is nonzero. A = T'F T (+ rho Q_C) is MPRGP's operator (mprgp.hpp). F = B K^+ B'
// solves every subdomain - in FETI-DP a cluster of boxes joined by corners - on its own,
// so F x is nonzero only on the rows touching a subdomain that x's rows touch. T (the
// rigid-body modes held by the equality rows), the redundant rows' projection onto
// range(B) and Q_C (groups of floating subdomains held only by contacts) spread a vector
// further, but only along equality rows and along contact rows between two subdomains
// with rigid-body modes. So the subdomains are joined into blocks by the ends of those
// rows, and A u_c is nonzero only on the rows touching column c's blocks: its reach.
//
// Batches: columns none of whose blocks equals, or shares a row with, a block of another
// are applied as one vector (greedy colouring in column order), and A's result is split
// back to the columns by block. Components: E_ij is nonzero only when columns i and j
// share a block (a row of u_i lies in j's reach only if it touches one of j's blocks), so
// E is block diagonal over the columns linked by shared blocks. Many independent contacts
// thus take as many applications of A as the most crowded block has columns, and E is as
// large as its largest component, not |U| x |U| (issue 24: 5,000 contacts took 5,010
// applications of F, a dense 5,000^2 E and 100 s of set-up).
//
// Everything comes from the replicated decomposition: the same batches and components on
// every process.

#include <vector>

#include "solver/decomposition.hpp"

namespace fetic::solver {

struct ContactBatches {
  std::vector<int> block_of_subdomain;
  int block_count = 0;
  std::vector<std::vector<int>> column_blocks;  // per column, its blocks, increasing
  std::vector<std::vector<int>> batches;        // columns applied together
  std::vector<std::vector<int>> components;     // columns coupled in E, each increasing
};

// column_rows[c]: the global rows (of `d`) on which column c is nonzero.
ContactBatches batch_columns(const Decomposition& d,
                             const std::vector<std::vector<int>>& column_rows);

}  // namespace fetic::solver
